"""woundroll: wound-roll stresses from winder settings, and the hardness readings they cause.

The pipeline reads like the physics:

winder settings (:mod:`woundroll.case`)
-> stresses in the roll (:mod:`woundroll.winding`)
-> roll stiffness under the striker (:mod:`woundroll.contact`)
-> striker motion and the instrument reading (:mod:`woundroll.instruments`)
-> across the CMD (:mod:`woundroll.profile`).

``woundroll.load_case`` reads a case; ``woundroll.run`` runs it and returns a typed
:class:`~woundroll.pipeline.RunResult`.
The layout, and the rule that imports flow one way down it: docs/architecture.md.
"""

from typing import TYPE_CHECKING

from woundroll.errors import ConvergenceError, InputError, WoundrollError
from woundroll.util.lazy import lazy_names
from woundroll.util.moved import install as _install_moved

_install_moved()  # old module paths keep working, with a DeprecationWarning

if TYPE_CHECKING:
    from woundroll.case import Case, load_case
    from woundroll.pipeline import RunResult, run

__version__ = "0.1.0"

# loaded on first use: ``import woundroll`` (and so ``woundroll --help``) stays light,
# with no pydantic, pint registry, scipy or numba behind it
_LAZY = {
    "Case": "woundroll.case",
    "load_case": "woundroll.case",
    "RunResult": "woundroll.pipeline",
    "run": "woundroll.pipeline",
}


__getattr__ = lazy_names(__name__, _LAZY)


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
