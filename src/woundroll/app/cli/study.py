"""``woundroll study NAME``: the reference paper's studies (Figures 14-18)."""

from __future__ import annotations

import sys
from typing import Annotated

import typer

from woundroll.app.cli.console import console, err, escape, fail, out, table, with_progress
from woundroll.app.cli.options import out_option
from woundroll.errors import ConvergenceError, InputError


def study(
    name: Annotated[
        str,
        typer.Argument(
            help="tension (Figures 14/15), pile-height (16/17), slip (18), all, dynamic "
            "(the FE impact in time against the 1.5D models), layered (interlayer friction "
            "beside the continuum) or layered-3d (the same rolls in 3D too: tens of CPU minutes)."
        ),
    ],
    out_dir: out_option("study.json and PNG plots") = None,  # type: ignore[valid-type]
    as_json: Annotated[
        bool, typer.Option("--json", help="Print the study as JSON on stdout.")
    ] = False,
    workers: Annotated[
        int, typer.Option(help="Rolls run in parallel (processes).", min=1, max=64)
    ] = 1,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar.")] = False,
    model: Annotated[
        str | None,
        typer.Option(
            help="Roll model that reads the rolls of the tension, pile-height, slip and all "
            "studies (2d, 2d+cmd-spread, 3d; slip: 2d or 3d). Default: the registry's (2d)."
        ),
    ] = None,
) -> None:
    """Run one of the reference paper's studies on its Table 2 rolls; print its tables."""
    from woundroll.pipeline.vocabulary import versioned
    from woundroll.studies import run_study
    from woundroll.util.output import strict_json

    def job(progress):  # type: ignore[no-untyped-def]
        return run_study(name, progress=progress, workers=workers, model=model)

    from woundroll.util.pool import Interrupted, clean_stop

    with clean_stop():  # SIGINT/SIGTERM end the study's worker pool too
        try:
            if quiet or as_json or not sys.stderr.isatty():
                result = job(None)
            else:
                result = with_progress(job)
            written = result.write(out_dir) if out_dir is not None else []
        except InputError as exc:
            fail(exc, 2)
        except ConvergenceError as exc:
            fail(exc, 1)
        except OSError as exc:
            fail(InputError(f"cannot write to {out_dir}: {exc.strerror or exc}", "--out"), 2)
        except Interrupted as exc:
            err.print(f"stopped by {exc}: workers ended, no output written", highlight=False)
            raise typer.Exit(128 + exc.signum) from None
    if as_json:
        sys.stdout.write(strict_json(versioned(result.to_dict())) + "\n")
        return
    wide = out if out.is_terminal else console(width=160)
    for title, header, rows in result.summary():
        t = table(*[escape(h) for h in header], title=escape(title))
        for row in rows:
            t.add_row(*[escape(str(c)) for c in row])
        wide.print(t)
    for note in result.notes():
        out.print(f"note: {escape(note)}", highlight=False)
    for p in written:
        out.print(f"wrote {escape(str(p))}")


def register(app: typer.Typer) -> None:
    """Add ``study`` to the ``woundroll`` app."""
    app.command("study")(study)
