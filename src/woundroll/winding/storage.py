"""Temperature and moisture after winding: the change of the stresses in a wound roll.

A wound roll that cools or heats in the warehouse, or whose web takes up moisture, changes
its stresses: the web and the core expand by different amounts, and the radial (stack)
direction of a web expands differently from its MD. This module adds that change to the
wound-in state of :func:`woundroll.winding.hakiel.wind`.

Model (assumptions named):

* Free strains of the web: ``eps_r* = alpha_r dT + beta_r dM`` (through the stack) and
  ``eps_theta* = alpha_theta dT + beta_theta dM`` (MD), uniform through the roll (the whole
  roll at one temperature and moisture content: equilibrium storage, no gradients). The core
  expands freely by ``alpha_c dT`` (a core takes up no moisture).
* Plane stress in r-theta, as the winding model; the web's compliance with its Poisson
  ratio ``nu_theta_r`` (``nu_r_theta / E_r = nu_theta_r / E_theta``).
* The increment is elastic with the radial modulus at the current pressure: a Picard loop
  evaluates E_r of the loading law at the mean of the pressure before and after (the chord
  of the stack curve; for a linear law exactly E_r). Unloading hysteresis is not applied
  (a cooling roll that unloads would be stiffer: :mod:`woundroll.materials.unloading`).
* No slip between layers and no loss of contact: a layer whose radial stress turns
  tensile is reported (the stack cannot carry it) but not released.

Equations. Equilibrium ``sigma_theta = d(r sigma_r)/dr`` and compatibility
``d(r eps_theta)/dr = eps_r`` with the constitutive law give, for the increment ``s`` of
the radial stress (Hakiel's equation with a thermal load; ``nu_theta_r`` cancels)::

    r^2 s'' + 3 r s' + (1 - E_theta / E_r) s = E_theta (eps_r* - eps_theta*)

with ``s(R) = 0`` at the surface and, at the core (Hakiel's core condition
``u = r sigma_r / E_c`` plus the core's free expansion)::

    ((1 - nu_theta_r) s + r_c s') / E_theta - s / E_c = alpha_c dT - eps_theta*

Solved by second-order finite differences on the winding's nodes (a banded solve).
For a constant E_r the solution is closed form (:func:`closed_form_linear`, the thermal
stress of a cylindrically orthotropic annulus on an elastic core):
``s = A r^(g-1) + B r^(-g-1) + C``, ``g = sqrt(E_theta / E_r)``,
``C = E_theta (eps_r* - eps_theta*) / (1 - g^2)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.materials.web import Core, Web
from woundroll.winding.result import WindingResult

FloatArray = NDArray[np.float64]

#: Picard iterations on the chord modulus: tolerance on the increment (relative to its
#: largest value) and iteration limit. The chord converges in a few iterations for changes
#: that keep the roll in compression (tests/winding/test_storage.py).
RTOL = 1e-8
MAX_ITERATIONS = 50


def _number(value: Any, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(f"must be a number, got {value!r}", field)
    v = float(value)
    if not math.isfinite(v):
        raise InputError(f"must be a finite number, got {value!r}", field)
    return v


@dataclass(frozen=True)
class StorageChange:
    """A change after winding, uniform through the roll.

    Attributes
    ----------
    temperature_change : float [K]
        Roll and core temperature in storage minus at winding (cooling < 0).
    moisture_change : float [-]
        Change of the web's moisture content (mass fraction; 0.01 = one percentage point).
    """

    temperature_change: float = 0.0
    moisture_change: float = 0.0

    def __post_init__(self) -> None:
        _number(self.temperature_change, "storage.temperature_change")
        _number(self.moisture_change, "storage.moisture_change")

    @property
    def is_zero(self) -> bool:
        return self.temperature_change == 0.0 and self.moisture_change == 0.0

    def free_strains(self, web: Web) -> tuple[float, float]:
        """``(eps_r*, eps_theta*)``: the web's free strains [-] (module docstring)."""
        dT, dM = self.temperature_change, self.moisture_change
        return (
            web.alpha_r * dT + web.beta_r * dM,
            web.alpha_theta * dT + web.beta_theta * dM,
        )


def _fd_derivatives(r: FloatArray) -> tuple[FloatArray, ...]:
    """Three-point weights of s' and s'' at the interior nodes of a non-uniform mesh."""
    h0 = r[1:-1] - r[:-2]
    h1 = r[2:] - r[1:-1]
    # first derivative (second order): a s_{i-1} + b s_i + c s_{i+1}
    d1 = (-h1 / (h0 * (h0 + h1)), (h1 - h0) / (h0 * h1), h0 / (h1 * (h0 + h1)))
    d2 = (2.0 / (h0 * (h0 + h1)), -2.0 / (h0 * h1), 2.0 / (h1 * (h0 + h1)))
    return d1, d2


def solve_increment(
    radius: FloatArray,
    E_r: FloatArray,
    E_theta: float,
    nu_theta_r: float,
    eps_r: float | FloatArray,
    eps_theta: float,
    core_stiffness: float,
    core_strain: float,
) -> FloatArray:
    """The increment ``s`` [Pa] of the radial stress at the nodes (module docstring).

    Parameters
    ----------
    radius : nodes from the core to the surface [m] (strictly increasing)
    E_r : radial modulus at the nodes [Pa]
    E_theta, nu_theta_r : the web's MD modulus [Pa] and Poisson ratio [-]
    eps_r, eps_theta : the web's free strains [-] (``eps_r`` a number, or one per node: the
        equation holds pointwise, as ``eps_r*`` enters it undifferentiated)
    core_stiffness : E_c [Pa] (``inf``: rigid)
    core_strain : the core's free radial strain ``alpha_c dT`` [-]
    """
    from scipy.linalg import solve_banded

    r = np.asarray(radius, dtype=float)
    n = r.size
    if n < 3:
        raise InputError("the roll needs at least 3 nodes for a storage change", "storage")
    d1, d2 = _fd_derivatives(r)
    ri = r[1:-1]
    g2 = E_theta / np.asarray(E_r, dtype=float)[1:-1]
    # banded storage: (lower 1, upper 2); ab[u + i - j, j] = A[i, j]
    ab = np.zeros((4, n))
    rhs = np.zeros(n)
    lower = ri**2 * d2[0] + 3.0 * ri * d1[0]
    diag = ri**2 * d2[1] + 3.0 * ri * d1[1] + (1.0 - g2)
    upper = ri**2 * d2[2] + 3.0 * ri * d1[2]
    idx = np.arange(1, n - 1)
    ab[2 + 1, idx - 1] = lower  # A[i, i-1]
    ab[2, idx] = diag  # A[i, i]
    ab[1, idx + 1] = upper  # A[i, i+1]
    # a free radial strain may vary from node to node (creep, :mod:`woundroll.winding.creep`)
    rhs[1:-1] = E_theta * (np.broadcast_to(np.asarray(eps_r, dtype=float), (n,))[1:-1] - eps_theta)
    # core row: one-sided second-order s'(r0) = c0 s0 + c1 s1 + c2 s2
    h0, h1 = r[1] - r[0], r[2] - r[1]
    c0 = -(2.0 * h0 + h1) / (h0 * (h0 + h1))
    c1 = (h0 + h1) / (h0 * h1)
    c2 = -h0 / (h1 * (h0 + h1))
    inv_ec = 0.0 if math.isinf(core_stiffness) else 1.0 / core_stiffness
    r0 = r[0]
    # the row times E_theta (the scale of the interior rows)
    ab[2, 0] = 1.0 - nu_theta_r + r0 * c0 - E_theta * inv_ec
    ab[1, 1] = r0 * c1
    ab[0, 2] = r0 * c2
    rhs[0] = E_theta * (core_strain - eps_theta)
    # free surface
    ab[2, n - 1] = 1.0
    rhs[n - 1] = 0.0
    return solve_banded((1, 2), ab, rhs)


def hoop_increment(radius: FloatArray, s: FloatArray) -> FloatArray:
    """``d(r s)/dr`` [Pa] at the nodes (equilibrium), second order on the mesh."""
    r = np.asarray(radius, dtype=float)
    return np.gradient(r * s, r, edge_order=2)


def closed_form_linear(
    radius: FloatArray,
    inner_radius: float,
    outer_radius: float,
    E_r: float,
    E_theta: float,
    nu_theta_r: float,
    eps_r: float,
    eps_theta: float,
    core_stiffness: float,
    core_strain: float,
) -> FloatArray:
    """Closed-form increment ``s(r)`` [Pa] for a constant E_r (module docstring): the
    cylindrically orthotropic annulus ``inner_radius <= r <= outer_radius`` with free
    strains on an elastic core, traction-free outside. Requires ``E_theta != E_r``."""
    g = math.sqrt(E_theta / E_r)
    m1, m2 = g - 1.0, -g - 1.0
    C = E_theta * (eps_r - eps_theta) / (1.0 - g * g)
    a, b = inner_radius, outer_radius
    inv_ec = 0.0 if math.isinf(core_stiffness) else 1.0 / core_stiffness
    k = (1.0 - nu_theta_r) / E_theta - inv_ec
    # s(b) = 0;  k s(a) + a s'(a) / E_theta = core_strain - eps_theta
    M = np.array(
        [
            [b**m1, b**m2],
            [k * a**m1 + m1 * a**m1 / E_theta, k * a**m2 + m2 * a**m2 / E_theta],
        ]
    )
    rhs = np.array([-C, core_strain - eps_theta - k * C])
    A, B = np.linalg.solve(M, rhs)
    r = np.asarray(radius, dtype=float)
    return A * r**m1 + B * r**m2 + C


@dataclass(frozen=True)
class StorageResult:
    """The roll after the change and what changed.

    Attributes
    ----------
    winding : WindingResult
        The roll after the change (sigma_r, sigma_theta, E_r at the new pressure).
    change : StorageChange
    delta_sigma_r, delta_sigma_theta : ndarray [Pa]
        The increments at the nodes.
    core_pressure_before : float [Pa]
    iterations : int
        Picard iterations on the chord modulus.
    warnings : tuple of str
        Layers in radial tension, hoop stress beyond the web's strength.
    """

    winding: WindingResult
    change: StorageChange
    delta_sigma_r: FloatArray
    delta_sigma_theta: FloatArray
    core_pressure_before: float
    iterations: int
    warnings: tuple[str, ...] = ()

    @property
    def overstressed(self) -> bool:
        """True when a warning flags the roll (tension across layers or beyond strength)."""
        return bool(self.warnings)

    def to_dict(self) -> dict[str, Any]:
        w = self.winding
        return {
            "temperature_change_K": self.change.temperature_change,
            "moisture_change": self.change.moisture_change,
            "core_pressure_before_Pa": self.core_pressure_before,
            "core_pressure_Pa": float(w.core_pressure),
            "max_pressure_Pa": float(np.max(-w.sigma_r)),
            "max_sigma_theta_Pa": float(np.max(w.sigma_theta)),
            "min_sigma_theta_Pa": float(np.min(w.sigma_theta)),
            "delta_sigma_r_Pa": self.delta_sigma_r.tolist(),
            "delta_sigma_theta_Pa": self.delta_sigma_theta.tolist(),
            "iterations": self.iterations,
        }


def apply_storage(
    winding: WindingResult, web: Web, core: Core, change: StorageChange
) -> StorageResult:
    """The roll ``winding`` after ``change`` (module docstring).

    A zero change returns the wound-in state itself (the same arrays, bit for bit).
    """
    s = np.zeros_like(winding.sigma_r)
    if change.is_zero:
        return StorageResult(winding, change, s, s.copy(), float(winding.core_pressure), 0)
    eps_r, eps_theta = change.free_strains(web)
    core_strain = core.thermal_expansion * change.temperature_change
    p0 = -winding.sigma_r
    floor = float(np.min(winding.E_r))  # the winding's own floor (its smallest modulus)
    E_r = winding.E_r
    iterations, converged = 0, False
    while not converged and iterations < MAX_ITERATIONS:
        iterations += 1
        s_new = solve_increment(
            winding.radius,
            E_r,
            web.E_theta,
            web.nu_theta_r,
            eps_r,
            eps_theta,
            core.stiffness,
            core_strain,
        )
        scale = max(float(np.max(np.abs(s_new))), 1e-30)
        converged = float(np.max(np.abs(s_new - s))) <= RTOL * scale
        s = s_new
        p_mid = np.maximum(p0 - 0.5 * s, 0.0)
        E_r = np.maximum(web.radial_modulus.modulus_at_pressure(p_mid), floor)
    ds_theta = hoop_increment(winding.radius, s)
    sigma_r = winding.sigma_r + s
    sigma_r[-1] = 0.0
    sigma_theta = winding.sigma_theta + ds_theta
    E_after = np.maximum(web.radial_modulus.modulus_at_pressure(np.maximum(-sigma_r, 0.0)), floor)
    after = replace(
        winding,
        sigma_r=sigma_r,
        sigma_theta=sigma_theta,
        E_r=E_after,
        core_pressure=float(-sigma_r[0]),
    )
    return StorageResult(
        after,
        change,
        s,
        ds_theta,
        float(winding.core_pressure),
        iterations,
        _warnings(after, web, change)
        + (
            ()
            if converged
            else (
                f"storage: the chord modulus did not settle in {MAX_ITERATIONS} iterations; "
                "the stresses after the change are approximate",
            )
        ),
    )


def _warnings(after: WindingResult, web: Web, change: StorageChange) -> tuple[str, ...]:
    out = []
    what = (
        f"temperature change {change.temperature_change:g} K, "
        f"moisture change {change.moisture_change:g}"
    )
    tens = after.sigma_r[:-1] > 0.0
    if np.any(tens):
        r = after.radius[:-1][tens]
        out.append(
            f"storage: after the {what} the layers between r = {r.min() * 100:.2f} and "
            f"{r.max() * 100:.2f} cm are pulled apart (radial stress up to "
            f"{float(after.sigma_r[:-1].max()) / 1e3:.3g} kPa tensile): the stack separates "
            "there, which the model does not follow"
        )
    if web.tensile_strength is not None:
        top = float(np.max(after.sigma_theta))
        if top > web.tensile_strength:
            out.append(
                f"storage: after the {what} the hoop stress reaches {top / 1e6:.3g} MPa, "
                f"beyond web.tensile_strength {web.tensile_strength / 1e6:.3g} MPa: the web "
                "would break or yield there"
            )
    return tuple(out)
