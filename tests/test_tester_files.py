"""Tester files: the generic CSV, the TAPPI T 834 sheet and dense profile exports read back
exactly what was written (round trips), the samples under examples/data read as documented,
and bad files fail with one message naming the file and line."""

import re
from pathlib import Path

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.io.readings import read_readings, readings_from_arrays
from woundroll.io.tester_files import (
    TAPPI_LANE_WIDTH,
    detect_format,
    read_profile_export,
    read_tappi_sheet,
    read_tester_file,
    write_generic,
    write_profile_export,
    write_tappi_sheet,
)

DATA = Path(__file__).resolve().parents[1] / "examples" / "data"
IN = 0.0254


def _same(a, b):
    """Same readings: positions to 1e-12 m (unit conversions), values and passes exactly."""
    assert a.scale == b.scale
    np.testing.assert_allclose(a.raw_position, b.raw_position, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(a.raw_value, b.raw_value)
    np.testing.assert_array_equal(a.raw_pass, b.raw_pass)
    np.testing.assert_allclose(a.mean, b.mean, rtol=1e-15)


def test_tappi_sample():
    rolls = read_tappi_sheet(DATA / "tappi_t834_sheet.csv")
    assert list(rolls) == ["2611-01", "2611-02", "2611-03"]
    r1 = rolls["2611-01"]
    # lane k centred at (k - 1/2) x 6 in; two passes give the scatter
    np.testing.assert_allclose(r1.position / IN, [3, 9, 15, 21, 27, 33, 39, 45], atol=1e-12)
    assert r1.passes == 2 and r1.mean[0] == 52.5 and r1.lane_width == TAPPI_LANE_WIDTH
    r3 = rolls["2611-03"]
    assert r3.n_positions == 6  # the narrower roll: two empty lanes
    assert detect_format(DATA / "tappi_t834_sheet.csv") == "tappi"


def test_tappi_round_trip(tmp_path):
    rolls = read_tappi_sheet(DATA / "tappi_t834_sheet.csv")
    out = write_tappi_sheet(rolls, tmp_path / "sheet.csv")
    assert "lane 8" in out.read_text()
    again = read_tappi_sheet(out)
    assert list(again) == list(rolls)
    for k in rolls:
        _same(again[k], rolls[k])
    # positions that are not lane centres: written as positions in inches, read back
    odd = {"A": readings_from_arrays([0.05, 0.1234567, 0.3], [40.5, 41.25, 39.0], scale="R")}
    back = read_tappi_sheet(write_tappi_sheet(odd, tmp_path / "odd.csv"))
    _same(back["A"], odd["A"])


def test_generic_round_trip(tmp_path):
    r = read_readings(DATA / "readings_rho_3passes.csv")
    for unit in ("in", "mm", "m"):
        back = read_readings(write_generic(r, tmp_path / f"g_{unit}.csv", unit=unit))
        _same(back, r)
    assert detect_format(tmp_path / "g_in.csv") == "generic"


def test_profile_sample_and_round_trip(tmp_path):
    exp = read_profile_export(DATA / "profile_export_dense.csv")
    r = exp.readings
    assert r.scale == "g" and r.passes == 2 and r.n_positions == 62
    assert exp.metadata["Roll"] == "PET-2611-07" and exp.metadata["Unit"] == "g"
    np.testing.assert_allclose(r.position[[0, -1]], [0.0, 0.61], atol=1e-12)
    assert detect_format(DATA / "profile_export_dense.csv") == "profile"
    for comma in (True, False):
        p = write_profile_export(r, tmp_path / "p.csv", metadata=exp.metadata, decimal_comma=comma)
        back = read_profile_export(p)
        _same(back.readings, r)
        assert back.metadata == exp.metadata


def test_dispatch():
    assert read_tester_file(DATA / "profile_export_dense.csv").scale == "g"
    assert read_tester_file(DATA / "readings_rho_3passes.csv").passes == 3
    r = read_tester_file(DATA / "tappi_t834_sheet.csv", roll="2611-02")
    assert r.mean[3] == 60
    with pytest.raises(InputError, match="holds 3 rolls"):
        read_tester_file(DATA / "tappi_t834_sheet.csv")
    with pytest.raises(InputError, match="no roll 'x'"):
        read_tester_file(DATA / "tappi_t834_sheet.csv", roll="x")


@pytest.mark.parametrize(
    ("text", "fmt", "match"),
    [
        ("roll,pass,lane 1\nA,1,abc\n", "tappi", "line 2: lane 1 = 'abc' is not a number"),
        ("roll,pass,lane 0\nA,1,3\n", "tappi", "lane numbers start at 1"),
        ("roll,width,lane 1\nA,3,3\n", "tappi", "neither 'lane N' nor a position"),
        ("roll,pass,scale,lane 1\nA,1,Rho,50\nA,2,R,30\n", "tappi", "mixes scales"),
        ("roll,pass,lane 1\nA,x,3\n", "tappi", "pass 'x' is not a whole number"),
        ("Roll;1\nposition [ft];v [g]\n1;2\n", "profile", "position unit 'ft'"),
        ("position [mm];v\n1;2\n", "profile", "no scale"),
        ("position [mm];v [g]\n1;zwei\n", "profile", "line 2: v [g] = 'zwei'"),
        ("Roll;1\nDate;today\n", "profile", "no header row"),
    ],
)
def test_bad_files(tmp_path, text, fmt, match):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(InputError, match=re.escape(match)) as exc:
        read_tester_file(p, format=fmt)
    assert exc.value.field == "readings" and "\n" not in str(exc.value)


def test_cli_readings_formats_and_roll():
    """`woundroll readings FILE [--format F] [--roll ID]` reads every layout, as `report` does:
    the JSON equals the reader's readings; a roll-id problem is the --roll option's error."""
    import json

    from typer.testing import CliRunner

    from woundroll.app.cli import app

    runner = CliRunner()
    sheet = str(DATA / "tappi_t834_sheet.csv")
    rolls = read_tappi_sheet(DATA / "tappi_t834_sheet.csv")
    for args in (["--roll", "2611-01"], ["--roll", "2611-01", "--format", "tappi"]):
        res = runner.invoke(app, ["readings", sheet, *args, "--json"])
        assert res.exit_code == 0, res.output
        d = json.loads(res.output)
        assert d["passes"] == 2 and d["mean"] == rolls["2611-01"].mean.tolist()
    res = runner.invoke(app, ["readings", sheet, "--roll", "2611-03"])
    assert res.exit_code == 0 and "roll 2611-03" in res.output
    prof = str(DATA / "profile_export_dense.csv")
    exp = read_profile_export(DATA / "profile_export_dense.csv").readings
    for args in ([], ["--format", "profile"]):
        res = runner.invoke(app, ["readings", prof, *args, "--json"])
        assert res.exit_code == 0, res.output
        d = json.loads(res.output)
        assert d["scale"] == "g" and d["mean"] == exp.mean.tolist()
    res = runner.invoke(app, ["readings", str(DATA / "readings_rho_3passes.csv"), "--json"])
    assert res.exit_code == 0 and json.loads(res.output)["passes"] == 3
    for path, args, field in [
        (sheet, [], "--roll"),  # three rolls on the sheet: pick one
        (sheet, ["--roll", "nope"], "--roll"),
        (prof, ["--roll", "2611-01"], "--roll"),  # a profile export holds one roll
        (prof, ["--format", "pdf"], "--format"),
        (prof, ["--format", "tappi"], "CSV_FILE"),
    ]:
        res = runner.invoke(app, ["readings", path, *args])
        lines = [ln for ln in res.output.splitlines() if ln.strip()]
        assert res.exit_code == 2 and len(lines) == 1 and f"{field}:" in lines[0], res.output


def test_tappi_and_profile_values_off_the_scale_name_line_and_column(tmp_path):
    sheet = tmp_path / "t.csv"
    sheet.write_text("roll,pass,scale,lane 1,lane 2\nA,1,Rho,55,56\nB,1,R,20,5\n")
    with pytest.raises(InputError, match=r"t\.csv line 3, lane 2: 5 R is off .*10 to 100 R"):
        read_tappi_sheet(sheet)
    prof = tmp_path / "p.csv"
    prof.write_text(
        "roll id;4711\nposition [mm];scan 1 [Rho];scan 2 [Rho]\n10;50;51\n20;52;101,5\n"
    )
    with pytest.raises(InputError, match=r"p\.csv line 4, scan 2 \[Rho\]: 101.5 Rho is off"):
        read_tester_file(prof)
