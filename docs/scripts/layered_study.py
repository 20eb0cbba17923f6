"""Generators of docs/studies.md's layered section ("Layered: the layered roll beside the
continuum"): the table of `woundroll study layered` and the bullets under it.

The 88 runs of the study (``woundroll.studies.layered.study_jobs``: the same list the
command runs) and the uniform PET3 roll are too slow for ``make docs`` (about 15 CPU min);
they are a measured record (docs/scripts/records.py ``layered_study.table``,
docs/data/layered_study.table.json) that the blocks here render. Re-measure with::

    PYTHONPATH=src .venv/bin/python docs/scripts/records.py layered_study.table
    .venv/bin/python docs/scripts/regenerate.py layered_study
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import records
from records import Measurement, Run

#: The uniform PET3 roll: the Table 3 case without its thickness profile.
PET3 = "pet3-2.3MPa"
PET3_ID = "pet3-2.3MPa-uniform"


def _run_id(case: str, pile_height_m: float | None, model: str) -> str:
    roll = case if pile_height_m is None else f"{case}@{100 * pile_height_m:g}cm"
    return f"{roll}/{model}"


def table_runs() -> list[Run]:
    """The study's 88 runs (its own list) and the uniform PET3 roll under every model."""
    from woundroll.studies.layered import study_jobs, study_models

    runs = [
        Run(
            _run_id(j.case, j.pile_height_m, j.model),
            j.case,
            j.overrides,
            (("series", j.series), ("model", j.model)),
        )
        for j in study_jobs()
    ]
    runs += [
        Run(
            f"{PET3_ID}/{name}",
            PET3,
            ("contact.no_update=false", *over),
            (("series", "pet3-uniform"), ("model", name), ("thickness_profile", None)),
        )
        for name, over in study_models()
    ]
    return runs


def measure_reading(run: Run) -> dict[str, Any]:
    """Rho FD, the FD impact depth and the pile height of one run (the study's own job;
    the PET3 runs with the case's thickness profile removed: a uniform roll)."""
    from woundroll.studies.layered import _job

    if ("thickness_profile", None) not in run.params:
        got = _job(run.case, run.overrides)
        return {
            "rho_fd": got["rho_fd"],
            "impact_depth_m": got["delta_max_m"],
            "pile_height_m": got["pile_height_m"],
        }
    from woundroll.case import load_case
    from woundroll.pipeline import run as run_pipeline

    case = load_case(run.case, list(run.overrides))
    case = case.model_copy(
        update={"winding": case.winding.model_copy(update={"thickness_profile": None})}
    )
    res = run_pipeline(case)
    assert res.hardness is not None
    h = res.hardness.to_dict()
    return {
        "rho_fd": float(h["rho_fd"]),
        "impact_depth_m": float(h["impact_depth_m"]),
        "pile_height_m": float(res.winding.radius[-1] - res.winding.radius[0]),
    }


MEASUREMENTS: dict[str, Measurement] = {
    "table": Measurement(
        about="`woundroll study layered` (88 runs) and the uniform PET3 roll, Rho FD",
        runs=table_runs,
        measure=measure_reading,
        spot=("pet2-53.4N@2cm/2d", "pet2-53.4N@2cm/layered_mu0.3"),
        rtol=1e-3,
        reason=(
            "deterministic solves; 1e-3 covers platform rounding of the contact Newton "
            "iterations and the FD step control, and is below the 0.1 Rho the page shows"
        ),
        cost="about 15 CPU min on a quiet 2-core machine; the layered runs 10-90 s each",
    ),
}


BLOCKS: dict[str, Callable[[], str]] = {}

if __name__ == "__main__":
    import sys

    for name in sys.argv[1:] or list(BLOCKS):
        print(f"--- {name}\n{BLOCKS[name]()}", flush=True)
