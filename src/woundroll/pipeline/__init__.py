"""The forward chain, run: a case -> stresses in the roll -> roll stiffness under the
striker -> striker motion -> the instrument's reading (and, with a thickness profile,
across the CMD).

* :mod:`~woundroll.pipeline.runner` -- :func:`run` chains the steps;
* :mod:`~woundroll.pipeline.results` -- :class:`RunResult` and the flags of a run;
* :mod:`~woundroll.pipeline.summary` -- the headline lines of a result (CLI, report, web);
* :mod:`~woundroll.pipeline.vocabulary` -- every JSON key, its unit and meaning.

The names below load on first use, so that importing one light submodule (the vocabulary,
the summary) does not import the models: ``woundroll --help`` stays fast.
"""

from typing import TYPE_CHECKING

from woundroll.util.lazy import lazy_names

if TYPE_CHECKING:
    from woundroll.pipeline.results import NoUpdate, RunResult, result_flags
    from woundroll.pipeline.runner import Progress, hardness_on_roll, run

_LAZY = {
    "NoUpdate": "woundroll.pipeline.results",
    "RunResult": "woundroll.pipeline.results",
    "result_flags": "woundroll.pipeline.results",
    "Progress": "woundroll.pipeline.runner",
    "hardness_on_roll": "woundroll.pipeline.runner",
    "run": "woundroll.pipeline.runner",
}


__getattr__ = lazy_names(__name__, _LAZY)


__all__ = ["NoUpdate", "Progress", "RunResult", "hardness_on_roll", "result_flags", "run"]
