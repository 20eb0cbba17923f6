"""``woundroll calibrate-head``: the head's unknown dimension calibrated on the block through
the roll model that reads the rolls (:mod:`woundroll.contact.block`).

Registered in :mod:`woundroll.app.cli`; heavy imports happen inside the command.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Annotated, Any

import typer

from woundroll.app.cli.console import escape, table
from woundroll.app.cli.options import JsonOpt
from woundroll.errors import ConvergenceError, InputError


def instrument_file_text(
    preset_text: str, unknown: str, value: float, model: str, source: str
) -> str:
    """The preset's TOML text with ``unknown`` set to ``value`` [m] (written in mm), the
    calibration model and the value's source line replaced (other lines kept as written)."""
    line = f'{unknown} = "{value * 1e3:.4f} mm"'
    lines = preset_text.splitlines()
    out: list[str] = []
    table = ""
    seen = {"value": False, "model": False, "source": False}
    for ln in lines:
        head = re.match(r"\s*\[([^\]]+)\]", ln)
        if head:
            if table == "" and not seen["model"]:
                out.append(f'calibration_model = "{model}"')
                seen["model"] = True
            table = head.group(1).strip()
        key = re.match(r"\s*([A-Za-z_]+)\s*=", ln)
        k = key.group(1) if key else None
        if table == "" and k == unknown:
            out.append(f"{line}  # calibrated: woundroll calibrate-head --model {model}")
            seen["value"] = True
            continue
        if table == "" and k == "calibration_model":
            out.append(f'calibration_model = "{model}"')
            seen["model"] = True
            continue
        if table == "sources" and k == unknown:
            out.append(f"{unknown} = {_toml_str(source)}")
            seen["source"] = True
            continue
        out.append(ln)
    if not seen["model"]:
        out.append(f'calibration_model = "{model}"')
    if not seen["value"]:
        raise InputError(f"the instrument file has no {unknown} line", "--unknown")
    if not seen["source"]:
        out.append(f"\n[sources]\n{unknown} = {_toml_str(source)}")
    return "\n".join(out) + "\n"


def _toml_str(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def calibrate_head_cmd(
    instrument: Annotated[
        str, typer.Option("--instrument", help="Instrument preset (see the [tester] docs).")
    ] = "rho-meter",
    model: Annotated[
        str | None,
        typer.Option(
            "--model",
            help="Roll model that reads the block (2d, 2d+cmd-spread, 3d); default: the "
            "registry's, the model that reads the rolls.",
        ),
    ] = None,
    unknown: Annotated[
        str,
        typer.Option(
            "--unknown", help="The head dimension to solve for: head_radius, head_length."
        ),
    ] = "head_radius",
    target: Annotated[
        float | None, typer.Option("--target", help="Block reading to match (default: 77 Rho).")
    ] = None,
    write: Annotated[
        Path | None,
        typer.Option("--write", help="Write the calibrated instrument file (TOML) here."),
    ] = None,
    as_json: JsonOpt = False,
) -> None:
    """Calibrate the head on its calibration block through the roll model that reads rolls.

    The block (an isotropic solid, every modulus from its E and nu) is read by the same roll
    model as the rolls; the head's unknown dimension is solved so that it reads the device
    manual's 77 Rho. Prints the value, the block's reading before and after, and the
    [tester] line to paste; --write saves the instrument file with its source.
    """

    from woundroll.app.cli.console import fail, out
    from woundroll.contact.block import calibrate_head_in_model
    from woundroll.instruments import get_instrument
    from woundroll.pipeline.vocabulary import versioned
    from woundroll.util.output import strict_json

    try:
        inst = get_instrument(instrument, "--instrument")
        try:
            cal = calibrate_head_in_model(inst, model=model, unknown=unknown, target=target)
        except InputError as exc:  # name the option the user wrote
            fld = (exc.field or "").replace("calibration.", "--")
            raise InputError(exc.message, fld) from None
        text = None
        if write is not None:
            from woundroll.instruments.definitions import _data_dir

            preset = (_data_dir() / f"{inst.name}.toml").read_text(encoding="utf-8")
            text = instrument_file_text(preset, unknown, cal.value, cal.block.model, cal.source)
            try:
                write.write_text(text, encoding="utf-8")
            except OSError as exc:
                raise InputError(
                    f"cannot write {write}: {exc.strerror or exc}", "--write"
                ) from None
    except InputError as exc:
        fail(exc, 2)
    except ConvergenceError as exc:
        fail(exc, 1)
    d: dict[str, Any] = cal.to_dict()
    if write is not None:
        d["written"] = str(write)
    if as_json:
        sys.stdout.write(strict_json(versioned(d)) + "\n")
        return
    t = table(
        "quantity",
        "value",
        title=escape(f"{inst.title or inst.name}: head calibrated in '{cal.block.model}'"),
    )
    t.add_row(escape(unknown), f"{cal.before * 1e3:.3f} mm -> {cal.value * 1e3:.3f} mm")
    t.add_row("block reading (FD), file's head", f"{cal.block_before.reading:.2f} Rho")
    t.add_row(
        "block reading (FD), calibrated", f"{cal.block.reading:.2f} Rho (target {cal.target:g})"
    )
    t.add_row("block reading (energy), calibrated", f"{cal.block.reading_energy:.2f} Rho")
    t.add_row("block solves", f"{cal.evaluations}")
    out.print(t)
    out.print(
        escape(
            f'[tester] line: {unknown} = "{cal.value * 1e3:.3f} mm"   '
            f'calibration_model = "{cal.block.model}"'
        ),
        highlight=False,
    )
    if not 0.25 <= cal.value / cal.before <= 4.0:
        out.print(
            escape(
                f"warning: the calibrated {unknown} is {cal.value / cal.before:.2g} x the file's: "
                "this model is unlikely to represent this head on its block"
            ),
            highlight=False,
        )
    out.print(
        "note: the block does not pin a roll's reading: on the Table 2 rolls the head radius "
        "moves the reading by about 0.4 % (docs/instruments.md).",
        highlight=False,
    )
    if write is not None:
        out.print(f"wrote {escape(str(write))}", highlight=False)


def calibrate_cmd(
    readings: Annotated[
        str,
        typer.Argument(
            help="CSV of readings: a 'case' column naming each roll as given to --cases (the "
            "case file's stem) and a 'reading' column in the instrument's unit."
        ),
    ],
    cases: Annotated[
        list[str],
        typer.Option(
            "--cases",
            help="The rolls' case files (known winding settings), one --cases per roll.",
        ),
    ],
    fit: Annotated[
        list[str],
        typer.Option(
            "--fit",
            help="What is unknown: head_length, K2_scale, slip_fraction, mu (repeat for two).",
        ),
    ],
    out_file: Annotated[
        Path | None,
        typer.Option("--out", help="Write the fitted values (TOML, with standard errors) here."),
    ] = None,
    roll_scatter: Annotated[
        float,
        typer.Option(
            "--roll-scatter",
            help="SD of the mean reading between rolls wound alike, in the reading's unit "
            "(default 0: the leave-one-out test allows the tester's repeatability only).",
        ),
    ] = 0.0,
    as_json: JsonOpt = False,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="No progress.")] = False,
) -> None:
    """Calibrate the model on a mill's own rolls: fit what is unknown to readings of rolls of
    known winding settings, with standard errors and leave-one-out prediction errors."""

    from woundroll.app.cli.console import err, fail, out
    from woundroll.inverse.site_calibration import calibrate_site
    from woundroll.pipeline.vocabulary import versioned
    from woundroll.util.output import strict_json

    live = not (quiet or as_json) and err.is_terminal  # a pipe or a log gets no progress

    def progress(stage: str, runs: int) -> None:
        if live:
            err.print(f"\r{stage}: {runs} full model runs", end="", highlight=False)

    try:
        cal = calibrate_site(readings, cases, fit, roll_scatter=roll_scatter, progress=progress)
        if out_file is not None:
            try:
                out_file.write_text(cal.to_toml(), encoding="utf-8")
            except OSError as exc:
                raise InputError(
                    f"cannot write {out_file}: {exc.strerror or exc}", "--out"
                ) from None
    except InputError as exc:
        if live:
            err.print("")
        fail(exc, 2)
    except ConvergenceError as exc:
        if live:
            err.print("")
        fail(exc, 1)
    if live:
        err.print("")
    if as_json:
        sys.stdout.write(strict_json(versioned(cal.to_dict())) + "\n")
        return
    u = cal.scale_name
    t = table("parameter", "fitted", "1 SE", title="site calibration")
    for p, v, e in zip(cal.params, cal.values, cal.standard_errors, strict=True):
        k = 1e3 if p.unit == "m" else 1.0
        unit = " mm" if p.unit == "m" else ""
        t.add_row(escape(p.name), f"{v * k:.4g}{unit}", f"{e * k:.2g}{unit}")
    out.print(t)
    r = table(
        "roll",
        "readings",
        f"measured [{u}]",
        f"model before [{u}]",
        f"fitted [{u}]",
        f"left out: predicted [{u}]",
        f"error [{u}]",
        f"allowed [{u}]",
        title="rolls",
    )
    for i, lab in enumerate(cal.labels):
        r.add_row(
            escape(lab),
            f"{int(cal.n_readings[i])}",
            f"{cal.measured_mean[i]:.2f}",
            f"{cal.before[i]:.2f}",
            f"{cal.fitted[i]:.2f}",
            f"{cal.loo_predicted[i]:.2f}",
            f"{cal.loo_error[i]:+.2f}",
            f"{cal.loo_allowed[i]:.2f}",
        )
    out.print(r)
    rep = "n/a" if cal.scatter_repeat is None else f"{cal.scatter_repeat:.2f}"
    out.print(
        escape(f"scatter: {cal.scatter_fit:.2f} {u} about the fit, {rep} {u} between repeats"),
        highlight=False,
    )
    out.print(escape(cal.verdict), highlight=False)
    for note in cal.notes:
        out.print(f"note: {escape(note)}", highlight=False)
    if out_file is not None:
        out.print(f"wrote {escape(str(out_file))}", highlight=False)


def register(app: typer.Typer) -> None:
    app.command("calibrate-head")(calibrate_head_cmd)
    app.command("calibrate")(calibrate_cmd)
