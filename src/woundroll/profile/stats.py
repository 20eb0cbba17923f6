"""Profile statistics as practitioners read them: mean, SD, CoV, min, max, peak-to-peak.

A CMD hardness (or thickness) profile is judged by its coefficient of variation
CoV = SD / mean, with the customary acceptance bands of roll-hardness practice:

* CoV < 3 %          very good
* 3 % <= CoV < 6 %   acceptable
* CoV >= 6 %         bad

The SD is the sample standard deviation (divisor n - 1), as hand calculators and
spreadsheet STDEV give it; the CoV is reported as a fraction (0.03 = 3 %).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from woundroll.errors import InputError

#: Upper CoV limits of the acceptance bands (fractions).
COV_VERY_GOOD = 0.03
COV_ACCEPTABLE = 0.06


@dataclass(frozen=True)
class ProfileStats:
    """Statistics of one profile; ``cov`` is a fraction, ``band`` its acceptance band."""

    n: int
    mean: float
    sd: float
    cov: float
    min: float
    max: float
    peak_to_peak: float
    band: str

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


def cov_band(cov: float) -> str:
    """Acceptance band of a coefficient of variation (fraction): very good/acceptable/bad."""
    if not np.isfinite(cov) or cov < 0:
        raise InputError(f"must be a finite fraction >= 0, got {cov}", "profile.cov")
    if cov < COV_VERY_GOOD:
        return "very good"
    if cov < COV_ACCEPTABLE:
        return "acceptable"
    return "bad"


def profile_stats(values: ArrayLike, field: str = "profile") -> ProfileStats:
    """Mean, sample SD, CoV (SD / mean), min, max and peak-to-peak of a profile.

    Parameters
    ----------
    values : array_like
        Readings along the CMD (Rho, thickness [m], ...); at least two, finite, mean > 0.

    Raises
    ------
    InputError
        Fewer than two values, a non-finite value, or a mean <= 0 (CoV undefined).
    """
    v = np.asarray(values, dtype=float).ravel()
    if v.size < 2:
        raise InputError(f"needs at least 2 values, got {v.size}", field)
    if not np.all(np.isfinite(v)):
        raise InputError("contains a value that is not finite (NaN or inf)", field)
    mean = float(v.mean())
    if mean <= 0:
        raise InputError(
            f"the mean must be positive for a coefficient of variation, got {mean:g}", field
        )
    sd = float(v.std(ddof=1))
    cov = sd / mean
    return ProfileStats(
        n=int(v.size),
        mean=mean,
        sd=sd,
        cov=cov,
        min=float(v.min()),
        max=float(v.max()),
        peak_to_peak=float(np.ptp(v)),
        band=cov_band(cov),
    )


def reading_stats(
    values: ArrayLike, scale: tuple[float, float] | None, field: str = "profile.reading"
) -> ProfileStats | None:
    """:func:`profile_stats` of the readings on the instrument's ``scale`` only: a reading
    beyond it is the scale's end on the device (saturated) and says only that the roll is at
    least that hard (or soft), so it is excluded, not averaged in. None when fewer than two
    readings are on the scale. The caller reports how many were excluded."""
    from woundroll.instruments.definitions import beyond_scale

    v = np.asarray(values, dtype=float).ravel()
    on = v[~beyond_scale(v, scale)]
    return profile_stats(on, field) if on.size >= 2 else None
