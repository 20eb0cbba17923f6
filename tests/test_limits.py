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


def test_winding_estimate_form():
    # the estimate's form, not its seconds (no timed assertions; the fit against measured
    # times is benchmarks/bench_limits.py's table in docs/case-files.md)
    from woundroll.limits import winding_estimate

    ns = [1_000, 10_000, 100_000, 1_000_000]
    for kernels in ("compiled", "numpy"):
        t = [winding_estimate(n, 2, kernels).seconds for n in ns]
        assert all(b > a > 0 for a, b in zip(t, t[1:], strict=False))
        assert winding_estimate(10_000, 2, kernels).kernels == kernels
        # proportional to the nodes per layer
        assert winding_estimate(10_000, 6, kernels).seconds == pytest.approx(3 * t[1])
    # the compiled kernels' cost per increment grows slowly with the roll (the lazy deep
    # part's levels); the NumPy twin's is constant and larger (a Python loop per increment)
    per = [winding_estimate(n, 2).seconds / n for n in ns]
    assert all(b > a for a, b in zip(per, per[1:], strict=False)) and per[-1] < 2 * per[0]
    assert winding_estimate(2_000, 2, "numpy").seconds > 10 * winding_estimate(2_000).seconds
    # a roll that runs compiled only if the kernels are built is estimated as the NumPy twin
    either = winding_estimate(1_000, 2, "compiled if built, else numpy")
    assert either.seconds == winding_estimate(1_000, 2, "numpy").seconds


def test_winding_path_is_the_one_wind_takes():
    from woundroll.winding.hakiel import WindingOptions

    o = WindingOptions()
    assert o.kernels(50) == "numpy"  # 101 nodes: no load of compiled code
    assert o.kernels(1_000) == "compiled if built, else numpy"  # no one-off build
    assert o.kernels(100_000) == "compiled"
    assert WindingOptions(subdivisions=41).kernels(100) == "compiled"  # above 4,001 nodes


def test_long_run_warning_names_the_kernels():
    from woundroll.case import load_case

    # 5 um film to 1 m radius (~190,000 layers) with 30 elements a layer: 15x the work of
    # the default 2, estimated above the 20 s of a long run
    case = load_case(
        "pet1-26.7N",
        ["web.thickness='5 um'", "winding.outer_radius='1 m'", "winding.options.subdivisions=30"],
    )
    (w,) = [w for w in case.warnings if w.startswith("long run:") and "to wind" in w]
    assert "with the compiled kernels" in w and "layers_per_increment" in w
    assert not any(w.startswith("long run:") for w in load_case("pet1-26.7N").warnings)
