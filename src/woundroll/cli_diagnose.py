"""CLI commands of the reverse road: ``woundroll readings FILE`` (registered in woundroll.cli).

Kept out of :mod:`woundroll.cli` so that the shared module only registers them; imports of
numpy-heavy modules happen inside the commands (``woundroll --help`` stays light).
"""

from __future__ import annotations

import sys
from typing import Annotated

import typer
from rich.markup import escape
from rich.table import Table

from woundroll.errors import ConvergenceError, InputError


def _length(text: str | None, field: str) -> float | None:
    if text is None:
        return None
    from woundroll.units import to_si

    v = to_si(text, "length", field)
    if not v > 0:
        raise InputError(f"must be positive, got {text!r}", field)
    return v


def readings_cmd(
    csv_file: Annotated[
        str,
        typer.Argument(
            help="Readings CSV: 'position [in],reading [Rho]' (or [R], [L], [g]; lane numbers "
            "with --lane-width); several value columns or repeated positions are passes."
        ),
    ],
    width: Annotated[
        str | None,
        typer.Option(help="Web width ('24 in'): positions outside the roll are an error."),
    ] = None,
    lane_width: Annotated[
        str | None, typer.Option("--lane-width", help="Lane width for lane numbers ('6 in').")
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the readings as JSON.")] = False,
) -> None:
    """Read a sheet of hardness readings; print the mean and scatter per position."""
    from woundroll.cli import _fail, out
    from woundroll.readings import read_readings

    try:
        r = read_readings(
            csv_file,
            width=_length(width, "--width"),
            lane_width=_length(lane_width, "--lane-width"),
            field="CSV_FILE",
        )
    except InputError as exc:
        _fail(exc, 2)
    except ConvergenceError as exc:  # pragma: no cover - nothing iterative here
        _fail(exc, 1)
    if as_json:
        import json

        sys.stdout.write(json.dumps(r.to_dict()) + "\n")
        return
    t = Table(
        "position [in]",
        "position [m]",
        f"mean [{r.scale}]",
        f"SD [{r.scale}]",
        "count",
        title=escape(f"{r.source}: {r.passes} pass(es), scale {r.scale}"),
    )
    for x, m, s, n in zip(r.position, r.mean, r.sd, r.count, strict=True):
        t.add_row(f"{x / 0.0254:.2f}", f"{x:.4f}", f"{m:.2f}", f"{s:.2f}" if n > 1 else "-", f"{n}")
    out.print(t)
    pooled = r.pooled_sd
    if pooled is not None:
        out.print(f"pooled repeatability (SD): {pooled:.2f} {r.scale}", highlight=False)
    else:
        out.print("no repeated readings: the scatter must come from the instrument's repeatability")


def register(app: typer.Typer) -> None:
    """Add the reverse-road commands to the ``woundroll`` app."""
    app.command("readings")(readings_cmd)
