"""``woundroll fit-stack CSV --unloading``: one stack cycle -> loading law and unloading branch."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from woundroll.app.cli.console import escape, table
from woundroll.errors import ConvergenceError, InputError
from woundroll.pipeline.vocabulary import versioned
from woundroll.util.output import strict_json


def fit_cycle_cmd(
    csv_file: Path, as_json: bool, out: Any, fail: Callable[[Exception, int], None]
) -> None:
    """Fit :func:`woundroll.materials.unloading.fit_stack_cycle` and print the case-file
    tables (``radial_modulus`` and ``radial_unloading``) with the fit quality."""

    from woundroll.materials.radial_modulus import read_stack_csv
    from woundroll.materials.unloading import fit_stack_cycle

    try:
        eps, p = read_stack_csv(csv_file, "CSV_FILE")
        fit = fit_stack_cycle(eps, p)
    except InputError as exc:
        fail(exc, 2)
        return
    except ConvergenceError as exc:
        fail(exc, 1)
        return
    if as_json:
        sys.stdout.write(strict_json(versioned(fit.to_dict())) + "\n")
        return
    t = table("branch", "points", "RMS rel. error", "case-file key")
    t.add_row(
        "loading (pfeiffer)",
        str(fit.n_loading),
        f"{fit.loading.rms_rel_error:.2%}",
        escape(f"radial_modulus = {fit.loading.toml()}"),
    )
    t.add_row(
        "unloading",
        str(fit.n_unloading),
        f"{fit.unloading_rms_rel_error:.2%}",
        escape(f"radial_unloading = {fit.unloading.toml()}"),
    )
    out.print(t)
    out.print(
        f"turning point: strain {fit.strain_max:.4g}, pressure {fit.pressure_max / 1e3:.4g} kPa; "
        f"energy given back {fit.energy_ratio:.3f} (e = {fit.energy_ratio**0.5:.3f})"
    )
