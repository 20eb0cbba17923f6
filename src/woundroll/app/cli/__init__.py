"""The ``woundroll`` command line (``woundroll --help``).

:mod:`~woundroll.app.cli.entry` holds the command group (:data:`app`) and :func:`main`; one
module per command group adds its commands; :mod:`~woundroll.app.cli.console` is how they all
print, warn and fail. ``app`` loads on first use, so that importing one command's module does
not import them all.
"""

from typing import Any


def main() -> None:
    """Entry point of the ``woundroll`` script: :func:`woundroll.app.cli.entry.main`, with
    the code that dataclasses and typing compile at run time compiled once per machine
    (:mod:`woundroll.util.code_cache`) and no garbage collection while the command starts
    (:mod:`woundroll.util.gc_pause`), both set before the command line's imports."""
    from woundroll.util.code_cache import install
    from woundroll.util.gc_pause import pause

    pause()
    install()
    from woundroll.app.cli.entry import main as entry_main

    entry_main()


def __getattr__(name: str) -> Any:
    if name == "app":
        from woundroll.app.cli import entry

        return getattr(entry, name)
    raise AttributeError(f"module 'woundroll.app.cli' has no attribute {name!r}")


__all__ = ["app", "main"]
