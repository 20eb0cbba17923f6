"""The ``woundroll`` command line: the command group and its entry point.

Each command group lives in its own module of :mod:`woundroll.app.cli` and adds itself with
``register(app)``: ``run``, ``study``, ``cases``/``materials``/``fit-stack``, the reverse road
(``readings``, ``diagnose``, ``defects``, ``design``), ``report``, ``sweep``, ``serve`` and
``calibrate-head``/``calibrate``. Input errors print one line naming the field and exit with
status 2; a solver that does not converge exits with status 1 (:mod:`~woundroll.app.cli.console`).
"""

from __future__ import annotations

import copy
import sys
from typing import Annotated, Any

from woundroll.app.cli import setup_process
from woundroll.util.blas import single_thread_process
from woundroll.util.gc_pause import resume as resume_gc

# one BLAS thread for the command and its worker processes, set before NumPy loads
# (woundroll.util.blas: OpenBLAS's threads made the models' small solves up to 1000x slower
# on a loaded 2-core machine); OPENBLAS_NUM_THREADS set by the user is kept
single_thread_process()

import typer  # noqa: E402

from woundroll.app.cli import (  # noqa: E402
    calibrate,
    diagnose,
    materials,
    report,
    run,
    schema,
    serve,
    study,
    sweep,
)
from woundroll.app.cli.console import err, escape, out  # noqa: E402


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
    ctx: typer.Context,
    _version_flag: Annotated[
        bool,
        typer.Option(
            "--version", callback=_version, is_eager=True, help="Print the version and exit."
        ),
    ] = False,
) -> None:
    """Wound-roll stresses from winder settings, and the hardness readings they cause."""
    if ctx.invoked_subcommand != "run":  # run resumes once its case is read
        resume_gc()


for _group in (run, study, materials, diagnose, report, sweep, serve, calibrate, schema):
    _group.register(app)


def main() -> None:
    """Entry point of the ``woundroll`` command group: the process's settings
    (:func:`woundroll.app.cli.setup_process`), then the command."""
    setup_process()
    _app_for(sys.argv[1:])()


def _app_for(args: list[str]) -> typer.Typer:
    """The group that runs ``woundroll ARGS``: :data:`app` with only the command named by
    ``args[0]`` when it names one, else :data:`app` itself.

    Typer turns every command of a group into click's objects before it parses the command
    line: 0.04-0.09 s for this group's 20 commands against 0.004 s for one (issue 23
    item 1; ``woundroll run`` is the command a sweep or a script calls thousands of times).
    The one command's help, options, messages and exit codes are those of the whole group
    (the same callback, settings and class); anything else (``--help``, ``--version``, a
    misspelt command and its suggestions) goes through the whole group."""
    name = args[0] if args else None
    chosen = [c for c in app.registered_commands if c.name == name]
    if not chosen:
        return app
    one = copy.copy(app)
    one.registered_commands = chosen
    one.registered_groups = []
    return one


if __name__ == "__main__":
    main()
