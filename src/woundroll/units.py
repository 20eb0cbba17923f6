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
import sys
from collections.abc import Sequence
from functools import cache
from typing import TYPE_CHECKING, Any

import numpy as np

from woundroll.errors import InputError

if TYPE_CHECKING:
    import pint

# pint's "mil" is the angular mil (pi/32000 rad); in web handling a mil is 0.001 inch
# ("thou" in pint). Unit strings are rewritten before parsing.
_MIL = re.compile(r"\bmils?\b")


@cache
def registry() -> pint.UnitRegistry:
    """The pint unit registry with woundroll's units, built once on first use.

    Importing pint and building its registry costs 0.3-0.5 s, more than the whole one-roll
    run; the plain unit strings of case files take the table of :data:`_UNITS` instead, and
    pint only parses what that table does not know.
    """
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("pli = pound_force / inch")
    ureg.define("gsm = gram / meter ** 2")
    return ureg


def __getattr__(name: str) -> Any:
    # ``woundroll.units.ureg`` is the registry, built on first use
    if name == "ureg":
        return registry()
    raise AttributeError(f"module 'woundroll.units' has no attribute {name!r}")


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
    "acceleration": "[length] / [time] ** 2",
    "energy": "[energy]",
    "frequency": "1 / [time]",
    "bending_stiffness": "[force] * [length] ** 2",
    "dimensionless": "",
}

# Exponents of (length, mass, time) of each kind: the fast path's dimension check.
_KIND_DIMS: dict[str, tuple[int, int, int]] = {
    "length": (1, 0, 0),
    "mass": (0, 1, 0),
    "time": (0, 0, 1),
    "force": (1, 1, -2),
    "pressure": (-1, 1, -2),
    "force_per_length": (0, 1, -2),
    "stiffness": (0, 1, -2),
    "force_per_area": (-1, 1, -2),
    "density": (-3, 1, 0),
    "velocity": (1, 0, -1),
    "acceleration": (1, 0, -2),
    "energy": (2, 1, -2),
    "frequency": (0, 0, -1),
    "bending_stiffness": (3, 1, -2),
    "dimensionless": (0, 0, 0),
}

_LBF = 0.45359237 * 9.80665  # pound-force [N] (exact by definition)
_INCH = 0.0254
# The units of the fast path: SI value of one unit and its (length, mass, time) exponents.
# Exact factors as pint defines them; tests/test_units.py checks every entry against pint.
_BASE_UNITS: dict[str, tuple[float, tuple[int, int, int]]] = {
    "m": (1.0, (1, 0, 0)),
    "g": (1e-3, (0, 1, 0)),
    "s": (1.0, (0, 0, 1)),
    "N": (1.0, (1, 1, -2)),
    "Pa": (1.0, (-1, 1, -2)),
    "J": (1.0, (2, 1, -2)),
    "Hz": (1.0, (0, 0, -1)),
}
_PREFIXES = {"G": 1e9, "M": 1e6, "k": 1e3, "c": 1e-2, "m": 1e-3, "u": 1e-6, "µ": 1e-6, "n": 1e-9}
_UNITS: dict[str, tuple[float, tuple[int, int, int]]] = dict(_BASE_UNITS)
for _p, _f in _PREFIXES.items():
    for _u, (_v, _d) in _BASE_UNITS.items():
        if _p == "c" and _u != "m":
            continue
        _UNITS[_p + _u] = (_f * _v, _d)
_UNITS["μm"] = _UNITS["µm"]  # Greek mu and micro sign
_UNITS.update(
    {
        "rad": (1.0, (0, 0, 0)),
        "%": (0.01, (0, 0, 0)),
        "percent": (0.01, (0, 0, 0)),
        "kg": (1.0, (0, 1, 0)),
        "in": (_INCH, (1, 0, 0)),
        "inch": (_INCH, (1, 0, 0)),
        "ft": (12 * _INCH, (1, 0, 0)),
        "thou": (1e-3 * _INCH, (1, 0, 0)),
        "lb": (0.45359237, (0, 1, 0)),
        "lbf": (_LBF, (1, 1, -2)),
        "psi": (_LBF / _INCH**2, (-1, 1, -2)),
        "ksi": (1e3 * _LBF / _INCH**2, (-1, 1, -2)),
        "pli": (_LBF / _INCH, (0, 1, -2)),
        "bar": (1e5, (-1, 1, -2)),
        "mbar": (1e2, (-1, 1, -2)),
        "gsm": (1e-3, (-2, 1, 0)),
        "min": (60.0, (0, 0, 1)),
        "h": (3600.0, (0, 0, 1)),
        "d": (86400.0, (0, 0, 1)),  # storage times ("30 d") without pint
        "day": (86400.0, (0, 0, 1)),
    }
)
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_FACTOR = r"([A-Za-z%µμ]+)(?:\s*(?:\^|\*\*)\s*([-+]?\d+))?"
_FAST = re.compile(rf"\s*({_NUMBER}|nan|inf)\s*(.*?)\s*", re.IGNORECASE)
_FACTOR_RE = re.compile(rf"\s*{_FACTOR}\s*")


def _fast_unit(text: str) -> tuple[float, tuple[int, int, int]] | None:
    """Scale and dimension of a plain unit expression (``"N/m"``, ``"g/cm^3"``, ``"N m^2"``):
    factors of :data:`_UNITS` with integer powers, at most one ``/`` before the last factor.
    None for anything else (pint parses it)."""
    num, slash, den = text.partition("/")
    if "/" in den:
        return None
    scale, dims = 1.0, [0, 0, 0]
    for part, sign in ((num, 1), (den, -1)) if slash else ((num, 1),):
        factors = [f for f in re.split(r"\s*(?<!\*)\*(?!\*)\s*|\s+(?![\^*])", part.strip()) if f]
        if sign == -1 and len(factors) != 1:
            return None
        if sign == 1 and slash and num.strip() == "1":
            continue
        for f in factors:
            m = _FACTOR_RE.fullmatch(f)
            if m is None or m.group(1) not in _UNITS:
                return None
            v, d = _UNITS[m.group(1)]
            e = sign * (int(m.group(2)) if m.group(2) else 1)
            scale *= v**e
            dims = [a + e * b for a, b in zip(dims, d, strict=True)]
    return scale, (dims[0], dims[1], dims[2])


def _fast_parse(value: Any) -> tuple[float, tuple[int, int, int]] | None:
    """SI magnitude and (length, mass, time) exponents of a number or a plain quantity
    string; None when pint must parse it."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float | np.integer | np.floating):
        return float(value), (0, 0, 0)
    if not isinstance(value, str):
        return None
    m = _FAST.fullmatch(value)
    if m is None:
        return None
    unit = _MIL.sub("thou", m.group(2))
    if not unit:
        return float(m.group(1)), (0, 0, 0)
    parsed = _fast_unit(unit)
    if parsed is None:
        return None
    return float(m.group(1)) * parsed[0], parsed[1]


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
    "acceleration": "'9.81 m/s^2'",
    "energy": "'0.08 J'",
    "frequency": "'149.5 rad/s', '24 Hz'",
    "bending_stiffness": "'5.8e5 N m^2'",
    "dimensionless": "'0.3'",
}


@cache
def _dimensionality(kind: str) -> Any:
    ureg = registry()
    spec = DIMENSIONS[kind]
    return ureg.Quantity(1.0).dimensionality if not spec else ureg.get_dimensionality(spec)


def _is_quantity(value: Any) -> bool:
    pint = sys.modules.get("pint")  # a pint Quantity exists only once pint is imported
    return pint is not None and isinstance(value, pint.Quantity)


def parse_quantity(value: Any, field: str | None = None) -> pint.Quantity:
    """Parse ``value`` (str, number or pint Quantity) into a pint Quantity.

    A bare number (int, float, or a string holding only a number) is returned
    dimensionless; :func:`to_si` reads it as SI.
    """
    if _is_quantity(value):
        return value
    import pint

    ureg = registry()
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


def _finite(mag: float, value: Any, field: str | None) -> float:
    if not math.isfinite(mag):
        raise InputError(f"must be a finite number, got {value!r}", field)
    return mag


def quantity_kind(
    value: Any, kinds: Sequence[str], field: str | None = None
) -> tuple[str | None, float]:
    """The first of ``kinds`` whose dimension ``value`` has, and its SI magnitude.

    ``("", magnitude)`` for a bare number, ``(None, nan)`` when it has none of ``kinds``;
    :class:`InputError` for an unreadable or non-finite value.
    """
    fast = _fast_parse(value)
    if fast is not None:
        mag, dims = fast
        if not (isinstance(value, str) and _FAST.fullmatch(value)[2]):
            return "", _finite(mag, value, field)
        for kind in kinds:
            if _KIND_DIMS[kind] == dims:
                return kind, _finite(mag, value, field)
    q = parse_quantity(value, field)
    if q.unitless:
        return "", _finite(float(q.magnitude), value, field)
    for kind in kinds:
        if kind != "dimensionless" and q.dimensionality == _dimensionality(kind):
            return kind, _finite(float(q.to_base_units().magnitude), value, field)
    return None, math.nan


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
    fast = _fast_parse(value)
    if fast is not None:
        # plain numbers and unit strings of the table: no pint (start-up time)
        mag, dims = fast
        bare = not isinstance(value, str) or not _FAST.fullmatch(value)[2]
        if (bare and (bare_is_si or kind == "dimensionless")) or (
            not bare and dims == _KIND_DIMS[kind]
        ):
            return _finite(mag, value, field)
    try:
        q = parse_quantity(value, field)
    except InputError:
        if kind != "dimensionless" or not isinstance(value, str) or not value.strip():
            raise
        # a plain-number field: "lots" is not a number, not an unknown unit
        raise InputError(f"expects a number (e.g. '0.3'), got {value!r}", field) from None
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
            f"{value!r} is not {'an' if kind[0] in 'aeiou' else 'a'} {kind.replace('_', ' ')} "
            f"(it has dimension {q.dimensionality}); use e.g. {_EXAMPLES[kind]}",
            field,
        )
    else:
        mag = float(q.to_base_units().magnitude)
    return _finite(mag, value, field)


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


#: The SI unit a value of each kind is reported in (result.json ``inputs``, the report).
SI_UNITS: dict[str, str] = {
    "length": "m",
    "mass": "kg",
    "time": "s",
    "force": "N",
    "pressure": "Pa",
    "force_per_length": "N/m",
    "stiffness": "N/m",
    "force_per_area": "Pa",
    "density": "kg/m^3",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "energy": "J",
    "frequency": "1/s",
    "bending_stiffness": "N m^2",
    "dimensionless": "",
}


#: A quantity's text starts with its number ("26.7 N", "-3e-2 m", ".5 mm").
_NUMBER_START = re.compile(r"\s*[-+]?(\d|\.\d)")


def si_value(value: Any, kind: str | None = None) -> tuple[float, str] | None:
    """``value`` in SI and its SI unit (:data:`SI_UNITS`): of dimension ``kind`` when known,
    else of whichever kind its unit has (a bare number is SI, unit ``kind``'s or ``""``).

    None when ``value`` is not a quantity (text, a flag, a list) or not of ``kind``.
    """
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        return None
    if isinstance(value, str) and not _NUMBER_START.match(value):
        return None  # text (a preset's or an instrument's name): no pint parse
    if kind is not None:
        try:
            return to_si(value, kind), SI_UNITS[kind]
        except InputError:
            return None
    fast = _fast_parse(value)
    if fast is not None:  # a plain number or a unit of the table: no pint (start-up time)
        mag, dims = fast
        if not isinstance(value, str) or not _FAST.fullmatch(value)[2]:
            return mag, ""
        for k, unit in SI_UNITS.items():
            if _KIND_DIMS.get(k) == dims:
                return mag, unit
    for k in SI_UNITS:
        try:
            v = to_si(value, k, bare_is_si=False)
        except InputError:
            continue
        return v, SI_UNITS[k]
    return None
