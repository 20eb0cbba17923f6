"""The body of ``woundroll run CASE`` without the command line's parser (typer).

:mod:`~woundroll.app.cli.run` declares the command to typer and calls :func:`run_command`.
The ``woundroll`` script also calls it directly for the plain forms a sweep or a script
repeats thousands of times (``woundroll run CASE [--set KEY=VALUE]... [--json] [--quiet]
[--no-update]``: :func:`plain_run_args`): typer's import and its conversion of the command
(0.03-0.08 s, issue 23 item 1) are then skipped. Everything else (help, any other option or
form, a usage error) goes through typer. The outputs, messages and exit statuses are the
same either way: one body, and :func:`run_plain` exits as typer's group does.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

from woundroll.app.cli.console import err, escape, fail, out, table, warn, with_progress
from woundroll.errors import ConvergenceError, InputError


def run_command(
    case: str,
    set_: list[str] | None = None,
    out_dir: Path | None = None,
    as_json: bool = False,
    quiet: bool = False,
    uncertainty: int = 0,
    report: bool = False,
    fields: str | None = None,
    no_update: bool = False,
) -> None:
    """``woundroll run``: the models a case asks for, and the outputs asked for (the
    options of :func:`woundroll.app.cli.run.run`)."""
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
            uq = None
            if uncertainty:
                from woundroll.app.cli import diagnose

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
            import typer

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
        if uq is not None:
            from woundroll.app.cli import diagnose

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
    from woundroll.pipeline.summary import result_summary

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


#: the flags :func:`plain_run_args` takes, by the keyword of :func:`run_command` they set
_FLAGS = {"--json": "as_json", "--quiet": "quiet", "-q": "quiet", "--no-update": "no_update"}


def plain_run_args(args: list[str]) -> dict[str, Any] | None:
    """The keywords of :func:`run_command` for ``args`` (the command line after the program)
    when they are ``run CASE`` followed only by ``--set VALUE``, ``--json``, ``--quiet``/``-q``
    and ``--no-update``; else None (typer parses them). A value or case that starts with
    ``-`` is left to typer too, and so is everything on Windows (click expands wildcards in
    the arguments there) and a shell-completion request (``_WOUNDROLL_COMPLETE``-style
    variables: click answers those)."""
    if len(args) < 2 or args[0] != "run" or not args[1] or args[1].startswith("-"):
        return None
    if os.name == "nt" or any(k.startswith("_") and k.endswith("_COMPLETE") for k in os.environ):
        return None
    kwargs: dict[str, Any] = {"case": args[1]}
    sets: list[str] = []
    i = 2
    while i < len(args):
        a = args[i]
        if a in _FLAGS:
            kwargs[_FLAGS[a]] = True
        elif a == "--set" and i + 1 < len(args) and not args[i + 1].startswith("-"):
            i += 1
            sets.append(args[i])
        else:
            return None
        i += 1
    kwargs["set_"] = sets or None
    return kwargs


def run_plain(kwargs: dict[str, Any]) -> None:
    """:func:`run_command` with ``kwargs``, ending as typer's group ends the command: exit
    status of ``typer.Exit``, ``Aborted!`` (1) on an interrupt outside the models, and an
    unexpected error shown by typer's exception hook; after a run that succeeded, the
    process ends without the interpreter's teardown (:func:`_end_now`)."""
    try:
        run_command(**kwargs)
    except (KeyboardInterrupt, EOFError):
        sys.stderr.write("\n")
        err.print("Aborted!", highlight=False)
        sys.exit(1)
    except Exception as exc:
        import typer

        if isinstance(exc, typer.Exit):
            sys.exit(exc.exit_code)
        _as_typer_shows_it(exc)
        raise
    _end_now()


def _end_now() -> None:
    """End a plain run's process (status 0) without the interpreter's teardown, which frees
    every object of the models' modules one by one: 0.03-0.04 s of CPU of a Table 2 roll
    (issue 23 item 1). What a normal end does that anyone can see is done first: stdout and
    stderr flushed, the ``atexit`` handlers run (the code cache's file among them). Only
    when nothing else is running (no other thread, no ``multiprocessing``: a profile's or an
    uncertainty run's pools end as usual) and the flush succeeds (a closed pipe: the normal
    end reports it, as before); a plain run writes no file of its own (no ``--out``)."""
    import atexit
    import threading

    if threading.active_count() != 1 or "multiprocessing" in sys.modules:
        return
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (OSError, ValueError):
        return
    atexit._run_exitfuncs()
    os._exit(0)


def _as_typer_shows_it(exc: Exception) -> None:
    """Mark ``exc`` as typer's ``Typer.__call__`` does, so that its exception hook shows it
    as it would have: with typer's default ``pretty_exceptions_*`` settings, which the
    command group keeps (``entry.app`` sets none; a test holds the two equal)."""
    try:
        import typer
        from typer.main import _typer_developer_exception_attr_name, except_hook
        from typer.models import DeveloperExceptionConfig
    except ImportError:  # pragma: no cover - a typer without them: Python's own hook
        return
    app = typer.Typer()
    sys.excepthook = except_hook
    config = DeveloperExceptionConfig(
        pretty_exceptions_enable=app.pretty_exceptions_enable,
        pretty_exceptions_show_locals=app.pretty_exceptions_show_locals,
        pretty_exceptions_short=app.pretty_exceptions_short,
    )
    setattr(exc, _typer_developer_exception_attr_name, config)
