"""Defect risk: each criterion against its formula computed by hand, risk levels, lanes."""

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.assess.defects import (
    WATCH_MARGIN,
    DefectLimits,
    assess_roll,
    buckling_stress,
    defect_report,
)
from woundroll.case import load_case
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


def test_negative_hoop_stress_is_watch_by_rule_and_buckling_has_the_margin(roll):
    case, web, core, w = roll
    c = by_name(assess_roll(w, web, core, DefectLimits()))
    star, buck = c["starring"], c["buckling"]
    rm, st = w.layer_mean_hoop_stress()
    assert st.min() < 0 and star.demand == pytest.approx(-st.min())
    # the rule has no margin (nothing to draw against the watch line); the estimate's risk
    # follows its margin: far above the watch line is "low" (issue 22, item 10)
    assert star.risk == "watch" and star.margin is None
    assert buck.margin > WATCH_MARGIN and buck.risk == "low"
    assert buck.demand == star.demand and buck.where_m == star.where_m
    # the capacity is the wrinkling estimate with E_r and G = 2 E_r at the most compressed layer
    assert buck.capacity == pytest.approx(
        buckling_stress(
            web.E_theta,
            np.interp(buck.where_m, w.radius, w.E_r),
            2 * np.interp(buck.where_m, w.radius, w.E_r),
        ),
        rel=1e-12,
    )
    assert buck.margin == pytest.approx(buck.capacity / buck.demand, rel=1e-12)


@pytest.mark.parametrize("case_name", ["pet1-26.7N", "pet2-80N", "pet3-2.3MPa"])
def test_every_risk_agrees_with_its_margin(case_name):
    # a criterion with a margin is high below 1, watch below WATCH_MARGIN, low above: the
    # bar's colour in the plot and the table's word never disagree with where it is drawn
    rep = defect_report(load_case(case_name, ["defects.core_strength='150 kPa'"]))
    for c in rep.roll:
        if c.margin is None:
            assert c.risk in ("watch", "low", "n/a"), c
            continue
        want = "high" if c.margin < 1 else "watch" if c.margin < WATCH_MARGIN else "low"
        assert c.risk == want, (c.name, c.margin, c.risk)


def test_unchecked_criteria_name_their_key_once(tmp_path):
    rep = defect_report(load_case("pet1-26.7N", ["defects.core_strength='150 kPa'"]))
    assert rep.unchecked == [
        ("telescoping", "defects.axial_acceleration_g"),
        ("torque slip", "defects.torque"),
        ("blocking", "defects.blocking_pressure"),
    ]
    rows = {name: sentence for name, _, sentence in rep.summary()}
    for name, key in rep.unchecked:
        assert key in rows[name]
    assert rep.to_dict()["unchecked"][0] == {
        "name": "telescoping",
        "needs": "defects.axial_acceleration_g",
    }
    res = CliRunner().invoke(app, ["defects", "pet1-26.7N"], terminal_width=200)
    assert res.exit_code == 0, res.output
    out = res.output
    # each key once (its row), the how-to once (the note)
    for _, key in rep.unchecked:
        assert out.count(key) == 1, (key, out)
    assert out.count("--set KEY=VALUE") == 1
    # all limits given: no note
    full = defect_report(
        load_case(
            "pet1-26.7N",
            [
                "defects.core_strength='150 kPa'",
                "defects.blocking_pressure='1 MPa'",
                "defects.torque='10 N m'",
                "defects.axial_acceleration_g=1",
            ],
        )
    )
    assert full.unchecked == [] and full.needs_note() == ""


def test_slack_roll():
    case = load_case("pet2-26.7N", ["defects.slack_pressure='1 MPa'"])
    rep = defect_report(case)
    c = by_name(rep.roll)["slack"]
    assert c.risk == "high" and c.margin < 1
    assert rep.risk == "high"
    json.dumps(rep.to_dict())


def test_lanes_flag_the_slack_lane():
    from woundroll.inverse.diagnosis import Diagnosis, ForwardCurve, ForwardPoint
    from woundroll.io.readings import readings_from_arrays

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
    assert rep.lanes[2]["wound_on_tension_over_median"] == pytest.approx(0.9 / 1.75)
    # criteria without a limit are the roll's, said once there, not again per lane
    assert all(c["needs"] is None for ln in rep.lanes for c in ln["criteria"])
    assert {c["name"] for c in rep.lanes[0]["criteria"]} == {"starring", "buckling", "slack"}
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
