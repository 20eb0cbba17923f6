"""What the quasi-static 2D and 3D contact solvers share: inputs, depth steps, records, result.

:func:`woundroll.contact.plane_strain.solver.indent` and
:func:`woundroll.contact.solid3d.solver.indent3d` press a rigid head into the roll by
increasing depths and return a :class:`~woundroll.contact.result.ContactResult`. Their rolls,
meshes and linear solvers differ; this module holds what is the same:

* the input checks of a length and of the pre-impact stress profile
  (:func:`check_scalar`, :func:`check_profile`);
* the depth steps ``d_k = depth_max (k / n_steps)^step_exponent`` (:func:`depth_schedule`);
* the exact solve of the contact's linear complementarity problem (:func:`solve_lcp`) and
  the contact's edge between two surface nodes (:func:`half_width`);
* what is recorded at every depth (:class:`LoadHistory`) and the result's fields built from
  it (:func:`result_fields`: the spring fit {3}, the slip factor {23}, the histories).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.contact.result import fit_spring, slip_factor
from woundroll.errors import ConvergenceError, InputError
from woundroll.units import to_si

FloatArray = NDArray[np.float64]


def check_scalar(value: float | str, field: str, kind: str = "length") -> float:
    """A positive finite SI value; strings with units (``"10 mm"``) are converted."""
    if isinstance(value, bool):
        raise InputError(f"must be a number, got {value!r}", field)
    if isinstance(value, str):
        v = to_si(value, kind, field)
    else:
        try:
            v = float(value)
        except (TypeError, ValueError):
            raise InputError(f"must be a number, got {value!r}", field) from None
    if not math.isfinite(v) or v <= 0:
        raise InputError(f"must be a positive finite number, got {value!r}", field)
    return v


def check_profile(
    web: Any, core: Any, radius: object, sigma_r: object
) -> tuple[FloatArray, FloatArray]:
    """The pre-impact profile as arrays: radii increasing from the core, finite values."""
    try:
        r = np.asarray(radius, dtype=float)
        s = np.asarray(sigma_r, dtype=float)
    except (TypeError, ValueError):
        raise InputError("radius and sigma_r must be arrays of numbers", "radius") from None
    if r.ndim != 1 or r.size < 2:
        raise InputError("must be a 1D array of at least 2 radii [m]", "radius")
    if s.ndim != 1 or s.size != r.size:
        raise InputError(
            f"must be a 1D array of the same length as radius ({r.size}), got shape {s.shape}",
            "sigma_r",
        )
    if not np.all(np.isfinite(r)):
        raise InputError("must hold finite numbers only", "radius")
    if not np.all(np.isfinite(s)):
        raise InputError("must hold finite numbers only (NaN or inf found)", "sigma_r")
    if np.any(np.diff(r) <= 0):
        raise InputError("must increase strictly from the core outward", "radius")
    if r[0] < core.outer_radius - 1.01 * web.thickness:
        raise InputError(
            f"starts at {r[0]:g} m, inside the core (outer radius {core.outer_radius:g} m)",
            "radius",
        )
    if r[-1] <= core.outer_radius + web.thickness:
        raise InputError(
            f"the outer radius {r[-1]:g} m leaves no wound layer on the core "
            f"({core.outer_radius:g} m)",
            "radius",
        )
    return r, s


def depth_schedule(
    depth_max: float, n_steps: int, exponent: float, deepest: float | None = None
) -> FloatArray:
    """The depths ``d_k = depth_max (k / n_steps)^exponent`` from 0 to ``depth_max``; with
    ``deepest`` beyond it the same law goes on to ``deepest`` (the last depth clipped there;
    the depths up to ``depth_max`` are the same)."""
    n = n_steps
    if deepest is not None and deepest > depth_max:
        n = int(math.ceil(n_steps * (deepest / depth_max) ** (1.0 / exponent)))
    else:
        deepest = depth_max
    return np.minimum(depth_max * (np.arange(n + 1) / n_steps) ** exponent, deepest)


def solve_lcp(W: FloatArray, q: FloatArray, start: NDArray[np.bool_] | None = None) -> FloatArray:
    """Solve ``lam >= 0, g = q + W lam >= 0, lam . g = 0`` for symmetric positive definite W.

    It is the optimality condition of ``min 1/2 lam W lam + q lam, lam >= 0``, solved exactly
    by the finite active-set method of Lawson and Hanson (their NNLS algorithm written for
    the quadratic form itself): the passive set grows by the most violated contact, and
    where the unconstrained solution on it leaves a force negative, the step goes back to
    the boundary and that node leaves. NumPy only (no scipy.optimize at import: start-up).

    ``start`` (optional mask): a guess of the nodes in contact, e.g. the last increment's.
    Where the unconstrained solution on it is positive everywhere it is the method's first
    passive set (its invariant holds there), which saves the one-node-at-a-time growth up
    to it; otherwise the method starts from no contact. The solution is the same either
    way (the LCP's solution is unique for positive definite W).
    """
    W = 0.5 * (W + W.T)
    m = q.size
    scale = float(np.max(np.diag(W)))
    Ws, qs = W / scale, q / scale  # lam is unchanged by the common scale
    try:
        np.linalg.cholesky(Ws)
    except np.linalg.LinAlgError:
        raise ConvergenceError(
            "contact flexibility matrix is not positive definite "
            "(mesh too coarse or roll not supported)"
        ) from None
    lam = np.zeros(m)
    passive = np.zeros(m, dtype=bool)
    tol = 1e-13 * max(float(np.max(np.abs(qs))), 1e-300)
    if start is not None and np.any(start):
        idx = np.flatnonzero(start)
        z = np.linalg.solve(Ws[np.ix_(idx, idx)], -qs[idx])
        if np.all(z > 0):
            lam[idx] = z
            passive[idx] = True
    for _ in range(3 * m + 10):
        w = -(qs + Ws @ lam)  # minus the gradient: > 0 where a force would lower the energy
        w[passive] = -np.inf
        j = int(np.argmax(w))
        if w[j] <= tol:
            return lam
        passive[j] = True
        if not _lcp_passive_solve(Ws, qs, lam, passive):
            break
    raise ConvergenceError("contact active set did not settle")


def _lcp_passive_solve(
    Ws: FloatArray, qs: FloatArray, lam: FloatArray, passive: NDArray[np.bool_]
) -> bool:
    """The inner loop of :func:`solve_lcp`: the unconstrained solution on the passive set,
    stepping back to the boundary while a force would be negative (``lam`` and ``passive``
    updated in place); False if it did not settle."""
    m = qs.size
    for _ in range(3 * m + 10):
        idx = np.flatnonzero(passive)
        z = np.zeros(m)
        z[idx] = np.linalg.solve(Ws[np.ix_(idx, idx)], -qs[idx])
        if np.all(z[idx] > 0):
            lam[:] = z
            return True
        # back along lam -> z to where the first force reaches zero; that node leaves
        neg = idx[z[idx] <= 0]
        denom = lam[neg] - z[neg]
        ratio = np.where(denom > 0, lam[neg] / np.where(denom > 0, denom, 1.0), 0.0)
        k = int(np.argmin(ratio))
        lam[:] = lam + ratio[k] * (z - lam)
        passive[neg[k]] = False
        passive &= lam > 0
        lam[~passive] = 0.0
    return False


def half_width(
    s: FloatArray, lam: FloatArray, gap: FloatArray, j0: int, sides: tuple[int, ...] = (1, -1)
) -> float:
    """Contact half-width [m] from the active set, interpolated between nodes.

    Beyond the last node in contact the gap of a Hertz-type contact opens as
    (s - a)^(3/2); the edge ``a`` is placed where that law through the first two open
    nodes' gaps vanishes, clamped between the last closed and the first open node.
    """
    if lam.max() <= 0:
        return 0.0
    active = lam > 1e-9 * lam.max()
    out = []
    for sign in sides:
        j = j0
        while 0 <= j + 2 * sign < s.size and active[j + sign]:
            j += sign
        if not active[j]:
            out.append(0.0)
            continue
        j1, j2 = j + sign, j + 2 * sign
        s0, s1, s2 = abs(s[j]), abs(s[j1]), abs(s[j2])
        g1, g2 = gap[j1], gap[j2]
        if g1 <= 0:
            out.append(s1)
        elif g2 <= g1:
            out.append(0.5 * (s0 + s1))
        else:
            rho = (g1 / g2) ** (2.0 / 3.0)
            out.append(float(np.clip((s1 - rho * s2) / (1.0 - rho), s0, s1)))
    return float(np.mean(out))


@dataclass
class LoadHistory:
    """What an indentation records at every depth (row k at ``delta[k]``, row 0 before
    contact): the force on the head (per unit length in 2D), the semi-contact width, the
    peak contact pressure, the contact-induced (sigma_r, sigma_theta, tau_r_theta) of the
    elements and the contact pressure on the surface nodes of the head's centre line."""

    delta: FloatArray
    force: FloatArray
    half_width: FloatArray
    peak_pressure: FloatArray
    stress: FloatArray
    pressure: FloatArray

    @classmethod
    def start(cls, delta: FloatArray, n_elements: int, n_line: int) -> LoadHistory:
        n = delta.size
        return cls(
            delta=delta,
            force=np.zeros(n),
            half_width=np.zeros(n),
            peak_pressure=np.zeros(n),
            stress=np.zeros((n, n_elements, 3)),
            pressure=np.zeros((n, n_line)),
        )

    def record(
        self,
        k: int,
        force: float,
        half_width: float,
        peak_pressure: float,
        stress: FloatArray,
        pressure: FloatArray,
    ) -> None:
        self.force[k] = force
        self.half_width[k] = half_width
        self.peak_pressure[k] = peak_pressure
        self.stress[k] = stress
        self.pressure[k] = pressure

    def up_to(self, m: int) -> LoadHistory:
        """The first ``m`` depths (a loading stopped early)."""
        return LoadHistory(
            self.delta[:m],
            self.force[:m],
            self.half_width[:m],
            self.peak_pressure[:m],
            self.stress[:m],
            self.pressure[:m],
        )


def result_fields(
    h: LoadHistory,
    *,
    force: FloatArray,
    stress: tuple[FloatArray, FloatArray, FloatArray],
    sigma_pre: FloatArray,
    friction: float,
    elements: tuple[FloatArray, FloatArray, FloatArray, FloatArray],
    contact_s: FloatArray,
) -> dict[str, Any]:
    """The :class:`~woundroll.contact.result.ContactResult` fields of a loading that the 2D
    and 3D models fill alike: the curve and its spring fit {3} (``force`` [N] on the whole
    head at ``h.delta``), the contact pressure, the final contact-induced stresses
    ``stress`` (sigma_r, sigma_theta, tau_r_theta) with the slip factor {23}, the
    histories, and the element centres ``elements`` (x, y, r, theta)."""
    sig_r, sig_t, tau = stress
    sigma_r_total = sigma_pre + sig_r
    alpha, beta, r2, max_res = fit_spring(h.delta, force)
    x, y, r, theta = elements
    return {
        "delta": h.delta,
        "force": force,
        "contact_pressure": h.pressure[-1],
        "half_width": h.half_width,
        "peak_pressure": h.peak_pressure,
        "alpha": alpha,
        "beta": beta,
        "fit_r2": r2,
        "fit_max_rel_residual": max_res,
        "contact_s": contact_s,
        "element_x": x,
        "element_y": y,
        "element_r": r,
        "element_theta": theta,
        "sigma_r": sigma_r_total,
        "sigma_r_pre": sigma_pre,
        "sigma_theta": sig_t,
        "tau_r_theta": tau,
        "slip_factor": slip_factor(tau, sigma_r_total, friction),
        "sigma_r_history": sigma_pre[None, :] + h.stress[:, :, 0],
        "sigma_theta_history": h.stress[:, :, 1],
        "tau_r_theta_history": h.stress[:, :, 2],
        "contact_pressure_history": h.pressure,
        "friction": friction,
    }
