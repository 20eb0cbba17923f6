"""CMD (cross-machine direction) profiles: nip, hardness profile, statistics.

The CMD thickness profile is an input of the winding model and lives beside the web and the
core (:mod:`woundroll.materials.thickness_profile`); it is re-exported here, where the
profile API is documented (docs/profile.md).

Modules
-------
:mod:`woundroll.profile.stats`
    profile statistics as practitioners read them (mean, SD, CoV and its acceptance band).
:mod:`woundroll.profile.nip`
    nip roller as a beam on the roll, a nonlinear non-uniform elastic foundation.
:mod:`woundroll.profile.hardness`
    the integrated model: axisymmetric winding -> per-sector contact -> Rho(z).
"""

from typing import Any

from woundroll.materials.thickness_profile import (
    ThicknessProfile,
    bundled_profile,
    read_thickness_map,
    read_thickness_profile,
)
from woundroll.profile.nip import NipRoller, roller_from_induced_tension, solve_nip
from woundroll.profile.stats import ProfileStats, profile_stats

_LAZY = {"NipSpec", "ProfileResult", "predict_profile"}


def __getattr__(name: str) -> Any:
    # woundroll.profile.hardness imports the winding model (scipy): loaded on first use so
    # that importing woundroll.profile stays light
    if name in _LAZY:
        from woundroll.profile import hardness

        return getattr(hardness, name)
    raise AttributeError(f"module 'woundroll.profile' has no attribute {name!r}")


__all__ = [
    "NipRoller",
    "NipSpec",
    "ProfileResult",
    "ProfileStats",
    "ThicknessProfile",
    "bundled_profile",
    "predict_profile",
    "profile_stats",
    "read_thickness_map",
    "read_thickness_profile",
    "roller_from_induced_tension",
    "solve_nip",
]
