"""Readings in: the CSV of CMD positions and values, units, passes, scatter and bad files."""

from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.case import load_case
from woundroll.errors import InputError
from woundroll.io.readings import read_readings, readings_from_arrays

DATA = Path(__file__).resolve().parents[1] / "examples" / "data"
INCH = 0.0254


def write(tmp_path, text, name="r.csv"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_wide_sheet_three_passes_mean_and_sd():
    r = read_readings(DATA / "readings_rho_3passes.csv", width=6 * INCH)
    assert r.scale == "Rho" and r.readout == "rho"
    assert r.passes == 3
    np.testing.assert_allclose(r.position, np.array([0.75, 2.25, 3.75, 5.25]) * INCH, rtol=1e-12)
    # first row 50.2, 51.0, 49.6 by hand: mean 50.2667, SD (ddof 1) 0.70238
    assert r.mean[0] == pytest.approx((50.2 + 51.0 + 49.6) / 3, rel=1e-12)
    assert r.sd[0] == pytest.approx(np.std([50.2, 51.0, 49.6], ddof=1), rel=1e-12)
    assert list(r.count) == [3, 3, 3, 3]
    by_pass = r.values_by_pass()
    assert by_pass.shape == (3, 4)
    assert by_pass[1, 0] == pytest.approx(51.0)


def test_long_sheet_repeats_are_passes_and_pooled_sd():
    r = read_readings(DATA / "readings_schmidt_long.csv")
    assert r.scale == "R" and r.readout == "schmidt-r"
    np.testing.assert_allclose(r.position, [0.05, 0.15, 0.25], rtol=1e-12)
    assert r.passes == 2
    # every pair differs by 1 -> SD 1/sqrt(2) at each position, and pooled the same
    np.testing.assert_allclose(r.sd, 1 / np.sqrt(2), rtol=1e-12)
    assert r.pooled_sd == pytest.approx(1 / np.sqrt(2), rel=1e-12)
    np.testing.assert_allclose(r.sem, 0.5, rtol=1e-12)


def test_lanes_with_tappi_width_and_pass_column():
    r = read_readings(DATA / "readings_tappi_lanes.csv", lane_width=6 * INCH)
    # lane k centred at (k - 1/2) x 6 in
    np.testing.assert_allclose(r.position, [3 * INCH, 9 * INCH], rtol=1e-12)
    assert r.lane_width == pytest.approx(6 * INCH)
    assert r.passes == 2
    np.testing.assert_allclose(r.mean, [55.5, 57.5])


@pytest.mark.parametrize(
    ("header", "scale", "factor"),
    [
        ("position [m],reading [Rho]", "Rho", 1.0),
        ("position_cm,rho", "Rho", 0.01),
        ("position [mm],R", "R", 1e-3),
        ("x [in],parotester_l", "L", INCH),
        ("position (cm),value [g]", "g", 0.01),
        ("Position [in], Schmidt R", "R", INCH),
        ("position [in],L", "L", INCH),
    ],
)
def test_header_spellings(tmp_path, header, scale, factor):
    r = read_readings(write(tmp_path, f"{header}\n2,40\n4,42\n"))
    assert r.scale == scale
    np.testing.assert_allclose(r.position, [2 * factor, 4 * factor], rtol=1e-12)
    assert r.pooled_sd is None and not r.has_scatter
    np.testing.assert_array_equal(r.scatter, 0.0)


def test_single_reading_positions_take_the_pooled_sd(tmp_path):
    r = read_readings(write(tmp_path, "position [cm],rho\n1,50\n1,52\n2,60\n"))
    assert r.sd[1] == 0.0 and r.count[1] == 1
    assert r.scatter[1] == pytest.approx(np.sqrt(2.0))  # SD of (50, 52)


@pytest.mark.parametrize(
    ("text", "kw", "needle"),
    [
        ("1,50\n2,51\n", {}, "line 1: no header row"),
        ("position [in],reading [furlong]\n1,50\n", {}, "line 1: column 'reading [furlong]'"),
        ("position [in],reading\n1,50\n", {}, "line 1: column 'reading': no unit"),
        ("position,rho\n1,50\n", {}, "line 1: position column 'position' has no unit"),
        ("position [kPa],rho\n1,50\n", {}, "is not a length"),
        ("position [in],rho\n1,50\n2,nan\n", {}, "line 3: column 'rho': 'nan' is not a finite"),
        ("position [in],rho\n1,50\n2,abc\n", {}, "line 3: column 'rho': 'abc' is not a number"),
        ("position [in],rho\n1,50\n,51\n", {}, "line 3: column 'position [in]' is empty"),
        ("# c\nposition [in],rho\n1,50\n30,51\n", {"width": 0.3}, "line 4: position 30"),
        ("position [in],rho\n-2,50\n", {"width": 0.3}, "outside the roll"),
        ("lane,rho\n1,50\n", {}, "give the lane width"),
        ("lane,rho\n0,50\n", {"lane_width": 0.15}, "line 2: lane '0'"),
        ("lane,rho\n1.5,50\n", {"lane_width": 0.15}, "is not a lane number"),
        ("position [in],rho,R\n1,50,30\n", {}, "mix scales"),
        ("position [in]\n1\n", {}, "no reading column"),
        ("rho\n50\n", {}, "no position column"),
        ("position [in],rho\n", {}, "a header but no readings"),
        ("", {}, "empty"),
    ],
)
def test_bad_files_name_file_and_line(tmp_path, text, kw, needle):
    with pytest.raises(InputError) as exc:
        read_readings(write(tmp_path, text, "bad.csv"), **kw)
    assert "bad.csv" in str(exc.value)
    assert needle in str(exc.value)
    assert exc.value.field == "readings"


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        read_readings(tmp_path / "nope.csv")


def test_from_arrays_checks():
    r = readings_from_arrays([0.1, 0.1, 0.2], [50, 52, 55], scale="rho", width=0.3)
    assert r.scale == "Rho" and list(r.raw_pass) == [1, 2, 1]
    with pytest.raises(InputError, match="unknown scale"):
        readings_from_arrays([0.1], [50], scale="Shore A")
    with pytest.raises(InputError, match="outside the roll"):
        readings_from_arrays([0.5], [50], width=0.3)
    with pytest.raises(InputError, match="finite"):
        readings_from_arrays([0.1], [np.nan])


def test_case_readings_section_relative_path(tmp_path):
    (tmp_path / "r.csv").write_text("lane,reading [Rho]\n1,50\n1,51\n", encoding="utf-8")
    case = tmp_path / "c.toml"
    case.write_text(
        'title = "t"\n[web]\npreset = "PET1"\n[core]\nouter_radius = "4.45 cm"\nrigid = true\n'
        '[winding]\nouter_radius = "13 cm"\ntension = "26.7 N"\n'
        '[readings]\nfile = "r.csv"\nlane_width = "1.5 in"\nrepeatability = 1.0\n',
        encoding="utf-8",
    )
    c = load_case(case)
    r = c.measured_readings
    assert r.position[0] == pytest.approx(0.75 * INCH)
    assert c.readings.repeatability == 1.0
    # positions are checked against the web width at load time (PET1: 6 in = 4 lanes of 1.5 in)
    (tmp_path / "r.csv").write_text("lane,reading [Rho]\n5,50\n", encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_case(case)
    assert exc.value.field == "readings.file" and "r.csv line 2" in str(exc.value)


def test_cli_readings_table_json_and_one_line_error(tmp_path):
    runner = CliRunner()
    res = runner.invoke(app, ["readings", str(DATA / "readings_rho_3passes.csv"), "--json"])
    assert res.exit_code == 0, res.output
    assert '"passes": 3' in res.output
    res = runner.invoke(app, ["readings", str(DATA / "readings_schmidt_long.csv")])
    assert res.exit_code == 0 and "pooled repeatability" in res.output
    bad = write(tmp_path, "position [in],rho\n1,50\n2,nan\n", "bad.csv")
    res = runner.invoke(app, ["readings", str(bad)])
    assert res.exit_code == 2
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "bad.csv line 3" in lines[0], res.output
    sheet = str(DATA / "readings_rho_3passes.csv")
    res = runner.invoke(app, ["readings", sheet, "--width", "2 in"])
    assert res.exit_code == 2 and "outside the roll" in res.output


def test_plot_writes_png(tmp_path):
    import matplotlib.pyplot as plt

    r = read_readings(DATA / "readings_rho_3passes.csv")
    fig = r.plot(tmp_path / "r.png")
    assert (tmp_path / "r.png").stat().st_size > 1000
    assert len(fig.axes[0].lines) >= 3  # one marker series per pass (+ the mean)
    plt.close(fig)
    assert r.to_table().splitlines()[0] == "position [m],mean [Rho],sd [Rho],count"


@pytest.mark.parametrize("sep", [";", "\t"])
def test_spreadsheet_exports_semicolon_or_tab_and_decimal_comma(tmp_path, sep):
    text = f"# export\nposition [cm]{sep}reading [Rho]\n5{sep}52,5\n15{sep}53\n5{sep}51,5\n"
    r = read_readings(write(tmp_path, text))
    np.testing.assert_allclose(r.position, [0.05, 0.15])
    assert r.mean[0] == pytest.approx(52.0) and r.sd[0] == pytest.approx(np.sqrt(0.5))
    bad = write(tmp_path, f"position [cm]{sep}rho\n5{sep}52,x\n", "bad.csv")
    with pytest.raises(InputError, match="bad.csv line 2"):
        read_readings(bad)


# -- values off the instrument's scale (issue 22, item 3) ---------------------------------
@pytest.mark.parametrize(
    "header, value, span",
    [
        ("reading [Rho]", "-50", "0 to 100 Rho"),
        ("reading [Rho]", "5000", "0 to 100 Rho"),
        ("reading [Rho]", "100.5", "0 to 100 Rho"),
        ("R", "9.5", "10 to 100 R"),
        ("parotester_l", "1200", "0 to 1000 L"),
        ("g", "-3", "0 g or more"),
    ],
)
def test_values_off_the_scale_name_file_line_and_value(tmp_path, header, value, span):
    good = {"reading [Rho]": "50", "R": "40", "parotester_l": "600", "g": "30"}[header]
    p = write(tmp_path, f"# roll 7\nposition [in],{header}\n1,{good}\n2,{value}\n")
    with pytest.raises(InputError) as e:
        read_readings(p)
    msg = e.value.message
    assert msg.startswith("r.csv line 4, column") and f"{value} " in msg and span in msg, msg


def test_values_on_the_scale_ends_are_readings(tmp_path):
    # the ends of the dial are values the instrument can show: 0 and 100 Rho, 10 R
    r = read_readings(write(tmp_path, "position [in],reading [Rho]\n1,0\n2,100\n"))
    assert list(r.mean) == [0.0, 100.0]
    r = read_readings(write(tmp_path, "position [in],R\n1,10\n", "s.csv"))
    assert r.mean[0] == 10.0


def test_from_arrays_rejects_values_off_the_scale():
    with pytest.raises(InputError, match=r"roll 9, reading 2: 5000 Rho is off"):
        readings_from_arrays([0.01, 0.02], [50.0, 5000.0], source="roll 9")


def test_cli_readings_off_scale_is_one_line_exit_2(tmp_path):
    p = write(tmp_path, "position [in],reading [Rho]\n1,-50\n2,5000\n")
    res = CliRunner().invoke(app, ["readings", str(p)])
    assert res.exit_code == 2
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and "r.csv line 2" in lines[0] and "-50 Rho" in lines[0], res.output
    assert "Traceback" not in res.output


def test_web_api_rejects_readings_off_the_scale():
    pytest.importorskip("fastapi")
    pytest.importorskip("httpx2")
    from fastapi.testclient import TestClient

    from woundroll.app.web import create_app

    case = (
        'title = "fast"\n[web]\npreset = "PET1"\n[core]\nouter_radius = "4.45 cm"\nrigid = true\n'
        '[winding]\nouter_radius = "6 cm"\ntension = "26.7 N"\n[tester]\n'
        'instrument = "rho-meter"\n'
        'roll_spring = { alpha = "2.6e8 N/m^2", beta = "1.05e5 N/m" }\n'
    )
    with TestClient(create_app()) as client:
        r = client.post(
            "/api/run",
            json={"case": case, "readings": "position [in],rho\n0.5,-50\n1.5,5000\n"},
        )
    # rejected before any run (the issue: a mean of 2475 Rho came back without a warning)
    assert r.status_code in (400, 422), r.text
    text = r.text
    assert "line 2" in text and "-50 Rho" in text and "0 to 100 Rho" in text, text


@pytest.mark.parametrize(
    "cmd",
    [
        ["diagnose", "pet1-26.7N", "--readings", "FILE"],
        ["report", "pet1-26.7N", "--readings", "FILE", "--out", "OUT"],
        ["readings", "FILE", "--trend", "FILE"],
    ],
)
def test_every_command_rejects_readings_off_the_scale(tmp_path, cmd):
    # the issue: -50 and 5000 Rho were accepted; each reader names file, line and value
    p = write(tmp_path, "position [in],reading [Rho]\n1,52\n2,5000\n")
    args = [{"FILE": str(p), "OUT": str(tmp_path / "o")}.get(a, a) for a in cmd]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and "r.csv line 3" in lines[0] and "5000 Rho is off" in lines[0]
    assert not (tmp_path / "o").exists()
