"""``woundroll report CASE [--readings FILE] --out DIR``: the self-contained HTML report.

Registered in :mod:`woundroll.cli`; heavy imports happen inside the command.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from woundroll.errors import ConvergenceError, InputError


def load_readings(path: str | Path, case: Any, field: str = "--readings") -> Any:
    """Readings of ``path`` for ``case`` (positions checked against the web width).

    Raises
    ------
    InputError
        The file cannot be read, or this build has no readings reader (``woundroll.readings``).
    """
    try:
        from woundroll.readings import read_readings
    except ImportError:
        raise InputError(
            "reading files need woundroll.readings, which this build does not have", field
        ) from None
    return read_readings(path, width=case.web.width, field=field)


def report_cmd(
    case: Annotated[
        str, typer.Argument(help="Case file (TOML) or bundled case name (see `woundroll cases`).")
    ],
    out_dir: Annotated[Path, typer.Option("--out", help="Write DIR/report.html here.")],
    readings: Annotated[
        str | None,
        typer.Option("--readings", help="CSV of measured readings across the roll."),
    ] = None,
    set_: Annotated[
        list[str] | None,
        typer.Option("--set", help="Override a case key: dotted.key=value (repeatable)."),
    ] = None,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar.")] = False,
) -> None:
    """Run a case and write one self-contained HTML report (prints on A4 and Letter)."""
    from woundroll.case import load_case
    from woundroll.cli import _fail, _with_progress, out
    from woundroll.pipeline import run as run_case
    from woundroll.report import write_report

    try:
        c = load_case(case, set_ or [])
        r = load_readings(readings, c) if readings is not None else None
        if quiet or not sys.stderr.isatty():
            result = run_case(c)
        else:
            result = _with_progress(lambda progress: run_case(c, progress=progress))
        path = write_report(result, out_dir, readings=r)
    except InputError as exc:
        _fail(exc, 2)
    except ConvergenceError as exc:
        _fail(exc, 1)
    if not quiet:
        out.print(f"wrote {path}")


def register(app: typer.Typer) -> None:
    """Add ``report`` to the ``woundroll`` app."""
    app.command("report")(report_cmd)
