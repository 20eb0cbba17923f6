"""Property-based tests (Hypothesis) over the case schema.

Whatever a user writes into a case file -- any key of the schema replaced by any TOML value
(numbers from 1e-300 to 1e300, NaN, infinities, negative values, booleans, text with or without
units, lists, tables) and unknown keys added -- :func:`load_case` either returns a valid case
or raises :class:`InputError` naming a field, with a one-line message. Never another exception.

And the limits of :mod:`woundroll.limits` hold for every value: beyond the hard range of a
quantity, the error names exactly that quantity.
"""

import math
import os

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from woundroll.case import load_case
from woundroll.errors import InputError
from woundroll.limits import LIMITS

BASE = {
    "title": "t",
    "web": {
        "thickness": "100 um",
        "width": "0.3 m",
        "E_theta": "5 GPa",
        "radial_modulus": {"law": "pfeiffer", "K1": "5 kPa", "K2": 100},
    },
    "core": {"outer_radius": "4 cm", "rigid": True},
    "winding": {"outer_radius": "6 cm", "tension": "1 MPa"},
    "tester": {"instrument": "rho-meter"},
}

#: Keys of the schema a user can set (dotted), tables included.
KEYS = [
    "title",
    "web",
    "web.preset",
    "web.thickness",
    "web.width",
    "web.E_theta",
    "web.E_z",
    "web.density",
    "web.nu_theta_r",
    "web.nu_z_r",
    "web.nu_theta_z",
    "web.G_r_theta",
    "web.G_r_z",
    "web.G_theta_z",
    "web.radial_modulus",
    "web.radial_modulus.law",
    "web.radial_modulus.K1",
    "web.radial_modulus.K2",
    "core",
    "core.outer_radius",
    "core.stiffness",
    "core.rigid",
    "core.inner_radius",
    "core.E",
    "core.nu",
    "winding",
    "winding.outer_radius",
    "winding.length",
    "winding.tension",
    "winding.taper",
    "winding.taper.kind",
    "winding.taper.fraction",
    "winding.nip_load",
    "winding.friction",
    "winding.options",
    "winding.thickness_profile",
    "winding.nip_roller",
    "tester",
    "tester.instrument",
    "tester.mass",
    "tester.head_radius",
    "tester.head_length",
    "tester.spring_stiffness",
    "tester.release_position",
    "tester.contact_position",
    "tester.collision",
    "tester.time_step",
    "tester.steps_per_contact",
    "tester.pile_height",
    "tester.restitution",
    "tester.roll_spring",
    "contact",
    "contact.depth_max",
    "contact.friction",
    "contact.no_update",
    "contact.options",
    "profile",
    "profile.sectors",
    "profile.workers",
    "base_dir",
    "web.nonsense",
    "nonsense",
]

UNITS = [
    "",
    " m",
    " um",
    " mil",
    " cm",
    " Pa",
    " kPa",
    " GPa",
    " psi",
    " N",
    " pli",
    " N/m",
    " kg",
    " s",
    " %",
    " furlong",
    " m/s",
    " J",
]
numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -1.0, 1e-300, 1e300, 1e-30, 1e30, 0.3, 0.99, 1.5, 100.0]),
    st.integers(min_value=-(10**30), max_value=10**30),
)
quantity_text = st.builds(lambda x, u: f"{x:g}{u}", numbers, st.sampled_from(UNITS))
scalars = st.one_of(numbers, quantity_text, st.booleans(), st.text(max_size=12))
values = st.recursive(
    scalars,
    lambda inner: st.one_of(
        st.lists(inner, max_size=3), st.dictionaries(st.text(max_size=6), inner, max_size=3)
    ),
    max_leaves=6,
)


def _set(data: dict, key: str, value) -> None:
    node = data
    parts = key.split(".")
    for p in parts[:-1]:
        if not isinstance(node.get(p), dict):
            node[p] = {}
        node = node[p]
    node[parts[-1]] = value


def _fresh() -> dict:
    return {k: (dict(v) if isinstance(v, dict) else v) for k, v in BASE.items()} | {
        "web": {**BASE["web"], "radial_modulus": dict(BASE["web"]["radial_modulus"])}
    }


#: Examples per run (200 in the suite, about 8 s; WOUNDROLL_HYPOTHESIS_EXAMPLES for more).
EXAMPLES = int(os.environ.get("WOUNDROLL_HYPOTHESIS_EXAMPLES", "200"))


@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.sampled_from(KEYS), values), min_size=1, max_size=3))
def test_any_value_anywhere_is_a_case_or_an_input_error(changes):
    data = _fresh()
    for key, value in changes:
        _set(data, key, value)
    try:
        case = load_case(data)
    except InputError as exc:
        assert exc.field, f"no field named: {exc}"
        assert "\n" not in str(exc)
        return
    # accepted: the case is usable and its warnings are one-line strings
    assert all(isinstance(w, str) and "\n" not in w for w in case.warnings)
    assert math.isfinite(case.winding.final_radius(case.web.build(), case.core.build()))


HARD_KEYS = [
    "web.thickness",
    "web.width",
    "web.E_theta",
    "web.density",
    "core.outer_radius",
    "winding.nip_load",
    "tester.mass",
    "tester.head_radius",
    "tester.spring_stiffness",
]


@settings(max_examples=150, deadline=None)
@given(
    st.sampled_from(HARD_KEYS),
    st.one_of(st.floats(1e-300, 1e300), st.floats(-1e300, -1e-300)),
)
def test_beyond_the_hard_range_names_the_quantity(key, value):
    lo, hi = LIMITS[key].hard
    data = _fresh()
    _set(data, key, value)
    if lo <= value <= hi:
        return
    with pytest.raises(InputError) as info:
        load_case(data)
    assert info.value.field == key, str(info.value)
