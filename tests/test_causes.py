"""Profile -> causes: the band basis, the reduced model, and a round trip (slow)."""

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.errors import InputError
from woundroll.inverse.causes import ProfileModel, fit_causes
from woundroll.inverse.diagnosis import ForwardCurve, ForwardPoint, RollModel
from woundroll.io.readings import readings_from_arrays


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


def band_round_trip():  # noqa: ANN201
    """Readings made by the reduced model from known bands (+1.2 % at 10 in, -0.8 % at 18
    in) and 110 % tension on PET2 53.4 N 24 in wide, with 0.4 Rho noise over 3 passes, and
    the causes fitted to them: (roll, the reduced model, the true parameters, the fit).
    docs/scripts/diagnosis.py shows the same round trip."""
    from woundroll.inverse.diagnosis import forward_curve

    case = load_case("pet2-53.4N", ["web.width='24 in'"])
    roll = RollModel.from_case(case)
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
    return roll, m, theta, fit_causes(case, r, n_bands=6)


@pytest.mark.slow
def test_round_trip_thickness_bands_and_tension():
    """Readings made by the reduced model from known bands (+1.2 % at 10 in, -0.8 % at 18
    in) and 110 % tension, with 0.4 Rho noise over 3 passes, come back (measured: thickness
    within 0.2 % of h everywhere, tension 108.7 % with SD 1.5 %)."""
    roll, m, theta, fit = band_round_trip()
    zz, hf, hsd = fit.thickness_profile()
    ht = m.thickness(theta[1:], zz)
    assert np.max(np.abs(hf - ht)) < 0.004 * roll.web.thickness
    assert abs(fit.theta[0] - np.log(1.1)) < 3 * fit.sd[0]
    kinds = [c["cause"].split()[0] for c in fit.causes[:2]]
    assert sorted(kinds) == ["thick", "thin"]
    assert fit.verification["max_abs_error"] < 0.5
    assert fit.residual_rms < 0.3


#: the nip-deflection problem (docs/diagnosis.md): PET2 24 in wide, 2 pli nip, mu = 0.3
NIP_SETS = ["web.width='24 in'", "winding.nip_load='2 pli'", "winding.friction=0.3"]


def nip_deflection_fit():  # noqa: ANN201
    """Readings of the reduced model with a nip load 40 % higher at the edges, 0.3 Rho
    noise, fitted with 6 bands: ``(fit, roll, true readings)`` (the test below;
    docs/scripts/diagnosis.py renders the numbers)."""
    case = load_case("pet2-53.4N", NIP_SETS)
    roll = RollModel.from_case(case)
    from woundroll.inverse.diagnosis import forward_curve

    curve = forward_curve(roll, [10, 60])
    pos = np.linspace(0, case.web.width, 241)
    m = ProfileModel(roll, curve, pos, np.full(pos.size, roll.web.thickness), 6, 31, True)
    theta = np.zeros(8)
    theta[1] = 0.6
    x = np.linspace(1, 23, 12) * 0.0254
    truth = m.readings(theta, x)
    rng = np.random.default_rng(1)
    xs = np.repeat(x, 3)
    r = readings_from_arrays(xs, np.repeat(truth, 3) + 0.3 * rng.standard_normal(xs.size))
    return fit_causes(case, r, n_bands=6), roll, truth


@pytest.mark.slow
def test_nip_deflection_on_a_soft_web_is_reported_not_identifiable():
    """PET2 (K2 = 26) with a 2 pli nip, mu = 0.3: a nip load 40 % higher at the edges than in
    the middle changes the readings by only 0.02 Rho in the uncoupled-sector model (the lanes
    with more nip-induced tension compress more, build a smaller radius and are allocated less
    web tension). The fit must say the deflection is not identifiable, not invent bands."""
    fit, roll, truth = nip_deflection_fit()
    assert np.ptp(truth) < 0.05
    assert fit.identifiable[1] is False
    nip = next(c for c in fit.causes if c["cause"] == "nip deflection")
    assert "not identifiable" in nip["sentence"]
    # the bands fitted to the noise stay small (this noise draw leaves a -0.2 % band at about
    # 3 posterior SDs: the SDs of a frozen-Jacobian fit are optimistic, docs/diagnosis.md)
    _, h, _ = fit.thickness_profile()
    assert np.max(np.abs(h / roll.web.thickness - 1)) < 0.003


# slow: a fit of causes with many forward runs (~20 s)
@pytest.mark.slow
def test_posterior_sds_scaled_by_the_residuals():
    # a fast fit on 7 sectors with a synthetic P_s -> reading map (through the cache): the
    # readings are the reduced model's own at 105 % tension plus a CMD step the smooth
    # bands cannot follow (model error). The raw posterior SDs trust the weights; the
    # calibrated ones are scaled by sqrt(chi2 / (n - tr H)), the Birge ratio, here > 1
    m = small_model(k=3)
    case = load_case("pet2-53.4N", ["web.width='24 in'"])
    x = np.linspace(1, 23, 12) * 0.0254
    m7 = ProfileModel(m.roll, m.curve, m.base_position, m.base_thickness, 3, 7, False)
    theta = np.zeros(4)
    theta[0] = np.log(1.05)
    clean = m7.readings(theta, x)
    step = np.where(x > 12 * 0.0254, 0.6, -0.6)
    rng = np.random.default_rng(2)
    xs = np.repeat(x, 3)
    noise = 0.1 * rng.standard_normal(xs.size)
    r = readings_from_arrays(xs, np.repeat(clean + step, 3) + noise)
    cache = {"curve": m.curve}
    fit = fit_causes(case, r, n_bands=3, n_sectors=7, verify=False, cache=cache)
    raw = fit_causes(case, r, n_bands=3, n_sectors=7, verify=False, cache=cache, calibrate_sd=False)
    assert raw.forward_runs == fit.forward_runs - 5  # start and Jacobian from the cache
    assert raw.sd_scale == 1.0
    assert fit.sd_scale == pytest.approx(np.sqrt(fit.residual_chi2 / fit.residual_dof))
    assert fit.sd_scale > 3.0  # residuals of ~0.5 Rho against standard errors of 0.06
    np.testing.assert_allclose(fit.sd, raw.sd * fit.sd_scale, rtol=1e-12)
    assert any("posterior SDs are scaled" in n for n in fit.notes)
    # the same readings without the step: the residuals match the scatter, no inflation
    # beyond the chi-square's own spread (dof ~ 8: sqrt(chi2/dof) within 0.5-1.5)
    r2 = readings_from_arrays(xs, np.repeat(clean, 3) + noise)
    ok = fit_causes(case, r2, n_bands=3, n_sectors=7, verify=False, cache=cache)
    assert ok.sd_scale < 1.6


def full_profile_round_trip(tmp_path, seed=0, full_level=3, cache=None, verify=True):  # noqa: ANN001, ANN201
    """Readings made by the full profile model of the 24 in PET2 roll with two bands at 110 %
    tension (noise draw ``seed``), fitted by the reduced model with ``full_level`` full-model
    level corrections: ``(fit, model, true band coefficients)`` (the test below;
    docs/scripts/diagnosis.py's record of 30 noise draws). ``cache`` (a dict, kept between
    calls) shares the truth's full profile run and the fit's forward curve and starting
    Jacobian between draws; those are always draw 0's (a draw other than 0 first fits draw 0
    into an empty cache), so that a draw's numbers do not depend on the draws before it."""
    case = load_case("pet2-53.4N", ["web.width='24 in'", "profile.workers=1"])
    m = small_model()
    c = np.zeros(6)
    c[2], c[4] = 0.012, -0.008
    pos = m.base_position
    h = m.thickness(c, pos)
    path = tmp_path / "bands.csv"
    np.savetxt(path, np.column_stack([pos * 1e3, h * 1e6]), delimiter=",",
               header="position [mm],thickness [um]", comments="")  # fmt: skip
    from woundroll.pipeline import run

    t = RollModel.from_case(case).tension
    truth_case = load_case(
        "pet2-53.4N",
        [
            "web.width='24 in'",
            "profile.workers=1",
            "profile.sectors=31",
            f"winding.thickness_profile='{path}'",
            f"winding.tension='{1.1 * t} Pa'",
        ],
    )
    x = np.linspace(1, 23, 12) * 0.0254
    if cache is not None and "truth" in cache:
        truth = cache["truth"]
    else:
        prof = run(truth_case).profile
        truth = np.interp(x, prof.z, prof.rho)
        if cache is not None:
            cache["truth"] = truth

    def draw(s):  # noqa: ANN001, ANN202
        rng = np.random.default_rng(s)
        xs = np.repeat(x, 3)
        return readings_from_arrays(xs, np.repeat(truth, 3) + 0.4 * rng.standard_normal(xs.size))

    if cache is not None and seed != 0 and "curve" not in cache:
        fit_causes(case, draw(0), n_bands=6, verify=False, cache=cache)
    fit = fit_causes(case, draw(seed), n_bands=6, full_level=full_level, verify=verify, cache=cache)
    return fit, m, c


@pytest.mark.slow
def test_round_trip_against_the_full_profile_model(tmp_path):
    """Readings made by the FULL profile model (coupled axisymmetric winding, a contact solve
    per sector) of a 24 in PET2 roll at 110 % tension with bands of +1.2 % at 10 in and
    -0.8 % at 18 in (12 positions, 3 passes, 0.4 Rho noise), fitted by the reduced model.
    This is draw 0 of the record diagnosis.causes_full (30 noise draws; docs/diagnosis.md
    renders the bands, thickness errors, levels and coverages over them). Draw 0 on
    2026-11-26: the level path 102.9 -> 106.8 -> 108.2 -> 108.1 % of the case's tension
    against the true 110 % (with the 0.6 cm a on the profile only it was 28 -> ... ->
    102.1 %, beyond the bound)."""
    import math

    fit, m, c = full_profile_round_trip(tmp_path)
    zz, hf, hsd = fit.thickness_profile()
    ht = m.thickness(c, zz)
    # the bands: where they are and how large, within 0.45 % of h everywhere (draw 0:
    # 0.35 %; the record's mean and worst over its draws: docs/diagnosis.md)
    assert np.max(np.abs(hf - ht)) < 0.0045 * m.base_thickness[0]
    kinds = sorted(cz["cause"].split()[0] for cz in fit.causes[:2])
    assert kinds == ["thick", "thin"]
    # the tension level after the full-model correction: measured 102.9 % -> 106.8 % ->
    # 108.2 % -> 108.1 % (the first step along the reduced model's sensitivity at the fit,
    # then secants on the full model's runs): allowed 4 % in ln s (measured 1.7 %)
    assert abs(fit.theta[0] - math.log(1.1)) < 0.04
    assert fit.sd_scale >= 1.0
    assert fit.verification["full_level"]["full_runs"] == 3
