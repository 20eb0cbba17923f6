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

from woundroll.profile.stats import ProfileStats, profile_stats
from woundroll.profile.thickness import (
    ThicknessProfile,
    bundled_profile,
    read_thickness_map,
    read_thickness_profile,
)

__all__ = [
    "ProfileStats",
    "ThicknessProfile",
    "bundled_profile",
    "profile_stats",
    "read_thickness_map",
    "read_thickness_profile",
]
