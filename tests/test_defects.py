"""Defect risk: each criterion against its formula computed by hand, risk levels, lanes."""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.case import load_case
from woundroll.cli import app
from woundroll.defects import (
    WATCH_MARGIN,
    DefectLimits,
    assess_roll,
    buckling_stress,
    defect_report,
)
from woundroll.winding.hakiel import wind


@pytest.fixture(scope="module")
def roll():
    case = load_case("pet2-80N")
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    return case, web, core, w


def by_name(crit):
    return {c.name: c for c in crit}


def test_buckling_estimate_formula():
    # 0.5 (5 GPa x 6 MPa x 12 MPa)^(1/3) = 0.5 x (3.6e23)^(1/3)
    assert buckling_stress(5e9, 6e6, 12e6) == pytest.approx(0.5 * 3.6e23 ** (1 / 3), rel=1e-12)


def test_core_crush_and_blocking_margins_by_hand(roll):
    case, web, core, w = roll
    lim = DefectLimits(core_strength=150e3, blocking_pressure=1e6)
    c = by_name(assess_roll(w, web, core, lim))
    assert c["core crush"].margin == pytest.approx(150e3 / w.core_pressure, rel=1e-12)
    assert c["core crush"].risk == "high"  # 207 kPa on a 150 kPa core
    assert c["blocking"].margin == pytest.approx(1e6 / float(-w.sigma_r.min()), rel=1e-12)
    assert c["blocking"].risk == "low"
    # without limits: reported, not judged
    c0 = by_name(assess_roll(w, web, core, DefectLimits()))
    assert c0["core crush"].risk == "n/a" and c0["blocking"].risk == "n/a"


def test_torque_and_axial_slip_by_hand(roll):
    case, web, core, w = roll
    M, a_g, mu = 20.0, 2.0, 0.3
    c = by_name(assess_roll(w, web, core, DefectLimits(torque=M, axial_acceleration=a_g * 9.81)))
    r, P = w.radius, -w.sigma_r
    R, W = r[-1], web.width
    keep = r < R - 0.01 * (R - r[0])
    tau_t = M / (2 * math.pi * r**2 * W)
    assert c["torque slip"].margin == pytest.approx(np.min(mu * P[keep] / tau_t[keep]), rel=1e-12)
    m_out = web.density * math.pi * (R**2 - r**2) * W
    tau_a = m_out * a_g * 9.81 / (2 * math.pi * r * W)
    assert c["telescoping"].margin == pytest.approx(np.min(mu * P[keep] / tau_a[keep]), rel=1e-12)
    # ten times the torque: ten times less margin (tau is linear in M)
    c10 = by_name(assess_roll(w, web, core, DefectLimits(torque=10 * M)))
    assert c10["torque slip"].margin == pytest.approx(c["torque slip"].margin / 10, rel=1e-12)


def test_negative_hoop_stress_is_watch_and_margin_uses_the_layer_mean(roll):
    case, web, core, w = roll
    c = by_name(assess_roll(w, web, core, DefectLimits()))["starring"]
    rm, st = w.layer_mean_hoop_stress()
    assert st.min() < 0 and c.demand == pytest.approx(-st.min())
    assert c.risk == "watch" and c.margin > WATCH_MARGIN  # far from the wrinkling estimate
    # the capacity is the wrinkling estimate with E_r and G = 2 E_r at the most compressed layer
    assert c.capacity == pytest.approx(
        buckling_stress(
            web.E_theta,
            np.interp(c.where_m, w.radius, w.E_r),
            2 * np.interp(c.where_m, w.radius, w.E_r),
        ),
        rel=1e-12,
    )


def test_slack_roll():
    case = load_case("pet2-26.7N", ["defects.slack_pressure='1 MPa'"])
    rep = defect_report(case)
    c = by_name(rep.roll)["slack"]
    assert c.risk == "high" and c.margin < 1
    assert rep.risk == "high"
    json.dumps(rep.to_dict())


def test_lanes_flag_the_slack_lane():
    from woundroll.diagnosis import Diagnosis, ForwardCurve, ForwardPoint
    from woundroll.readings import readings_from_arrays

    case = load_case("pet1-26.7N")
    t = np.array([1.8e6, 1.75e6, 0.9e6])
    pts = tuple(ForwardPoint(x, x, 0.02 * x, 50.0 + i, 50.0, False) for i, x in enumerate(t[::-1]))
    nan = np.full(3, np.nan)
    d = Diagnosis(
        readings=readings_from_arrays([0.02, 0.07, 0.12], [52, 51, 38]),
        position=np.array([0.02, 0.07, 0.12]),
        reading=nan,
        reading_low=nan,
        reading_high=nan,
        web_tension=t,
        web_tension_low=nan,
        web_tension_high=nan,
        wound_on_tension=t,
        wound_on_tension_low=nan,
        wound_on_tension_high=nan,
        surface_pressure=nan,
        surface_pressure_low=nan,
        surface_pressure_high=nan,
        status=("ok", "ok", "ok"),
        curve=ForwardCurve(pts, "Rho"),
        confidence=0.95,
        pressure_depth=0.0065,
        case_tension=1.75e6,
    )
    rep = defect_report(case, d)
    # 0.9 / 1.75 = 0.51 of the median < 0.7
    assert [ln["slack_lane"] for ln in rep.lanes] == [False, False, True]
    assert rep.lanes[2]["wot_over_median"] == pytest.approx(0.9 / 1.75)
    assert any(row[0] == "slack lanes" and "4.7 in" in row[2] for row in rep.summary())
    import matplotlib.pyplot as plt

    fig = rep.plot()
    assert len(fig.axes) == 2  # roll margins, and the margins per lane
    plt.close(fig)


def test_cli_defects():
    res = CliRunner().invoke(
        app, ["defects", "pet2-80N", "--set", "defects.core_strength='150 kPa'", "--json"]
    )
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)["defects"]
    assert d["risk"] == "high"
    assert {c["name"] for c in d["roll"]} >= {"starring", "core crush", "blocking", "slack"}
    assert all(c["source"].startswith("docs/diagnosis.md#") for c in d["roll"])
    res = CliRunner().invoke(app, ["defects", "pet2-80N", "--set", "defects.core_strength=-1"])
    assert res.exit_code == 2 and "defects.core_strength" in res.output


def test_plot_with_and_without_lanes(tmp_path):
    import matplotlib.pyplot as plt

    rep = defect_report(load_case("pet2-80N", ["defects.core_strength='150 kPa'"]))
    fig = rep.plot(tmp_path / "d.png")
    assert (tmp_path / "d.png").stat().st_size > 1000 and len(fig.axes) == 1
    plt.close(fig)


def test_cli_defects_out_beside_a_run(tmp_path):
    # defects.json/png go into a run's --out directory beside its files (written atomically,
    # never a NaN token) and leave the run's own files and result.json alone
    (tmp_path / "result.json").write_text('{"files": ["winding.png", "result.json"]}')
    (tmp_path / "winding.png").write_bytes(b"png")
    res = CliRunner().invoke(app, ["defects", "pet2-80N", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    data = json.loads((tmp_path / "defects.json").read_text(), parse_constant=_no_nan)
    assert {c["name"] for c in data["roll"]} >= {"starring", "core crush", "slack"}
    assert (tmp_path / "defects.png").stat().st_size > 1000
    assert (tmp_path / "winding.png").read_bytes() == b"png"
    assert not list(tmp_path.glob(".woundroll-tmp-*"))


def _no_nan(token: str) -> float:
    raise AssertionError(f"non-standard JSON token {token}")
