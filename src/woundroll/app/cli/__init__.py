"""The ``woundroll`` command line (``woundroll --help``).

:mod:`~woundroll.app.cli.entry` holds the command group (:data:`app`) and :func:`main`; one
module per command group adds its commands; :mod:`~woundroll.app.cli.console` is how they all
print, warn and fail. ``app`` and ``main`` load on first use, so that importing one command's
module does not import them all.
"""

from typing import Any


def __getattr__(name: str) -> Any:
    if name in ("app", "main"):
        from woundroll.app.cli import entry

        return getattr(entry, name)
    raise AttributeError(f"module 'woundroll.app.cli' has no attribute {name!r}")


__all__ = ["app", "main"]
