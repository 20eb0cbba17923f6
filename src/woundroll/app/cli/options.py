"""The options several commands share, declared once: the case argument, ``--set``,
``--json``, ``--quiet``, ``--lane-width`` and ``--out`` (each command says what it writes)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer

CASE_HELP = "Case file (TOML) or bundled case name (see `woundroll cases`)."

#: the case: a TOML file or a bundled case's name
CaseArg = Annotated[str, typer.Argument(help=CASE_HELP)]
#: ``--set dotted.key=value`` (repeatable): values over the case
SetOpt = Annotated[
    list[str] | None,
    typer.Option("--set", help="Override a case key: dotted.key=value (repeatable)."),
]
#: ``--json``: the result as JSON on stdout
JsonOpt = Annotated[bool, typer.Option("--json", help="Print the result as JSON on stdout.")]
#: ``--quiet`` / ``-q``
QuietOpt = Annotated[bool, typer.Option("--quiet", "-q", help="No progress bar or table.")]
#: ``--lane-width``: lane numbers from positions
LaneWidthOpt = Annotated[
    str | None, typer.Option("--lane-width", help="Lane width for lane numbers ('6 in').")
]


def out_option(writes: str, *, required: bool = False) -> Any:
    """``--out DIR`` with the files the command writes there (``writes``)."""
    opt = typer.Option("--out", help=f"Write {writes} here.")
    return Annotated[Path, opt] if required else Annotated[Path | None, opt]
