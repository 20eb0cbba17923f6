"""Units at the edges: parse quantities given with units into SI floats.

Case files and the CLI accept strings such as ``"4.62 kPa"``, ``"2 pli"``, ``"3 mil"``,
``"30 psi"``. A bare number means SI. Everything inside woundroll is SI
(m, kg, s, N, Pa).

Units beyond pint's defaults
----------------------------
``pli``
    pound-force per linear inch, the US unit of web tension and nip load
    (1 pli = 175.127 N/m).
``mil``
    one thousandth of an inch (25.4 um), the US unit of web thickness. pint's own
    ``mil`` is an angle; woundroll redefines it.
``Rho``
    not defined here: a Rho-meter reading is not a physical unit but a scaled
    deceleration (1 Rho = 3.76 g), handled in :mod:`woundroll.instruments`.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from functools import cache
from typing import Any

import numpy as np
import pint

from woundroll.errors import InputError

ureg = pint.UnitRegistry()
ureg.define("pli = pound_force / inch")
# pint's "mil" is the angular mil (pi/32000 rad); in web handling a mil is 0.001 inch
# ("thou" in pint). Unit strings are rewritten before parsing.
_MIL = re.compile(r"\bmils?\b")
ureg.define("gsm = gram / meter ** 2")

#: Named dimensions, as used in error messages and by :func:`to_si`.
DIMENSIONS: dict[str, str] = {
    "length": "[length]",
    "mass": "[mass]",
    "time": "[time]",
    "force": "[force]",
    "pressure": "[pressure]",
    "force_per_length": "[force] / [length]",
    "stiffness": "[force] / [length]",
    "force_per_area": "[force] / [length] ** 2",
    "density": "[mass] / [length] ** 3",
    "velocity": "[length] / [time]",
    "energy": "[energy]",
    "frequency": "1 / [time]",
    "bending_stiffness": "[force] * [length] ** 2",
    "dimensionless": "",
}

_EXAMPLES = {
    "length": "'0.01 cm', '3 mil', '12 um'",
    "mass": "'125 g', '0.125 kg'",
    "time": "'1 ms'",
    "force": "'26.7 N', '6 lbf'",
    "pressure": "'4.62 kPa', '30 psi', '5 GPa'",
    "force_per_length": "'2 pli', '350 N/m'",
    "stiffness": "'28 N/cm'",
    "force_per_area": "'1e9 N/m^2'",
    "density": "'1.4 g/cm^3'",
    "velocity": "'1.1 m/s'",
    "energy": "'0.08 J'",
    "frequency": "'149.5 rad/s', '24 Hz'",
    "bending_stiffness": "'5.8e5 N m^2'",
    "dimensionless": "'0.3'",
}


@cache
def _dimensionality(kind: str):
    spec = DIMENSIONS[kind]
    return ureg.Quantity(1.0).dimensionality if not spec else ureg.get_dimensionality(spec)


def parse_quantity(value: Any, field: str | None = None) -> pint.Quantity:
    """Parse ``value`` (str, number or pint Quantity) into a pint Quantity.

    A bare number (int, float, or a string holding only a number) is returned
    dimensionless; :func:`to_si` reads it as SI.
    """
    if isinstance(value, pint.Quantity):
        return value
    if isinstance(value, bool):
        raise InputError(f"expected a quantity, got the boolean {value!r}", field)
    if isinstance(value, int | float | np.integer | np.floating):
        return ureg.Quantity(float(value))
    if not isinstance(value, str):
        raise InputError(f"expected a number or a quantity string, got {value!r}", field)
    text = value.strip()
    if not text:
        raise InputError("empty value", field)
    text = _MIL.sub("thou", text)
    try:
        q = ureg.Quantity(text)
    except pint.errors.UndefinedUnitError as exc:
        raise InputError(f"unknown unit in {value!r} ({exc})", field) from None
    except Exception:  # pint raises a variety of parser errors
        raise InputError(f"cannot read {value!r} as a quantity", field) from None
    if not isinstance(q, pint.Quantity):  # a plain number string
        q = ureg.Quantity(float(q))
    return q


def to_si(value: Any, kind: str, field: str | None = None, *, bare_is_si: bool = True) -> float:
    """Convert ``value`` to a float in SI units of dimension ``kind``.

    Parameters
    ----------
    value : str, float, int or pint.Quantity
        ``"4.62 kPa"``, ``"2 pli"``, ``0.0001`` ...; a bare number is taken as SI.
    kind : str
        A key of :data:`DIMENSIONS` (``"length"``, ``"pressure"`` ...).
    field : str, optional
        Dotted name used in error messages.

    Raises
    ------
    InputError
        Unknown unit, wrong dimension, or a value that is not finite.
    """
    q = parse_quantity(value, field)
    target = _dimensionality(kind)
    if kind == "dimensionless":
        if not q.dimensionless:
            raise InputError(
                f"{value!r} must be a plain number (it has dimension {q.dimensionality})", field
            )
        mag = float(q.to("").magnitude)
    elif q.unitless:
        if not bare_is_si:
            raise InputError(f"needs a unit (e.g. {_EXAMPLES[kind]})", field)
        mag = float(q.magnitude)
    elif q.dimensionality != target:
        raise InputError(
            f"{value!r} is not a {kind.replace('_', ' ')} "
            f"(it has dimension {q.dimensionality}); use e.g. {_EXAMPLES[kind]}",
            field,
        )
    else:
        mag = float(q.to_base_units().magnitude)
    if not math.isfinite(mag):
        raise InputError(f"must be a finite number, got {value!r}", field)
    return mag


def to_si_array(
    values: Sequence[Any] | np.ndarray, kind: str, field: str | None = None
) -> np.ndarray:
    """Vector form of :func:`to_si`; every entry must be finite."""
    return np.array([to_si(v, kind, f"{field}[{i}]") for i, v in enumerate(values)], dtype=float)


def check_positive(value: float, field: str, *, allow_zero: bool = False) -> float:
    """Raise :class:`InputError` unless ``value`` is > 0 (or >= 0 with ``allow_zero``)."""
    if not math.isfinite(value):
        raise InputError(f"must be a finite number, got {value}", field)
    if value < 0 or (value == 0 and not allow_zero):
        raise InputError(
            f"must be {'zero or ' if allow_zero else ''}positive, got {value:g}", field
        )
    return value


def unit_scale(unit: str, kind: str, field: str | None = None) -> float:
    """SI value of one ``unit`` (``"mil"`` -> 2.54e-5), checked against ``kind``."""
    return to_si(f"1 {unit}", kind, field)
