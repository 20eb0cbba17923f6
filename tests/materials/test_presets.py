"""Web presets (woundroll/data/materials/*.toml): every preset loads into a Web with an
unloading law and expansion coefficients, names the source of every number, and one number
per preset is checked against its source; every bundled case of the new webs reads on the
rho-meter's scale."""

from __future__ import annotations

import math

import pytest

from woundroll.case.schema import WebSpec
from woundroll.materials.presets import list_materials, material_preset

PRESETS = sorted(list_materials())
NEW_WEBS = ("NEWSPRINT", "COATED-PAPER", "ALUMINIUM-FOIL", "NONWOVEN")


@pytest.mark.parametrize("name", PRESETS)
def test_every_preset_loads_with_an_unloading_law(name):
    web = WebSpec(preset=name).build()
    assert web.radial_unloading is not None
    assert web.tensile_strength is not None and web.tensile_strength > 0
    assert web.alpha_theta > 0  # every web expands with temperature
    # the stack loses energy in a cycle to 100 kPa (what rebound testers read); PET3's
    # loading law (K1 = 0, Table 3) carries no pressure from zero strain, so its cycle
    # is degenerate and the ratio stays 1 (elastic) for the FD model
    e2 = web.radial_unloading.energy_ratio(web.radial_modulus, 1e5)
    if web.radial_modulus.K1 > 0:
        assert 0.0 < e2 < 0.95, e2
    else:
        assert e2 == 1.0
    table = list_materials()[name]
    assert table["source"].strip() and 0 < table["friction"] < 1


def test_all_four_new_webs_are_bundled():
    assert set(NEW_WEBS) <= set(PRESETS)


@pytest.mark.parametrize("name", NEW_WEBS)
def test_every_number_names_its_source(name):
    source = list_materials()[name]["source"]
    for key in material_preset(name):
        assert key in source, f"{name}: no source for {key}"
    assert "friction" in source


# grammage = density x caliper, the grade data each preset's source cites [g/m^2];
# 1 % covers the rounding of the printed caliper and density
GRAMMAGE = {"NEWSPRINT": 45.0, "COATED-PAPER": 100.0, "NONWOVEN": 30.0}


@pytest.mark.parametrize("name", sorted(GRAMMAGE))
def test_paper_and_nonwoven_grammage(name):
    web = WebSpec(preset=name).build()
    assert web.density * web.thickness * 1e3 == pytest.approx(GRAMMAGE[name], rel=0.01)


def test_aluminium_foil_handbook_values():
    # ASM handbook values of aluminium, as the preset's source states (exact transcription)
    web = WebSpec(preset="ALUMINIUM-FOIL").build()
    assert (web.density, web.E_theta, web.alpha_theta) == (2700.0, 70e9, 2.3e-5)
    assert web.beta_theta == web.beta_r == 0.0  # no moisture uptake


@pytest.mark.parametrize("name", ["PET1", "PET2", "PET3"])
def test_pet_unloading_is_the_stated_typical_rule(name):
    # pet.toml: K1u = K1 (1 kPa where K1 = 0), K2u = 1.6 K2, rounded to 4 digits;
    # PET film in-plane thermal expansion 17 ppm/K (product data)
    web = WebSpec(preset=name).build()
    K1, K2 = web.radial_modulus.K1, web.radial_modulus.K2
    assert web.radial_unloading.K2 == pytest.approx(1.6 * K2, rel=1e-3)
    assert web.radial_unloading.K1 == (K1 if K1 > 0 else 1e3)
    assert web.alpha_theta == 1.7e-5


CASES = ("newsprint-300Nm", "coated-paper-500Nm", "aluminium-foil-8MPa", "nonwoven-200Nm")


@pytest.mark.slow
@pytest.mark.parametrize("case", CASES)
def test_bundled_case_reads_on_the_scale(case):
    # 3-10 s CPU each on the shared machine: slow. Measured: 42.9, 64.8, 84.2, 12.1 Rho
    from woundroll.pipeline import run

    res = run(case)
    reading = res.hardness.reading
    assert math.isfinite(reading) and 0.0 < reading < 100.0
    assert not res.flags["reading_outside_range"], res.warnings
