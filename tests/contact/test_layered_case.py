"""The layered roll's and the other explanations' case keys: parsed into the model's
options, and bad values refused with the field named (no solve here)."""

from __future__ import annotations

import pytest

from woundroll.case import load_case
from woundroll.contact.layered.solver import LayeredOptions
from woundroll.errors import InputError


def test_zone_keys_reach_the_layered_options() -> None:
    case = load_case(
        "pet1-26.7N",
        ["contact.model=layered", "contact.layered_depth=2 mm", "contact.layers_per_shell=2"],
    )
    opts = case.contact.layered_options()
    assert isinstance(opts, LayeredOptions)
    assert opts.layered_depth == pytest.approx(2e-3)  # SI inside
    assert opts.layers_per_shell == 2
    assert opts.base.newton is False


def test_shear_keys_reach_the_contact_options() -> None:
    case = load_case("pet1-26.7N", ["contact.shear_ratio=0.8", "contact.shear_frozen=true"])
    opts = case.contact.contact_options()
    assert opts.shear_ratio == pytest.approx(0.8)
    assert opts.shear_frozen is True
    # unset: the web's rule and G following E_r
    plain = load_case("pet1-26.7N").contact.contact_options()
    assert plain.shear_ratio is None and plain.shear_frozen is False


@pytest.mark.parametrize(
    ("overrides", "field"),
    [
        (["contact.layered_depth=2 mm"], "contact.layered_depth"),  # not the layered model
        (["contact.model=layered", "contact.layers_per_shell=0"], "contact.layers_per_shell"),
        (["contact.model=layered", "contact.layered_depth=30 cm"], "contact.layered_depth"),
        (["contact.shear_ratio=0"], "contact.shear_ratio"),
        (["contact.options.shear_frozen=true"], "contact.options.shear_frozen"),
        (["contact.dynamic=true", "contact.shear_frozen=true"], "contact.shear_frozen"),
    ],
)
def test_bad_keys_name_the_field(overrides: list[str], field: str) -> None:
    with pytest.raises(InputError) as err:
        case = load_case("pet1-26.7N", overrides)
        spec = case.contact
        spec.layered_options() if spec.model == "layered" else spec.contact_options()
        if spec.model == "layered":  # the zone against the roll is checked at the solve
            from woundroll.contact.layered.solver import layered_mesh_inputs

            web, core = case.web.build(), case.core.build()
            r_out = case.winding.final_radius(web, core)
            layered_mesh_inputs(web, core, r_out, 6.565e-3, 1e-3, spec.layered_options())
    assert err.value.field.endswith(field.split("contact.", 1)[1])
