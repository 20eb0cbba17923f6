"""Hardness-tester models: the striker, the roll side, the 1.5D impact models, the readouts.

* :mod:`~woundroll.instruments.definitions` -- instrument presets as data (TOML with units):
  :func:`get_instrument`, :func:`list_instruments`, :class:`Instrument`.
* :mod:`~woundroll.instruments.roll_side` -- the roll spring {3} with an unloading branch,
  the tapered-column active mass {14}-{18}.
* :mod:`~woundroll.instruments.impact` -- finite differences {4}-{13} (:func:`impact_fd`) and
  energy conservation {19}-{22} (:func:`impact_energy`, vectorised :func:`rho_energy`).
* :mod:`~woundroll.instruments.readout` -- Rho, g, Schmidt R, Parotester L.
* :mod:`~woundroll.instruments.calibration` -- Hertz line contact on the calibration block and
  :func:`calibrate_head`.
* :mod:`~woundroll.instruments.case_section` -- the case file's ``[tester]`` table.
"""

from woundroll.instruments.calibration import (
    CalibrationBlock,
    HeadCalibration,
    HertzLineContact,
    calibrate_head,
    fit_quadratic,
)
from woundroll.instruments.case_section import (
    HardnessResult,
    TesterSetup,
    hardness_from_spring,
    tester_from_spec,
)
from woundroll.instruments.definitions import (
    Instrument,
    get_instrument,
    list_instruments,
    load_instrument_file,
)
from woundroll.instruments.impact import (
    COLLISIONS,
    EnergyResult,
    ImpactResult,
    energy_max_depth,
    impact_energy,
    impact_fd,
    rho_energy,
)
from woundroll.instruments.roll_side import (
    ForceLaw,
    QuadraticLaw,
    RollSpring,
    TabulatedLaw,
    as_roll_spring,
    roll_effective_mass,
    tapered_column_factor,
)

__all__ = [
    "COLLISIONS",
    "CalibrationBlock",
    "HardnessResult",
    "HeadCalibration",
    "HertzLineContact",
    "TesterSetup",
    "calibrate_head",
    "fit_quadratic",
    "hardness_from_spring",
    "tester_from_spec",
    "EnergyResult",
    "ForceLaw",
    "ImpactResult",
    "Instrument",
    "QuadraticLaw",
    "RollSpring",
    "TabulatedLaw",
    "as_roll_spring",
    "energy_max_depth",
    "get_instrument",
    "impact_energy",
    "impact_fd",
    "list_instruments",
    "load_instrument_file",
    "rho_energy",
    "roll_effective_mass",
    "tapered_column_factor",
]
