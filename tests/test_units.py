"""Units at the edges: US and SI inputs give the same SI numbers; bad units are clear errors."""

import math

import pytest

from woundroll.errors import InputError
from woundroll.units import to_si


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        # exact conversion factors (NIST SP 811): 1 lbf = 4.4482216152605 N, 1 in = 0.0254 m
        ("2 pli", "force_per_length", 2 * 4.4482216152605 / 0.0254),
        ("3 mil", "length", 3 * 25.4e-6),
        ("3 mils", "length", 3 * 25.4e-6),
        ("30 psi", "pressure", 30 * 4.4482216152605 / 0.0254**2),
        ("4.62 kPa", "pressure", 4620.0),
        ("0.01 cm", "length", 1e-4),
        ("26.7 N", "force", 26.7),
        ("28 N/cm", "stiffness", 2800.0),
        ("125 g", "mass", 0.125),
        ("1.4 g/cm^3", "density", 1400.0),
        ("149.5 rad/s", "frequency", 149.5),
        ("20 %", "dimensionless", 0.2),
        ("3 milliseconds", "time", 3e-3),
        (0.0001, "length", 1e-4),
        ("0.0001", "length", 1e-4),
        (5, "pressure", 5.0),
    ],
)
def test_conversions_to_si(text, kind, expected):
    # 1e-12 relative: only floating-point rounding separates these from the exact factors
    assert math.isclose(to_si(text, kind, "x"), expected, rel_tol=1e-12)


@pytest.mark.parametrize(
    ("text", "kind", "fragment"),
    [
        ("3 furlongs", "pressure", "is not a pressure"),
        ("3 foo", "length", "unknown unit"),
        ("nan", "length", "finite"),
        ("nan mm", "length", "finite"),
        ("inf Pa", "pressure", "finite"),
        ("abc", "length", "unknown unit"),
        ("", "length", "empty"),
        ("3 m", "dimensionless", "plain number"),
        (True, "length", "boolean"),
        ([1, 2], "length", "expected a number"),
    ],
)
def test_bad_quantities_name_the_field(text, kind, fragment):
    with pytest.raises(InputError) as info:
        to_si(text, kind, "web.thickness")
    assert info.value.field == "web.thickness"
    assert fragment in str(info.value)
    assert str(info.value).startswith("web.thickness: ")
