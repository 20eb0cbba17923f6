"""The exception family of woundroll.

Every problem with what a user gave us (a case file, a CLI option, an argument of a
public function) raises :class:`InputError` or a subclass, naming the offending field.
The CLI turns any :class:`InputError` into a one-line message and exit status 2.
A numerical method that fails to converge raises :class:`ConvergenceError`.
"""

from __future__ import annotations


class WoundrollError(Exception):
    """Base class of every error woundroll raises on purpose."""


class InputError(WoundrollError, ValueError):
    """Bad input: a wrong value, unit, dimension, key or file.

    Parameters
    ----------
    message : str
        What is wrong, in words an engineer understands.
    field : str, optional
        Dotted path of the offending input (``"web.thickness"``, ``"tester.head_radius"``).
    """

    def __init__(self, message: str, field: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.field = _printable(field) if field is not None else None

    def __str__(self) -> str:
        msg = _printable(self.message)
        return f"{self.field}: {msg}" if self.field else msg

    def at(self, prefix: str) -> InputError:
        """Return the same error with ``prefix`` prepended to its field path."""
        field = f"{prefix}.{self.field}" if self.field else prefix
        return type(self)(self.message, field)


def _printable(text: str) -> str:
    """``text`` on one line: control characters (a newline in a quoted TOML key) escaped."""
    text = str(text)
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else c.encode("unicode_escape").decode() for c in text)


class ConvergenceError(WoundrollError, RuntimeError):
    """A numerical method did not converge; the message says which and how far it got."""
