"""Site calibration (``woundroll calibrate``): parameters recovered from synthetic readings of
a known model, a mis-specified model caught by the leave-one-out errors, bad input refused.

The rolls are small (rigid 3.5 in core, 7 cm outer radius: about 0.5 s a run) so that the
whole fit, its leave-one-out refits and the standard errors stay within about a minute.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

import woundroll
from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.inverse.site_calibration import calibrate_site

runner = CliRunner()

ROLLS = {"a": ("PET1", "10 N"), "b": ("PET1", "18 N"), "c": ("PET2", "30 N"), "d": ("PET2", "70 N")}
CASE = """title = "{name}"
[web]
preset = "{preset}"
[core]
outer_radius = "4.45 cm"
rigid = true
[winding]
outer_radius = "7 cm"
tension = "{tension}"
[tester]
instrument = "rho-meter"
"""


def _cases(tmp_path):
    paths = []
    for name, (preset, tension) in ROLLS.items():
        p = tmp_path / f"{name}.toml"
        p.write_text(CASE.format(name=name, preset=preset, tension=tension), encoding="utf-8")
        paths.append(str(p))
    return paths


def _readings(tmp_path, paths, truth, sd=0.3, n=3, seed=7):
    """Readings the model gives with the ``truth`` overrides (per roll), plus noise."""
    rng = np.random.default_rng(seed)
    rows = ["case,reading [Rho]"]
    for p in paths:
        name = p.rsplit("/", 1)[-1].removesuffix(".toml")
        r = woundroll.run(woundroll.load_case(p, truth(name))).hardness.reading
        rows += [f"{name},{v:.4f}" for v in r + rng.normal(0.0, sd, n)]
    f = tmp_path / "readings.csv"
    f.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return f


def test_recovers_head_length_from_synthetic_readings(tmp_path):
    # truth: an effective head length of 30 mm (the file says 25.4 mm); the fit through the
    # command line must find it within three standard errors (seeded noise, SD 0.3 Rho)
    paths = _cases(tmp_path)
    f = _readings(tmp_path, paths, lambda _: ["tester.head_length=0.030 m"])
    out = tmp_path / "fitted.toml"
    args = ["calibrate", str(f), "--fit", "head_length", "--out", str(out), "--json"]
    for p in paths:
        args += ["--cases", p]
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)
    fit = d["fitted"]["head_length"]
    assert abs(fit["value_m"] - 0.030) <= 3 * fit["standard_error_m"]
    assert 0 < fit["standard_error_m"] < 0.002  # the readings pin it to a few per cent
    assert d["predicts_left_out_rolls"] is True
    # the repeat scatter estimates the noise's 0.3 Rho (8 degrees of freedom: within 2x)
    assert 0.15 < d["scatter_repeat"] < 0.6
    text = out.read_text(encoding="utf-8")
    assert 'head_length = "' in text and "1 SE" in text
    # the written value applied as an override reproduces the fitted readings
    val = fit["value_m"]
    r0 = woundroll.run(woundroll.load_case(paths[0], [f"tester.head_length={val!r} m"]))
    assert r0.hardness.reading == pytest.approx(d["rolls"][0]["model_fitted"], rel=1e-3)


# slow: a synthetic calibration study, ~50 full model runs (the command line path stays in the
# default suite)
@pytest.mark.slow
def test_misspecified_model_is_caught_by_leave_one_out(tmp_path):
    # truth: the PET2 stack is 2.5x softer than its preset (K2 / 2.5) while PET1 is as
    # preset; fitting the head length alone cannot serve both, and the rolls left out say so
    paths = _cases(tmp_path)
    k2 = woundroll.load_case(paths[2]).web.build().radial_modulus.K2  # PET2 preset
    soft = {"c": k2 / 2.5, "d": k2 / 2.5}

    def truth(name):
        return [f"web.radial_modulus.K2={soft[name]!r}"] if name in soft else []

    f = _readings(tmp_path, paths, truth, sd=0.2)
    cal = calibrate_site(f, paths, ["head_length"])
    assert not cal.predicts
    assert "does NOT predict" in cal.verdict
    worst = np.max(np.abs(cal.loo_error) / cal.loo_allowed)
    assert worst > 1.5  # clearly beyond its allowance, not a borderline call


@pytest.mark.parametrize(
    ("edit", "text"),
    [
        ("same", "same settings"),
        ("offscale", "outside the instrument's scale"),
        ("unknown", "unknown parameter"),
        ("notanumber", "is not a number"),
        ("missing", "no reading of case"),
    ],
)
def test_bad_input_one_line_exit_2(tmp_path, edit, text):
    paths = _cases(tmp_path)[:2]
    rows = ["case,reading", "a,40", "a,41", "b,60"]
    fit = "head_length"
    if edit == "same":
        same = tmp_path / "a2.toml"
        same.write_text((tmp_path / "a.toml").read_text().replace('"a"', '"a2"'))
        paths = [paths[0], str(same)]
        rows = ["case,reading", "a,40", "a2,41"]
    elif edit == "offscale":
        rows.append("b,-50")
    elif edit == "unknown":
        fit = "lots"
    elif edit == "notanumber":
        rows.append("b,high")
    elif edit == "missing":
        rows = ["case,reading", "a,40"]
    f = tmp_path / "r.csv"
    f.write_text("\n".join(rows) + "\n")
    args = ["calibrate", str(f), "--fit", fit, "-q"]
    for p in paths:
        args += ["--cases", p]
    res = runner.invoke(app, args)
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and text in lines[0], res.output
    if edit in ("offscale", "notanumber"):
        assert "line 5" in lines[0]


def test_two_parameters_need_three_rolls(tmp_path):
    paths = _cases(tmp_path)[:2]
    f = tmp_path / "r.csv"
    f.write_text("case,reading\na,40\nb,60\n")
    with pytest.raises(InputError, match="at least 3 rolls") as exc:
        calibrate_site(f, paths, ["head_length", "K2_scale"])
    assert exc.value.field == "--cases"


def test_a_parameter_the_readings_do_not_see_is_not_identifiable(tmp_path, monkeypatch):
    # a model whose readings do not depend on the parameter (each roll its own constant):
    # the fit must refuse with "not identifiable", not return a number with a huge error
    from woundroll.inverse import site_calibration as sc

    paths = _cases(tmp_path)[:3]
    f = tmp_path / "r.csv"
    f.write_text("case,reading\na,40\na,41\nb,60\nb,61\nc,30\nc,31\n")
    flat = {0: 40.2, 1: 60.9, 2: 30.1}
    monkeypatch.setattr(sc._Model, "reading", lambda self, k, x: flat[k])
    with pytest.raises(InputError, match="not identifiable") as exc:
        calibrate_site(f, paths, ["head_length"])
    assert exc.value.field == "--fit"


def test_a_reading_at_the_scale_end_is_left_out(tmp_path):
    from woundroll.inverse.site_calibration import read_calibration_readings

    f = tmp_path / "r.csv"
    f.write_text("case,reading [Rho]\na,100\na,98\nb,0\nb,3\n")
    ys, notes = read_calibration_readings(f, ["a", "b"], (0.0, 100.0))
    assert [y.tolist() for y in ys] == [[98.0], [3.0]]
    assert notes and "2 reading(s) at the scale's end" in notes[0]
