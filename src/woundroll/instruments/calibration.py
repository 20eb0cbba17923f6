"""The calibration block and the head calibration.

The Rho-meter's head geometry is not published; the one documented check is that the rubber
calibration block delivered with the device reads 77 Rho (reference paper, Table 1 and
"Striker Side"). woundroll therefore *calibrates* the head radius: for a stated head length,
find the radius R for which the impact model on the block reads the target.

Contact model of the head on the block (:class:`HertzLineContact`)
    A rigid cylinder (radius R, length L, axis along the CMD) pressed on an elastic body with
    plane-strain modulus ``E* = E/(1 - nu^2)``, load per unit length ``P = F/L``. Hertz line
    contact: half-width ``a = sqrt(4 P R/(pi E*))``, pressure ``p0 sqrt(1 - x^2/a^2)``,
    ``p0 = 2P/(pi a)``. In 2D the approach of a half-space is only defined relative to a
    reference point at some depth; woundroll takes the point on the load axis at depth ``h``
    = the block thickness (the block rests on a rigid table) and integrates the plane-strain
    strain along the axis, using the half-space stresses under the Hertz pressure
    (``sigma_z = -p0 a/sqrt(a^2+z^2)``,
    ``sigma_x = -p0 ((a^2 + 2 z^2)/sqrt(a^2+z^2) - 2z)/a``):

        d(P) = 2P/(pi E) [ (1 - nu^2) asinh(h/a) - nu (1 + nu) (h sqrt(a^2+h^2) - h^2)/a^2 ]

    which tends to ``2P(1-nu^2)/(pi E) (ln(2h/a) - nu/(2(1-nu)))`` for ``a << h``. Assumptions
    (stated where they are made): rigid head, frictionless contact, the block as a half-space
    down to depth h (its finite width and the table's reaction on the stress field ignored),
    quasi-static contact law during the impact, block inertia neglected (``effective_mass``
    can add it). The curve F(d) is tabulated (:class:`~woundroll.instruments.TabulatedLaw`)
    and used exactly in both the FD and the energy model; :func:`fit_quadratic` gives the
    ``alpha d^2 + beta d`` {3} fit over the impact's depth range for reference.

Calibration (:func:`calibrate_head`)
    Brent's method on ``log R``; the reading is the FD model's (the accelerometer's: spring
    plus contact force) by default, the model the paper's 76.1 Rho (3D, rigid striker) compares
    with the device. The roll-side model is pluggable: ``contact(instrument) -> roll source``
    may return a :class:`~woundroll.instruments.RollSpring`, a force law, ``(alpha, beta)`` or a
    callable ``F(d)`` -- the 2D contact model of :mod:`woundroll.contact` can replace Hertz.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import ConvergenceError, InputError
from woundroll.instruments.definitions import Instrument, preset_table
from woundroll.instruments.impact import impact_energy, impact_fd
from woundroll.instruments.roll_side import RollSpring, TabulatedLaw, as_roll_spring
from woundroll.units import to_si

__all__ = [
    "CalibrationBlock",
    "HeadCalibration",
    "HertzLineContact",
    "calibrate_head",
    "fit_quadratic",
]


@dataclass(frozen=True)
class CalibrationBlock:
    """An elastic calibration block (SI).

    Attributes
    ----------
    youngs_modulus : float [Pa]
    poisson_ratio : float [-]
    density : float [kg/m^3]
    thickness : float [m]
        Reference depth of the Hertz approach (block on a rigid table).
    target_rho : float [Rho]
        The reading the device must show on it.
    width : float or None [m]
        Extent along the head's axis (the 3D model of the block,
        :mod:`woundroll.contact.block`); None: not given.
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float
    thickness: float
    target_rho: float = 77.0
    width: float | None = None

    def __post_init__(self) -> None:
        if self.width is not None and not (math.isfinite(self.width) and self.width > 0):
            raise InputError(f"must be a positive length, got {self.width!r}", "block.width")
        for name in ("youngs_modulus", "density", "thickness", "target_rho"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise InputError(f"must be a positive number, got {v!r}", f"block.{name}")
        nu = self.poisson_ratio
        if not (isinstance(nu, int | float) and math.isfinite(nu) and -1.0 < nu < 0.5):
            raise InputError(f"must lie in (-1, 0.5), got {nu!r}", "block.poisson_ratio")

    @property
    def plane_strain_modulus(self) -> float:
        """``E* = E/(1 - nu^2)`` [Pa]."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)

    @classmethod
    def from_preset(cls, instrument: str = "rho-meter") -> CalibrationBlock:
        """The block of a preset's ``[calibration_block]`` table (Rho-meter: Table 1)."""
        t = preset_table(instrument, "calibration_block")
        if t is None:
            raise InputError(f"preset {instrument!r} has no calibration block", "block")
        return cls(
            youngs_modulus=to_si(t["youngs_modulus"], "pressure", "block.youngs_modulus"),
            poisson_ratio=to_si(t["poisson_ratio"], "dimensionless", "block.poisson_ratio"),
            density=to_si(t["density"], "density", "block.density"),
            thickness=to_si(t["thickness"], "length", "block.thickness"),
            target_rho=float(t.get("target_rho", 77.0)),
            width=to_si(t["width"], "length", "block.width") if "width" in t else None,
        )


@dataclass(frozen=True)
class HertzLineContact:
    """Rigid cylinder (radius R, length L) on an elastic block: Hertz line contact (module doc).

    Parameters
    ----------
    radius : float [m]
    length : float [m]
        Along the cylinder axis (the CMD).
    block : CalibrationBlock
    """

    radius: float
    length: float
    block: CalibrationBlock

    def __post_init__(self) -> None:
        for name in ("radius", "length"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                raise InputError(f"must be a positive number, got {v!r}", f"tester.head_{name}")

    def half_width(self, force: ArrayLike) -> NDArray[np.float64]:
        """Hertz half-width ``a = sqrt(4 P R/(pi E*))`` [m], ``P = F/L``."""
        P = np.asarray(force, dtype=float) / self.length
        return np.sqrt(4.0 * P * self.radius / (math.pi * self.block.plane_strain_modulus))

    def approach(self, force: ArrayLike) -> NDArray[np.float64]:
        """Approach d [m] of the head relative to the block's bottom face at force F [N]."""
        F = np.asarray(force, dtype=float)
        E, nu, h = self.block.youngs_modulus, self.block.poisson_ratio, self.block.thickness
        P = F / self.length
        a = self.half_width(F)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = h / a
            g = (np.sqrt(1.0 + ratio**2) - ratio) * ratio  # (h sqrt(a^2+h^2) - h^2)/a^2
            d = 2.0 * P / (math.pi * E) * ((1.0 - nu**2) * np.arcsinh(ratio) - nu * (1.0 + nu) * g)
        return np.where(F > 0, d, 0.0)

    def law(self, energy: float, n: int = 4001) -> TabulatedLaw:
        """Tabulated F(d) reaching at least twice the stored ``energy`` [J].

        Raises
        ------
        InputError
            The approach stops growing with the force (contact too wide for the block:
            the half-space reference depth is no longer large against the contact width).
        """
        F_hi = 100.0
        for _ in range(60):
            F = F_hi * np.linspace(0.0, 1.0, n) ** 2
            d = self.approach(F)
            if np.any(np.diff(d) <= 0):
                raise InputError(
                    f"head radius {self.radius:g} m: the Hertz approach stops growing before the "
                    f"roll spring stores {energy:g} J (contact half-width "
                    f"{float(self.half_width(F_hi)):.3g} m vs block thickness "
                    f"{self.block.thickness:g} m)",
                    "tester.head_radius",
                )
            W = float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(d)))
            if W >= 2.0 * energy:
                return TabulatedLaw(d, F, "block")
            F_hi *= 2.0
        raise ConvergenceError("Hertz table: could not reach the required energy")


def fit_quadratic(law: Any, max_depth: float, n: int = 201) -> tuple[float, float]:
    """Least-squares ``F ~ alpha d^2 + beta d`` {3} over ``[0, max_depth]`` [m].

    Returns
    -------
    (alpha [N/m^2], beta [N/m])
    """
    d = np.linspace(0.0, max_depth, n)
    F = np.asarray(law.force(d), dtype=float)
    X = np.column_stack([d * d, d])
    coef, *_ = np.linalg.lstsq(X, F, rcond=None)
    return float(coef[0]), float(coef[1])


@dataclass(frozen=True)
class HeadCalibration:
    """Result of :func:`calibrate_head`.

    Attributes
    ----------
    instrument : Instrument
        The instrument with the calibrated head radius.
    head_radius : float [m]
    rho_fd, rho_energy : float [Rho]
        Readings on the block with the calibrated head (FD: accelerometer; energy: {22}).
    max_depth : float [m]
        FD maximum depth on the block.
    peak_force : float [N]
    half_width : float [m]
        Hertz half-width at the peak force (Hertz model only, else nan).
    alpha, beta : float [N/m^2], [N/m]
        Quadratic fit {3} of the block's F(d) over [0, max_depth].
    rho_fd_fit : float [Rho]
        FD reading with that quadratic fit instead of the exact curve.
    model : str
        Which reading was matched ("fd" or "energy").
    """

    instrument: Instrument
    head_radius: float
    rho_fd: float
    rho_energy: float
    max_depth: float
    peak_force: float
    half_width: float
    alpha: float
    beta: float
    rho_fd_fit: float
    model: str


def calibrate_head(
    instrument: Instrument,
    block: CalibrationBlock | None = None,
    target_rho: float | None = None,
    *,
    contact: Callable[[Instrument], object] | None = None,
    model: str = "fd",
    collision: str = "plastic",
    effective_mass: float = 0.0,
    radius_bracket: tuple[float, float] = (1e-4, 0.2),
    rtol: float = 1e-10,
) -> HeadCalibration:
    """Find the head radius for which ``instrument`` reads ``target_rho`` on ``block``.

    Parameters
    ----------
    instrument : Instrument
        Its ``head_length`` is kept (stated, not calibrated).
    block : CalibrationBlock, optional
        Default: the preset's block (Rho-meter: Table 1).
    target_rho : float, optional [Rho]
        Default: the block's ``target_rho`` (77).
    contact : callable, optional
        ``contact(instrument) -> roll source`` (RollSpring, force law, (alpha, beta) or F(d));
        default: :class:`HertzLineContact` of the instrument's head on the block.
    model : {"fd", "energy"}
        Which reading to match; default the FD (accelerometer) reading.
    collision : str
        Collision model of the FD run (irrelevant when the block's active mass is 0).
    effective_mass : float [kg]
        Active mass of the block (default 0: block inertia neglected).
    radius_bracket : (float, float) [m]
        Search interval for R.

    Raises
    ------
    ConvergenceError
        The target is not reachable within ``radius_bracket``.
    """
    if model not in ("fd", "energy"):
        raise InputError(f"must be 'fd' or 'energy', got {model!r}", "calibration.model")
    if block is None:
        block = CalibrationBlock.from_preset(instrument.name)
    target = block.target_rho if target_rho is None else float(target_rho)
    if not (math.isfinite(target) and target > 0):
        raise InputError(f"must be positive, got {target_rho!r}", "calibration.target_rho")
    if instrument.head_length is None:
        raise InputError("the head calibration needs a head length", "tester.head_length")

    def source(inst: Instrument) -> RollSpring:
        if contact is None:
            law = HertzLineContact(inst.head_radius, inst.head_length, block).law(
                inst.impact_energy + 0.5 * inst.spring_stiffness * inst.contact_position**2
            )
            return RollSpring(law, effective_mass)
        return as_roll_spring(contact(inst), effective_mass)

    def reading(radius: float) -> float:
        inst = instrument.with_overrides(head_radius=radius)
        spring = source(inst)
        if model == "fd":
            return impact_fd(inst, spring, collision=collision).rho
        return impact_energy(inst, spring).rho

    lo, hi = radius_bracket
    r_lo, r_hi = reading(lo) - target, reading(hi) - target
    if r_lo * r_hi > 0:
        raise ConvergenceError(
            f"calibrate_head: {target:g} Rho is not reached for head radii {lo:g}..{hi:g} m "
            f"(readings {r_lo + target:.4g}..{r_hi + target:.4g} Rho)"
        )
    from scipy.optimize import brentq  # here, not at import (start-up time)

    log_r = brentq(
        lambda s: reading(math.exp(s)) - target, math.log(lo), math.log(hi), xtol=1e-12, rtol=rtol
    )
    R = math.exp(log_r)
    inst = instrument.with_overrides(head_radius=R)
    return _calibrated(
        inst, R, source(inst), block, contact is None, collision, effective_mass, model
    )


def _calibrated(
    inst: Instrument,
    R: float,
    spring: RollSpring,
    block: CalibrationBlock,
    hertz: bool,
    collision: str,
    effective_mass: float,
    model: str,
) -> HeadCalibration:
    """The calibrated head's readings on the block (FD, energy, and the FD reading of the
    fitted quadratic spring); the Hertz half-width when the block is the Hertz contact."""
    fd = impact_fd(inst, spring, collision=collision)
    en = impact_energy(inst, spring)
    alpha, beta = fit_quadratic(spring.law, fd.max_depth)
    fit = impact_fd(inst, RollSpring.quadratic(alpha, beta, effective_mass), collision=collision)
    a = (
        float(HertzLineContact(R, inst.head_length, block).half_width(fd.peak_force))
        if hertz
        else math.nan
    )
    return HeadCalibration(
        instrument=inst,
        head_radius=R,
        rho_fd=fd.rho,
        rho_energy=en.rho,
        max_depth=fd.max_depth,
        peak_force=fd.peak_force,
        half_width=a,
        alpha=alpha,
        beta=beta,
        rho_fd_fit=fit.rho,
        model=model,
    )
