"""Creep of the stack in its thickness direction: the creep laws of the radial modulus.

A stack of web held at a constant pressure keeps compressing: its strain grows from the
instantaneous ``eps_0 = P / E_r`` by the creep function ``phi(t)``::

    eps(t) = eps_0 (1 + phi(t)),     J(t) = (1 + phi(t)) / E_r        (creep compliance)

(linear viscoelasticity in the increments, separable in time and pressure: the shape of the
creep, ``phi``, is the same at every pressure, its size scales with the tangent compliance
``1 / E_r(P)`` of the loading law; an assumption, named in docs/winding.md "Storage time").

Laws (``phi(0) = 0``):

``power``
    ``phi(t) = (t / tau)^n``, ``0 < n < 1``; ``tau`` is the time at which the creep strain
    equals the instantaneous strain. Power laws describe the compressive creep of paper and
    polymer stacks over decades of time (Coffin, "The creep response of paper", Trans. XIIIth
    Fund. Res. Symp., Cambridge 2005, pp. 651-747; Lin and Westmann, "Viscoelastic winding
    mechanics", J. Appl. Mech. 56 (1989) 821, use a viscoelastic tape of this kind).
``prony``
    ``phi(t) = sum_i c_i (1 - exp(-t / tau_i))``, ``c_i >= 0``: a chain of Kelvin-Voigt
    elements (one term: the standard linear solid); a linear viscoelastic radial law of the
    kind in Qualls and Good's winding model ("An orthotropic viscoelastic winding model
    including a nonlinear radial stiffness", J. Appl. Mech. 64 (1997) 201-208). It creeps to
    ``1 + sum c_i`` times the instantaneous strain.

No law has a default: its parameters come from a creep test of the web
(``woundroll fit-stack CSV --creep``). The numbers in docs/winding.md are typical,
unpublished.

Each law also gives ``Psi(t) = integral_0^t phi``, from which the mean of ``phi`` over a
time step (exact product integration of a stress that is linear in time within a step,
:mod:`woundroll.winding.creep`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.units import to_si

FloatArray = NDArray[np.float64]

CREEP_LAWS = ("power", "prony")


@dataclass(frozen=True)
class PowerCreep:
    """``phi(t) = (t / tau)^n`` (module docstring).

    Attributes
    ----------
    n : float [-]
        Exponent, 0 < n < 1.
    tau : float [s]
        Time at which the creep strain equals the instantaneous strain.
    """

    n: float
    tau: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.n) and 0.0 < self.n < 1.0):
            raise InputError(f"must lie in (0, 1), got {self.n!r}", "radial_creep.n")
        if not (math.isfinite(self.tau) and self.tau > 0.0):
            raise InputError(f"must be a positive time, got {self.tau!r}", "radial_creep.tau")

    def phi(self, t: ArrayLike) -> FloatArray:
        """The creep function ``phi(t)`` [-] (``t < 0`` taken as 0)."""
        return (np.maximum(np.asarray(t, dtype=float), 0.0) / self.tau) ** self.n

    def psi(self, t: ArrayLike) -> FloatArray:
        """``integral_0^t phi`` [s]."""
        x = np.maximum(np.asarray(t, dtype=float), 0.0) / self.tau
        return self.tau * x ** (self.n + 1.0) / (self.n + 1.0)

    def to_dict(self) -> dict[str, Any]:
        return {"law": "power", "exponent": self.n, "tau_s": self.tau}

    def toml(self) -> str:
        """The case-file inline table (``storage.radial_creep``)."""
        return f'{{ law = "power", n = {self.n:.6g}, tau = "{self.tau:.6g} s" }}'


@dataclass(frozen=True)
class PronyCreep:
    """``phi(t) = sum_i c_i (1 - exp(-t / tau_i))`` (module docstring).

    Attributes
    ----------
    c : tuple of float [-]
        Weights, >= 0 (at least one > 0).
    tau : tuple of float [s]
        Retardation times, > 0.
    """

    c: tuple[float, ...]
    tau: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.c) == 0 or len(self.c) != len(self.tau):
            raise InputError(
                "needs as many weights c as retardation times tau (at least one)",
                "radial_creep.c",
            )
        for i, (c, tau) in enumerate(zip(self.c, self.tau, strict=True)):
            if not (math.isfinite(c) and c >= 0.0):
                raise InputError(f"must be >= 0, got {c!r}", f"radial_creep.c[{i}]")
            if not (math.isfinite(tau) and tau > 0.0):
                raise InputError(f"must be a positive time, got {tau!r}", f"radial_creep.tau[{i}]")

    def phi(self, t: ArrayLike) -> FloatArray:
        t = np.maximum(np.asarray(t, dtype=float), 0.0)
        out = np.zeros_like(t)
        for c, tau in zip(self.c, self.tau, strict=True):
            out = out + c * -np.expm1(-t / tau)
        return out

    def psi(self, t: ArrayLike) -> FloatArray:
        t = np.maximum(np.asarray(t, dtype=float), 0.0)
        out = np.zeros_like(t)
        for c, tau in zip(self.c, self.tau, strict=True):
            # t - tau (1 - exp(-t/tau)), written without cancellation for t << tau
            x = t / tau
            small = x < 1e-4
            tail = np.where(small, tau * x * x * (0.5 - x / 6.0), t + tau * np.expm1(-x))
            out = out + c * tail
        return out

    def to_dict(self) -> dict[str, Any]:
        return {"law": "prony", "weights": list(self.c), "tau_s": list(self.tau)}

    def toml(self) -> str:
        cs = ", ".join(f"{c:.6g}" for c in self.c)
        ts = ", ".join(f'"{t:.6g} s"' for t in self.tau)
        return f'{{ law = "prony", c = [{cs}], tau = [{ts}] }}'


CreepLaw = PowerCreep | PronyCreep


def step_mean_phi(law: CreepLaw, t: float, a: ArrayLike, b: ArrayLike) -> FloatArray:
    """Mean of ``phi(t - t')`` over ``a <= t' <= b`` (``b <= t``), exact:
    ``(Psi(t - a) - Psi(t - b)) / (b - a)``."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return (law.psi(t - a) - law.psi(t - b)) / (b - a)


def creep_from_spec(spec: Any, field: str = "storage.radial_creep") -> CreepLaw:
    """A law from a case-file inline table, e.g. ``{ law = "power", n = 0.2, tau = "40 d" }``
    or ``{ law = "prony", c = [0.1, 0.2], tau = ["1 h", "10 d"] }`` (times with units)."""
    if isinstance(spec, PowerCreep | PronyCreep):
        return spec
    if not isinstance(spec, dict):
        raise InputError(
            'must be an inline table such as { law = "power", n = 0.2, tau = "40 d" }', field
        )
    spec = dict(spec)
    law = spec.pop("law", None)
    if law not in CREEP_LAWS:
        raise InputError(
            f"unknown law {law!r}; choose one of {', '.join(CREEP_LAWS)}", f"{field}.law"
        )
    for key in ("n", "tau", "c"):
        if (
            key not in spec
            and not (law == "power" and key == "c")
            and not (law == "prony" and key == "n")
        ):
            raise InputError(f"missing for law {law!r}", f"{field}.{key}")
    try:
        if law == "power":
            n = to_si(spec.pop("n"), "dimensionless", f"{field}.n")
            tau = to_si(spec.pop("tau"), "time", f"{field}.tau")
            out: CreepLaw = PowerCreep(n, tau)
        else:
            c, tau = spec.pop("c"), spec.pop("tau")
            if not isinstance(c, list) or not isinstance(tau, list):
                raise InputError("c and tau must be lists of equal length", f"{field}.c")
            out = PronyCreep(
                tuple(to_si(v, "dimensionless", f"{field}.c[{i}]") for i, v in enumerate(c)),
                tuple(to_si(v, "time", f"{field}.tau[{i}]") for i, v in enumerate(tau)),
            )
    except InputError as exc:
        f = exc.field or field
        raise InputError(
            exc.message, f if f.startswith(field) else f"{field}.{f.split('.')[-1]}"
        ) from None
    if spec:
        raise InputError(f"unknown key(s) {', '.join(sorted(spec))} for law {law!r}", field)
    return out


def relaxation(law: CreepLaw, times: ArrayLike, steps_per_decade: int = 40) -> FloatArray:
    """Relaxation function ``g(t) = P(t) / P(0+)`` of a stack held at a constant strain
    (the single compressed layer): the Volterra equation
    ``P(t) + integral_0^t phi(t - t') dP(t') = P_0`` solved by the product-integration steps
    of :mod:`woundroll.winding.creep` on a graded grid (``steps_per_decade`` per decade from
    1e-6 of the last time or a hundredth of the first, whichever is earlier), interpolated at
    ``times`` [s] (>= 0)."""
    t_out = np.asarray(times, dtype=float)
    t_end = float(np.max(t_out)) if t_out.size else 0.0
    if t_end <= 0.0:
        return np.ones_like(t_out)
    # from 1e-6 of the last time, or a hundredth of the first positive time if earlier
    t_pos = t_out[t_out > 0.0]
    lo = min(-6.0, float(np.log10(t_pos.min() / t_end)) - 2.0)
    n = max(int(-lo * steps_per_decade), 8)
    grid = np.concatenate([[0.0], t_end * np.logspace(lo, 0, n)])
    g = np.empty_like(grid)
    g[0] = 1.0
    # strain (times E) held at 1: 1 = g(t) + phi(t) g(0) + sum_j dg_j mean phi over step j
    dg: list[float] = []
    for k in range(1, grid.size):
        tk = grid[k]
        a, b = grid[:k], grid[1 : k + 1]
        m = step_mean_phi(law, tk, a, b)
        known = float(law.phi(tk)) + float(np.dot(dg, m[:-1]))
        # g_k = 1 + sum_j dg_j, so 1 = 1 + sum_{j<k} dg_j + dg_k + known + dg_k M_kk
        dk = -(float(np.sum(dg)) + known) / (1.0 + float(m[-1]))
        dg.append(dk)
        g[k] = g[k - 1] + dk
    return np.interp(t_out, grid, g)
