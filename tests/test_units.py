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


def test_fast_table_agrees_with_pint():
    # every unit of the pint-free fast path (woundroll.units._UNITS), alone and in the
    # compound forms case files use, gives pint's SI value and dimension; 1e-12 relative:
    # floating-point rounding only
    from woundroll import units

    ureg = units.registry()
    dims = {"[length]": 0, "[mass]": 1, "[time]": 2}
    texts = [f"2.5 {u}" for u in units._UNITS] + [
        "1.4 g/cm^3",
        "28 N/cm",
        "1e9 N/m^2",
        "5.8e5 N m^2",
        "5.8e5 N*m**2",
        "9.81 m/s^2",
        "149.5 rad/s",
        "3 mils",
        "1 1/s",
        "12um",
        "-4 kPa",
    ]
    for text in texts:
        fast = units._fast_parse(text)
        assert fast is not None, text
        q = ureg.Quantity(units._MIL.sub("thou", text)).to_base_units()
        expo = [0, 0, 0]
        for name, e in q.dimensionality.items():
            expo[dims[name]] = e
        assert fast[1] == tuple(expo), text
        assert math.isclose(fast[0], q.magnitude, rel_tol=1e-12), text


def test_units_outside_the_table_go_to_pint():
    from woundroll import units

    for text in ("3 furlongs", "3 milliseconds", "2 * 3 m", "1 N/m/s", "3 m ^ 2"):
        assert units._fast_parse(text) is None, text
    assert math.isclose(to_si("3 milliseconds", "time"), 3e-3, rel_tol=1e-12)


def test_import_woundroll_is_light():
    # issue 14: nothing heavy behind ``import woundroll`` (a fresh interpreter: the test
    # process itself has imported everything)
    import subprocess
    import sys

    code = (
        "import sys, woundroll, woundroll.app.cli; from woundroll.units import to_si;"
        "to_si('2 pli', 'force_per_length');"
        "print(','.join(m for m in ('pint', 'scipy', 'numba', 'matplotlib', 'pydantic')"
        " if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
