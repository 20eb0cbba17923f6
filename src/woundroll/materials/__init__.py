"""Materials: radial-modulus laws, web and core data, presets, stack-test fitting, and the
web's CMD thickness profile (:mod:`woundroll.materials.thickness_profile`, imported on use)."""

from woundroll.materials.radial_modulus import (
    LAWS,
    Constant,
    Pfeiffer,
    Polynomial,
    RadialModulusLaw,
    Tabulated,
    law_from_spec,
)
from woundroll.materials.web import INTERLAYER_FRICTION, Core, Web

__all__ = [
    "INTERLAYER_FRICTION",
    "LAWS",
    "Constant",
    "Core",
    "Pfeiffer",
    "Polynomial",
    "RadialModulusLaw",
    "Tabulated",
    "Web",
    "law_from_spec",
]
