"""``woundroll run CASE``: the forward chain on one case, with its outputs (the command's
options; its body: :mod:`woundroll.app.cli.run_core`)."""

from __future__ import annotations

from typing import Annotated

import typer

from woundroll.app.cli.options import CaseArg, JsonOpt, SetOpt, out_option
from woundroll.app.cli.run_core import run_command


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
    run_command(case, set_, out_dir, as_json, quiet, uncertainty, report, fields, no_update)


def register(app: typer.Typer) -> None:
    """Add ``run`` to the ``woundroll`` app."""
    app.command("run")(run)
