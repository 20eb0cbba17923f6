"""Winding speed and entrained air (woundroll.winding.air): speed 0 equal to today's model
bit for bit; the lay-on film against its closed forms and in their limits; the gas-spring
layer in series with the stack; the after-the-air solve against the closed form of the
annulus and its convergence rate; convergence of the wound roll under refinement; the
published trends (more air with speed, less with tension and nip load); result.json keys
and bad input through the CLI."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.materials.radial_modulus import Constant, Pfeiffer
from woundroll.materials.web import Core, Web
from woundroll.pipeline import run
from woundroll.pipeline.vocabulary import undescribed_keys
from woundroll.winding.air import (
    FOIL_COEFFICIENT,
    AirLayerLaw,
    AirSettings,
    _banded_increment,
    air_thickness,
    entrained_air,
    foil_bearing_film,
    lay_on_film,
    nip_film,
    wind_with_air,
)
from woundroll.winding.hakiel import WindingOptions, wind
from woundroll.winding.storage import closed_form_linear
from woundroll.winding.tension import TensionSchedule

runner = CliRunner()

# a 12 um film on a rigid 3.8 cm core wound to 5 cm (1000 layers), 5 MPa in the web
WEB = Web(thickness=12e-6, width=0.5, E_theta=4.9e9, radial_modulus=Pfeiffer(K1=10e3, K2=100.0))
CORE = Core(outer_radius=0.038)
R_OUT = 0.05
TENSION = TensionSchedule(web_stress=5e6)

CASE = """
title = "air"
[web]
thickness = "12 um"
width = "0.5 m"
E_theta = "4.9 GPa"
radial_modulus = { law = "pfeiffer", K1 = "10 kPa", K2 = 100 }
[core]
outer_radius = "3.8 cm"
rigid = true
[winding]
outer_radius = "5 cm"
tension = "5 MPa"
"""


def _case(tmp_path: Path, extra: str = "", winding: str = "") -> Path:
    text = CASE.replace('tension = "5 MPa"', 'tension = "5 MPa"\n' + winding) + extra
    path = tmp_path / "case.toml"
    path.write_text(text, encoding="utf-8")
    return path


# ----------------------------------------------------------------- speed 0 = today's model


def test_speed_zero_is_todays_model_bit_for_bit(tmp_path):
    """A run that does not ask for air, or asks for speed 0, is today's run: the same arrays
    bit for bit and no air block."""
    base = run(_case(tmp_path))
    zero = run(_case(tmp_path, winding="speed = 0"))
    for a in ("radius", "sigma_r", "sigma_theta", "E_r", "wot"):
        assert np.array_equal(getattr(base.winding, a), getattr(zero.winding, a))
    assert base.winding.air is None and zero.winding.air is None
    # and wind_with_air at speed 0 hands back the roll it was given
    w = wind(WEB, CORE, R_OUT, TENSION)
    res = wind_with_air(WEB, CORE, R_OUT, TENSION, AirSettings(speed=0.0), no_air=w)
    assert res.after is w and res.at_winding is w and res.air == 0.0
    assert res.outer_radius_at_winding == res.outer_radius_no_air


def test_film_within_the_roughness_is_todays_model():
    """A film the roughness closes (a0 = max(h - 3 sigma, 0) = 0) entrains nothing."""
    w = wind(WEB, CORE, R_OUT, TENSION)
    air = AirSettings(speed=0.5, roughness=5e-6)
    film = lay_on_film(np.array([R_OUT]), np.array([5e6 * 12e-6]), 0.0, air)[0]
    assert film < 3 * 5e-6
    res = wind_with_air(WEB, CORE, R_OUT, TENSION, air, no_air=w)
    assert res.after is w and res.air == 0.0
    assert float(entrained_air(4e-6, 1e-6)[()]) == pytest.approx(1e-6, rel=1e-12)


# ----------------------------------------------------------------- the film's closed forms


def test_foil_bearing_film_closed_form_and_scaling():
    """h0 = 0.643 R (6 eta U / T)^(2/3) (Eshel and Elrod; Knox and Sweeney): a number worked
    by hand, and the exponents 1 (R), 2/3 (U), -2/3 (T) to rounding."""
    # R = 0.1 m, U = 5 m/s, T = 200 N/m, eta = 1.8e-5: (5.4e-4 / 200)^(2/3) = 1.9390e-4
    h = float(foil_bearing_film(0.1, 5.0, 200.0, 1.8e-5))
    assert h == pytest.approx(FOIL_COEFFICIENT * 0.1 * (6 * 1.8e-5 * 5 / 200) ** (2 / 3))
    assert h == pytest.approx(12.47e-6, rel=1e-3)  # hand value
    slope = lambda f, a, b: math.log(f(b) / f(a)) / math.log(b / a)  # noqa: E731
    assert slope(lambda R: foil_bearing_film(R, 5.0, 200.0), 0.05, 0.2) == pytest.approx(1.0)
    assert slope(lambda U: foil_bearing_film(0.1, U, 200.0), 1.0, 10.0) == pytest.approx(2 / 3)
    assert slope(lambda T: foil_bearing_film(0.1, 5.0, T), 50.0, 500.0) == pytest.approx(-2 / 3)


def test_nip_film_limits():
    """The nip's film: the rigid-isoviscous (Martin) form for a hard nip, the
    isoviscous-elastic (Herrebrugh) form for a soft one; no nip load: the foil bearing's
    film (a nip only removes air)."""
    R, Rn, U, w, eta = 0.1, 0.05, 5.0, 500.0, 1.8e-5
    Re = 1 / (1 / R + 1 / Rn)
    hard = float(nip_film(R, U, w, nip_radius=Rn, nip_modulus=200e9, viscosity=eta))
    assert hard == pytest.approx(4.9 * eta * U * Re / w, rel=1e-12)
    soft = float(nip_film(R, U, w, nip_radius=Rn, nip_modulus=1e5, viscosity=eta))
    Ep = 2e5
    assert soft == pytest.approx(
        2.32 * Re * (eta * U / (Ep * Re)) ** 0.6 * (w / (Ep * Re)) ** -0.2, rel=1e-12
    )
    air = AirSettings(speed=U)
    T = 60.0
    foil = float(foil_bearing_film(R, U, T))
    assert float(lay_on_film(R, T, 0.0, air)) == foil
    assert float(lay_on_film(R, T, 1e-9, air)) == foil  # a vanishing nip takes no air
    assert float(lay_on_film(R, T, 500.0, air)) < foil


def test_air_layer_law_is_the_series_of_stack_and_gas_spring():
    """1/E_eff = [h/E_r + p_atm a0 / (p_atm + P)^2] / (h + a0); a0 = 0 is the stack; at
    P >> p_atm the gas spring is stiff (E_eff -> E_r (h + a0) / h)."""
    law = AirLayerLaw(Constant(E_r=5e6), 10e-6, 5e-6, 1e5)
    P = np.array([0.0, 1e5, 1e9])
    expected = 15e-6 / (10e-6 / 5e6 + 1e5 * 5e-6 / (1e5 + P) ** 2)
    assert np.allclose(law.modulus_at_pressure(P), expected, rtol=1e-14)
    assert law.modulus_at_pressure(1e12) == pytest.approx(5e6 * 1.5, rel=1e-6)
    stack_only = AirLayerLaw(Constant(E_r=5e6), 10e-6, 0.0).modulus_at_pressure(3e4)
    assert float(stack_only) == pytest.approx(5e6, rel=1e-14)
    # the gas spring: (p_atm + P) h_a = p_atm a0
    assert float(air_thickness(1e5, 5e-6, 1e5)) == pytest.approx(2.5e-6)
    p, e = law.tabulate(1e6)
    assert p[0] == 0.0 and np.all(np.diff(p) > 0)
    mid = 0.5 * (p[1:] + p[:-1])
    # the knots resolve the gas spring: linear interpolation within 0.2 % of the law
    assert np.max(np.abs(np.interp(mid, p, e) / law.modulus_at_pressure(mid) - 1)) < 2e-3


# ----------------------------------------------------------------- the after-the-air solve


@pytest.mark.parametrize("core_stiffness", [math.inf, 2e9])
def test_free_strain_solve_matches_the_annulus_closed_form(core_stiffness):
    """The banded solve of the after-the-air increment against the closed form of the
    cylindrically orthotropic annulus with a uniform radial free strain (storage's
    closed_form_linear): second order, within 1e-4 on 2000 nodes."""
    a, b, Er, Et, nu, eps = 0.038, 0.05, 5e6, 4.9e9, 0.0, -0.02
    errs = []
    for n in (250, 500, 1000, 2000):
        r = np.linspace(a, b, n + 1)
        s = _banded_increment(
            r, np.full(r.size, Er), Et, nu, np.full(r.size, eps), core_stiffness,
            np.zeros(r.size, dtype=bool), np.zeros(r.size),
        )  # fmt: skip
        exact = closed_form_linear(r, a, b, Er, Et, nu, eps, 0.0, core_stiffness, 0.0)
        errs.append(np.max(np.abs(s - exact)) / np.max(np.abs(exact)))
    rates = [math.log2(errs[i] / errs[i + 1]) for i in range(len(errs) - 1)]
    assert errs[-1] < 1e-4, errs
    assert all(1.8 < q < 2.2 for q in rates), rates


# ----------------------------------------------------------------- the wound roll


@pytest.fixture(scope="module")
def fast_roll():
    w = wind(WEB, CORE, R_OUT, TENSION)
    return w, wind_with_air(WEB, CORE, R_OUT, TENSION, AirSettings(speed=8.0), no_air=w)


def test_air_makes_the_roll_bigger_and_softer(fast_roll):
    """With air: a larger diameter for the same length and a lower pressure; after the air
    has left: the pressure lower still, the diameter between (the outer layer's hoop strain
    only), never tension between layers."""
    w, res = fast_roll
    assert res.air > 0
    assert res.outer_radius_at_winding > res.outer_radius_no_air
    assert res.at_winding.core_pressure < w.core_pressure
    assert res.after.core_pressure <= res.at_winding.core_pressure
    assert res.outer_radius_no_air < res.outer_radius_after <= res.outer_radius_at_winding
    assert np.all(res.after.sigma_r <= 0.0)
    # the wound length is kept: the roll with air has fewer, larger layers
    assert res.at_winding.n_layers < w.n_layers
    # the compacted roll without air: within the stack's strain of the uncompacted one
    assert 0.99 * R_OUT < res.outer_radius_no_air < R_OUT
    # the wound-in tension of the top layer is the web's (the composite's hoop stress / f)
    assert res.at_winding.sigma_theta[-1] == pytest.approx(5e6, rel=1e-9)


def test_roll_with_air_converges_under_refinement():
    """A nipped roll with a thin air layer (it stays tight after the air has left) on
    finer grids, subdivisions 1 -> 2 -> 4 -> 8: the core pressure at winding and after the
    air has left converge at better than first order (each difference less than half the
    one before; the discretisation is second order, Hakiel's kernels and the banded
    free-strain solve), the finest pair within 1e-6."""
    nipt = replace(TENSION, nip_load=300.0)
    air = AirSettings(speed=8.0, roughness=0.05e-6)
    pw, pa = [], []
    for ns in (1, 2, 4, 8):
        opts = WindingOptions(subdivisions=ns)
        res = wind_with_air(WEB, CORE, R_OUT, nipt, air, options=opts)
        assert res.air > 0 and res.after.core_pressure > 0
        pw.append(res.at_winding.core_pressure)
        pa.append(res.after.core_pressure)
    for p in (pw, pa):
        d = np.abs(np.diff(p))
        assert np.all(d[1:] < 0.5 * d[:-1]), p
        assert d[-1] < 1e-6 * p[-1], p


def test_published_trends():
    """More air with speed; less with web tension and with nip load (Good and Holmberg 1993;
    Forrest 1995); the roll's pressure at winding falls as the speed rises."""
    U = np.array([2.0, 5.0, 10.0, 20.0])
    f_speed = [float(foil_bearing_film(0.1, u, 100.0)) for u in U]
    f_tension = [float(foil_bearing_film(0.1, 5.0, t)) for t in (50.0, 100.0, 200.0)]
    f_nip = [float(nip_film(0.1, 5.0, w)) for w in (100.0, 300.0, 1000.0, 3000.0)]
    assert np.all(np.diff(f_speed) > 0)
    assert np.all(np.diff(f_tension) < 0)
    assert np.all(np.diff(f_nip) < 0)
    w = wind(WEB, CORE, R_OUT, TENSION)
    rolls = [
        wind_with_air(WEB, CORE, R_OUT, TENSION, AirSettings(speed=u), no_air=w) for u in (3, 8)
    ]
    assert rolls[0].air < rolls[1].air
    assert rolls[0].at_winding.core_pressure > rolls[1].at_winding.core_pressure
    assert rolls[0].outer_radius_at_winding < rolls[1].outer_radius_at_winding
    # a tighter web entrains less
    tight = wind_with_air(
        WEB, CORE, R_OUT, replace(TENSION, web_stress=10e6), AirSettings(speed=8.0)
    )
    assert tight.air < rolls[1].air
    # a nip entrains less than none, and less with more load
    nipped = [
        wind_with_air(WEB, CORE, R_OUT, replace(TENSION, nip_load=n), AirSettings(speed=8.0)).air
        for n in (200.0, 2000.0)
    ]
    assert nipped[0] < rolls[1].air and nipped[1] <= nipped[0]


def test_leakage_time_grows_with_width_and_depth(fast_roll):
    """tau = 12 eta W^2 / (pi^2 p h_g^2): twice the width, four times the time; deeper
    layers (higher pressure, thinner air) keep their air longer."""
    _, res = fast_roll
    tau = res.leakage_time
    assert tau[0] > tau[-1]
    wide = wind_with_air(
        replace(WEB, width=1.0), CORE, R_OUT, TENSION, AirSettings(speed=8.0)
    ).leakage_time
    assert np.allclose(wide, 4 * tau, rtol=1e-9)


# ----------------------------------------------------------------- pipeline, JSON, CLI


def test_air_run_json_is_described(tmp_path):
    """An air run through the CLI: the air block in result.json, every key in the
    vocabulary, the summary line printed, ft/min accepted."""
    path = _case(tmp_path, winding='speed = "1500 ft/min"\n', extra='[air]\npressure = "1 bar"\n')
    res = runner.invoke(app, ["run", str(path), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    air = doc["winding"]["air"]
    assert air["speed_m_per_s"] == pytest.approx(1500 * 0.3048 / 60)
    assert air["ambient_pressure_Pa"] == pytest.approx(1e5)
    assert air["outer_diameter_at_winding_m"] > air["outer_diameter_no_air_m"]
    assert undescribed_keys(doc) == []
    text = runner.invoke(app, ["run", str(path)])
    assert text.exit_code == 0 and "film at lay-on" in text.output


@pytest.mark.parametrize(
    ("winding", "extra", "field"),
    [
        ("speed = -2", "", "winding.speed"),
        ('speed = "-100 ft/min"', "", "winding.speed"),
        ("speed = 5", "[air]\nviscosity = -1\n", "air.viscosity"),
    ],
)
def test_bad_air_input_exits_2_naming_the_field(tmp_path, winding, extra, field):
    res = runner.invoke(app, ["run", str(_case(tmp_path, extra, winding)), "-q"])
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.strip().splitlines() if ln.strip()]
    assert len(lines) == 1 and field in lines[0], res.output


def test_roughness_beyond_the_thickness_exits_2(tmp_path):
    path = _case(tmp_path)
    text = path.read_text().replace(
        'E_theta = "4.9 GPa"', 'E_theta = "4.9 GPa"\nroughness = "20 um"'
    )
    path.write_text(text)
    res = runner.invoke(app, ["run", str(path), "-q"])
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.strip().splitlines() if ln.strip()]
    assert len(lines) == 1 and "web.roughness" in lines[0], res.output
    # the same through --set
    res = runner.invoke(app, ["run", str(_case(tmp_path)), "-q", "--set", "web.roughness=12 um"])
    assert res.exit_code == 2 and "web.roughness" in res.output


def test_thickness_profile_with_speed_is_refused(tmp_path):
    prof = tmp_path / "p.csv"
    prof.write_text("position_m,thickness_m\n0,12e-6\n0.5,12e-6\n")
    path = _case(tmp_path, winding='speed = 5\nthickness_profile = "p.csv"\n')
    res = runner.invoke(app, ["run", str(path), "-q"])
    assert res.exit_code == 2 and "winding.speed" in res.output, res.output


def test_diameter_curve_ends_at_the_outer_diameters(fast_roll):
    """The diameter against wound length (where metre L sits in the finished roll) starts at
    the core and ends at the outer diameters (the same length: within one layer's share)."""
    _, res = fast_roll
    L, d0, d1 = res.curve
    assert L[0] == 0.0 and d0[0] == pytest.approx(2 * CORE.outer_radius)
    assert np.all(np.diff(d0) > 0) and np.all(d1 >= d0)
    assert d0[-1] == pytest.approx(2 * res.outer_radius_no_air, rel=1e-3)
    assert d1[-1] == pytest.approx(2 * res.outer_radius_at_winding, rel=1e-3)


def test_air_figure_is_written(tmp_path):
    path = _case(tmp_path, winding="speed = 3\n")
    out = tmp_path / "out"
    res = runner.invoke(app, ["run", str(path), "-q", "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert (out / "winding.png").is_file() and (out / "winding_air.png").is_file()
    doc = json.loads((out / "result.json").read_text())
    assert "winding_air.png" in doc["files"]
    assert len(doc["winding"]["air"]["wound_length_m"]) == 101


def test_film_per_turn_against_a_published_example():
    """A published example (Rheologic's TopWeb, "roll winding" example page): 3000 m of
    100 um PET at 50 m/min and 150 N/m, no nip: 636 mm without air, 660.7 mm "on the basis
    of the air being entrained at each turn" (uncompressed). Each turn laid on with its
    foil-bearing film here: 667.0 mm, 1 % above (the air part, 15.5 mm of radius against
    12.35 mm, 25 % above: their constant and speed convention are not published; the sum
    of the two surface speeds, 12 eta U, would give 59 % more air). Core radius from the
    636 mm and the length (7.5 cm)."""
    h, L, U, T = 100e-6, 3000.0, 50 / 60, 150.0
    rc = math.sqrt(0.318**2 - L * h / math.pi)
    r, wound = rc, 0.0
    while wound < L:
        f = float(foil_bearing_film(r, U, T))
        wound += 2 * math.pi * (r + (h + f) / 2)
        r += h + f
    assert 2 * r == pytest.approx(0.6607, rel=0.015)


def test_leaving_time_closed_form():
    """t_f = C int dh / (h (h + sigma)^2): against a numerical integral (1e-6), 49.5 initial
    time constants for 90 % on a smooth web, and the roughness' valleys keep it finite."""
    from woundroll.winding.air import leaving_time

    a, sig, p, W = 5e-6, 0.2e-6, 2e5, 0.5
    C = 12 * 1.8e-5 * W**2 / (math.pi**2 * p)
    h = np.geomspace(0.1 * a, a, 200_001)
    f = 1 / (h * (h + sig) ** 2)
    numeric = C * float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(h)))
    assert float(leaving_time(a, sig, p, W, 0.9)) == pytest.approx(numeric, rel=1e-6)
    tau0 = C / a**2
    assert float(leaving_time(a, 0.0, p, W, 0.9)) == pytest.approx(49.5 * tau0, rel=1e-12)
    t = [float(leaving_time(a, sig, p, W, q)) for q in (0.5, 0.9, 0.99)]
    assert t[0] < t[1] < t[2] < math.inf


def test_loose_roll_is_flagged(tmp_path):
    """A fast roll without nip whose air cannot be replaced by the stack comes apart once the
    air has left: the flag air_loose, a warning, and the roll downstream without pressure."""
    path = _case(tmp_path, winding="speed = 8\n")
    res = run(path)
    assert res.flags["air_loose"] is True
    assert any("pulled apart" in w for w in res.warnings)
    assert res.winding.air["core_pressure_at_winding_Pa"] > 0
    assert res.winding.core_pressure == pytest.approx(0.0, abs=1e-9)
    # a nip and a little roughness: 0.31 um of air per layer, which the stack makes up
    path = _case(tmp_path, winding='speed = 8\nnip_load = "300 N/m"\n')
    text = path.read_text().replace(
        'E_theta = "4.9 GPa"', 'E_theta = "4.9 GPa"\nroughness = "0.05 um"'
    )
    path.write_text(text)
    tight = run(path)
    assert tight.winding.air["entrained_air_m"] > 0
    assert tight.flags["air_loose"] is False and tight.winding.core_pressure > 0


def test_roll_some_time_after_winding():
    """air.time: the roll keeps the air the leakage model leaves it; at time 0 it is the
    roll at winding (to the solver's tolerance), and with time it moves monotonically
    toward the roll after all the air has left."""
    nipt = replace(TENSION, nip_load=300.0)
    base = AirSettings(speed=8.0, roughness=0.05e-6)
    w = wind(WEB, CORE, R_OUT, nipt)
    done = wind_with_air(WEB, CORE, R_OUT, nipt, base, no_air=w)
    p = []
    for t in (0.0, 60.0, 600.0, 3600.0):
        res = wind_with_air(WEB, CORE, R_OUT, nipt, replace(base, time=t), no_air=w)
        p.append(res.after.core_pressure)
        if t == 0.0:
            assert res.gone == 0.0
            assert res.after.core_pressure == pytest.approx(res.at_winding.core_pressure, rel=1e-9)
    assert p[0] > p[1] > p[2] > p[3] > done.after.core_pressure
    assert done.gone == 1.0


def test_bad_air_time_exits_2(tmp_path):
    res = runner.invoke(
        app, ["run", str(_case(tmp_path, '[air]\ntime = "-1 h"\n', "speed = 5")), "-q"]
    )
    assert res.exit_code == 2 and "air.time" in res.output, res.output
