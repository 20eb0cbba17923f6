"""``woundroll report CASE [--readings FILE] --out DIR``: the self-contained HTML report.

Registered in :mod:`woundroll.app.cli`; heavy imports happen inside the command.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from woundroll.app.cli.console import escape
from woundroll.app.cli.options import CaseArg, LaneWidthOpt, SetOpt, out_option
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
    """Readings of one roll from a tester file (:func:`woundroll.io.tester_files.read_tester_file`:
    generic CSV, TAPPI T 834 sheet, dense profile export), positions checked against the web
    width; lane numbers use ``lane_width`` or the case's ``readings.lane_width``."""
    from woundroll.io.tester_files import read_tester_file

    if lane_width is None and case.readings is not None:
        lane_width = case.readings.lane_width
    return read_tester_file(
        path, format=fmt, roll=roll, width=case.web.width, lane_width=lane_width, field=field
    )


def readings_ids(path: str | Path, readings: Any, fmt: str = "auto") -> dict[str, str]:
    """Roll, lot and customer named in a readings file
    (:func:`woundroll.assess.profile_check.file_ids`; a TAPPI sheet's roll is the roll read)."""
    from woundroll.assess.profile_check import file_ids
    from woundroll.io.tester_files import detect_format, read_profile_export

    layout = detect_format(path, "--readings") if fmt == "auto" else fmt
    if layout == "profile":
        ids = file_ids(path, read_profile_export(path, field="--readings").metadata)
    else:
        ids = file_ids(path)
    if layout == "tappi" and ": roll " in readings.source:
        ids["roll"] = readings.source.split(": roll ", 1)[1]
    return ids


def report_ids(
    given: dict[str, str | None], from_file: dict[str, str], file_name: str
) -> tuple[dict[str, tuple[str, str]], list[str]]:
    """The header's ids with their provenance: an option given on the command line wins
    over the readings file; a disagreement between the two is returned as a warning."""
    ids: dict[str, tuple[str, str]] = {}
    notes = []
    for key in ("roll", "lot", "customer"):
        opt = given.get(key)
        found = from_file.get(key)
        if opt is not None and opt.strip():
            ids[key] = (opt.strip(), "")
            if found and found != opt.strip():
                notes.append(
                    f"{key} given as {opt.strip()!r} on the command line, {file_name} says "
                    f"{found!r}: the report shows {opt.strip()!r}"
                )
        elif found:
            ids[key] = (found, f"from {file_name}")
    return ids, notes


def report_cmd(
    case: CaseArg,
    out_dir: out_option("DIR/report.html", required=True),  # type: ignore[valid-type]
    readings: Annotated[
        str | None,
        typer.Option(
            "--readings",
            help="Readings CSV (default: the case's [readings]); adds the measured profile, "
            "the diagnosis and per-lane defect risk.",
        ),
    ] = None,
    lane_width: LaneWidthOpt = None,
    fmt: Annotated[
        str,
        typer.Option(
            "--format", help="Readings file layout: auto, generic, tappi (T 834 sheet), profile."
        ),
    ] = "auto",
    roll: Annotated[
        str | None, typer.Option("--roll", help="Roll id on a TAPPI sheet with several rolls.")
    ] = None,
    set_: SetOpt = None,
    roll_id: Annotated[
        str | None,
        typer.Option(
            "--roll-id", help="Roll ID for the report's header (default: the readings file's)."
        ),
    ] = None,
    lot: Annotated[
        str | None,
        typer.Option("--lot", help="Lot (set, batch) for the header (default: the file's)."),
    ] = None,
    customer: Annotated[
        str | None,
        typer.Option("--customer", help="Customer for the header (default: the file's)."),
    ] = None,
    title: Annotated[
        str | None, typer.Option("--title", help="Report title (default: the case's title).")
    ] = None,
    trend_files: Annotated[
        list[str] | None,
        typer.Option(
            "--trend",
            help="Readings file of earlier rolls (repeatable, production order): adds the "
            "roll-to-roll trend with X-mR control charts of mean and CoV.",
        ),
    ] = None,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar.")] = False,
) -> None:
    """Run a case and write one self-contained HTML report (prints on A4 and Letter)."""

    from woundroll.app.cli.console import fail, out, with_progress
    from woundroll.app.report import write_report
    from woundroll.case import load_case
    from woundroll.pipeline import run as run_case

    def job(progress):  # type: ignore[no-untyped-def]
        from woundroll.assess.defects import defect_report
        from woundroll.inverse.diagnosis import diagnose

        result = run_case(c, progress=progress)
        d = diagnose(c, r, progress=progress) if r is not None else None
        return result, d, defect_report(c, d, winding=result.winding)

    try:
        c = load_case(case, set_ or [])
        lw = None
        if lane_width is not None:
            from woundroll.units import to_si

            lw = to_si(lane_width, "length", "--lane-width")
        for key, text in (("--roll-id", roll_id), ("--lot", lot), ("--customer", customer)):
            if text is not None and (not text.strip() or len(text) > 200 or "\n" in text):
                raise InputError("give one line of text, at most 200 characters", key)
        from_file: dict[str, str] = {}
        file_name = ""
        if readings is not None:
            r = load_readings(readings, c, lw, fmt=fmt, roll=roll)
            from_file, file_name = readings_ids(readings, r, fmt), Path(readings).name
        else:
            r = c.measured_readings
            if r is not None and c.readings is not None:
                path_ = c._path(c.readings.file)
                from_file, file_name = readings_ids(path_, r), path_.name
        ids, id_notes = report_ids(
            {"roll": roll_id, "lot": lot, "customer": customer}, from_file, file_name
        )
        trend = _trend(trend_files or [], r, from_file, c, lw)
        if quiet or not sys.stderr.isatty():
            result, d, defects = job(None)
        else:
            result, d, defects = with_progress(job)
        path = write_report(
            result,
            out_dir,
            readings=r,
            diagnosis=d,
            defects=defects,
            ids=ids,
            title=title,
            trend=trend,
            warnings=id_notes,
        )
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:
        fail(exc, 1)
    if not quiet:
        out.print(f"wrote {escape(str(path))}")


def _trend(files: list[str], r: Any, ids: dict[str, str], case: Any, lane_width: Any) -> Any:
    """The trend of the ``--trend`` files' rolls followed by this report's roll (when it has
    readings), or None without ``--trend``."""
    if not files:
        return None
    from woundroll.assess.profile_check import check_profile, read_rolls, roll_trend

    if lane_width is None and case.readings is not None:
        lane_width = case.readings.lane_width
    # earlier rolls may be slit to other widths: their positions are not held to this web's
    rolls = read_rolls(files, lane_width=lane_width, field="--trend")
    if r is not None:
        if rolls and rolls[0][0].scale != r.scale:
            raise InputError(
                f"{rolls[0][0].source} reads in {rolls[0][0].scale}, the report's readings in "
                f"{r.scale}: a trend needs one instrument",
                "--trend",
            )
        rolls.append((r, ids))
    checks = []
    for rr, i in rolls:
        if rr.n_positions < 2:
            raise InputError(f"{rr.source}: needs readings at 2 positions or more", "--trend")
        checks.append(check_profile(rr, ids=i))
    return roll_trend(checks)


def register(app: typer.Typer) -> None:
    """Add ``report`` to the ``woundroll`` app."""
    app.command("report")(report_cmd)
