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
:mod:`woundroll.profile.interpolated`
    the contact stage on a few sectors, interpolated between them and checked.
"""

from woundroll.materials.thickness_profile import (
    ThicknessProfile,
    bundled_profile,
    read_thickness_map,
    read_thickness_profile,
)
from woundroll.profile.stats import ProfileStats, profile_stats
from woundroll.util.lazy import lazy_names

# woundroll.profile.nip (scipy.linalg, 0.3 s) and woundroll.profile.hardness (the winding
# model) are loaded on first use, so that importing woundroll.profile (the case schema
# reads the contact stage's defaults from woundroll.profile.interpolated) stays light
__getattr__ = lazy_names(
    __name__,
    {
        "NipRoller": "woundroll.profile.nip",
        "roller_from_induced_tension": "woundroll.profile.nip",
        "solve_nip": "woundroll.profile.nip",
        "NipSpec": "woundroll.profile.hardness",
        "ProfileResult": "woundroll.profile.hardness",
        "predict_profile": "woundroll.profile.hardness",
    },
)


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
