"""``woundroll run CASE``: the forward chain on one case, with its outputs."""

from __future__ import annotations

import json
import sys
from typing import Annotated

import typer

from woundroll.app.cli import diagnose
from woundroll.app.cli.console import err, escape, fail, out, table, warn, with_progress
from woundroll.app.cli.options import CaseArg, JsonOpt, SetOpt, out_option
from woundroll.errors import ConvergenceError, InputError
from woundroll.pipeline.summary import result_summary


def run(
    case: CaseArg,
    set_: SetOpt = None,
    out_dir: out_option("result.json and PNG plots") = None,  # type: ignore[valid-type]
    as_json: JsonOpt = False,
    quiet: Annotated[
        bool, typer.Option("--quiet", "-q", help="No progress bar or summary.")
    ] = False,
    uncertainty: Annotated[
        int,
        typer.Option(
            "--uncertainty",
            help="Monte Carlo samples of the case's [uncertainty] (0: none).",
            min=0,
        ),
    ] = 0,
    report: Annotated[
        bool, typer.Option("--report", help="With --out: also write the HTML report.html.")
    ] = False,
    fields: Annotated[
        str | None,
        typer.Option(
            "--fields",
            help="compact (the default): arrays over 4,000 points go to result.npz (--out) "
            "and are left out of the JSON (listed in arrays_omitted); full: every array in "
            "the JSON.",
        ),
    ] = None,
    no_update: Annotated[
        bool,
        typer.Option(
            "--no-update",
            help="Also solve with E_r frozen at its pre-impact value (contact.no_update).",
        ),
    ] = False,
) -> None:
    """Run the models a case asks for: winding, and with a tester section the hardness reading."""
    from woundroll.case import load_case
    from woundroll.pipeline import run as run_case
    from woundroll.util.gc_pause import resume as resume_gc
    from woundroll.util.pool import Interrupted, clean_stop

    with clean_stop():
        try:
            if report and out_dir is None:
                raise InputError("the report goes into the --out directory: give --out", "--report")
            from woundroll.pipeline.results import DEFAULT_FIELDS, FIELDS

            fields = DEFAULT_FIELDS if fields is None else fields
            if fields not in FIELDS:
                raise InputError(f"--fields is compact or full, got {fields!r}", "--fields")
            flags = [("contact.no_update=true", "--no-update")] if no_update else []
            c = load_case(case, [*(set_ or []), *flags])
            resume_gc()  # start-up is over: the models' modules are in (util/gc_pause.py)
            if out_dir is not None:
                from woundroll.util.output import check_out_dir

                check_out_dir(out_dir)  # a bad --out fails now, not after the run
            # the estimate of a long run is for the wait: now; the other warnings follow a
            # run that succeeded (a case that fails prints its error alone)
            for w in c.warnings:
                if w.startswith("long run:"):
                    warn(w)
            if quiet or as_json or not sys.stderr.isatty():
                result = run_case(c)
            else:
                result = with_progress(lambda progress: run_case(c, progress=progress))
            written = result.write(out_dir, fields) if out_dir is not None else []
            uq = diagnose.run_uncertainty(
                c, uncertainty, out_dir, written, quiet or as_json, result.profile
            )
            if report:
                from woundroll.app.report import write_report
                from woundroll.assess.defects import defect_report

                defects = defect_report(c, winding=result.winding)
                readings = c.measured_readings
                written.append(write_report(result, out_dir, readings=readings, defects=defects))
        except InputError as exc:
            fail(exc, 2)
        except ConvergenceError as exc:
            fail(exc, 1)
        except Interrupted as exc:
            err.print(f"stopped by {exc}: workers ended, no output written", highlight=False)
            raise typer.Exit(128 + exc.signum) from None
    for w in c.warnings:
        if not w.startswith("long run:"):
            warn(w)
    for w in result.warnings:
        if w not in c.warnings:
            warn(w)
    if as_json:
        sys.stdout.write(_json(result, uq, fields) + "\n")
        return
    if not quiet:
        _summary(result)
        diagnose.print_uncertainty(uq)
        for p in written:
            out.print(f"wrote {escape(str(p))}")


def _json(result, uq, fields: str) -> str:  # type: ignore[no-untyped-def]
    """The run's JSON (with ``uncertainty`` when it was propagated), compact or full."""
    from woundroll.pipeline.results import compact
    from woundroll.util.output import strict_json

    d = result.to_dict()
    if uq is not None:
        d["uncertainty"] = uq.to_dict()
    return strict_json(d if fields == "full" else compact(d)[0])


def _inputs(case) -> None:  # type: ignore[no-untyped-def]
    """The inputs the run used as given, with their source (defaults counted, listed in
    result.json)."""
    t = table("input", "value", "source", title="inputs", show_header=True)
    defaults = 0
    for v in case.inputs:
        if v.source == "default":
            defaults += 1
            continue
        given = v.given if isinstance(v.given, str) else json.dumps(v.given)
        t.add_row(escape(v.key), escape(given), escape(v.source))
    out.print(t)
    if defaults:
        out.print(
            f"{defaults} more keys at their defaults (docs/case-files.md; listed in "
            "result.json 'inputs')",
            highlight=False,
        )


def _summary(result) -> None:  # type: ignore[no-untyped-def]
    _inputs(result.case)
    t = table(title=escape(result.case.display_title or "result"), show_header=True)
    t.add_column("quantity")
    t.add_column("value", justify="right")
    for name, value in result_summary(result):
        t.add_row(escape(name), escape(value))
    out.print(t)
    for note in result.notes:
        out.print(f"note: {escape(note)}", highlight=False)
    raised = [k.replace("_", " ") for k, v in result.flags.items() if v]
    if raised:
        out.print(f"[bold yellow]flags:[/] {escape(', '.join(raised))}", highlight=False)


def register(app: typer.Typer) -> None:
    """Add ``run`` to the ``woundroll`` app."""
    app.command("run")(run)
