"""Stack-test fitting recovers known parameters and reports fit quality."""

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.materials import Pfeiffer
from woundroll.materials.stack_fit import fit_stack

EPS = np.linspace(0.002, 0.06, 25)


def test_pfeiffer_fit_recovers_parameters_exactly():
    true = Pfeiffer(K1=4620.0, K2=123.88)
    fit = fit_stack(EPS, true.pressure(EPS), "pfeiffer")
    # noiseless data: the least-squares optimum is the generating law (to solver precision)
    assert fit.law.K1 == pytest.approx(4620.0, rel=1e-6)
    assert fit.law.K2 == pytest.approx(123.88, rel=1e-6)
    assert fit.r2 == pytest.approx(1.0, abs=1e-12)


def test_pfeiffer_fit_with_noise():
    true = Pfeiffer(K1=20270.0, K2=26.24)
    rng = np.random.default_rng(7)
    eps = np.linspace(0.005, 0.15, 40)
    noisy = true.pressure(eps) * (1 + 0.02 * rng.standard_normal(eps.size))
    fit = fit_stack(eps, noisy, "pfeiffer")
    # 2 % multiplicative noise on 40 points: parameters within a few per cent, and the
    # reported RMS relative error close to the noise level
    assert fit.law.K2 == pytest.approx(26.24, rel=0.03)
    assert fit.law.K1 == pytest.approx(20270.0, rel=0.08)
    assert 0.01 < fit.rms_rel_error < 0.03


def test_constant_and_polynomial_fits_exact_on_their_own_curves():
    fit = fit_stack(EPS, 3e6 * EPS, "constant")
    assert fit.law.E_r == pytest.approx(3e6, rel=1e-12)
    p = 2e5 * EPS + 3e6 * EPS**2 + 4e8 * EPS**3
    fit = fit_stack(EPS, p, "polynomial")
    assert (fit.law.C1, fit.law.C2, fit.law.C3) == pytest.approx((2e5, 3e6, 4e8), rel=1e-6)


def test_toml_snippet_round_trips():
    import tomllib

    from woundroll.materials import law_from_spec

    fit = fit_stack(EPS, Pfeiffer(K1=4620.0, K2=123.88).pressure(EPS))
    law = law_from_spec(tomllib.loads(f"x = {fit.toml()}")["x"])
    assert law.K2 == pytest.approx(123.88, rel=1e-5)


@pytest.mark.parametrize(
    ("eps", "p"),
    [
        ([0.01, 0.02], [1, 2]),
        ([0.01, 0.02, np.nan], [1, 2, 3]),
        ([0.01, 0.02, 0.03], [1, -2, 3]),
        ([0.01, 0.02, 0.03], [0, 0, 3]),
    ],
)
def test_bad_stack_data(eps, p):
    with pytest.raises(InputError):
        fit_stack(eps, p)
