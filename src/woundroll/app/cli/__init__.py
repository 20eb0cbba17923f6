"""The ``woundroll`` command line (``woundroll --help``).

:mod:`~woundroll.app.cli.entry` holds the command group (:data:`app`) and :func:`main`; one
module per command group adds its commands; :mod:`~woundroll.app.cli.console` is how they all
print, warn and fail. ``app`` loads on first use, so that importing one command's module does
not import them all.
"""

import os
import sys
from typing import Any


def main() -> None:
    """Entry point of the ``woundroll`` script: the process's settings
    (:func:`setup_process`), then the command: the plain forms of ``woundroll run`` without
    typer (:mod:`woundroll.app.cli.run_core`), everything else through the command group
    (:func:`woundroll.app.cli.entry.main`)."""
    setup_process()
    from woundroll.app.cli.run_core import plain_run_args

    plain = plain_run_args(sys.argv[1:])
    if plain is not None:
        from woundroll.app.cli.run_core import run_plain

        run_plain(plain)
        return
    from woundroll.app.cli.entry import main as entry_main

    entry_main()


def setup_process() -> None:
    """The command's own process, set before its imports (the library, ``import woundroll``,
    leaves them alone):

    * one BLAS thread for it and the workers it starts (:mod:`woundroll.util.blas`; a value
      of ``OPENBLAS_NUM_THREADS`` the user set is kept);
    * no search for pydantic plugins: woundroll uses none, and the search reads the metadata
      of every installed distribution, 0.1-0.15 s of each run (set
      ``PYDANTIC_DISABLE_PLUGINS`` to any other value, e.g. an empty string, to have them
      loaded);
    * no garbage collection while the command starts (:mod:`woundroll.util.gc_pause`);
    * the code that dataclasses and typing compile at run time compiled once per machine
      (:mod:`woundroll.util.code_cache`).

    Calling it again changes nothing."""
    from woundroll.util.blas import single_thread_process
    from woundroll.util.code_cache import install
    from woundroll.util.gc_pause import pause

    single_thread_process()
    os.environ.setdefault("PYDANTIC_DISABLE_PLUGINS", "__all__")
    pause()
    install(sys.argv[1] if len(sys.argv) > 1 else "")


def __getattr__(name: str) -> Any:
    if name == "app":
        from woundroll.app.cli import entry

        return getattr(entry, name)
    raise AttributeError(f"module 'woundroll.app.cli' has no attribute {name!r}")


__all__ = ["app", "main"]
