"""Case files: presets, units, overrides, and a clear error for every kind of bad input."""

import math
from pathlib import Path

import pytest

from woundroll.case import bundled_cases, case_from_dict, load_case
from woundroll.errors import InputError
from woundroll.materials import Pfeiffer


def minimal(**over):
    data = {
        "web": {
            "thickness": "100 um",
            "width": "15 cm",
            "E_theta": "5 GPa",
            "radial_modulus": {"law": "pfeiffer", "K1": "5 kPa", "K2": 100},
        },
        "core": {"outer_radius": "4 cm", "rigid": True},
        "winding": {"outer_radius": "10 cm", "tension": "1 MPa"},
    }
    for key, value in over.items():
        section, _, name = key.partition("__")
        if name:
            data[section][name] = value
        else:
            data[section] = value
    return data


def test_bundled_pet1_case_has_table2_values():
    case = load_case("pet1-26.7N")
    web = case.web.build()
    assert web.thickness == pytest.approx(1e-4)
    assert web.width == pytest.approx(0.1524)
    assert web.E_theta == pytest.approx(5681e6)
    assert web.radial_modulus == Pfeiffer(K1=4620.0, K2=123.88)
    # 26.7 N over 15.24 cm x 100 um
    sched = case.winding.schedule(web)
    assert sched.web_stress == pytest.approx(26.7 / (0.1524 * 1e-4), rel=1e-12)


def test_tension_forms_are_equivalent():
    """26.7 N over the width, the same per width (N/m), and the same as stress agree."""
    width, h = 0.15, 100e-6
    forms = ["26.7 N", f"{26.7 / width} N/m", f"{26.7 / (width * h)} Pa"]
    stresses = [
        case_from_dict(minimal(winding__tension=f))
        .winding.schedule(case_from_dict(minimal()).web.build())
        .web_stress
        for f in forms
    ]
    assert stresses == pytest.approx([stresses[0]] * 3, rel=1e-12)


def test_pli_tension_and_mil_thickness():
    case = case_from_dict(minimal(web__thickness="3 mil", winding__tension="2 pli"))
    web = case.web.build()
    assert web.thickness == pytest.approx(76.2e-6)
    assert case.winding.schedule(web).web_stress == pytest.approx(350.2536704929529 / 76.2e-6)


def test_length_gives_outer_radius_by_area():
    case = case_from_dict(minimal(winding__outer_radius=None, winding__length="1000 m"))
    case.winding.model_copy()
    web, core = case.web.build(), case.core.build()
    r = case.winding.final_radius(web, core)
    assert math.pi * (r**2 - 0.04**2) == pytest.approx(1000 * 100e-6, rel=1e-12)


def test_core_tube_stiffness_is_lame():
    case = case_from_dict(
        minimal(
            core={"outer_radius": "4.45 cm", "inner_radius": "3.81 cm", "E": "200 GPa", "nu": 0.3}
        )
    )
    a, b = 0.0381, 0.0445
    expected = 200e9 / ((b**2 + a**2) / (b**2 - a**2) - 0.3)
    assert case.core.build().stiffness == pytest.approx(expected, rel=1e-12)


def test_override_nested_preset_key():
    case = load_case("pet1-26.7N", ["web.radial_modulus.K2=50", "winding.tension='2 pli'"])
    assert case.web.radial_modulus == Pfeiffer(K1=4620.0, K2=50.0)


def test_override_replaces_law():
    case = load_case("pet1-26.7N", ['web.radial_modulus={law="constant", E_r="1 MPa"}'])
    assert case.web.radial_modulus.modulus([0.0])[0] == 1e6


@pytest.mark.parametrize(
    ("override", "field"),
    [
        ("web.thickness=-1", "web.thickness"),
        ("web.thickness=0", "web.thickness"),
        ("web.width='0 cm'", "web.width"),
        ("web.thickness='3 foo'", "web.thickness"),
        ("web.thickness='3 kPa'", "web.thickness"),
        ("web.thickness=nan", "web.thickness"),
        ("web.E_theta='nan GPa'", "web.E_theta"),
        ("web.radial_modulus.K2=0", "web.radial_modulus.K2"),
        ("web.radial_modulus.K2=-3", "web.radial_modulus.K2"),
        ("web.radial_modulus.K1='-1 kPa'", "web.radial_modulus.K1"),
        ("web.radial_modulus.law='magic'", "web.radial_modulus.law"),
        ("web.nu_theta_z='3 m'", "web.nu_theta_z"),
        ("web.thicknes=3", "web.thicknes"),
        ("winding.outer_radius='3 cm'", "winding.outer_radius"),
        ("winding.outer_radius='4.455 cm'", "winding.outer_radius"),
        ("winding.tension=5", "winding.tension"),
        ("winding.tension='5 kg'", "winding.tension"),
        ("winding.tension='-5 N'", "winding.tension"),
        ("winding.nip_load='3 N'", "winding.nip_load"),
        ("winding.taper.kind='sideways'", "winding.taper.kind"),
        ("core.inner_radius='5 cm'", "core.inner_radius"),
        ("core.E=0", "core.E"),
        ("web.preset='PET9'", "web.preset"),
    ],
)
def test_bad_input_names_the_field(override, field):
    with pytest.raises(InputError) as info:
        load_case("pet1-26.7N", [override])
    assert info.value.field == field, str(info.value)


def test_missing_section_and_key():
    with pytest.raises(InputError) as info:
        case_from_dict({"web": minimal()["web"], "core": minimal()["core"]})
    assert info.value.field == "winding"
    data = minimal()
    del data["web"]["E_theta"]
    with pytest.raises(InputError) as info:
        case_from_dict(data)
    assert info.value.field == "web.E_theta"


def test_unknown_case_and_bad_toml(tmp_path: Path):
    with pytest.raises(InputError, match="no case file"):
        load_case("no-such-case")
    bad = tmp_path / "bad.toml"
    bad.write_text("[web\nthickness = 1", encoding="utf-8")
    with pytest.raises(InputError, match="not valid TOML"):
        load_case(bad)


def test_every_bundled_case_loads():
    names = bundled_cases()
    assert "pet1-26.7N" in names
    for name in names:
        assert load_case(name).title
