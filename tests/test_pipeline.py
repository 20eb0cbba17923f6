"""The whole chain from a case: winding -> contact -> impact, and across the CMD.

Consistency between models that must agree, the JSON a user scripts against, the files
``--out`` writes, and the errors of the coupled path.
"""

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import woundroll
from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.instruments import get_instrument, impact_energy
from woundroll.instruments.roll_side import RollSpring

runner = CliRunner()


@pytest.fixture(scope="module")
def pet1():
    return woundroll.run(woundroll.load_case("pet1-26.7N", ["contact.no_update=true"]))


def test_coupled_json_has_every_documented_key(pet1):
    d = json.loads(pet1.to_json())
    c, h = d["contact"], d["hardness"]
    n = len(c["depth_m"])
    assert n >= 10 and len(c["force_N"]) == n and len(c["half_width_m"]) == n
    for key in ("alpha_N_per_m2", "beta_N_per_m", "semi_contact_width_m", "impact_depth_m"):
        assert np.isfinite(c[key]) and c[key] > 0
    for key in (
        "rho_energy",
        "rho_fd",
        "impulse_N_s",
        "impact_depth_m",
        "peak_force_N",
        "contact_time_s",
    ):
        assert np.isfinite(h[key]) and h[key] > 0
    assert len(h["time_s"]) == len(h["force_N"]) == len(h["deceleration_m_per_s2"])
    assert {"rho_fd", "rho_energy", "impulse_N_s"} <= set(d["no_update"])


def test_contact_fields_are_reported_at_the_impact_depth(pet1):
    # the fields and the slip factor {23} belong to the striker's deepest point, not to
    # the deepest contact increment computed
    c = pet1.contact.to_dict()
    at = c["at_impact_depth"]
    assert at["depth_m"] == pytest.approx(c["impact_depth_m"], rel=1e-12)
    assert at["depth_m"] < c["depth_max_m"]
    assert c["semi_contact_width_m"] == pytest.approx(at["semi_contact_width_m"], rel=1e-12)
    # the force there is the computed F(d) interpolated at that depth
    f = np.interp(at["depth_m"], c["depth_m"], c["force_N"])
    assert at["force_N"] == pytest.approx(f, rel=1e-9)
    assert at["max_slip_factor_near_contact"] >= 1.0  # Figure 18: slip around the head


def test_fd_and_energy_agree_on_the_contact_spring(pet1):
    # they differ by the striker spring's force at maximum depth (eq. 22 leaves it out,
    # ~1.7 Rho) and by the roll's active mass (FD only): a few per cent
    h = pet1.hardness.to_dict()
    assert abs(h["rho_energy"] / h["rho_fd"] - 1) < 0.06


def test_energy_reading_is_eq22_of_the_fitted_spring(pet1):
    # the pipeline hands the fitted spring to the energy model unchanged
    ins = get_instrument("rho-meter")
    e = impact_energy(ins, RollSpring.quadratic(pet1.contact.alpha, pet1.contact.beta, 0.0))
    assert pet1.hardness.to_dict()["rho_energy"] == pytest.approx(e.rho, rel=1e-12)


def test_striker_depth_lies_within_the_fitted_range(pet1):
    # no extrapolation of the quadratic: the energy model's depth is inside the computed
    # F(d), and the fit used the points up to 1.25 of it
    c = pet1.contact
    assert c.impact_depth <= c.contact.delta[-1]
    assert c.spring.fit_depth >= c.impact_depth
    assert c.spring.max_depth == pytest.approx(
        pet1.hardness.to_dict()["impact_depth_energy_m"], rel=1e-9
    )


def test_no_update_reads_markedly_lower(pet1):
    # the paper's Figure 8: E_r frozen at its pre-impact value is far softer; the updated
    # model reads well over 1.5x (2.4x measured for PET1 26.7 N)
    assert pet1.hardness.to_dict()["rho_fd"] > 1.5 * pet1.no_update.to_dict()["rho_fd"]


def test_out_writes_json_and_plots(tmp_path):
    res = runner.invoke(
        app,
        [
            "run",
            "pet1-26.7N",
            "--set",
            "contact.no_update=false",
            "--out",
            str(tmp_path),
            "--quiet",
        ],
    )
    assert res.exit_code == 0, res.output
    names = {p.name for p in tmp_path.iterdir()}
    assert {
        "result.json",
        "winding.png",
        "contact.png",
        "contact_slip.png",
        "hardness.png",
    } <= names
    assert "no_update" not in json.loads((tmp_path / "result.json").read_text())


def test_head_length_override_scales_the_force():
    # plane strain: the force on the head is the per-length force times the head length,
    # so doubling tester.head_length doubles F(d) exactly (same mesh, same depths)
    opts = ["contact.no_update=false", "contact.depth_max='1 mm'", "contact.model='2d'"]
    base = woundroll.run(woundroll.load_case("pet1-26.7N", opts))
    long = woundroll.run(woundroll.load_case("pet1-26.7N", [*opts, "tester.head_length='5.08 cm'"]))
    assert long.contact.contact.force == pytest.approx(2 * base.contact.contact.force, rel=1e-9)
    assert long.contact.to_dict()["head_length_m"] == pytest.approx(0.0508)
    # and the reading rises (a stiffer spring for the same striker)
    assert long.hardness.to_dict()["rho_energy"] > base.hardness.to_dict()["rho_energy"]
    # the CMD-spreading path adds the load spread past the ends, s(d), which does not
    # depend on the head's length: F_long / F = (2 L + 2 s) / (L + 2 s)
    opts[-1] = "contact.model='2d+cmd-spread'"
    base = woundroll.run(woundroll.load_case("pet1-26.7N", opts)).contact
    long = woundroll.run(woundroll.load_case("pet1-26.7N", [*opts, "tester.head_length='5.08 cm'"]))
    s, L = base.cmd_spread.spread[1:], 0.0254
    assert long.contact.contact.force[1:] == pytest.approx(
        base.contact.force[1:] * (2 * L + 2 * s) / (L + 2 * s), rel=1e-9
    )


@pytest.mark.parametrize(
    ("overrides", "field"),
    [
        (["tester.instrument='schmidt-n'", "contact.model='2d'"], "contact.model"),
        (["contact.depth_max='10 um'", "contact.no_update=false"], "contact.depth_max"),
        (["contact.options.bogus=1"], "contact.options.bogus"),
        (["contact.friction=-1"], "contact.friction"),
        (["tester.natural_frequency='0 rad/s'"], "tester.natural_frequency"),
    ],
)
def test_coupled_path_errors_name_the_field(overrides, field):
    with pytest.raises(InputError) as exc:
        woundroll.run(woundroll.load_case("pet1-26.7N", overrides))
    assert exc.value.field == field


# ---------------------------------------------------------------- CMD profile runs


def _profile_case(tmp_path: Path, thickness: str, extra: str = "") -> Path:
    (tmp_path / "prof.csv").write_text(thickness, encoding="utf-8")
    case = tmp_path / "case.toml"
    case.write_text(
        f"""
title = "small profile roll"
[web]
preset = "PET1"
[core]
outer_radius = "4.45 cm"
rigid = true
[winding]
outer_radius = "6 cm"
tension = "26.7 N"
thickness_profile = "prof.csv"
{extra}
[tester]
instrument = "rho-meter"
[profile]
sectors = 3
workers = 1
""",
        encoding="utf-8",
    )
    return case


UNIFORM = "position [cm],thickness [um]\n0,100\n7.62,100\n15.24,100\n"


def test_uniform_profile_reads_like_the_1d_chain(tmp_path):
    # the axisymmetric model with a uniform web reproduces the 1D winding model (within
    # 2 %, tests/winding), and each sector's contact + energy reading must then match the
    # 1D chain's energy reading; 3 % allows for the winding models' difference near the
    # surface, which the reading is sensitive to
    case = _profile_case(tmp_path, UNIFORM)
    prof = woundroll.run(case).profile
    one_d = woundroll.run(
        woundroll.load_case(
            {
                "web": {"preset": "PET1"},
                "core": {"outer_radius": "4.45 cm", "rigid": True},
                "winding": {"outer_radius": "6 cm", "tension": "26.7 N"},
                "tester": {"instrument": "rho-meter"},
                "contact": {"no_update": False},
            }
        )
    )
    rho_1d = one_d.hardness.to_dict()["rho_energy"]
    # uniform: symmetric about mid-width; the edge sectors differ slightly (free CMD edges)
    assert prof.rho[0] == pytest.approx(prof.rho[2], rel=1e-9)
    assert prof.rho_energy == pytest.approx(np.full(3, rho_1d), rel=0.03)
    # the headline per sector is the FD model (the instrument's own reading): it reads the
    # striker spring too and has the roll's active mass (a = 0.6 cm), so it differs from
    # the energy model by a few per cent
    assert prof.rho == pytest.approx(prof.rho_energy, rel=0.06)
    d = prof.to_dict()
    assert d["roll_model"] == "2d" and d["reading_model"] == pytest.approx(list(prof.rho))


def test_profile_json_and_plots(tmp_path):
    case = _profile_case(
        tmp_path, "position_m,thickness_m\n0,99e-6\n0.05,101e-6\n0.1,100e-6\n0.1524,99.5e-6\n"
    )
    out = tmp_path / "out"
    res = runner.invoke(app, ["run", str(case), "--json", "--out", str(out)])
    assert res.exit_code == 0, res.output
    p = json.loads(res.stdout)["profile"]
    keys = ("z_m", "reading", "reading_model", "saturated", "reading_energy", "thickness_m")
    for key in (*keys, "wound_on_tension_Pa", "sigma_r_outer_Pa", "sigma_r_core_Pa"):
        assert len(p[key]) == 3, key
    # a 2 % thickness spread on a 1.5 cm pile keeps every lane taut: nothing flagged
    assert p["slack"] == [False, False, False]
    assert {"profile_cmd.png", "profile_sigma_r.png"} <= {f.name for f in out.iterdir()}


@pytest.mark.parametrize(
    ("thickness", "extra", "field"),
    [
        (None, "", "winding.thickness_profile"),  # missing file
        ("position [cm],thickness [um]\n0,100\n5,100\n", "", "winding.thickness_profile"),
        (UNIFORM, "[winding.nip_roller]\nEI = '1e5 N m^2'\nE = '200 GPa'", "winding.nip_roller"),
    ],
)
def test_profile_input_errors(tmp_path, thickness, extra, field):
    case = _profile_case(tmp_path, thickness or UNIFORM, extra)
    if thickness is None:
        (tmp_path / "prof.csv").unlink()
    res = runner.invoke(app, ["run", str(case)])
    assert res.exit_code == 2, res.output
    assert f"{field}" in res.output and "Traceback" not in res.output


def test_unknown_profile_key_is_rejected():
    with pytest.raises(InputError) as exc:
        woundroll.load_case("pet1-26.7N", ["profile.bogus=1"])
    assert exc.value.field == "profile.bogus"


def test_nip_roller_needs_a_thickness_profile():
    with pytest.raises(InputError) as exc:
        woundroll.load_case("pet1-26.7N", ["winding.nip_roller.EI='1e5 N m^2'"])
    assert exc.value.field == "winding.nip_roller"


def test_measured_profile_is_compared(tmp_path):
    case = _profile_case(tmp_path, UNIFORM)
    (tmp_path / "rho.csv").write_text("position [cm],rho\n2,40\n7.6,41\n13,39\n")
    # 12 N keeps this small roll's lanes on the dial (at 26.7 N they all read past 100 and
    # show the scale's end: no shape to correlate)
    args = ["--set", "profile.measured='rho.csv'", "--set", "winding.tension='12 N'", "--json"]
    res = runner.invoke(app, ["run", str(case), *args])
    assert res.exit_code == 0, res.output
    prof = json.loads(res.stdout)["profile"]
    assert not any(prof["saturated"])
    m = prof["measured"]
    assert m["measured"] == [40.0, 41.0, 39.0]
    # bias = mean of (predicted - measured) at the measured positions
    diff = np.array(m["predicted"]) - np.array(m["measured"])
    assert m["bias"] == pytest.approx(diff.mean(), rel=1e-9)
    assert m["rms_difference"] == pytest.approx(np.sqrt(np.mean(diff**2)), rel=1e-9)
    assert -1.0 <= m["correlation"] <= 1.0


def test_output_atomic_files_recorded_and_stale_removed(tmp_path):
    import json

    from woundroll.case import load_case
    from woundroll.pipeline import run

    base = {
        "web": {
            "thickness": "100 um",
            "width": "15 cm",
            "E_theta": "5 GPa",
            "radial_modulus": {"law": "pfeiffer", "K1": "5 kPa", "K2": 100},
        },
        "core": {"outer_radius": "4 cm", "rigid": True},
        "winding": {"outer_radius": "6 cm", "tension": "1 MPa"},
        "tester": {
            "instrument": "rho-meter",
            "roll_spring": {"alpha": "1e9 N/m^2", "beta": "2e5 N/m"},
        },
    }
    out = tmp_path / "out"
    first = run(load_case(base)).write(out)
    names = sorted(p.name for p in first)
    # the impact's time series (> COMPACT_MAX_POINTS steps) go to result.npz
    assert names == ["hardness.png", "result.json", "result.npz", "winding.png"]
    data = json.loads((out / "result.json").read_text())
    assert sorted(data["files"]) == names
    assert set(data["flags"]) >= {"reading_outside_range", "spring_extrapolated"}
    # a second run without the tester: the first run's hardness.png is removed
    (out / "profile_cmd.png").write_bytes(b"")  # a stray plot nobody recorded: reported
    del base["tester"]
    second = run(load_case(base))
    written = second.write(out)
    assert sorted(p.name for p in written) == ["result.json", "winding.png"]
    assert not (out / "hardness.png").exists() and not (out / "result.npz").exists()
    assert any("profile_cmd.png" in n for n in second.notes)
    assert sorted(p.name for p in out.iterdir()) == [
        "profile_cmd.png",
        "result.json",
        "winding.png",
    ]


def test_strict_json_has_no_nan_tokens():
    import json
    import math

    from woundroll.util.output import strict_json

    text = strict_json({"a": math.nan, "b": [1.0, math.inf], "c": np.float64("nan")})
    assert json.loads(text) == {"a": None, "b": [1.0, None], "c": None}
    # arrays take the whole-array path: every kind, nested, non-finite in any position
    arrays = {
        "f": np.array([[1.5, np.nan], [-np.inf, 2.0]]),
        "f32": np.array([np.inf, 0.5], dtype=np.float32),
        "i": np.arange(3),
        "b": np.array([True, False]),
        "clean": np.linspace(0.0, 1.0, 3),
    }
    assert json.loads(strict_json(arrays)) == {
        "f": [[1.5, None], [None, 2.0]],
        "f32": [None, 0.5],
        "i": [0, 1, 2],
        "b": [True, False],
        "clean": [0.0, 0.5, 1.0],
    }


def test_reading_outside_the_instrument_range_is_flagged():
    from woundroll.case import load_case
    from woundroll.pipeline import run

    case = {
        "web": {
            "thickness": "100 um",
            "width": "15 cm",
            "E_theta": "5 GPa",
            "radial_modulus": {"law": "pfeiffer", "K1": "5 kPa", "K2": 100},
        },
        "core": {"outer_radius": "4 cm", "rigid": True},
        "winding": {"outer_radius": "6 cm", "tension": "1 MPa"},
        # a steel-block-like spring: far beyond 100 Rho
        "tester": {"instrument": "rho-meter", "roll_spring": {"alpha": 1e13, "beta": 1e8}},
    }
    r = run(load_case(case))
    assert r.hardness.reading > 100
    assert r.flags["reading_outside_range"]
    assert any("beyond the rho-meter's scale 0-100" in w for w in r.warnings)
    assert r.to_dict()["flags"]["reading_outside_range"] is True
