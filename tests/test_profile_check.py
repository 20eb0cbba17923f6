"""The hardness profiler's view of measured profiles (issue 22, item 9): statistics and band
verdict, hard and soft bands by hand, ids from files, the X-mR trend by hand, and the CLI."""

import json
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.assess.profile_check import (
    FAULT_BAND,
    XMR_LIMIT,
    check_profile,
    control_chart,
    file_ids,
    find_faults,
    read_rolls,
    roll_trend,
)
from woundroll.errors import InputError
from woundroll.io.readings import readings_from_arrays

DATA = Path(__file__).resolve().parents[1] / "examples" / "data"
IN = 0.0254
SHEET = DATA / "tappi_t834_sheet.csv"


def test_faults_by_hand_on_a_lane_grid():
    # 8 lanes of 6 in (centres 3, 9, ..., 45 in); mean 55; +-5 % = 52.25 .. 57.75
    x = (np.arange(8) + 0.5) * 6 * IN
    v = np.array([52.0, 55.0, 58.0, 59.0, 55.0, 55.0, 54.0, 52.0])
    assert v.mean() == 55.0
    f = find_faults(x, v)
    assert [b.kind for b in f] == ["soft", "hard", "soft"]
    soft, hard, edge = f
    # an edge lane stands for its whole lane (0-6 in), an inner run for its lanes (12-24 in)
    assert soft.start_m == pytest.approx(0.0, abs=1e-15)
    assert soft.end_m == pytest.approx(6 * IN, rel=1e-12)
    assert hard.start_m == pytest.approx(12 * IN, rel=1e-12)
    assert hard.end_m == pytest.approx(24 * IN, rel=1e-12)
    assert hard.width_m == pytest.approx(12 * IN, rel=1e-12) and hard.n_positions == 2
    assert hard.peak == 59.0 and hard.peak_position_m == pytest.approx(21 * IN, rel=1e-12)
    assert hard.deviation == pytest.approx(4 / 55, rel=1e-12)
    assert edge.start_m == pytest.approx(42 * IN) and edge.end_m == pytest.approx(48 * IN)
    # a wider band finds nothing: 59 is 7.3 % above, 52 is 5.5 % below
    assert find_faults(x, v, band=0.08) == []
    assert [b.kind for b in find_faults(x, v, band=0.06)] == ["hard"]


@pytest.mark.parametrize("band", [0.0, 1.0, float("nan"), -0.1])
def test_fault_band_must_be_a_fraction(band):
    with pytest.raises(InputError, match="--band"):
        find_faults([0.0, 0.1], [50.0, 51.0], band=band)


def test_check_profile_statistics_and_verdict():
    x = np.array([0.05, 0.1, 0.15, 0.2])
    v = np.array([50.0, 52.0, 51.0, 58.0])
    r = readings_from_arrays(x, v, source="roll 9")
    c = check_profile(r, ids={"roll": "9", "lot": "L1"})
    # by hand: mean 52.75, SD (n-1) 3.5940, CoV 6.81 % -> "bad" (>= 6 %), p2p 8
    assert c.mean == pytest.approx(52.75, rel=1e-12)
    assert c.sd == pytest.approx(np.std(v, ddof=1), rel=1e-12)
    assert c.cov == pytest.approx(np.std(v, ddof=1) / 52.75, rel=1e-12)
    assert c.peak_to_peak == 8.0 and c.band == "bad" and c.label == "9"
    # +-5 % of 52.75 = 50.1125 .. 55.3875: 50 is soft, 58 hard, 52 and 51 inside
    assert [b.kind for b in c.faults] == ["soft", "hard"]
    assert c.verdict.startswith("bad: CoV 6.8 %, peak-to-peak 8 Rho")
    d = c.to_dict()
    assert d["ids"] == {"roll": "9", "lot": "L1"} and d["fault_band"] == FAULT_BAND
    # every position in the JSON carries its unit
    keys = set().union(*(f.keys() for f in d["faults"]))
    assert {k for k in keys if k.startswith(("start", "end", "width", "peak_pos"))} == {
        "start_m",
        "end_m",
        "width_m",
        "peak_position_m",
    }
    assert all(not re.search(r"^position$", k) for k in keys)


def test_check_profile_needs_two_positions():
    with pytest.raises(InputError, match="2 positions"):
        check_profile(readings_from_arrays([0.1, 0.1], [50.0, 51.0], source="one"))


def test_ids_from_metadata_and_comments(tmp_path):
    e = read_rolls([DATA / "profile_export_dense.csv"])
    assert e[0][1]["roll"] == "PET-2611-07"
    p = tmp_path / "r.csv"
    p.write_text(
        "# Roll No: 4711-3\n# lot = L-07\n# Customer: ACME Films\n# a note: not an id\n"
        "position [in],reading [Rho]\n1,50\n2,52\n"
    )
    assert file_ids(p) == {"roll": "4711-3", "lot": "L-07", "customer": "ACME Films"}
    # a sheet's roll column is the roll id; a lot comment applies to every roll
    sheet = tmp_path / "s.csv"
    sheet.write_text("# lot: L9\n" + SHEET.read_text())
    rolls = read_rolls([sheet])
    assert [ids for _, ids in rolls] == [
        {"lot": "L9", "roll": "2611-01"},
        {"lot": "L9", "roll": "2611-02"},
        {"lot": "L9", "roll": "2611-03"},
    ]


def test_control_chart_by_hand():
    v = [10.0, 12.0, 11.0, 30.0, 11.0]
    c = control_chart(v, "mean")
    mr = (2 + 1 + 19 + 19) / 4
    assert c.center == pytest.approx(74 / 5, rel=1e-12)
    assert c.mr_bar == pytest.approx(mr, rel=1e-12)
    assert c.ucl == pytest.approx(74 / 5 + 2.66 * mr, rel=1e-12) and XMR_LIMIT == 2.66
    assert c.mr_ucl == pytest.approx(3.267 * mr, rel=1e-12)
    # a steady run with one jump: the jump is beyond the upper limit
    steady = [50.0, 50.5, 49.8, 50.2, 50.1, 49.9, 50.3, 50.0, 56.0, 50.1]
    c2 = control_chart(steady)
    assert c2.out_of_control == (8,)
    # the CoV chart's lower limit stops at 0
    assert control_chart([0.01, 0.05, 0.01], floor=0.0).lcl == 0.0
    with pytest.raises(InputError, match="2 rolls"):
        control_chart([1.0])


def test_trend_of_the_sample_sheet():
    checks = [check_profile(r, ids=i) for r, i in read_rolls([SHEET])]
    t = roll_trend(checks)
    means = [c.mean for c in checks]
    # by hand from the sheet: roll means 55.625, 58.0, 52.1667 Rho
    assert means == pytest.approx([55.625, 58.0, 313 / 6], rel=1e-12)
    assert t.mean_chart.center == pytest.approx(np.mean(means), rel=1e-12)
    assert t.provisional and t.flagged() == []
    assert t.to_csv().splitlines()[1].startswith("1,2611-01,,")
    with pytest.raises(InputError, match="2 rolls or more"):
        roll_trend(checks[:1])


def test_trend_rejects_mixed_scales():
    with pytest.raises(InputError, match=r"profile_export_dense\.csv reads in g"):
        read_rolls([SHEET, DATA / "profile_export_dense.csv"])


# ------------------------------------------------------------------------------- CLI
def test_cli_one_roll_profile_check_json_and_table(tmp_path):
    runner = CliRunner()
    res = runner.invoke(app, ["readings", str(SHEET), "--roll", "2611-01", "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)["profile_check"]
    assert d["ids"] == {"roll": "2611-01"} and d["band"] == "acceptable"
    # roll 2611-01 lane means 52.5 55.5 57.5 57.5 58.5 56.5 55.5 51.5, mean 55.625:
    # soft lane 1 (0-6 in), hard lane 5 (24-30 in), soft lane 8 (42-48 in)
    got = [(f["kind"], f["start_m"] / IN, f["end_m"] / IN) for f in d["faults"]]
    assert got == [
        ("soft", pytest.approx(0.0, abs=1e-9), pytest.approx(6.0)),
        ("hard", pytest.approx(24.0), pytest.approx(30.0)),
        ("soft", pytest.approx(42.0), pytest.approx(48.0)),
    ]
    res = runner.invoke(
        app,
        ["readings", str(SHEET), "--roll", "2611-01", "--unit", "cm", "--out", str(tmp_path)],
        terminal_width=160,
    )
    assert res.exit_code == 0, res.output
    # positions in the unit asked for: the first soft band ends at 6 in = 15.24 cm
    assert "[cm]" in res.output and "15.24" in res.output
    assert "acceptable: CoV 4.4 %" in res.output
    assert (tmp_path / "profile.png").stat().st_size > 1000
    saved = json.loads((tmp_path / "readings.json").read_text())
    assert saved["profile_check"]["faults"] == d["faults"]


def test_cli_trend_over_files_and_sheet_rolls(tmp_path):
    one = tmp_path / "a.csv"
    one.write_text("# roll: A7\n# lot: L2\nposition [in],reading [Rho]\n3,60\n9,61\n15,59\n")
    res = CliRunner().invoke(app, ["readings", str(SHEET), str(one), "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)
    assert [r["ids"].get("roll") for r in d["rolls"]] == ["2611-01", "2611-02", "2611-03", "A7"]
    assert d["rolls"][3]["ids"]["lot"] == "L2"
    assert d["mean_chart"]["values"][3] == pytest.approx(60.0, rel=1e-12)
    assert d["provisional"] is True and "2.66" in d["chart"]
    res = CliRunner().invoke(
        app, ["readings", str(SHEET), "--trend", "--out", str(tmp_path / "t")], terminal_width=160
    )
    assert res.exit_code == 0, res.output
    assert "roll-to-roll trend: 3 rolls" in res.output and "provisional" in res.output
    assert (tmp_path / "t" / "trend.csv").read_text().count("\n") == 4
    assert (tmp_path / "t" / "trend.png").stat().st_size > 1000


@pytest.mark.parametrize(
    "args, field",
    [
        (["--band", "abc"], "--band"),
        (["--band", "150 %"], "--band"),
        (["--unit", "furlong"], "--unit"),
        (["--trend", "--roll", "2611-01"], "--roll"),
    ],
)
def test_cli_bad_options_one_line_exit_2(args, field):
    res = CliRunner().invoke(app, ["readings", str(SHEET), *args])
    assert res.exit_code == 2, res.output
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and field in lines[0] and "Traceback" not in res.output


def test_cli_trend_of_one_roll_and_mixed_scales_exit_2():
    res = CliRunner().invoke(app, ["readings", str(DATA / "readings_rho_3passes.csv"), "--trend"])
    assert res.exit_code == 2 and "2 rolls or more" in res.output
    res = CliRunner().invoke(app, ["readings", str(SHEET), str(DATA / "profile_export_dense.csv")])
    assert res.exit_code == 2 and "one instrument" in res.output
