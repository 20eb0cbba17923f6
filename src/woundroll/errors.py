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
        self.field = field

    def __str__(self) -> str:
        return f"{self.field}: {self.message}" if self.field else self.message

    def at(self, prefix: str) -> InputError:
        """Return the same error with ``prefix`` prepended to its field path."""
        field = f"{prefix}.{self.field}" if self.field else prefix
        return type(self)(self.message, field)


class ConvergenceError(WoundrollError, RuntimeError):
    """A numerical method did not converge; the message says which and how far it got."""
