"""The NumPy PCHIP equals SciPy's PchipInterpolator (the same slopes) to round-off."""

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from woundroll.util.pchip import pchip


@pytest.mark.parametrize("seed", range(6))
def test_equals_scipy(seed):
    rng = np.random.default_rng(seed)
    n = 2 + seed * 5
    x = np.cumsum(rng.uniform(0.1, 1.0, n))
    # monotone, rising-steeply (like F(d)), and with sign changes and flat runs
    y = [np.cumsum(rng.uniform(0, 1, n)), np.exp(x), rng.normal(size=n)][seed % 3]
    if seed == 5:
        y[2:4] = y[2]
    t = np.linspace(x[0] - 0.3, x[-1] + 0.3, 301)
    ref = PchipInterpolator(x, y)(t)
    # round-off of a cubic in y's scale
    np.testing.assert_allclose(pchip(x, y)(t), ref, rtol=1e-12, atol=1e-12 * np.max(np.abs(y)))


def test_bad_points():
    with pytest.raises(ValueError):
        pchip([0.0, 0.0, 1.0], [0.0, 1.0, 2.0])
