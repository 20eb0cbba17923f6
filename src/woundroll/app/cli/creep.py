"""``woundroll fit-stack CSV --creep``: a stack creep (or relaxation) test -> the creep law
of ``[storage] radial_creep`` (:mod:`woundroll.materials.creep_fit`)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from woundroll.app.cli.console import escape, table
from woundroll.errors import ConvergenceError, InputError
from woundroll.pipeline.vocabulary import versioned
from woundroll.util.output import strict_json


def fit_creep_cmd(
    csv_file: Path, law: str, as_json: bool, out: Any, fail: Callable[[Exception, int], None]
) -> None:
    """Fit the creep laws to the CSV (columns ``time`` and ``strain``: a creep test at a
    constant pressure; ``time`` and ``pressure``: a relaxation test at a constant strain;
    units in the header, ``time [h]``) and print the case-file lines."""

    from woundroll.materials.creep_fit import fit_creep, fit_relaxation
    from woundroll.util.tables import parse_header, read_columns, read_header_row

    try:
        if law not in ("all", "power", "prony"):
            raise InputError(f"with --creep choose power, prony or all, got {law!r}", "--law")
        names = {parse_header(h)[0] for h in read_header_row(csv_file, "CSV_FILE")}
        if "time" not in names:
            raise InputError(
                f"{csv_file.name}: a creep test needs a column 'time' and 'strain' (creep at a "
                "constant pressure) or 'pressure' (relaxation at a constant strain)",
                "CSV_FILE",
            )
        creep = "strain" in names
        kind = "dimensionless" if creep else "pressure"
        col = "strain" if creep else "pressure"
        cols = read_columns(csv_file, {"time": "time", col: kind}, "CSV_FILE")
        laws = ("power", "prony") if law == "all" else (law,)
        fits = {}
        for name in laws:
            fitter = fit_creep if creep else fit_relaxation
            try:
                fits[name] = fitter(cols["time"], cols[col], name)
            except InputError as exc:
                raise InputError(f"{csv_file.name}: {exc.message}", "CSV_FILE") from None
    except InputError as exc:
        fail(exc, 2)
        return
    except ConvergenceError as exc:
        fail(exc, 1)
        return
    if as_json:
        sys.stdout.write(strict_json(versioned({k: f.to_dict() for k, f in fits.items()})) + "\n")
        return
    t = table("law", "test", "RMS rel. error", "max rel. error", "case-file key")
    for name, f in fits.items():
        t.add_row(
            name,
            f.test,
            f"{f.rms_rel_error:.2%}",
            f"{f.max_rel_error:.2%}",
            escape(f"radial_creep = {f.law.toml()}"),
        )
    out.print(t)
    best = min(fits.values(), key=lambda f: f.rms_rel_error)
    out.print(escape(best.case_lines()), highlight=False, soft_wrap=True)
