"""``woundroll report CASE [--readings FILE] --out DIR``: the self-contained HTML report.

Registered in :mod:`woundroll.cli`; heavy imports happen inside the command.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from woundroll.errors import ConvergenceError, InputError


def load_readings(
    path: str | Path,
    case: Any,
    lane_width: float | None = None,
    *,
    fmt: str = "auto",
    roll: str | None = None,
    field: str = "--readings",
) -> Any:
    """Readings of one roll from a tester file (:func:`woundroll.tester_files.read_tester_file`:
    generic CSV, TAPPI T 834 sheet, dense profile export), positions checked against the web
    width; lane numbers use ``lane_width`` or the case's ``readings.lane_width``."""
    from woundroll.tester_files import read_tester_file

    if lane_width is None and case.readings is not None:
        lane_width = case.readings.lane_width
    return read_tester_file(
        path, format=fmt, roll=roll, width=case.web.width, lane_width=lane_width, field=field
    )


def report_cmd(
    case: Annotated[
        str, typer.Argument(help="Case file (TOML) or bundled case name (see `woundroll cases`).")
    ],
    out_dir: Annotated[Path, typer.Option("--out", help="Write DIR/report.html here.")],
    readings: Annotated[
        str | None,
        typer.Option(
            "--readings",
            help="Readings CSV (default: the case's [readings]); adds the measured profile, "
            "the diagnosis and per-lane defect risk.",
        ),
    ] = None,
    lane_width: Annotated[
        str | None, typer.Option("--lane-width", help="Lane width for lane numbers ('6 in').")
    ] = None,
    fmt: Annotated[
        str,
        typer.Option(
            "--format", help="Readings file layout: auto, generic, tappi (T 834 sheet), profile."
        ),
    ] = "auto",
    roll: Annotated[
        str | None, typer.Option("--roll", help="Roll id on a TAPPI sheet with several rolls.")
    ] = None,
    set_: Annotated[
        list[str] | None,
        typer.Option("--set", help="Override a case key: dotted.key=value (repeatable)."),
    ] = None,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar.")] = False,
) -> None:
    """Run a case and write one self-contained HTML report (prints on A4 and Letter)."""
    from rich.markup import escape

    from woundroll.case import load_case
    from woundroll.cli import _fail, _with_progress, out
    from woundroll.pipeline import run as run_case
    from woundroll.report import write_report

    def job(progress):  # type: ignore[no-untyped-def]
        from woundroll.defects import defect_report
        from woundroll.diagnosis import diagnose

        result = run_case(c, progress=progress)
        d = diagnose(c, r, progress=progress) if r is not None else None
        return result, d, defect_report(c, d, winding=result.winding)

    try:
        c = load_case(case, set_ or [])
        lw = None
        if lane_width is not None:
            from woundroll.units import to_si

            lw = to_si(lane_width, "length", "--lane-width")
        if readings is not None:
            r = load_readings(readings, c, lw, fmt=fmt, roll=roll)
        else:
            r = c.measured_readings
        if quiet or not sys.stderr.isatty():
            result, d, defects = job(None)
        else:
            result, d, defects = _with_progress(job)
        path = write_report(result, out_dir, readings=r, diagnosis=d, defects=defects)
    except InputError as exc:
        _fail(exc, 2)
    except ConvergenceError as exc:
        _fail(exc, 1)
    if not quiet:
        out.print(f"wrote {escape(str(path))}")


def register(app: typer.Typer) -> None:
    """Add ``report`` to the ``woundroll`` app."""
    app.command("report")(report_cmd)
