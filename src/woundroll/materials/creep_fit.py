"""Fitting a creep law (:mod:`woundroll.materials.creep`) to a stack creep test.

Two kinds of test, told apart by the CSV's columns:

* **creep** (``time``, ``strain``; the pressure held constant): ``eps(t) = eps_0 (1 + phi(t))``
  with the instantaneous strain ``eps_0`` fitted too (the first sample is rarely at t = 0+).
  Power law: least squares on the relative error in (ln eps_0, ln tau, n) (bounded,
  trust-region reflective). Prony: retardation times fixed one per decade over the data's
  time span, ``eps_0`` and ``eps_0 c_i >= 0`` by non-negative least squares (linear in them).
* **relaxation** (``time``, ``pressure``; the strain held constant): ``P(t) = P_0 g(t)``,
  ``g`` the relaxation function of the law (:func:`woundroll.materials.creep.relaxation`,
  the Volterra equation solved numerically); both laws by bounded least squares on the
  relative error (Prony: the same fixed retardation times).

The pressure level does not enter: the law is the shape of the creep, its size scales with
the tangent compliance (the separable assumption of :mod:`woundroll.materials.creep`).
Quality reported: RMS and maximum relative error.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import least_squares, nnls

from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.creep import CreepLaw, PowerCreep, PronyCreep, relaxation


@dataclass(frozen=True)
class CreepFit:
    """A fitted creep law and how well it fits."""

    law: CreepLaw
    test: str  # "creep" or "relaxation"
    initial: float  # eps_0 [-] (creep) or P_0 [Pa] (relaxation)
    rms_rel_error: float
    max_rel_error: float
    n_points: int

    def to_dict(self) -> dict[str, Any]:
        return {
            "radial_creep": self.law.to_dict(),
            "test": self.test,
            ("strain_initial" if self.test == "creep" else "pressure_initial_Pa"): self.initial,
            "rms_rel_error": self.rms_rel_error,
            "max_rel_error": self.max_rel_error,
            "n_points": self.n_points,
        }

    def case_lines(self) -> str:
        """The case-file lines (``[storage]``) of the fit."""
        return f'[storage]\ntime = "30 d"  # the storage time\nradial_creep = {self.law.toml()}'


def _check(t: ArrayLike, y: ArrayLike, name: str) -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.ndim != 1 or t.shape != y.shape or t.size < 4:
        raise InputError(f"needs at least 4 points of time and {name}", "creep")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        raise InputError("time and values must be finite numbers", "creep")
    if np.any(t <= 0) or np.any(np.diff(t) <= 0):
        raise InputError("times must be positive and increasing (t = 0: the load's start)", "creep")
    if np.any(y <= 0):
        raise InputError(f"the {name} must be positive (compression positive)", "creep")
    return t, y


def _prony_times(t: np.ndarray) -> np.ndarray:
    lo, hi = np.floor(np.log10(t[0])), np.ceil(np.log10(t[-1]))
    return 10.0 ** np.arange(lo, hi + 1.0)


def _quality(model: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    rel = np.abs(model - y) / y
    return float(np.sqrt(np.mean(rel**2))), float(rel.max())


def fit_creep(time: ArrayLike, strain: ArrayLike, law: str = "power") -> CreepFit:
    """Fit ``law`` ("power" or "prony") to a creep test: strain against time [s] at a
    constant pressure."""
    t, e = _check(time, strain, "strain")
    if not e[-1] > e[0]:
        raise InputError("the strain does not grow with time: not a creep test", "creep")
    if law == "power":

        def model(x: np.ndarray) -> np.ndarray:
            e0, tau, n = np.exp(x[0]), np.exp(x[1]), x[2]
            return e0 * (1.0 + (t / tau) ** n)

        x0 = np.array([np.log(e[0]), np.log(t[-1]), 0.3])
        sol = least_squares(
            lambda x: model(x) / e - 1.0,
            x0,
            bounds=([-np.inf, -np.inf, 1e-3], [np.inf, np.inf, 0.999]),
        )
        if not sol.success:
            raise ConvergenceError(f"power creep fit did not converge: {sol.message}")
        fitted: CreepLaw = PowerCreep(float(sol.x[2]), float(np.exp(sol.x[1])))
        e0 = float(np.exp(sol.x[0]))
    elif law == "prony":
        taus = _prony_times(t)
        A = np.column_stack([np.ones_like(t), *(-np.expm1(-t / tau) for tau in taus)]) / e[:, None]
        coef, _ = nnls(A, np.ones_like(t))
        if not coef[0] > 0:
            raise ConvergenceError("Prony creep fit gave no instantaneous strain")
        e0 = float(coef[0])
        keep = coef[1:] > 0
        if not np.any(keep):
            keep[-1] = True
        fitted = PronyCreep(
            tuple(float(c / e0) for c in coef[1:][keep]), tuple(float(v) for v in taus[keep])
        )
    else:
        raise InputError(f"cannot fit law {law!r}; choose power or prony", "law")
    rms, mx = _quality(e0 * (1.0 + fitted.phi(t)), e)
    return CreepFit(fitted, "creep", e0, rms, mx, int(t.size))


def fit_relaxation(time: ArrayLike, pressure: ArrayLike, law: str = "power") -> CreepFit:
    """Fit ``law`` to a relaxation test: pressure [Pa] against time [s] at a constant strain."""
    t, p = _check(time, pressure, "pressure")
    if not p[-1] < p[0]:
        raise InputError("the pressure does not fall with time: not a relaxation test", "creep")
    if law == "power":

        def build(x: np.ndarray) -> CreepLaw:
            return PowerCreep(float(x[2]), float(np.exp(x[1])))

        x0 = np.array([np.log(p[0]), np.log(t[-1]), 0.3])
        lower, upper = [-np.inf, -np.inf, 1e-3], [np.inf, np.inf, 0.999]
    elif law == "prony":
        taus = _prony_times(t)

        def build(x: np.ndarray) -> CreepLaw:
            return PronyCreep(tuple(float(v) for v in x[1:]), tuple(float(v) for v in taus))

        x0 = np.concatenate([[np.log(p[0])], np.full(taus.size, 0.05)])
        lower, upper = [-np.inf, *([0.0] * taus.size)], [np.inf, *([np.inf] * taus.size)]
    else:
        raise InputError(f"cannot fit law {law!r}; choose power or prony", "law")

    def resid(x: np.ndarray) -> np.ndarray:
        return np.exp(x[0]) * relaxation(build(x), t) / p - 1.0

    sol = least_squares(resid, x0, bounds=(lower, upper))
    if not sol.success:
        raise ConvergenceError(f"{law} relaxation fit did not converge: {sol.message}")
    fitted = build(sol.x)
    if isinstance(fitted, PronyCreep):
        keep = [i for i, c in enumerate(fitted.c) if c > 1e-9] or [int(np.argmax(fitted.c))]
        fitted = PronyCreep(tuple(fitted.c[i] for i in keep), tuple(fitted.tau[i] for i in keep))
    p0 = float(np.exp(sol.x[0]))
    rms, mx = _quality(p0 * relaxation(fitted, t), p)
    return CreepFit(fitted, "relaxation", p0, rms, mx, int(t.size))
