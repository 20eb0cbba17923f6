"""The forward chain, run: a case -> stresses in the roll -> roll stiffness under the
striker -> striker motion -> the instrument's reading (and, with a thickness profile,
across the CMD).

* :mod:`~woundroll.pipeline.runner` -- :func:`run` chains the steps;
* :mod:`~woundroll.pipeline.results` -- :class:`RunResult` and the flags of a run;
* :mod:`~woundroll.pipeline.summary` -- the headline lines of a result (CLI, report, web).
"""

from woundroll.pipeline.results import NoUpdate, RunResult, result_flags
from woundroll.pipeline.runner import Progress, hardness_on_roll, run

__all__ = ["NoUpdate", "Progress", "RunResult", "hardness_on_roll", "result_flags", "run"]
