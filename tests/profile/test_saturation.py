"""The instrument's scale is real: a model reading beyond it is what the device shows, the
scale's end, flagged saturated; profile statistics use the on-scale readings only."""

from __future__ import annotations

import numpy as np
import pytest

from woundroll.instruments import get_instrument
from woundroll.instruments.definitions import as_shown, beyond_scale
from woundroll.profile.stats import profile_stats, reading_stats

SCALE = get_instrument("rho-meter").reading_range


def test_rho_meter_scale_is_the_dial():
    assert SCALE == (0.0, 100.0)


def test_shown_and_saturated():
    model = np.array([-3.0, 0.0, 42.0, 100.0, 318.9])
    assert as_shown(model, SCALE).tolist() == [0.0, 0.0, 42.0, 100.0, 100.0]
    # the scale's ends themselves are on the scale; beyond them the device shows the end
    assert beyond_scale(model, SCALE).tolist() == [True, False, False, False, True]
    # no scale (a g readout): nothing saturates, nothing is clipped
    assert not beyond_scale(model, None).any()
    assert as_shown(model, None).tolist() == model.tolist()


def test_statistics_exclude_saturated_readings():
    # the example: a profile with readings far off the scale must not enter the
    # mean or the CoV; the statistics equal those of the on-scale readings alone
    model = np.array([40.0, 42.0, 41.0, 130.0, 234.0, 39.0])
    st = reading_stats(model, SCALE)
    ref = profile_stats([40.0, 42.0, 41.0, 39.0])
    assert st == ref
    assert st.n == 4 and st.max == 42.0
    assert reading_stats([150.0, 160.0, 50.0], SCALE) is None  # one reading on the scale


def test_hardness_result_reports_the_scale_end(tmp_path):
    import woundroll

    # a very hard roll: an explicit stiff spring reads far beyond 100 Rho
    case = woundroll.load_case(
        {
            "web": {"preset": "PET1"},
            "core": {"outer_radius": "4.45 cm", "rigid": True},
            "winding": {"outer_radius": "6 cm", "tension": "26.7 N"},
            "tester": {
                "instrument": "rho-meter",
                "roll_spring": {"alpha": "1e11 N/m^2", "beta": "1e7 N/m"},
            },
        }
    )
    r = woundroll.run(case)
    d = r.to_dict()["hardness"]
    assert r.hardness.reading > 100.0
    assert d["saturated"] is True and d["reading"] == 100.0
    assert d["reading_model"] == pytest.approx(r.hardness.reading, rel=1e-15)
    assert r.flags["reading_outside_range"]
    assert any("shows the scale's end" in w for w in r.warnings)


# slow: the whole Table 3 profile (~25 s); the README command
# test runs the same CLI path (3 sectors) in the default suite
@pytest.mark.slow
def test_table3_profile_through_the_cli(tmp_path):
    # the user's path: `woundroll run pet3-2.3MPa --json --out DIR`; the Table 3 roll's
    # thick lanes read beyond the dial in plane strain: shown at 100, flagged, excluded
    import json

    from typer.testing import CliRunner

    from woundroll.app.cli import app

    res = CliRunner().invoke(app, ["run", "pet3-2.3MPa", "--json", "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    p = json.loads(res.stdout)["profile"]
    sat = np.array(p["saturated"])
    shown, model = np.array(p["reading"]), np.array(p["reading_model"])
    assert p["roll_model"] == "2d" and p["scale"] == [0.0, 100.0]
    assert 0 < sat.sum() < sat.size  # some lanes saturate, most do not
    assert np.all(shown <= 100.0) and np.all(shown[sat] == 100.0)
    assert np.all(model[sat] > 100.0) and np.array_equal(shown[~sat], model[~sat])
    st = p["stats"]
    assert st["reading_n_saturated"] == int(sat.sum())
    assert st["reading"]["n"] == int((~sat).sum())
    assert st["reading"]["max"] == pytest.approx(float(model[~sat].max()), rel=1e-12)
    assert len(p["reading_energy"]) == sat.size
    assert (tmp_path / "profile_cmd.png").stat().st_size > 10_000
