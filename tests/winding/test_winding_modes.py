"""Winding modes (woundroll.winding.tension, winding.mode): centre winding unchanged bit for
bit, the closed-form limits of surface and centre-surface winding, the published trend
(surface winding: the wound-on tension rises with the nip load and levels off), bad input
through the CLI (one line naming the field, exit 2)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.winding.tension import TensionSchedule

runner = CliRunner()

H = 1e-4  # web thickness [m]
TW = 2e6  # web stress [Pa], T_w h = 200 N/m
R = np.linspace(0.05, 0.2, 7)


def wot(**kw) -> np.ndarray:
    return TensionSchedule(web_stress=TW, **kw).wound_on_tension(R, 0.05, 0.2, H)


def surface(**kw) -> dict:
    return (
        dict(mode="surface", nip_load=500.0, friction=0.2, drum_friction=0.3, nip_saturation=1000.0)
        | kw
    )


def test_center_mode_is_todays_formula_bit_for_bit():
    kw = dict(nip_load=500.0, friction=0.2)
    assert np.array_equal(wot(**kw), TW + 0.2 * 500.0 / H + 0 * R)
    assert np.array_equal(wot(**kw), wot(mode="center", **kw))


def test_center_run_unchanged_through_the_cli():
    nip = ["--set", "winding.nip_load=300 N/m", "--set", "winding.friction=0.2"]
    full = ["--json", "--fields", "full", "--no-update"]  # per-node fields compared
    a = runner.invoke(app, ["run", "pet1-26.7N", *full, *nip])
    b = runner.invoke(app, ["run", "pet1-26.7N", *full, *nip, "--set", "winding.mode=center"])
    assert a.exit_code == 0 and b.exit_code == 0, b.output
    wa, wb = json.loads(a.stdout)["winding"], json.loads(b.stdout)["winding"]
    assert wa["sigma_r_Pa"] == wb["sigma_r_Pa"]
    assert wa["wound_on_tension_Pa"] == wb["wound_on_tension_Pa"]
    assert json.loads(a.stdout)["hardness"] == json.loads(b.stdout)["hardness"]


def test_surface_limits():
    # low nip load: NIT -> mu_eff N (tanh x ~ x; relative error x^2/3 = 3.3e-7 at N = N_s/1000)
    low = wot(**surface(nip_load=1.0))
    assert low - TW == pytest.approx(0.2 * 1.0 / H, rel=1e-6)
    # high nip load: NIT -> mu_eff N_s (tanh(50) = 1 to round-off)
    high = wot(**surface(nip_load=50_000.0))
    assert high == pytest.approx(TW + 0.2 * 1000.0 / H, rel=1e-14)
    # the drum grips less than the layers: the slope is the drum's friction
    assert wot(**surface(nip_load=1.0, drum_friction=0.1)) - TW == pytest.approx(0.1 / H, rel=1e-6)
    # zero layer friction: no nip-induced tension
    assert np.array_equal(wot(**surface(friction=0.0)), TW + 0 * R)


def test_surface_wot_rises_with_nip_load_and_levels_off():
    # the published trend (Pfeiffer 1977; Good, Hartwig and Markum 1999): proportional at low
    # load, independent of the load at high load
    loads = np.array([0.1, 250, 500, 1000, 2000, 4000, 8000, 16000])
    w = np.array([wot(**surface(nip_load=n))[0] for n in loads])
    assert np.all(np.diff(w) > 0)
    nit = (w - TW) * H
    assert nit[1] / loads[1] == pytest.approx(0.2, rel=0.03)  # slope mu at 250 N/m
    assert nit[-1] - nit[-2] < 1e-6 * nit[-1]  # no rise left at 8 -> 16 kN/m
    # centre winding keeps rising linearly
    wc = np.array([wot(nip_load=n, friction=0.2)[0] for n in loads])
    assert (wc[-1] - TW) * H == pytest.approx(0.2 * loads[-1], rel=1e-12)


def test_center_surface_limits():
    base = wot(**surface())
    # zero differential: surface winding
    assert np.array_equal(wot(**surface(mode="center-surface", tension_differential=0.0)), base)
    # a small differential adds dT / h
    dT = 10.0  # N/m
    got = wot(**surface(mode="center-surface", tension_differential=dT))
    assert got == pytest.approx(base + dT / H, rel=1e-14)
    # beyond the drum's hold the web slips and the differential stays at the limit
    mu, beta, N = 0.3, math.pi / 2, 500.0
    limit = TW * H * math.expm1(mu * beta) + mu * N
    s = TensionSchedule(web_stress=TW, **surface(mode="center-surface", tension_differential=1e5))
    assert s.wound_on_tension(R, 0.05, 0.2, H) == pytest.approx(base + limit / H, rel=1e-12)
    assert s.drum_slips(R, 0.05, 0.2, H)


def test_surface_run_through_the_cli_reports_wot_against_radius():
    sets = [
        "winding.nip_load=582.7 N/m",
        "winding.mode=surface",
        "winding.drum_friction=0.3",
        "winding.nip_saturation=1000 N/m",
        "winding.friction=0.2",
    ]
    args = ["run", "pet1-26.7N", "--json", "--fields", "full", "-q"]  # per-node wot
    for s in sets:
        args += ["--set", s]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    w = json.loads(res.stdout)["winding"]
    nip = 582.7  # [N/m]
    d = json.loads(res.stdout)
    thick = next(v["value"] for v in d["case"]["inputs"] if v["key"] == "web.thickness")
    expected_nit = 0.2 * 1000.0 * math.tanh(nip / 1000.0) / thick
    assert w["wound_on_tension_Pa"][-1] - w["wound_on_tension_Pa"][0] == pytest.approx(0, abs=1e-6)
    tw = w["inputs"]["tension"]["web_stress_Pa"]
    assert w["wound_on_tension_Pa"][0] == pytest.approx(tw + expected_nit, rel=1e-9)


@pytest.mark.parametrize(
    ("sets", "field"),
    [
        (["winding.mode=sideways"], "winding.mode"),
        (["winding.drum_friction=0.3"], "winding.drum_friction"),
        (["winding.mode=surface", "winding.drum_friction=0.3"], "winding.nip_saturation"),
        (
            ["winding.mode=surface", "winding.nip_saturation=1 kN/m"],
            "winding.drum_friction",
        ),
        (
            [
                "winding.mode=center-surface",
                "winding.drum_friction=0.3",
                "winding.nip_saturation=1 kN/m",
            ],
            "winding.tension_differential",
        ),
        (
            [
                "winding.mode=center-surface",
                "winding.drum_friction=0.3",
                "winding.nip_saturation=1 kN/m",
                "winding.drum_torque=5 N m",
            ],
            "winding.drum_radius",
        ),
        (
            ["winding.mode=surface", "winding.drum_friction=-0.3", "winding.nip_saturation=1 kN/m"],
            "winding.drum_friction",
        ),
    ],
)
def test_bad_mode_input_is_one_line_naming_the_field(sets, field):
    args = ["run", "pet1-26.7N", "--json", "--set", "winding.nip_load=300 N/m"]
    for s in sets:
        args += ["--set", s]
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    assert field in res.output and "Traceback" not in res.output
    assert len(res.output.strip().splitlines()) <= 2


def test_surface_without_nip_is_an_error():
    with pytest.raises(InputError) as e:
        TensionSchedule(web_stress=TW, **surface(nip_load=0.0))
    assert e.value.field == "winding.nip_load"


def test_drum_slip_is_flagged_with_a_warning():
    sets = [
        "winding.friction=0.2",
        "winding.nip_load=500 N/m",
        "winding.mode=center-surface",
        "winding.drum_friction=0.3",
        "winding.nip_saturation=1000 N/m",
        "winding.tension_differential=1000 N/m",
    ]
    args = ["run", "pet1-26.7N", "--json", "--fields", "full"]  # per-node wot
    for s in sets:
        args += ["--set", s]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["flags"]["drum_slip"] is True
    assert any("slips on the drum" in w for w in d["warnings"])
    # the cap: T_w h (exp(mu_d beta) - 1) + mu_d N over h on top of surface winding
    tw = d["winding"]["inputs"]["tension"]["web_stress_Pa"]
    h = 1e-4
    limit = tw * h * math.expm1(0.3 * math.pi / 2) + 0.3 * 500
    nit = 0.2 * 1000 * math.tanh(0.5)
    assert d["winding"]["wound_on_tension_Pa"][0] == pytest.approx(tw + (nit + limit) / h, rel=1e-9)
