"""woundroll.limits: the closed-form positive-definiteness bound, and the ranges' behaviour."""

import math

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.limits import LIMITS, check, max_compliant_radial_modulus


def _compliance(E_r, E_t, E_z, nu_tr, nu_zr, nu_tz):
    s_tr, s_zr, s_tz = -nu_tr / E_t, -nu_zr / E_z, -nu_tz / E_t
    return np.array([[1 / E_r, s_tr, s_zr], [s_tr, 1 / E_t, s_tz], [s_zr, s_tz, 1 / E_z]])


@pytest.mark.parametrize("seed", range(20))
def test_pd_bound_matches_eigenvalues(seed):
    rng = np.random.default_rng(seed)
    E_t, E_z = 10 ** rng.uniform(8, 11, 2)
    nu_tr, nu_zr = rng.uniform(0.05, 0.6, 2)
    nu_tz = rng.uniform(0.0, 0.5) * math.sqrt(E_t / E_z)  # keep the in-plane block PD
    e_max = max_compliant_radial_modulus(E_t, E_z, nu_tr, nu_zr, nu_tz)
    assert 0 < e_max < math.inf
    # just below the bound all eigenvalues are positive, just above one is negative (1e-6:
    # the bound is exact, the margin only has to exceed the eigenvalue solver's rounding)
    below = np.linalg.eigvalsh(_compliance(e_max * (1 - 1e-6), E_t, E_z, nu_tr, nu_zr, nu_tz))
    above = np.linalg.eigvalsh(_compliance(e_max * (1 + 1e-6), E_t, E_z, nu_tr, nu_zr, nu_tz))
    assert below.min() > 0 > above.min()


def test_pd_bound_uncoupled_and_single_ratio():
    # no coupling to r: any E_r
    assert max_compliant_radial_modulus(5e9, 5e9, 0.0, 0.0, 0.3) == math.inf
    # only nu_theta_r: the 2x2 (r, theta) condition nu_tr^2 E_r / E_t < 1, E_r < E_t / nu^2
    # (with nu_theta_z = 0 the z direction decouples)
    assert max_compliant_radial_modulus(5e9, 5e9, 0.3, 0.0, 0.0) == pytest.approx(5e9 / 0.09)


def test_check_hard_and_plausible():
    lim = LIMITS["web.thickness"]
    assert check("web.thickness", 50e-6) is None
    w = check("web.thickness", 0.5e-6)  # inside hard, outside plausible
    assert w and w.startswith("web.thickness:") and "usual range" in w
    with pytest.raises(InputError) as info:
        check("web.thickness", lim.hard[1] * 2)
    assert info.value.field == "web.thickness" and "physical range" in info.value.message
