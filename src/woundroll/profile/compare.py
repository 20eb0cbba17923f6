"""A measured CMD hardness profile beside the predicted one.

The shop-floor question is "does the model see what the tester sees?". A measured profile
is a CSV with a position column (with its unit, from the same web edge as the thickness
profile) and one reading column in the instrument's units: ``position [in],rho`` or
``position_m,reading``. Several readings at one position (repeat hits) are averaged.

The comparison, at the measured positions (the prediction interpolated linearly between
sector centres, held flat beyond the outermost centres):

* bias: mean of (predicted - measured);
* RMS difference, and the RMS after removing the bias (the shape error: a level offset
  from an unknown calibration or modulus is common, the CMD pattern is what diagnoses);
* Pearson correlation of the two profiles (does the pattern follow?); None when either is
  flat (a uniform prediction has no pattern);
* the statistics and CoV band of each (:mod:`woundroll.profile.stats`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.profile.stats import ProfileStats, profile_stats
from woundroll.util.tables import parse_header, read_columns, read_header_row

FloatArray = NDArray[np.float64]

FIELD = "profile.measured"

#: Accepted names of the reading column.
READING_COLUMNS = ("rho", "reading", "hardness")


@dataclass(frozen=True)
class MeasuredProfile:
    """Readings along the CMD: ``position`` [m] (increasing, unique) and ``reading``."""

    position: FloatArray
    reading: FloatArray
    source: str = ""


@dataclass(frozen=True)
class ProfileComparison:
    """Predicted vs measured readings at the measured positions (module docstring)."""

    measured: MeasuredProfile
    predicted: FloatArray
    bias: float
    rms: float
    rms_shape: float
    correlation: float | None
    measured_stats: ProfileStats
    predicted_stats: ProfileStats

    def to_dict(self) -> dict[str, Any]:
        return {
            "position_m": self.measured.position.tolist(),
            "measured": self.measured.reading.tolist(),
            "predicted": self.predicted.tolist(),
            "bias": self.bias,
            "rms_difference": self.rms,
            "rms_difference_after_bias": self.rms_shape,
            "correlation": self.correlation,
            "stats": {
                "measured": self.measured_stats.to_dict(),
                "predicted_at_measured": self.predicted_stats.to_dict(),
            },
            "source": self.measured.source,
        }


def read_measured_profile(path: Path | str, field: str = FIELD) -> MeasuredProfile:
    """Read a measured CMD hardness profile CSV (module docstring); SI positions."""
    path = Path(path)
    header = read_header_row(path, field)
    names = [parse_header(h)[0] for h in header]
    col = next((c for c in READING_COLUMNS if c in names), None)
    if col is None:
        raise InputError(
            f"{path.name}: no reading column (one of {', '.join(READING_COLUMNS)}); "
            f"columns: {', '.join(header)}",
            field,
        )
    cols = read_columns(path, {"position": "length", col: "dimensionless"}, field)
    pos, val = cols["position"], cols[col]
    if pos.size < 2:
        raise InputError(f"{path.name}: needs readings at >= 2 positions", field)
    order = np.argsort(pos, kind="stable")
    pos, val = pos[order], val[order]
    uniq, inv = np.unique(pos, return_inverse=True)
    mean = np.bincount(inv, weights=val) / np.bincount(inv)
    if uniq.size < 2:
        raise InputError(f"{path.name}: needs readings at >= 2 distinct positions", field)
    return MeasuredProfile(uniq, mean, path.name)


def compare_profiles(
    z: ArrayLike, predicted: ArrayLike, measured: MeasuredProfile, field: str = FIELD
) -> ProfileComparison:
    """Compare a predicted profile (sector centres ``z`` [m], readings) with a measured one.

    Raises
    ------
    InputError
        Measured positions outside the predicted profile's extent by more than half a
        sector (a different edge reference or unit).
    """
    z = np.asarray(z, dtype=float)
    p = np.asarray(predicted, dtype=float)
    half = 0.5 * float(np.min(np.diff(z))) if z.size > 1 else np.inf
    x = measured.position
    if x.min() < z.min() - half or x.max() > z.max() + half:
        raise InputError(
            f"measured positions {x.min():.4g}-{x.max():.4g} m lie outside the predicted "
            f"profile ({z.min() - half:.4g}-{z.max() + half:.4g} m): same edge and units?",
            field,
        )
    at = np.interp(x, z, p)
    diff = at - measured.reading
    bias = float(diff.mean())
    corr = None
    flat = 1e-9 * max(float(np.max(np.abs(at))), 1e-300)  # round-off of a uniform roll
    if np.ptp(at) > flat and np.ptp(measured.reading) > 0:
        corr = float(np.corrcoef(at, measured.reading)[0, 1])
    return ProfileComparison(
        measured=measured,
        predicted=at,
        bias=bias,
        rms=float(np.sqrt(np.mean(diff**2))),
        rms_shape=float(np.sqrt(np.mean((diff - bias) ** 2))),
        correlation=corr,
        measured_stats=profile_stats(measured.reading, field),
        predicted_stats=profile_stats(at, field),
    )
