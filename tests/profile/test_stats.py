"""Profile statistics and the CoV acceptance bands."""

from __future__ import annotations

import math

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.profile.stats import cov_band, profile_stats


def test_known_values() -> None:
    # 1, 2, 3, 4: mean 2.5, sample SD sqrt(5/3) (divisor n - 1), range 3
    st = profile_stats([1.0, 2.0, 3.0, 4.0])
    assert st.n == 4
    assert st.mean == pytest.approx(2.5, rel=1e-15)
    assert st.sd == pytest.approx(math.sqrt(5.0 / 3.0), rel=1e-14)
    assert st.cov == pytest.approx(math.sqrt(5.0 / 3.0) / 2.5, rel=1e-14)
    assert (st.min, st.max, st.peak_to_peak) == (1.0, 4.0, 3.0)
    assert st.band == "bad"  # CoV 52 %
    assert st.to_dict()["band"] == "bad"


@pytest.mark.parametrize(
    ("cov", "band"),
    [
        (0.0, "very good"),
        (0.0299, "very good"),
        (0.03, "acceptable"),
        (0.0599, "acceptable"),
        (0.06, "bad"),
        (0.2, "bad"),
    ],
)
def test_bands(cov: float, band: str) -> None:
    assert cov_band(cov) == band


def test_constant_profile_is_very_good() -> None:
    st = profile_stats(np.full(61, 55.0))
    assert st.sd == 0.0 and st.cov == 0.0 and st.band == "very good"


def test_band_from_a_profile() -> None:
    # +-4 % square wave: sample SD = 4 % * sqrt(n / (n - 1)) -> CoV just above 4 %: acceptable
    v = 50.0 * (1 + 0.04 * np.tile([1.0, -1.0], 10))
    st = profile_stats(v)
    assert st.cov == pytest.approx(0.04 * math.sqrt(20 / 19), rel=1e-12)
    assert st.band == "acceptable"


@pytest.mark.parametrize("bad", [[1.0], [1.0, float("nan")], [-1.0, -2.0], [0.0, 0.0]])
def test_bad_input(bad: list[float]) -> None:
    with pytest.raises(InputError) as exc:
        profile_stats(bad, "profile.rho")
    assert exc.value.field == "profile.rho"
