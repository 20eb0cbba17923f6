"""Storage time: the wound roll's stresses after its stack has crept for a time.

A roll stored for days loses pressure: the stack keeps compressing under its interlayer
pressure (radial creep) while the web's MD holds the hoop strain, so the wound-in stresses
relax. This module takes the roll after winding (and after any temperature or moisture
change, :mod:`woundroll.winding.storage`) and follows it through ``time``.

Model (assumptions named; docs/winding.md "Storage time (creep)"):

* The radial (stack) direction is linear viscoelastic in the increments with the creep
  compliance ``J(t) = (1 + phi(t)) / E_r`` (:mod:`woundroll.materials.creep`); ``E_r`` is
  the tangent modulus of the loading law at the pressure the roll has when storage begins,
  held through storage (time-pressure separable, the pressure changes by creep are a
  fraction of the pressure). The MD (E_theta), the Poisson ratio and the core are elastic.
* The roll's stresses at the start of storage act from ``t = 0`` (winding takes minutes,
  storage days: the winding history inside the roll is not followed).
* Plane stress, axisymmetric, no slip, no separation (as the winding model); the surface
  stays free.

Equations. With Boltzmann superposition the radial strain is
``eps_r(t) = [sigma_r(t) + integral_{0-}^t phi(t - t') d sigma_r(t')] / E_r - nu ...``.
The stress history is taken linear in time within each step ``[t_{j-1}, t_j]``; the
integral over each step is then exact (``step_mean_phi``). Step k's change ``s`` of the
radial stress satisfies the increment equation of :mod:`woundroll.winding.storage`
(Hakiel's equation with a free radial strain) with

    E_eff = E_r / (1 + M_kk),    eps_r* = H_k / E_r,
    H_k = (phi(t_k) - phi(t_{k-1})) sigma_0 + sum_{j<k} ds_j (M_kj - M_{k-1,j}),

``M_kj`` the mean of ``phi(t_k - t')`` over step j, ``sigma_0`` the radial stress at the start
of storage. Each step is one banded solve; the history sum costs O(K) per node and step
(K steps, default 40, graded ``t_k = T (k/K)^3`` because the power law's creep rate is
singular at t = 0). Hoop change: equilibrium, ``d(r s)/dr``.

Checks (tests/winding/test_creep.py): zero time returns the roll itself; a standard linear
solid annulus under a held outer pressure tends to the elastic annulus with the relaxed
modulus ``E_r / (1 + c)`` (closed form); the single compressed layer relaxes as the SLS's
closed form; second-order convergence in the number of time steps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.materials.creep import CreepLaw, step_mean_phi
from woundroll.materials.web import Core, Web
from woundroll.winding.result import WindingResult
from woundroll.winding.storage import hoop_increment, solve_increment

FloatArray = NDArray[np.float64]

#: Time steps of the storage time and their grading exponent (``t_k = T (k/K)^q``);
#: tests/winding/test_creep.py measures the error of these defaults (< 0.1 % of the change).
TIME_STEPS = 40
GRADING = 3.0


def time_grid(time: float, steps: int = TIME_STEPS, grading: float = GRADING) -> FloatArray:
    """``t_k = time (k / steps)^grading``, k = 0 .. steps [s]."""
    k = np.arange(steps + 1, dtype=float)
    return time * (k / steps) ** grading


@dataclass(frozen=True)
class CreepResult:
    """The roll after the storage time and its history at the surface side.

    Attributes
    ----------
    winding : WindingResult
        The roll after storage.
    time : float [s]
    law : CreepLaw
    core_pressure_before : float [Pa]
        Core pressure when storage began.
    pressure_before : ndarray [Pa]
        ``-sigma_r`` per node when storage began.
    times : ndarray [s]
        The time steps.
    core_pressure_history : ndarray [Pa]
        Core pressure at each time step.
    """

    winding: WindingResult
    time: float
    law: CreepLaw
    core_pressure_before: float
    pressure_before: FloatArray
    times: FloatArray
    core_pressure_history: FloatArray

    def to_dict(self) -> dict[str, Any]:
        return {
            "storage_time_s": self.time,
            "radial_creep": self.law.to_dict(),
            "core_pressure_before_creep_Pa": self.core_pressure_before,
            "core_pressure_after_creep_Pa": float(self.winding.core_pressure),
            "pressure_before_creep_Pa": self.pressure_before.tolist(),
            "pressure_after_creep_Pa": (-self.winding.sigma_r).tolist(),
            "creep_time_s": self.times.tolist(),
            "creep_core_pressure_Pa": self.core_pressure_history.tolist(),
        }


def apply_creep(
    winding: WindingResult,
    web: Web,
    core: Core,
    law: CreepLaw,
    time: float,
    *,
    steps: int = TIME_STEPS,
    grading: float = GRADING,
) -> CreepResult:
    """The roll ``winding`` after ``time`` [s] of radial creep under ``law`` (module
    docstring). ``time = 0`` returns the roll itself (the same arrays, bit for bit)."""
    if not (isinstance(time, int | float) and math.isfinite(time) and time >= 0.0):
        raise InputError(f"must be zero or a positive time, got {time!r}", "storage.time")
    if not (isinstance(steps, int) and steps >= 1):
        raise InputError(f"must be a positive whole number, got {steps!r}", "storage.time_steps")
    p0 = -winding.sigma_r
    cp0 = float(winding.core_pressure)
    if time == 0.0:
        return CreepResult(winding, 0.0, law, cp0, p0.copy(), np.zeros(1), np.array([cp0]))
    r = winding.radius
    E = np.asarray(winding.E_r, dtype=float)
    sigma0 = np.asarray(winding.sigma_r, dtype=float)
    t = time_grid(float(time), steps, grading)
    K = steps
    ds = np.zeros((K, r.size))  # stress change of each step
    core_hist = np.empty(K + 1)
    core_hist[0] = cp0
    m_prev = np.zeros(0)
    total = np.zeros_like(sigma0)
    for k in range(1, K + 1):
        m = step_mean_phi(law, t[k], t[:k], t[1 : k + 1])  # M_kj, j = 1..k
        H = float(law.phi(t[k]) - law.phi(t[k - 1])) * sigma0
        if k > 1:
            H = H + (m[:-1] - m_prev) @ ds[: k - 1]
        E_eff = E / (1.0 + m[-1])
        s = solve_increment(r, E_eff, web.E_theta, web.nu_theta_r, H / E, 0.0, core.stiffness, 0.0)
        ds[k - 1] = s
        total = total + s
        core_hist[k] = -(sigma0[0] + total[0])
        m_prev = m
    sigma_r = sigma0 + total
    sigma_theta = winding.sigma_theta + hoop_increment(r, total)
    # E_r as the winding reports it: the loading law's tangent at the pressure now (floored
    # as the winding's); the creep itself used the tangent at the start (module docstring)
    floor = float(np.min(E))
    E_after = np.maximum(web.radial_modulus.modulus_at_pressure(np.maximum(-sigma_r, 0.0)), floor)
    after = replace(
        winding,
        sigma_r=sigma_r,
        sigma_theta=sigma_theta,
        E_r=E_after,
        core_pressure=float(-sigma_r[0]),
    )
    return CreepResult(after, float(time), law, cp0, p0.copy(), t, core_hist)
