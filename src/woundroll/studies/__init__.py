"""The reference paper's studies on the Table 2 PET rolls, as data, tables and plots.

Three studies, each a function that runs the whole pipeline (winding -> 2D contact ->
impact, :func:`woundroll.run`) on bundled cases and returns a result object:

* :func:`tension_study` -- Figures 14/15 (and the no-update comparison of Figures 8/9):
  per roll of Table 2 the Rho reading by the finite-difference (FD) model {4}-{13} and the
  energy model {19}-{22}, the same with E_r frozen at its pre-impact value ("no update"),
  the impulse (FD), the roll spring alpha, beta {3}, the semi-contact width a and the
  impact's maximum depth.
* :func:`pile_height_study` -- Figures 16/17: one roll wound to several outer radii
  (pile height H = outer radius - core radius); the pre-impact radial pressure against
  radius, and Rho against H, with columns that take the H dependence of the plane-strain
  model apart (active mass, pre-stress, geometry; where along the axis the head's
  approach comes from; see :class:`PileHeightStudy`).
* :func:`slip_factor_study` -- Figure 18: the slip factor {23} near the head, the region
  where SF >= 1 and the largest SF.

Interface for the command line (``woundroll study NAME [--out DIR] [--json]``)
-------------------------------------------------------------------------------
::

    from woundroll.studies import STUDIES, run_study

    result = run_study(name, progress=progress)   # name in STUDIES: "tension",
                                                  # "pile-height", "slip", "all"
    result.to_dict()       # JSON-ready dict (SI, unit in every key): for --json
    result.summary()       # list[SummaryTable]; each unpacks as (title, header, rows),
                           # header a tuple of column titles (units in brackets), rows a
                           # list of tuples of already formatted strings: print as tables
    result.notes()         # list[str]: one-line remarks to print under the tables
    result.write(out_dir)  # writes study.json and the PNGs, returns list[Path]

``progress(stage: str, fraction: float)`` is called as the runs advance (``fraction`` of
the whole study, 0..1). An unknown ``name`` raises :class:`~woundroll.errors.InputError`
with field ``"study"``. ``run_study(name, workers=2)`` runs independent rolls in a
2-process pool (spawn start method); the default is 1 (serial), see ``docs/studies.md``.

Layout: one module per study (``tension.py``, ``pile_height.py``, ``slip.py``,
``all_studies.py``), each with its result class, its function and ``run(progress=None, *,
workers=1)``; ``_common.py`` holds what they share (one roll as a row, the process-pool
map, :class:`SummaryTable`). Adding a study is one new module with a ``run`` and one line
in :data:`STUDIES` below.

Units: every function takes and returns SI (lengths [m], tensions [N], Rho [-], impulse
[N s]); ``pile_heights`` also accepts strings with a unit (``"4 cm"``). Plots use cm/mm.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from woundroll.errors import InputError
from woundroll.studies import all_studies, dynamic, layered, pile_height, slip, tension
from woundroll.studies._common import TABLE2, Progress, StudyResult, SummaryTable
from woundroll.studies.all_studies import AllStudies
from woundroll.studies.pile_height import DEFAULT_PILE_HEIGHTS, PileHeightStudy, pile_height_study
from woundroll.studies.slip import SlipStudy, slip_factor_study
from woundroll.studies.tension import MANUAL_IMPULSE_NS, TensionStudy, tension_study

#: Study name -> ``run(progress, *, workers)`` returning a :class:`StudyResult`.
#: A new study: a module in this package with a ``run`` function, and one line here.
STUDIES: dict[str, Callable[..., Any]] = {
    "tension": tension.run,
    "pile-height": pile_height.run,
    "slip": slip.run,
    "all": all_studies.run,
    "dynamic": dynamic.run,
    "layered": layered.run,
    "layered-3d": layered.run_3d,
}


#: Studies whose rolls are read by one roll model the user may choose (``--model``); the
#: others fix their models (``dynamic``: 2D and 3D rows side by side).
MODEL_STUDIES = ("tension", "pile-height", "slip", "all")


def run_study(
    name: str,
    *,
    progress: Progress | None = None,
    workers: int = 1,
    model: str | None = None,
) -> StudyResult:
    """Run the study ``name`` (a key of :data:`STUDIES`) and return its result.

    ``model``: the roll model (a name in :data:`woundroll.contact.models.ROLL_MODELS`) for
    the studies of :data:`MODEL_STUDIES`; None: the registry's default.

    Raises
    ------
    InputError
        Field ``"study"`` for an unknown name (the message lists the known ones);
        ``"--model"`` for a model the study does not take.
    """
    fn = STUDIES.get(name) if isinstance(name, str) else None
    if fn is None:
        raise InputError(f"unknown study {name!r}; known: {', '.join(STUDIES)}", "study")
    if model is None:
        return fn(progress, workers=workers)
    from woundroll.contact.models import check_model_name

    check_model_name(model, "--model")
    if name not in MODEL_STUDIES:
        raise InputError(
            f"the {name} study fixes its roll models; --model is for {', '.join(MODEL_STUDIES)}",
            "--model",
        )
    return fn(progress, workers=workers, model=model)


__all__ = [
    "DEFAULT_PILE_HEIGHTS",
    "MANUAL_IMPULSE_NS",
    "STUDIES",
    "TABLE2",
    "AllStudies",
    "PileHeightStudy",
    "SlipStudy",
    "StudyResult",
    "SummaryTable",
    "TensionStudy",
    "pile_height_study",
    "run_study",
    "slip_factor_study",
    "tension_study",
]
