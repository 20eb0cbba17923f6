"""``woundroll cases``, ``materials`` and ``fit-stack``: what is bundled, and the web's
radial-modulus law fitted to a stack test."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from woundroll.app.cli.console import err, escape, fail, out, table
from woundroll.errors import ConvergenceError, InputError


def cases() -> None:
    """List the bundled cases."""
    from woundroll.case import bundled_cases

    t = table("name", "title")
    for name, title in bundled_cases().items():
        t.add_row(escape(name), escape(title))
    out.print(t)


def materials() -> None:
    """List the bundled web-material presets and their sources."""
    from woundroll.materials.presets import list_materials

    t = table("preset", "description", "source")
    for name, preset in list_materials().items():
        t.add_row(
            escape(name),
            escape(str(preset.get("description", ""))),
            escape(str(preset.get("source", ""))),
        )
    out.print(t)


def fit_stack_cmd(
    csv_file: Annotated[
        Path,
        typer.Argument(
            help="CSV with columns strain and pressure (units in the header: 'pressure [kPa]')."
        ),
    ],
    law: Annotated[str, typer.Option(help="pfeiffer, polynomial, constant, or all.")] = "all",
    as_json: Annotated[bool, typer.Option("--json")] = False,
    unloading: Annotated[
        bool,
        typer.Option(
            "--unloading",
            help="One loading/unloading cycle: fit Pfeiffer loading and the unloading branch "
            "(web.radial_unloading).",
        ),
    ] = False,
    creep: Annotated[
        bool,
        typer.Option(
            "--creep",
            help="A creep test (time, strain at a constant pressure) or relaxation test (time, "
            "pressure at a constant strain): fit [storage] radial_creep (power, prony or all).",
        ),
    ] = False,
) -> None:
    """Fit radial-modulus laws to a stack test and print their parameters and fit quality."""
    if creep:
        from woundroll.app.cli.creep import fit_creep_cmd

        fit_creep_cmd(csv_file, law, as_json, out, fail)
        return
    if unloading:
        from woundroll.app.cli.unloading import fit_cycle_cmd

        fit_cycle_cmd(csv_file, as_json, out, fail)
        return

    from woundroll.materials.radial_modulus import read_stack_csv
    from woundroll.materials.stack_fit import FIT_LAWS, check_stack_data, fit_stack
    from woundroll.pipeline.vocabulary import versioned
    from woundroll.util.output import strict_json

    try:
        eps, p = read_stack_csv(csv_file, "CSV_FILE")
        try:
            check_stack_data(eps, p)
        except InputError as exc:
            # strain rising, then falling in file order: a loading/unloading cycle
            top = int(eps.argmax())
            hint = (
                "; this looks like a loading/unloading cycle: fit it with "
                "`woundroll fit-stack --unloading`"
                if 0 < top < eps.size - 1 and bool((eps[top + 1 :] <= eps[top:-1]).all())
                else ""
            )
            raise InputError(f"{csv_file.name}: {exc.message}{hint}", "CSV_FILE") from None
        laws = FIT_LAWS if law == "all" else (law,)
        fits = {}
        for name in laws:
            try:
                fits[name] = fit_stack(eps, p, name)
            except InputError as exc:
                if law != "all":
                    raise
                err.print(f"{name}: {escape(exc.message)}", highlight=False, soft_wrap=True)
        if not fits:
            raise InputError("no law could be fitted to this stack test (see above)", "CSV_FILE")
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:
        fail(exc, 1)
    if as_json:
        sys.stdout.write(strict_json(versioned({k: f.to_dict() for k, f in fits.items()})) + "\n")
        return
    t = table("law", "R^2", "RMS rel. error", "max rel. error", "case-file table")
    for name, f in fits.items():
        t.add_row(
            name,
            f"{f.r2:.5f}",
            f"{f.rms_rel_error:.2%}",
            f"{f.max_rel_error:.2%}",
            escape(f.toml()),
        )
    out.print(t)
    for name, f in fits.items():  # the fit's covariance, ready for the case's [uncertainty]
        if f.uncertainty_toml():
            out.print(escape(f"{name}: [uncertainty] (1 SD)\n{f.uncertainty_toml()}"))


def register(app: typer.Typer) -> None:
    """Add ``cases``, ``materials`` and ``fit-stack`` to the ``woundroll`` app."""
    app.command("cases")(cases)
    app.command("materials")(materials)
    app.command("fit-stack")(fit_stack_cmd)
