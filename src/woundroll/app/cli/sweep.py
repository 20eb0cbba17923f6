"""``woundroll sweep CASE --vary KEY=SPEC ... [--uncertainty N] --out DIR``: parameter sweeps
(woundroll.app.sweep).

Registered in :mod:`woundroll.app.cli`; heavy imports happen inside the command.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from woundroll.app.cli.console import escape
from woundroll.app.cli.options import CaseArg
from woundroll.errors import InputError


def sweep_cmd(
    case: CaseArg,
    vary: Annotated[
        list[str],
        typer.Option(
            "--vary",
            help="KEY=START:STOP:COUNT or KEY=V1,V2,... with units as in a case file, e.g. "
            "'winding.tension=20 N:80 N:13' (repeatable).",
        ),
    ],
    out_dir: Annotated[
        Path, typer.Option("--out", help="Write sweep.parquet, sweep.csv, main_effects.png.")
    ],
    design: Annotated[str, typer.Option(help="grid, random or lhs (Latin hypercube).")] = "grid",
    samples: Annotated[
        int | None, typer.Option(help="Rolls of a random or lhs design.", min=1)
    ] = None,
    seed: Annotated[int, typer.Option(help="Seed of the random and lhs designs.")] = 0,
    workers: Annotated[
        int | None,
        typer.Option(
            help="Local processes (default: all cores when the rolls take over 15 s serially).",
            min=1,
            max=256,
        ),
    ] = None,
    scheduler: Annotated[
        str | None,
        typer.Option(help="Dask scheduler address (tcp://host:8786): run on that cluster."),
    ] = None,
    uncertainty: Annotated[
        int,
        typer.Option(
            "--uncertainty",
            help="Monte Carlo samples of the case's [uncertainty] per roll (0: none; >= 10): "
            "adds 95 % band columns (winding.core_pressure_low/_high, hardness.reading_low/_high).",
            min=0,
        ),
    ] = 0,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar.")] = False,
) -> None:
    """Run a case over a grid, random or Latin-hypercube design of inputs; write one table."""

    from woundroll.app.cli.console import err, fail, out
    from woundroll.app.sweep import run_sweep

    def job(progress):  # type: ignore[no-untyped-def]
        def tick(done: int, total: int) -> None:
            if progress is not None:
                progress(f"rolls ({total})", done / max(total, 1))

        return run_sweep(
            case,
            vary,
            design=design,
            samples=samples,
            seed=seed,
            workers=workers,
            scheduler=scheduler,
            progress=tick,
            uncertainty=uncertainty,
        )

    try:
        if quiet or not sys.stderr.isatty():
            result = job(None)
        else:
            from woundroll.app.cli.console import with_progress

            result = with_progress(job)
        written = result.write(out_dir)
    except InputError as exc:
        fail(exc, 2)
    if not quiet:
        n = len(result.rows)
        out.print(f"{n} rolls, {n - result.n_failed} ran, {result.n_failed} failed")
        for note in result.notes:
            err.print(f"note: {escape(note)}", highlight=False)
        for p in written:
            out.print(f"wrote {escape(str(p))}")


def register(app: typer.Typer) -> None:
    """Add ``sweep`` to the ``woundroll`` app."""
    app.command("sweep")(sweep_cmd)
