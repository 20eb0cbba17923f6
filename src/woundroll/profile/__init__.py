"""CMD (cross-machine direction) profiles: thickness input, nip, hardness profile, statistics.

Modules
-------
:mod:`woundroll.profile.thickness`
    read and validate a CMD thickness profile or a full CMD x MD map; resample onto sectors.
:mod:`woundroll.profile.stats`
    profile statistics as practitioners read them (mean, SD, CoV and its acceptance band).
:mod:`woundroll.profile.nip`
    nip roller as a beam on the roll, a nonlinear non-uniform elastic foundation.
:mod:`woundroll.profile.hardness`
    the integrated model: axisymmetric winding -> per-sector contact -> Rho(z).
"""

from typing import Any

from woundroll.profile.nip import NipRoller, roller_from_induced_tension, solve_nip
from woundroll.profile.stats import ProfileStats, profile_stats
from woundroll.profile.thickness import (
    ThicknessProfile,
    bundled_profile,
    read_thickness_map,
    read_thickness_profile,
)

_LAZY = {"NipSpec", "ProfileResult", "predict_profile"}


def __getattr__(name: str) -> Any:
    # woundroll.profile.hardness imports woundroll.winding.axisymmetric, which imports
    # woundroll.profile.thickness: loaded on first use to keep the import graph acyclic
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
