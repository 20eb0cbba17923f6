"""woundroll: wound-roll stresses from winder settings, and the hardness readings they cause.

The pipeline reads like the physics:

winder settings (:mod:`woundroll.case`)
-> stresses in the roll (:mod:`woundroll.winding`)
-> roll stiffness under the striker (:mod:`woundroll.contact`)
-> striker motion and the instrument reading (:mod:`woundroll.instruments`)
-> across the CMD (:mod:`woundroll.profile`).

``woundroll.load_case`` reads a case; ``woundroll.run`` runs it and returns a typed
:class:`~woundroll.pipeline.RunResult`.
"""

from woundroll.case import Case, load_case
from woundroll.errors import ConvergenceError, InputError, WoundrollError
from woundroll.pipeline import RunResult, run

__version__ = "0.1.0"

__all__ = [
    "Case",
    "ConvergenceError",
    "InputError",
    "RunResult",
    "WoundrollError",
    "__version__",
    "load_case",
    "run",
]
