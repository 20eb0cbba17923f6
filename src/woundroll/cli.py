"""The ``woundroll`` command line.

``woundroll run CASE`` runs a case file or a bundled case; ``woundroll cases`` lists the
bundled ones; ``woundroll materials`` lists material presets; ``woundroll fit-stack``
fits radial-modulus laws to a stack test. Input errors print one line naming the field
and exit with status 2; a solver that does not converge exits with status 1.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from woundroll.errors import ConvergenceError, InputError

if TYPE_CHECKING:
    from woundroll.pipeline import RunResult


class _Commands(typer.core.TyperGroup):
    """The ``woundroll`` command group; a usage error (an option's value out of range, an
    unknown option, a missing argument) is one line naming the option, exit 2, like every
    other input error, instead of click's usage block."""

    def main(  # type: ignore[override]
        self,
        args: Any = None,
        prog_name: str | None = None,
        complete_var: str | None = None,
        standalone_mode: bool = True,
        **extra: Any,
    ) -> Any:
        try:  # typer >= 0.20 parses with its own copy of click
            from typer._click import exceptions as click
        except ImportError:  # pragma: no cover - older typer: click itself
            from click import exceptions as click  # type: ignore[no-redef]

        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except click.NoArgsIsHelpError as exc:  # bare `woundroll CMD`: its help
            exc.show()
            sys.exit(exc.exit_code)
        except click.UsageError as exc:
            where = exc.ctx.command_path if exc.ctx is not None else "woundroll"
            msg = f"error: {exc.format_message()} (see '{where} --help')"
            err.print(escape(msg), highlight=False, soft_wrap=True)
            sys.exit(exc.exit_code)
        except click.ClickException as exc:
            exc.show()
            sys.exit(exc.exit_code)
        except typer.Abort:
            err.print("Aborted!", highlight=False)
            sys.exit(1)
        sys.exit(rv if isinstance(rv, int) else 0)


app = typer.Typer(
    cls=_Commands,
    add_completion=False,
    # help texts are plain text: "[kPa]", "[readings]" are units and case sections, not markup
    rich_markup_mode=None,
    no_args_is_help=True,
    help="Wound-roll stresses from winder settings, and the hardness readings they cause.",
)
# emoji=False: ":x:" in a user file name or a CSV header stays text, never an emoji
err = Console(stderr=True, emoji=False)
out = Console(emoji=False)


def _fail(exc: Exception, status: int) -> None:
    err.print(f"[bold red]error:[/] {escape(str(exc))}", highlight=False, soft_wrap=True)
    raise typer.Exit(status)


def _warn(text: str) -> None:
    err.print(f"[yellow]warning:[/] {escape(text)}", highlight=False, soft_wrap=True)


def _version(value: bool) -> None:
    if value:
        from importlib.metadata import PackageNotFoundError, version

        try:
            v = version("woundroll")
        except PackageNotFoundError:  # running from a source tree without installing
            v = "unknown"
        out.print(f"woundroll {v}", highlight=False)
        raise typer.Exit()


@app.callback()
def _main(
    _version_flag: Annotated[
        bool,
        typer.Option(
            "--version", callback=_version, is_eager=True, help="Print the version and exit."
        ),
    ] = False,
) -> None:
    """Wound-roll stresses from winder settings, and the hardness readings they cause."""


@app.command()
def run(
    case: Annotated[
        str, typer.Argument(help="Case file (TOML) or bundled case name (see `woundroll cases`).")
    ],
    set_: Annotated[
        list[str] | None,
        typer.Option("--set", help="Override a case key: dotted.key=value (repeatable)."),
    ] = None,
    out_dir: Annotated[
        Path | None, typer.Option("--out", help="Write result.json and PNG plots here.")
    ] = None,
    as_json: Annotated[
        bool, typer.Option("--json", help="Print the result as JSON on stdout.")
    ] = False,
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
    no_update: Annotated[
        bool,
        typer.Option(
            "--no-update",
            help="Also solve with E_r frozen at its pre-impact value (contact.no_update).",
        ),
    ] = False,
) -> None:
    """Run the models a case asks for: winding, and with a tester section the hardness reading."""
    from woundroll._pool import Interrupted, clean_stop
    from woundroll.case import load_case
    from woundroll.pipeline import run as run_case

    with clean_stop():
        try:
            if report and out_dir is None:
                raise InputError("the report goes into the --out directory: give --out", "--report")
            flags = [("contact.no_update=true", "--no-update")] if no_update else []
            c = load_case(case, [*(set_ or []), *flags])
            if out_dir is not None:
                from woundroll._output import check_out_dir

                check_out_dir(out_dir)  # a bad --out fails now, not after the run
            # the estimate of a long run is for the wait: now; the other warnings follow a
            # run that succeeded (a case that fails prints its error alone)
            for w in c.warnings:
                if w.startswith("long run:"):
                    _warn(w)
            if quiet or as_json or not sys.stderr.isatty():
                result = run_case(c)
            else:
                result = _with_progress(lambda progress: run_case(c, progress=progress))
            written = result.write(out_dir) if out_dir is not None else []
            uq = _cli_diagnose.run_uncertainty(
                c, uncertainty, out_dir, written, quiet or as_json, result.profile
            )
            if report:
                from woundroll.defects import defect_report
                from woundroll.report import write_report

                defects = defect_report(c, winding=result.winding)
                readings = c.measured_readings
                written.append(write_report(result, out_dir, readings=readings, defects=defects))
        except InputError as exc:
            _fail(exc, 2)
        except ConvergenceError as exc:
            _fail(exc, 1)
        except Interrupted as exc:
            err.print(f"stopped by {exc}: workers ended, no output written", highlight=False)
            raise typer.Exit(128 + exc.signum) from None
    for w in c.warnings:
        if not w.startswith("long run:"):
            _warn(w)
    for w in result.warnings:
        if w not in c.warnings:
            _warn(w)
    if as_json:
        sys.stdout.write(_cli_diagnose.json_with_uncertainty(result, uq) + "\n")
        return
    if not quiet:
        _summary(result)
        _cli_diagnose.print_uncertainty(uq)
        for p in written:
            out.print(f"wrote {escape(str(p))}")


def _with_progress(job):  # type: ignore[no-untyped-def]
    """Run ``job(progress)`` under a rich progress bar on stderr (one bar per stage)."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeElapsedColumn(),
        console=err,
        transient=True,
    ) as bar:
        tasks: dict[str, int] = {}

        def progress(stage: str, fraction: float) -> None:
            if stage not in tasks:
                tasks[stage] = bar.add_task(stage, total=1.0)
            bar.update(tasks[stage], completed=min(max(fraction, 0.0), 1.0))

        return job(progress)


def _inputs(case) -> None:  # type: ignore[no-untyped-def]
    """The inputs the run used as given, with their source (defaults counted, listed in
    result.json)."""
    t = Table("input", "value", "source", title="inputs", show_header=True)
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
    t = Table(title=escape(result.case.display_title or "result"), show_header=True)
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


def _num(x: float, spec: str) -> str:
    """``format(x, spec)`` without a minus sign on a value that rounds to zero ("-0.0 kPa"
    at zero tension is a rounding artefact, not a tensile pressure)."""
    text = format(x, spec)
    if text.startswith("-") and not any(c in "123456789" for c in text.split("e")[0]):
        text = text[1:]
    return text


def result_summary(result: RunResult) -> list[tuple[str, str]]:
    """Headline numbers of a run, as (label, formatted value) rows."""
    rows: list[tuple[str, str]] = []
    w = result.winding
    if w is not None:
        rows += [
            ("layers", f"{w.n_layers}"),
            ("outer radius", f"{_num(w.radius[-1] * 100, '.3f')} cm"),
            ("core pressure", f"{_num(w.core_pressure / 1e3, '.1f')} kPa"),
            ("max pressure", f"{_num(-w.sigma_r.min() / 1e3, '.1f')} kPa"),
        ]
    h = result.hardness
    if h is not None:
        d = h.to_dict()
        model = d.get("roll_model") or (c.model if (c := result.contact) else "")
        shown = _num(d["reading"], ".1f")
        if d["saturated"]:
            shown += f" (saturated: the model reads {d['reading_model']:.1f}, off the scale)"
        rows += [
            (f"{d['readout']} reading ({d['instrument']}, roll model {model})", shown),
            (
                "Rho (finite difference / energy)",
                f"{_num(d['rho_fd'], '.1f')} / {_num(d['rho_energy'], '.1f')}",
            ),
            ("impulse", f"{_num(d['impulse_Ns'], '.4f')} N s"),
            ("max depth", f"{_num(d['delta_max_m'] * 1e3, '.3f')} mm"),
            ("contact time", f"{_num(d['contact_time_s'] * 1e3, '.2f')} ms"),
        ]
    c = result.contact
    if c is not None:
        rows += [
            ("roll spring alpha", f"{_num(c.alpha, '.4g')} N/m^2"),
            ("roll spring beta", f"{_num(c.beta, '.4g')} N/m"),
            ("roll spring extrapolated", "yes" if c.extrapolated else "no"),
            ("semi-contact width at max depth", f"{_num(c.semi_contact_width * 1e3, '.3f')} mm"),
        ]
    nu = result.no_update
    if nu is not None:
        d = nu.to_dict()
        rows.append(
            (
                "Rho, no E_r update (FD / energy)",
                f"{_num(d['rho_fd'], '.1f')} / {_num(d['rho_energy'], '.1f')}",
            )
        )
    dy = getattr(result, "dynamic", None)
    if dy is not None:
        rows += [
            ("Rho, FE impact in time", f"{_num(dy.rho, '.1f')}"),
            (
                "impulse / contact time (FE)",
                f"{_num(dy.impulse, '.4f')} N s / {_num(dy.contact_time * 1e3, '.2f')} ms",
            ),
            ("restitution (FE, elastic material)", f"{_num(dy.restitution, '.3f')}"),
        ]
    p = result.profile
    if p is not None:
        st, th = p.rho_stats, p.thickness_stats
        n_sat = int(p.saturated.sum())
        rows += [
            ("CMD sectors", f"{p.z.size}"),
            ("roll model / reading", f"{p.roll_model} / FD (energy model beside it)"),
            (
                "thickness mean / CoV",
                f"{_num(th.mean * 1e6, '.2f')} um / {_num(100 * th.cov, '.2f')} %",
            ),
        ]
        if n_sat:
            rows.append(("saturated sectors (off the scale, excluded)", f"{n_sat}"))
        if st is None:
            rows.append(("Rho statistics", "fewer than two readings on the scale"))
        else:
            rows += [
                ("Rho mean / SD (on the scale)", f"{_num(st.mean, '.1f')} / {_num(st.sd, '.1f')}"),
                ("Rho CoV", f"{_num(100 * st.cov, '.1f')} % ({st.band})"),
                (
                    "Rho min / max / peak-to-peak",
                    f"{_num(st.min, '.1f')} / {_num(st.max, '.1f')} / "
                    f"{_num(st.peak_to_peak, '.1f')}",
                ),
            ]
        n_slack = int(p.slack.sum())
        if n_slack:
            rows.append(("slack sectors (reading set by the E_r floor)", f"{n_slack}"))
        c = p.comparison
        if c is not None:
            ms = c.measured_stats
            r = "n/a" if c.correlation is None else f"{_num(c.correlation, '.2f')}"
            rows += [
                (
                    "measured Rho mean / CoV",
                    f"{_num(ms.mean, '.1f')} / {_num(100 * ms.cov, '.1f')} % ({ms.band})",
                ),
                (
                    "predicted - measured: bias / RMS",
                    f"{_num(c.bias, '+.1f')} / {_num(c.rms, '.1f')}",
                ),
                ("RMS after bias / correlation", f"{_num(c.rms_shape, '.1f')} / {r}"),
            ]
    return rows


@app.command()
def study(
    name: Annotated[
        str,
        typer.Argument(
            help="tension (Figures 14/15), pile-height (16/17), slip (18), all, or dynamic "
            "(the FE impact in time against the 1.5D models)."
        ),
    ],
    out_dir: Annotated[
        Path | None, typer.Option("--out", help="Write study.json and PNG plots here.")
    ] = None,
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
    from woundroll._output import strict_json
    from woundroll.studies import run_study

    def job(progress):  # type: ignore[no-untyped-def]
        return run_study(name, progress=progress, workers=workers, model=model)

    from woundroll._pool import Interrupted, clean_stop

    with clean_stop():  # SIGINT/SIGTERM end the study's worker pool too
        try:
            if quiet or as_json or not sys.stderr.isatty():
                result = job(None)
            else:
                result = _with_progress(job)
            written = result.write(out_dir) if out_dir is not None else []
        except InputError as exc:
            _fail(exc, 2)
        except ConvergenceError as exc:
            _fail(exc, 1)
        except OSError as exc:
            _fail(InputError(f"cannot write to {out_dir}: {exc.strerror or exc}", "--out"), 2)
        except Interrupted as exc:
            err.print(f"stopped by {exc}: workers ended, no output written", highlight=False)
            raise typer.Exit(128 + exc.signum) from None
    if as_json:
        sys.stdout.write(strict_json(result.to_dict()) + "\n")
        return
    wide = out if out.is_terminal else Console(width=160, emoji=False)
    for title, header, rows in result.summary():
        t = Table(*[escape(h) for h in header], title=escape(title))
        for row in rows:
            t.add_row(*[escape(str(c)) for c in row])
        wide.print(t)
    for note in result.notes():
        out.print(f"note: {escape(note)}", highlight=False)
    for p in written:
        out.print(f"wrote {escape(str(p))}")


@app.command()
def cases() -> None:
    """List the bundled cases."""
    from woundroll.case import bundled_cases

    t = Table("name", "title")
    for name, title in bundled_cases().items():
        t.add_row(escape(name), escape(title))
    out.print(t)


@app.command()
def materials() -> None:
    """List the bundled web-material presets and their sources."""
    from woundroll.materials.presets import list_materials

    t = Table("preset", "description", "source")
    for name, table in list_materials().items():
        t.add_row(
            escape(name),
            escape(str(table.get("description", ""))),
            escape(str(table.get("source", ""))),
        )
    out.print(t)


@app.command("fit-stack")
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
) -> None:
    """Fit radial-modulus laws to a stack test and print their parameters and fit quality."""
    if unloading:
        from woundroll.cli_unloading import fit_cycle_cmd

        fit_cycle_cmd(csv_file, as_json, out, _fail)
        return

    from woundroll._output import strict_json
    from woundroll.materials.radial_modulus import read_stack_csv
    from woundroll.materials.stack_fit import FIT_LAWS, check_stack_data, fit_stack

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
        _fail(exc, 2)
    except ConvergenceError as exc:
        _fail(exc, 1)
    if as_json:
        sys.stdout.write(strict_json({k: f.to_dict() for k, f in fits.items()}) + "\n")
        return
    t = Table("law", "R^2", "RMS rel. error", "max rel. error", "case-file table")
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


# the reverse road (readings -> stresses): commands in their own module
from woundroll import cli_diagnose as _cli_diagnose  # noqa: E402

_cli_diagnose.register(app)


# the shop floor and sweeps: commands in their own modules (woundroll.cli_*)
from woundroll import cli_report as _cli_report  # noqa: E402
from woundroll import cli_serve as _cli_serve  # noqa: E402
from woundroll import cli_sweep as _cli_sweep  # noqa: E402

_cli_report.register(app)
_cli_sweep.register(app)
_cli_serve.register(app)

# calibration: the head on its block, and the model on a mill's own rolls
from woundroll import cli_calibrate as _cli_calibrate  # noqa: E402

_cli_calibrate.register(app)


def main() -> None:
    """Entry point of the ``woundroll`` script."""
    app()


if __name__ == "__main__":
    main()
