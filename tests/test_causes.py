"""Profile -> causes: the band basis, the reduced model, and a round trip (slow)."""

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.causes import ProfileModel, fit_causes
from woundroll.diagnosis import ForwardCurve, ForwardPoint, RollModel
from woundroll.errors import InputError
from woundroll.readings import readings_from_arrays


def small_model(nip=False, k=6):
    case = load_case("pet2-53.4N", ["web.width='24 in'"])
    roll = RollModel.from_case(case)
    pts = tuple(ForwardPoint(t, t, p, r, r, False) for t, p, r in
                [(1e5, 1e3, 10.0), (1e6, 1e4, 17.0), (1e7, 1e5, 30.0)])  # fmt: skip
    pos = np.linspace(0, case.web.width, 241)
    return ProfileModel(roll, ForwardCurve(pts, "Rho"), pos, np.full(241, 1e-4), k, 31, nip)


def test_bands_keep_the_mean_thickness_and_sit_where_named():
    m = small_model()
    c = np.array([0.0, 0.0, 0.012, 0.0, -0.008, 0.0])
    h = m.thickness(c)
    # mean removed: the width-averaged thickness stays the nominal one (trapezoid rule)
    assert np.trapezoid(h, m.base_position) / m.width == pytest.approx(1e-4, rel=1e-12)
    # band k is centred at (k + 1/2) W / K: the thick one at 10 in, the thin one at 18 in
    z = m.base_position / 0.0254
    assert z[np.argmax(h)] == pytest.approx(10.0, abs=0.2)
    assert z[np.argmin(h)] == pytest.approx(18.0, abs=0.2)


def test_pressure_to_reading_map_is_the_curve_and_extends_log_linearly():
    m = small_model()
    np.testing.assert_allclose(m.reading_of_pressure(np.array([1e3, 1e4, 1e5])), [10, 17, 30])
    # beyond the curve: linear in ln P with the end segment's slope (13 Rho per decade)
    assert m.reading_of_pressure(np.array([1e6]))[0] == pytest.approx(43.0, rel=1e-12)


def test_needs_three_positions():
    r = readings_from_arrays([0.1, 0.2], [15.0, 16.0])
    with pytest.raises(InputError, match=">= 3 positions"):
        fit_causes(load_case("pet2-53.4N", ["web.width='24 in'"]), r)


@pytest.mark.slow
def test_round_trip_thickness_bands_and_tension():
    """Readings made by the reduced model from known bands (+1.2 % at 10 in, -0.8 % at 18
    in) and 110 % tension, with 0.4 Rho noise over 3 passes, come back (measured: thickness
    within 0.2 % of h everywhere, tension 108.7 % with SD 1.5 %)."""
    case = load_case("pet2-53.4N", ["web.width='24 in'"])
    roll = RollModel.from_case(case)
    from woundroll.diagnosis import forward_curve

    curve = forward_curve(roll, [15, 40])
    pos = np.linspace(0, case.web.width, 241)
    m = ProfileModel(roll, curve, pos, np.full(pos.size, roll.web.thickness), 6, 31, False)
    theta = np.zeros(7)
    theta[0], theta[3], theta[5] = np.log(1.1), 0.012, -0.008
    x = np.linspace(1, 23, 12) * 0.0254
    truth = m.readings(theta, x)
    rng = np.random.default_rng(0)
    xs = np.repeat(x, 3)
    r = readings_from_arrays(xs, np.repeat(truth, 3) + 0.4 * rng.standard_normal(xs.size))
    fit = fit_causes(case, r, n_bands=6)
    zz, hf, hsd = fit.thickness_profile()
    ht = m.thickness(theta[1:], zz)
    assert np.max(np.abs(hf - ht)) < 0.004 * roll.web.thickness
    assert abs(fit.theta[0] - np.log(1.1)) < 3 * fit.sd[0]
    kinds = [c["cause"].split()[0] for c in fit.causes[:2]]
    assert sorted(kinds) == ["thick", "thin"]
    assert fit.verification["max_abs_error"] < 0.5
    assert fit.residual_rms < 0.3
