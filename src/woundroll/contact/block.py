"""The calibration block read through a roll model, and the head calibrated in that model.

The one documented check of the Rho-meter's head is that its rubber calibration block reads
77 Rho (device manual, quoted in the reference paper). The head radius was first found with
plane-strain Hertz contact on the block (:func:`woundroll.instruments.calibrate_head`); a roll
is read through a registered roll model (:mod:`woundroll.contact.models`). Calibrating the
head in one model and reading rolls in another mixes two models: here the block is an FE
"roll" read by the same roll model as the rolls, and :func:`calibrate_head_in_model` solves
for the head's unknown dimension so that this model reads the target on the block.

The block as a roll (:func:`block_roll`): an isotropic linear-elastic solid, every modulus
from the block's E and nu (:meth:`woundroll.materials.Web.isotropic`), ``thickness`` thick on
a rigid "table" of radius :data:`BLOCK_CORE_RADIUS` (1 m: its curvature is negligible against
the head's 6.6 mm), free of pre-stress. In 3D its extent along the head's axis is the block's
``width`` (instrument file; not published: an assumption stated there); in plane strain the
width plays no part. The reading is the FD model's {4}-{13} on the computed F(d) curve itself
(tabulated, no quadratic fit), the block's inertia neglected as in the Hertz calibration.

Assumptions (docs/instruments.md): rigid head, frictionless contact with the block, the
block's E and nu of Table 1 at the impact's strain rate, its thickness (assumed 25.4 mm) and
width (assumed 101.6 mm) where the instrument file says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from woundroll.errors import ConvergenceError, InputError

#: Radius of the rigid "table" under the block in the FE models [m].
BLOCK_CORE_RADIUS = 1.0

#: Head dimensions the calibration can solve for, with their search brackets [m].
UNKNOWNS: dict[str, tuple[float, float]] = {
    "head_radius": (1e-3, 0.05),
    "head_length": (5e-3, 0.1),
}


def block_roll(block: Any, model: str = "2d") -> tuple[Any, Any, Any, Any]:
    """The block as an FE roll for ``model``: ``(web, core, radius, sigma_r)``.

    ``block``: a :class:`~woundroll.instruments.calibration.CalibrationBlock`. In 3D its
    ``width`` is the extent along the head's axis (an InputError when the instrument file
    does not give it).
    """
    from woundroll.materials import Core, Web

    width = block.width
    if model == "3d" and width is None:
        raise InputError(
            "the 3D model needs the block's width along the head's axis: set "
            "[calibration_block] width in the instrument file",
            "calibration_block.width",
        )
    web = Web.isotropic(
        block.youngs_modulus,
        block.poisson_ratio,
        thickness=1e-4,  # sets the FE surface ring (0.1 mm): a block has no layers
        width=width if width is not None else 0.1,  # plane strain: not used
        density=block.density,
    )
    radius = np.array([BLOCK_CORE_RADIUS, BLOCK_CORE_RADIUS + block.thickness])
    return web, Core(BLOCK_CORE_RADIUS), radius, np.zeros(2)


@dataclass(frozen=True)
class BlockReading:
    """The instrument on its calibration block through a roll model.

    Attributes
    ----------
    model : str            roll model (registry name).
    reading : float        FD reading {4}-{13} on the computed F(d) [Rho].
    reading_energy : float energy model {19}-{22} on the same curve [Rho].
    max_depth : float      FD maximum depth [m].
    peak_force : float     [N].
    """

    model: str
    reading: float
    reading_energy: float
    max_depth: float
    peak_force: float


def read_block(
    instrument: Any, block: Any = None, model: str | None = None, options3d: Any = None
) -> BlockReading:
    """What ``instrument`` reads on its calibration ``block`` (default the preset's)
    through the roll ``model`` (None: the registry's default for its head)."""
    from woundroll.contact.models import resolve_model
    from woundroll.contact.spring import roll_stiffness
    from woundroll.instruments import RollSpring, TabulatedLaw, impact_energy, impact_fd
    from woundroll.instruments.calibration import CalibrationBlock

    name = resolve_model(model, instrument.head_shape, "calibration.model").name
    if block is None:
        block = CalibrationBlock.from_preset(instrument.name)
    web, core, r, s = block_roll(block, name)
    st = roll_stiffness(
        web, core, r, s, instrument, model=name, options3d=options3d, field="calibration"
    )
    curve = TabulatedLaw(st.contact.delta, st.contact.force)
    fd = impact_fd(instrument, RollSpring(curve, 0.0))
    en = impact_energy(instrument, curve)
    return BlockReading(name, float(fd.rho), float(en.rho), float(fd.max_depth), fd.peak_force)


@dataclass(frozen=True)
class ModelCalibration:
    """The head calibrated in a roll model (:func:`calibrate_head_in_model`).

    Attributes
    ----------
    instrument : Instrument     with the calibrated dimension.
    unknown : str               "head_radius" or "head_length".
    value : float [m]           the calibrated dimension.
    before : float [m]          its value in the instrument file.
    target : float [Rho]        the block's target reading.
    block : BlockReading        the block read with the calibrated head.
    block_before : BlockReading the block read with the file's head, same model.
    evaluations : int           block solves of the search.
    """

    instrument: Any
    unknown: str
    value: float
    before: float
    target: float
    block: BlockReading
    block_before: BlockReading
    evaluations: int

    @property
    def source(self) -> str:
        """The source line to store with the calibrated value in an instrument file."""
        return (
            f"calibrated: the calibration block reads {self.target:g} Rho (FD model) through "
            f"the {self.block.model!r} roll model (woundroll calibrate-head)"
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "instrument": self.instrument.name,
            "model": self.block.model,
            "unknown": self.unknown,
            f"{self.unknown}_m": self.value,
            f"{self.unknown}_before_m": self.before,
            "target_rho": self.target,
            "block_reading": self.block.reading,
            "block_reading_energy": self.block.reading_energy,
            "block_reading_before": self.block_before.reading,
            "block_impact_depth_m": self.block.max_depth,
            "evaluations": self.evaluations,
            "source": self.source,
        }


def calibrate_head_in_model(
    instrument: Any,
    *,
    model: str | None = None,
    unknown: str = "head_radius",
    block: Any = None,
    target: float | None = None,
    rtol: float = 1e-4,
    options3d: Any = None,
) -> ModelCalibration:
    """Solve for the head's ``unknown`` dimension so that the block reads ``target``
    (default the block's 77 Rho) through the roll ``model`` (None: the registry's default),
    the model that reads the rolls.

    Brent's method on the log of the dimension, within :data:`UNKNOWNS`' bracket narrowed
    around the file's value (a factor 4 each way) and widened to the full bracket when the
    target lies outside; ``rtol`` on the dimension (1e-4: 0.01 % of the radius moves a roll's
    reading by far less than the model's step error of 0.2 %).

    Raises
    ------
    InputError
        An unknown ``unknown``, a head the model cannot take, a bad target.
    ConvergenceError
        No dimension within the bracket reads the target (the message gives the range).
    """
    from scipy.optimize import brentq

    from woundroll.instruments.calibration import CalibrationBlock

    if unknown not in UNKNOWNS:
        raise InputError(
            f"must be one of {', '.join(UNKNOWNS)}, got {unknown!r}", "calibration.unknown"
        )
    if unknown == "head_length" and instrument.head_shape != "cylinder":
        raise InputError("only a cylindrical head has a length", "calibration.unknown")
    if block is None:
        block = CalibrationBlock.from_preset(instrument.name)
    goal = block.target_rho if target is None else float(target)
    if not (math.isfinite(goal) and goal > 0):
        raise InputError(f"must be a positive reading, got {target!r}", "calibration.target")
    before = float(getattr(instrument, unknown))
    count = [0]

    def reading(log_x: float) -> float:
        count[0] += 1
        inst = instrument.with_overrides(**{unknown: math.exp(log_x)})
        return read_block(inst, block, model, options3d).reading - goal

    lo, hi = math.log(before / 4.0), math.log(before * 4.0)
    f_lo, f_hi = reading(lo), reading(hi)
    if f_lo * f_hi > 0:
        wide = [math.log(v) for v in UNKNOWNS[unknown]]
        f_lo, f_hi = reading(wide[0]), reading(wide[1])
        lo, hi = wide
        if f_lo * f_hi > 0:
            raise ConvergenceError(
                f"calibrate-head: no {unknown} in {math.exp(lo) * 1e3:.3g}-"
                f"{math.exp(hi) * 1e3:.3g} mm reads {goal:g} Rho on the block "
                f"(readings {f_lo + goal:.4g}-{f_hi + goal:.4g})"
            )
    x = brentq(reading, lo, hi, xtol=rtol / 4, rtol=rtol / 4)
    value = math.exp(x)
    inst = instrument.with_overrides(**{unknown: value})
    return ModelCalibration(
        instrument=inst,
        unknown=unknown,
        value=value,
        before=before,
        target=goal,
        block=read_block(inst, block, model, options3d),
        block_before=read_block(instrument, block, model, options3d),
        evaluations=count[0],
    )


__all__ = [
    "BLOCK_CORE_RADIUS",
    "BlockReading",
    "ModelCalibration",
    "block_roll",
    "calibrate_head_in_model",
    "read_block",
]
