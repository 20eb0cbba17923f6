"""woundroll: wound-roll stresses from winder settings, and the hardness readings they cause.

The pipeline reads like the physics:

winder settings (:mod:`woundroll.case`)
-> stresses in the roll (:mod:`woundroll.winding`)
-> roll stiffness under the striker (:mod:`woundroll.contact`)
-> striker motion (:mod:`woundroll.instruments`)
-> instrument reading (:mod:`woundroll.instruments.readout`).
"""

from woundroll.errors import ConvergenceError, InputError, WoundrollError

__version__ = "0.1.0"

__all__ = ["ConvergenceError", "InputError", "WoundrollError", "__version__"]
