"""One default, one place: the interlayer friction mu and the reduced-shear fraction are
defined once (materials.web) and every entry point that takes them reads that value: the
case file, the contact models' options and signatures, the defect limits, the diagnosis's
roll model and the slip study. Each default must equal the constant, and the modules must
not type the value again beside the name (a copy equal today would drift silently)."""

from __future__ import annotations

import inspect

import pytest

from woundroll.materials import web


def _default(obj: object, name: str) -> object:
    if inspect.isfunction(obj):
        return inspect.signature(obj).parameters[name].default
    fields = getattr(obj, "model_fields", None)  # pydantic
    if fields is not None:
        return fields[name].default
    return {f.name: f.default for f in __import__("dataclasses").fields(obj)}[name]


def _friction_users() -> list[object]:
    from woundroll.assess.defects import DefectLimits
    from woundroll.case.schema import ContactSpec
    from woundroll.contact.layered.roll3d import indent_layered3d
    from woundroll.contact.layered.solver import indent_layered
    from woundroll.contact.plane_strain.solver import indent
    from woundroll.contact.solid3d.solver import indent3d
    from woundroll.contact.spring import roll_stiffness
    from woundroll.inverse.diagnosis import RollModel
    from woundroll.studies.slip import slip_factor_study

    return [
        ContactSpec,
        indent,
        indent3d,
        indent_layered,
        indent_layered3d,
        roll_stiffness,
        DefectLimits,
        RollModel,
        slip_factor_study,
    ]


def test_every_interlayer_friction_default_is_the_one_constant() -> None:
    for obj in _friction_users():
        assert _default(obj, "friction") == web.INTERLAYER_FRICTION, obj
    src = {obj: inspect.getsource(inspect.getmodule(obj)) for obj in _friction_users()}
    for obj, text in src.items():
        assert "friction: float = 0.3" not in text, obj
        assert 'friction: Q("dimensionless", "nonnegative") = 0.3' not in text, obj


@pytest.mark.parametrize(
    "where",
    [
        "woundroll.case.schema:ContactSpec",
        "woundroll.contact.plane_strain.solver:ContactOptions",
        "woundroll.contact.solid3d.options:Contact3DOptions",
        "woundroll.studies.slip:SlipStudy",
        "woundroll.studies.slip:slip_factor_study",
    ],
)
def test_every_reduced_shear_fraction_default_is_the_one_constant(where: str) -> None:
    import importlib

    module, name = where.split(":")
    mod = importlib.import_module(module)
    assert _default(getattr(mod, name), "slip_shear_fraction") == web.SLIP_SHEAR_FRACTION
    text = inspect.getsource(mod)
    assert "slip_shear_fraction: float = 0.01" not in text
    assert 'slip_shear_fraction: Q("dimensionless") = 0.01' not in text
