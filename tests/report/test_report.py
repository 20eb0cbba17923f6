"""The HTML report: self-contained, inputs with units and sources, escaped, hashed, printable."""

import base64
import re

import numpy as np
import pytest
from typer.testing import CliRunner

import woundroll
from woundroll.app.cli import app
from woundroll.app.report import build_report, case_hash, write_report

# an explicit roll spring bypasses the contact model: the report's content, not the physics,
# is under test here, and this run takes milliseconds
FAST = [
    "tester.roll_spring={alpha='2.6e8 N/m^2', beta='1.05e5 N/m'}",
    "winding.outer_radius='6 cm'",
]


@pytest.fixture(scope="module")
def result():
    return woundroll.run(woundroll.load_case("pet1-26.7N", FAST))


@pytest.fixture(scope="module")
def html(result):
    return build_report(result)


def test_self_contained(html):
    # nothing that a browser would fetch: no links, scripts, stylesheets or remote images
    assert not re.search(r"""(src|href)\s*=\s*["'](?!data:|#)""", html)
    assert "<link" not in html and "<script" not in html
    assert "@import" not in html and "url(" not in html
    imgs = re.findall(r'src="data:image/png;base64,([^"]+)"', html)
    # winding (1) + hardness (1) figures: the contact model did not run
    assert len(imgs) == 2
    for data in imgs:
        assert base64.b64decode(data).startswith(b"\x89PNG\r\n\x1a\n")


def test_numbers_and_provenance(html, result):
    d = result.hardness.to_dict()
    assert f"{d['reading']:.1f}" in html
    assert f"woundroll {woundroll.__version__}" in html
    assert case_hash(result.case) in html
    # inputs with units and sources: the material preset with its source, the instrument's
    # own [sources] entries, the case file
    assert "preset PET1 (Reference paper, Table 2;" in html  # then the typical values named
    assert "reference paper, Table 1 (0.8 cm)" in html  # rho-meter release_position source
    assert re.search(r"web.thickness</code></td><td class=\"num\">100</td><td>um", html)
    assert "roll spring given explicitly: contact model bypassed" in html  # run notes


def test_prints_on_a4_and_letter(html):
    assert "@media print" in html
    page = re.search(r"@page\s*{([^}]*)}", html).group(1)
    # no page size: the printer's A4 or Letter; the content width (180 mm) fits both
    assert "size" not in page and "margin" in page
    assert "max-width: 180mm" in html


def test_user_strings_escaped():
    case = woundroll.load_case("pet1-26.7N", [*FAST, "title='<script>alert(1)</script> & co'"])
    html = build_report(woundroll.run(case))
    assert "<script>" not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt; &amp; co" in html


def test_case_hash_follows_values_not_spelling():
    a = woundroll.load_case("pet1-26.7N", ["winding.tension='6 lbf'"])
    b = woundroll.load_case("pet1-26.7N", ["winding.tension='26.689329691563 N'"])
    c = woundroll.load_case("pet1-26.7N", ["winding.tension='26.8 N'"])
    assert case_hash(a) == case_hash(b)
    assert case_hash(a) != case_hash(c)
    assert re.fullmatch(r"[0-9a-f]{16}", case_hash(a))


class _Readings:
    """A stand-in with the interface of woundroll.io.readings.Readings.to_dict()."""

    def to_dict(self):
        return {
            "source": "roll_4711.csv",
            "scale": "Rho",
            "passes": 2,
            "pooled_sd": 1.25,
            "position_m": [0.0762, 0.2286],
            "mean": [55.5, 58.0],
            "sd": [0.7, 0.0],
            "count": [2, 1],
        }


class _Diagnosis:
    def to_dict(self):
        return {
            "summary": "outer layers soft on the drive side",
            "defect_risks": [
                {"name": "telescoping", "level": "high", "reason": "low core pressure"},
                "starring",
            ],
            "fit": {"rms": 1.234567, "tension_N": 31.0},
        }


def test_readings_and_diagnosis_render_when_given(result):
    html = build_report(result, readings=_Readings(), diagnosis=_Diagnosis())
    assert 'id="readings"' in html and 'id="diagnosis"' in html
    assert "roll_4711.csv" in html and '<td class="num">76.2</td><td class="num">3.00' in html
    assert "pooled repeatability SD 1.25 Rho" in html
    assert 'class="risk-high">high' in html and "starring" in html
    assert "fit.rms" in html and "1.2346" in html
    plain = build_report(result)
    assert 'id="readings"' not in plain and 'id="diagnosis"' not in plain


def test_cli_report_and_run_report(tmp_path):
    runner = CliRunner()
    sets = [a for s in FAST for a in ("--set", s)]
    res = runner.invoke(app, ["report", "pet1-26.7N", *sets, "--out", str(tmp_path / "r")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "r" / "report.html").stat().st_size > 10_000
    res = runner.invoke(app, ["run", "pet1-26.7N", *sets, "--out", str(tmp_path / "x"), "--report"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "x" / "report.html").is_file()
    assert (tmp_path / "x" / "result.json").is_file()


@pytest.mark.parametrize(
    ("args", "field"),
    [
        (["run", "pet1-26.7N", "--report"], "--report"),
        (["report", "pet1-26.7N", "--out", "OUT", "--readings", "no/such.csv"], "--readings"),
        (["report", "pet1-26.7N", "--out", "/proc/no/way"], "--out"),
        (["report", "pet1-26.7N", "--out", "OUT", "--readings", "SHEET"], "--readings"),
        (
            ["report", "pet1-26.7N", "--out", "OUT", "--readings", "SHEET", "--roll", "9"],
            "--readings",
        ),
        (
            ["report", "pet1-26.7N", "--out", "OUT", "--readings", "SHEET", "--format", "x"],
            "--readings",
        ),
        # a roll id on a one-roll file: an error, not silently ignored
        (
            ["report", "pet1-26.7N", "--out", "OUT", "--readings", "PROFILE", "--roll", "9"],
            "--roll",
        ),
    ],
)
def test_cli_bad_input_one_line(args, field, tmp_path):
    from pathlib import Path

    sheet = Path(__file__).resolve().parents[2] / "examples" / "data" / "tappi_t834_sheet.csv"
    subs = {"OUT": str(tmp_path / "o"), "SHEET": str(sheet)}
    subs["PROFILE"] = str(sheet.with_name("readings_rho_3passes.csv"))
    args = [subs.get(a, a) for a in args]
    res = CliRunner().invoke(app, [*args, "--set", FAST[0], "--set", FAST[1]])
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and f"{field}:" in lines[0], res.output


def test_write_report_path(result, tmp_path):
    p = write_report(result, tmp_path / "deep" / "er")
    assert p == tmp_path / "deep" / "er" / "report.html"
    assert np.isclose(len(p.read_text(encoding="utf-8")), len(build_report(result)), rtol=0.01)


def test_real_readings_and_defects(result):
    from pathlib import Path

    from woundroll.assess.defects import defect_report
    from woundroll.io.readings import read_readings

    sheet = Path(__file__).resolve().parents[2] / "examples" / "data" / "readings_rho_3passes.csv"
    r = read_readings(sheet, width=result.case.web.width)
    defects = defect_report(result.case, winding=result.winding)
    html = build_report(result, readings=r, defects=defects)
    assert 'id="defects"' in html and "Defect risk: " in html
    for name, risk, _ in defects.summary():
        assert f"<td>{name}</td><td" in html and f">{risk}</td>" in html
    # the readings table: every position's mean, in mm and in
    for x, m in zip(r.position, r.mean, strict=True):
        assert f'<td class="num">{x * 1e3:.1f}</td><td class="num">{x / 0.0254:.2f}</td>' in html
        assert f"{m:.2f}" in html


@pytest.mark.slow
def test_report_with_diagnosis(tmp_path):
    """The whole road: readings -> diagnosis (full forward runs) -> report (about a minute)."""
    from pathlib import Path

    sheet = Path(__file__).resolve().parents[2] / "examples" / "data" / "readings_rho_3passes.csv"
    res = CliRunner().invoke(
        app, ["report", "pet1-26.7N", "--readings", str(sheet), "--out", str(tmp_path), "-q"]
    )
    assert res.exit_code == 0, res.output
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert 'id="diagnosis"' in html and "wound-on tension [MPa]" in html
    assert 'id="readings"' in html and 'id="defects"' in html
    assert html.count("data:image/png;base64,") >= 8
