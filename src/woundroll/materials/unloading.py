"""Unloading of the roll's radial response: stack tests unload stiffer than they load.

A stack test loaded to ``(eps_max, P_max)`` and unloaded does not come back along its
loading curve: the unloading branch is steeper and ends at a residual strain; the area
between the branches is the energy the stack does not give back. The paper's roll is
elastic (E_r from Pfeiffer's law {2} on loading and unloading alike), so its models cannot
predict rebound testers (Schmidt R, Parotester L), which read exactly that loss.

Law (choice): the unloading branch is Pfeiffer-shaped with its own constants, started at the
turning point::

    E_r,u = K2u (P + K1u)                                  (tangent, as {2})
    P_u(eps) = (P_max + K1u) exp(K2u (eps - eps_max)) - K1u

(``P = -sigma_r`` the pressure, eps the compressive strain). It reaches P = 0 at the
residual strain ``eps_res = eps_max - ln(1 + P_max / K1u) / K2u``. ``K2u > K2`` makes
unloading stiffer than loading at high pressure. Reloading below the largest pressure an
element has seen follows the same branch (no new loss until the old maximum is passed), the
simplest memory rule (Masing-type) that a single loading/unloading cycle can calibrate.

Fit (:func:`fit_stack_cycle`): the CSV of one stack cycle (strain rising, then falling) is
split at the largest strain; the loading branch is fitted by
:func:`woundroll.materials.stack_fit.fit_stack` (Pfeiffer), the unloading branch by least
squares on the relative pressure error of ``P_u`` through the measured turning point
(log K1u, log K2u; Levenberg-Marquardt).

The energy ratio of a stack cycle to the pressure P, :meth:`PfeifferUnloading.energy_ratio`
= (energy given back) / (energy stored) = e^2, is what the 1.5D FD model's roll spring uses as
its coefficient of restitution (:class:`woundroll.instruments.RollSpring`), taken at the
peak pressure under the head (an assumption: the stack under the head as one uniform stack).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import ConvergenceError, InputError

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class PfeifferUnloading:
    """Unloading branch ``E_r,u = K2u (P + K1u)`` (module docstring).

    Attributes
    ----------
    K1 : float [Pa]
        K1u > 0.
    K2 : float [-]
        K2u > 0.
    """

    K1: float
    K2: float

    def __post_init__(self) -> None:
        for name in ("K1", "K2"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise InputError(f"must be a positive number, got {v!r}", f"unloading.{name}")

    def modulus_at_pressure(self, pressure: ArrayLike) -> FloatArray:
        """Unloading tangent modulus [Pa] at pressure P [Pa] (P < 0 taken as 0)."""
        p = np.maximum(np.asarray(pressure, dtype=float), 0.0)
        return self.K2 * (p + self.K1)

    def pressure(self, strain: ArrayLike, strain_max: float, pressure_max: float) -> FloatArray:
        """Unloading branch ``P_u(eps)`` [Pa] from the turning point (negative below eps_res)."""
        eps = np.asarray(strain, dtype=float)
        return (pressure_max + self.K1) * np.exp(self.K2 * (eps - strain_max)) - self.K1

    def residual_strain(self, strain_max: float, pressure_max: float) -> float:
        """Strain where the unloading branch reaches zero pressure [-]."""
        return strain_max - math.log1p(pressure_max / self.K1) / self.K2

    def energy_ratio(self, loading: Any, pressure_max: float) -> float:
        """e^2: energy given back / energy stored in a stack cycle to ``pressure_max`` [Pa].

        ``loading`` is the loading law (a :class:`~woundroll.materials.radial_modulus
        .RadialModulusLaw` with ``pressure(strain)``); the loading energy is its integral from
        zero to the strain at ``pressure_max`` (found by bisection on the monotone curve).
        """
        if not (math.isfinite(pressure_max) and pressure_max > 0):
            return 1.0
        hi = 1e-6
        with np.errstate(over="ignore", invalid="ignore"):
            while float(loading.pressure(hi)) < pressure_max and hi < 10.0:
                hi *= 2.0
            if not float(loading.pressure(hi)) >= pressure_max:
                # the loading law never reaches the pressure (Pfeiffer with K1 = 0 carries
                # none from zero strain): no stack cycle to compare, elastic
                return 1.0
        lo = 0.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if float(loading.pressure(mid)) < pressure_max:
                lo = mid
            else:
                hi = mid
        eps_max = 0.5 * (lo + hi)
        e = np.linspace(0.0, eps_max, 2001)
        p = np.asarray(loading.pressure(e), dtype=float)
        w_load = float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(e)))
        eps_res = max(self.residual_strain(eps_max, pressure_max), 0.0)
        # exact integral of the exponential branch from eps_res to eps_max
        a = pressure_max + self.K1
        w_un = a / self.K2 * (1.0 - math.exp(self.K2 * (eps_res - eps_max))) - self.K1 * (
            eps_max - eps_res
        )
        return float(min(max(w_un / w_load, 0.0), 1.0)) if w_load > 0 else 1.0

    def to_dict(self) -> dict[str, Any]:
        return {"law": "pfeiffer", "K1_Pa": self.K1, "K2": self.K2}

    def toml(self) -> str:
        """The case-file table: ``[web] radial_unloading = {...}``."""
        return f'{{ law = "pfeiffer", K1 = "{self.K1:.6g} Pa", K2 = {self.K2:.6g} }}'


def unloading_from_spec(spec: Any, field: str = "web.radial_unloading") -> PfeifferUnloading:
    """The case file's ``radial_unloading = { law = "pfeiffer", K1 = "1 kPa", K2 = 300 }``."""
    from woundroll.units import to_si

    if isinstance(spec, PfeifferUnloading):
        return spec
    if not isinstance(spec, dict):
        raise InputError(
            'must be a table such as { law = "pfeiffer", K1 = "1 kPa", K2 = 300 }', field
        )
    spec = dict(spec)
    law = spec.pop("law", "pfeiffer")
    if law != "pfeiffer":
        raise InputError(f"unknown unloading law {law!r}; known: pfeiffer", f"{field}.law")
    for key in spec:
        if key not in ("K1", "K2"):
            raise InputError("unknown key (known: law, K1, K2)", f"{field}.{key}")
    for key in ("K1", "K2"):
        if key not in spec:
            raise InputError("missing", f"{field}.{key}")
    try:
        return PfeifferUnloading(
            to_si(spec["K1"], "pressure", f"{field}.K1"),
            to_si(spec["K2"], "dimensionless", f"{field}.K2"),
        )
    except InputError as exc:
        raise InputError(exc.message, f"{field}.{(exc.field or '').split('.')[-1]}") from None


@dataclass(frozen=True)
class CycleFit:
    """A stack cycle fitted: loading law, unloading branch and their quality.

    Attributes
    ----------
    loading : StackFit
        Pfeiffer fit of the loading branch.
    unloading : PfeifferUnloading
    strain_max, pressure_max : float
        The turning point [-], [Pa].
    unloading_rms_rel_error : float
        RMS relative pressure error of the unloading fit over its points with P > 0.
    energy_ratio : float
        e^2 of the measured cycle (trapezoids on the data: unloading area / loading area).
    n_loading, n_unloading : int
    """

    loading: Any
    unloading: PfeifferUnloading
    strain_max: float
    pressure_max: float
    unloading_rms_rel_error: float
    energy_ratio: float
    n_loading: int
    n_unloading: int

    def to_dict(self) -> dict[str, Any]:
        return {
            "loading": self.loading.to_dict(),
            "unloading": {
                **self.unloading.to_dict(),
                "rms_rel_error": self.unloading_rms_rel_error,
                "n_points": self.n_unloading,
            },
            "strain_max": self.strain_max,
            "pressure_max_Pa": self.pressure_max,
            "energy_ratio_measured": self.energy_ratio,
            "restitution_measured": math.sqrt(self.energy_ratio),
        }


def split_cycle(strain: ArrayLike, pressure: ArrayLike) -> tuple[FloatArray, ...]:
    """Split one stack cycle at its largest strain: ``(eps_load, p_load, eps_un, p_un)``
    (the turning point belongs to both branches)."""
    e = np.asarray(strain, dtype=float).ravel()
    p = np.asarray(pressure, dtype=float).ravel()
    if e.shape != p.shape or e.size < 6:
        raise InputError("need strain and pressure columns of >= 6 points", "stack")
    if not (np.all(np.isfinite(e)) and np.all(np.isfinite(p))):
        raise InputError("strain and pressure must be finite", "stack")
    k = int(np.argmax(e))
    if k < 2 or e.size - 1 - k < 2:
        raise InputError(
            "no unloading branch: the strain must rise to its largest value and fall again "
            "(at least 3 points on each branch)",
            "stack",
        )
    return e[: k + 1], p[: k + 1], e[k:], p[k:]


def fit_stack_cycle(strain: ArrayLike, pressure: ArrayLike) -> CycleFit:
    """Fit a stack cycle (module docstring): Pfeiffer loading, Pfeiffer-shaped unloading."""
    from scipy.optimize import least_squares

    from woundroll.materials.stack_fit import fit_stack

    e_l, p_l, e_u, p_u = split_cycle(strain, pressure)
    loading = fit_stack(e_l, p_l, "pfeiffer")
    eps_max, p_max = float(e_u[0]), float(p_u[0])
    if p_max <= 0:
        raise InputError("the turning point carries no pressure", "stack")
    keep = p_u[1:] > 0
    eu, pu = e_u[1:][keep], p_u[1:][keep]
    if eu.size < 2:
        raise InputError("the unloading branch needs >= 2 points with pressure > 0", "stack")
    # start: K2u from the log slope near the top, K1u small against P_max
    k2_0 = max(
        float(np.polyfit(eu - eps_max, np.log(pu), 1)[0]) if eu.size >= 2 else 10.0,
        1.0,
    )
    k1_0 = 1e-3 * p_max

    def resid(x: FloatArray) -> FloatArray:
        k1, k2 = np.exp(x)
        model = (p_max + k1) * np.exp(k2 * (eu - eps_max)) - k1
        return (model - pu) / pu

    sol = least_squares(resid, np.log([k1_0, k2_0]), method="lm", x_scale="jac")
    if not sol.success or not np.all(np.isfinite(sol.x)):
        raise ConvergenceError(f"unloading fit did not converge: {sol.message}")
    k1u, k2u = (float(v) for v in np.exp(sol.x))
    un = PfeifferUnloading(k1u, k2u)
    rms = float(np.sqrt(np.mean(resid(sol.x) ** 2)))
    w_l = float(np.sum(0.5 * (p_l[1:] + p_l[:-1]) * np.diff(e_l)))
    w_u = float(np.sum(0.5 * (p_u[1:] + p_u[:-1]) * -np.diff(e_u)))
    # close the unloading area to zero pressure along the fitted branch
    last_e, last_p = float(e_u[-1]), float(p_u[-1])
    if last_p > 0:
        eps_res = un.residual_strain(eps_max, p_max)
        w_u += 0.5 * last_p * max(last_e - eps_res, 0.0)
    ratio = min(max(w_u / w_l, 0.0), 1.0) if w_l > 0 else 1.0
    return CycleFit(
        loading=loading,
        unloading=un,
        strain_max=eps_max,
        pressure_max=p_max,
        unloading_rms_rel_error=rms,
        energy_ratio=ratio,
        n_loading=int(e_l.size),
        n_unloading=int(e_u.size),
    )


def restitution_at_pressure(web: Any, pressure: float) -> float:
    """Energetic coefficient of restitution e of the web's stack cycle to ``pressure`` [Pa]:
    ``sqrt(energy_ratio)`` of :meth:`PfeifferUnloading.energy_ratio` with the web's loading
    law; 1 without an unloading law (elastic). What the 1.5D FD model's roll spring uses
    (the stack under the head taken as one uniform stack at its peak pressure)."""
    un = getattr(web, "radial_unloading", None)
    if un is None:
        return 1.0
    return math.sqrt(max(un.energy_ratio(web.radial_modulus, pressure), 1e-12))
