"""Setpoint design: constraints by hand, target validation, and a verified design (slow)."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.case import load_case
from woundroll.errors import InputError
from woundroll.inverse.design import DesignTarget, _constraints, design_setpoints
from woundroll.winding.hakiel import wind


def test_constraints_by_hand():
    case = load_case("pet2-53.4N")
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    depth = 0.0065
    inside = w.radius <= w.radius[-1] - depth
    P = -w.sigma_r[inside]
    tgt = DesignTarget(reading=30, pressure_min=P.min() * 1.1, pressure_max=P.max() * 0.9)
    pmin, pmax, hoop, viol, score = _constraints(w, depth, tgt)
    assert (pmin, pmax) == (pytest.approx(P.min()), pytest.approx(P.max()))
    assert hoop == pytest.approx(w.layer_mean_hoop_stress()[1].min())
    assert len(viol) == 3  # below, above, negative hoop
    # relative excesses: 0.1/1.1 below, 1/0.9 - 1 above, plus the hoop term
    assert score == pytest.approx(0.1 / 1.1 + (1 / 0.9 - 1) + -hoop / P.max(), rel=1e-9)
    ok = replace(tgt, pressure_min=0.0, pressure_max=math.inf, allow_negative_hoop=True)
    assert _constraints(w, depth, ok)[3] == []


@pytest.mark.parametrize(
    ("kw", "field"),
    [
        ({"reading": -3}, "--target"),
        ({"reading": 50, "taper_kind": "parabolic"}, "--taper"),
        ({"reading": 50, "taper_kind": "table", "knots": 1}, "--knots"),
        ({"reading": 50, "hoop_min": 5e3}, "--hoop-min"),
        ({"reading": 50, "taper_max": 1.5}, "--max-taper"),
        ({"reading": 50, "pressure_min": 5e5, "pressure_max": 1e5}, "--pressure"),
        ({"reading": 50, "tolerance": 0}, "--tolerance"),
    ],
)
def test_bad_targets(kw, field):
    with pytest.raises(InputError) as exc:
        DesignTarget(**kw)
    assert exc.value.field == field


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["--target", "60 furlongs"], "--target"),
        (["--target", "60 Rho", "--pressure", "10 kPa"], "--pressure"),
        (["--target", "60 Rho", "--tension", "1 pli..x"], "--tension"),
        (["--target", "60 R"], "readings"),  # a Schmidt target for a Rho-meter case
        (["--target", "60 Rho", "--taper", "table", "--knots", "1"], "--knots"),
        (["--target", "60 Rho", "--hoop-min", "5 kPa"], "--hoop-min"),
        (["--target", "60 Rho", "--hoop-min", "-5 m"], "--hoop-min"),
    ],
)
def test_cli_design_bad_input_one_line(args, field):
    res = CliRunner().invoke(app, ["design", "pet1-26.7N", *args])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and f"{field}:" in lines[0], res.output


@pytest.mark.slow
def test_design_reads_the_target_and_reports_what_it_cannot_meet():
    from woundroll.inverse.diagnosis import RollModel
    from woundroll.winding.tension import Taper

    # the target is what the case's own roll reads on the default path, so that a design
    # exists inside the pressure window: PET1 26.7 N reads 51.2 Rho FD with today's plane
    # strain default and the 7.820 mm head (docs/studies.md). The test was set at 80 when
    # that roll read 80.8 on the former default path (2d+cmd-spread); today 80 Rho needs
    # 57 N untapered and 333 kPa near the core (measured), above the 200 kPa window. At 51
    # (measured): the best compromise is a 40 % taper, 35.4 N, hoop -34 kPa binding; with
    # negative hoop allowed, untapered 26.5 N (the case's own 26.7 N), 40-83 kPa.
    target = 51.0
    case = load_case("pet1-26.7N")
    tgt = DesignTarget(
        reading=target,
        pressure_min=10e3,
        pressure_max=200e3,
        tension_min=0.3e6,
        tension_max=8e6,
        taper_max=0.6,
    )
    d = design_setpoints(case, tgt)
    # an independent full forward run at the designed setpoints reads the target
    model = RollModel.from_case(case)
    model = replace(model, schedule=replace(model.schedule, taper=Taper("linear", d.taper)))
    assert abs(model.evaluate(d.web_tension).reading - target) <= 1.0
    # PET1 on its steel core keeps a negative hoop stress near the core for every linear
    # taper up to 60 %: reported as infeasible, with the reason, not hidden
    assert not d.feasible
    assert any("negative hoop" in v for v in d.violations)
    assert d.margins["min_hoop_stress_Pa"] < 0
    # the best available compromise: the candidate whose worst constraint is least violated,
    # with that constraint named and what relaxing it would take
    solved = [c for c in d.candidates if c.web_tension is not None]
    assert max(c.worst_slack for c in solved) == pytest.approx(
        next(c.worst_slack for c in solved if c.taper == d.taper)
    )
    assert d.slacks[d.binding] == min(d.slacks.values()) < 0
    assert d.relaxations and d.relaxations[0]["constraint"] == d.binding
    assert "hoop" in {r["constraint"] for r in d.relaxations}
    assert any("1D model's physics" in n for n in d.notes)
    json.dumps(d.to_dict())
    # allowing it, the design is feasible and keeps the pressure inside the window
    d2 = design_setpoints(case, replace(tgt, allow_negative_hoop=True))
    assert d2.feasible
    assert 10e3 <= d2.margins["min_pressure_Pa"] and d2.margins["max_pressure_Pa"] <= 200e3
    assert np.isfinite(d2.reading) and abs(d2.reading - target) <= 1.0


def test_table_taper_parameters_round_trip():
    # knot factors <-> the optimiser's unconstrained parameters: monotone tables stay within
    # [1 - taper_max, 1] and never rise; the inverse is exact inside the open interval
    from woundroll.inverse.design import _table_factors, _table_params

    tgt = DesignTarget(reading=50, taper_kind="table", taper_max=0.6, knots=5)
    f = np.array([1.0, 0.9, 0.75, 0.6, 0.55])
    np.testing.assert_allclose(_table_factors(_table_params(f, tgt), tgt), f, rtol=1e-12)
    rng = np.random.default_rng(0)
    for x in rng.normal(0, 3, (50, 4)):
        g = np.array(_table_factors(x, tgt))
        assert g[0] == 1.0 and np.all(np.diff(g) <= 0) and g.min() >= 0.4 - 1e-12
    free = replace(tgt, monotone=False)
    g = np.array(_table_factors(np.array([3.0, -3.0, 3.0, -3.0]), free))
    assert np.any(np.diff(g) > 0) and g.min() >= 0.4 and g.max() <= 1.6


def test_slacks_by_hand():
    from woundroll.inverse.design import _slacks

    tgt = DesignTarget(
        reading=50, pressure_min=1e4, pressure_max=2e5, tension_min=1e6, tension_max=4e6,
        hoop_min=-2e4,
    )  # fmt: skip
    s = _slacks(2e4, 1.8e5, -3e4, 1.5e6, 3e6, tgt)
    assert s["pressure_min"] == pytest.approx(1.0)
    assert s["pressure_max"] == pytest.approx(0.1)
    assert s["hoop"] == pytest.approx(-1e4 / 2e5)  # 10 kPa beyond the accepted -20 kPa
    assert s["tension_min"] == pytest.approx(0.5)
    assert s["tension_max"] == pytest.approx(0.25)
    assert "hoop" not in _slacks(
        2e4, 1.8e5, -3e4, 1.5e6, 3e6, replace(tgt, allow_negative_hoop=True)
    )
