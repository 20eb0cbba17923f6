"""The calibration block read through a roll model, and the head calibrated in that model
(``woundroll calibrate-head``, :mod:`woundroll.contact.block`)."""

from __future__ import annotations

import json
import math
import tomllib

import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.contact.block import block_roll, calibrate_head_in_model, read_block
from woundroll.contact.models import default_model_name
from woundroll.errors import InputError
from woundroll.instruments import get_instrument
from woundroll.instruments.calibration import CalibrationBlock
from woundroll.instruments.definitions import load_instrument_file

RM = get_instrument("rho-meter")
BLOCK = CalibrationBlock.from_preset("rho-meter")


@pytest.mark.parametrize("model", ["2d", "3d"])
def test_block_is_isotropic_in_every_model(model):
    # every modulus of the block follows from its E and nu (the 3D block once kept the web
    # default G_r_z = 2 E_r, 5.8x the rubber's shear modulus: about 6 Rho too hard)
    web, core, r, s = block_roll(BLOCK, model)
    E, nu = BLOCK.youngs_modulus, BLOCK.poisson_ratio
    G = E / (2 * (1 + nu))
    assert web.E_r(-1e6) == pytest.approx(E, rel=1e-12)
    assert web.E_theta == web.E_z == E
    assert web.nu_theta_r == web.nu_z_r == web.nu_theta_z == nu
    for g in (web.shear_r_theta(E), web.shear_r_z(E), web.G_theta_z):
        assert float(g) == pytest.approx(G, rel=1e-12)
    assert r[-1] - r[0] == pytest.approx(BLOCK.thickness)
    assert not any(s)
    if model == "3d":
        assert web.width == pytest.approx(BLOCK.width)


def test_bundled_head_reads_77_through_the_default_model():
    # the deliverable: the shipped head is calibrated in the model that reads the rolls;
    # tolerance 0.05 Rho: the file keeps the radius to 0.001 mm (0.01 %), and the model's
    # step error on the block is below 0.02 % (the calibration's own rtol is 1e-4)
    assert RM.calibration_model == default_model_name("cylinder") == "2d"
    got = read_block(RM)
    assert got.model == "2d"
    assert got.reading == pytest.approx(77.0, abs=0.05)


def test_calibration_recovers_a_radius_it_was_given():
    # the block read with a 7 mm head, then the radius solved back from that reading: the
    # search must return 7 mm (rtol 1e-4 on the radius, the block reading to 1e-3 Rho)
    seven = RM.with_overrides(head_radius=7e-3)
    target = read_block(seven).reading
    cal = calibrate_head_in_model(RM, target=target)
    assert cal.value == pytest.approx(7e-3, rel=3e-4)
    assert cal.block.reading == pytest.approx(target, abs=1e-3)
    assert cal.block_before.reading == pytest.approx(read_block(RM).reading, rel=1e-12)
    # a sharper head reads softer: the radius and the reading move together on the block
    assert (cal.value > RM.head_radius) == (target > cal.block_before.reading)


def test_unreachable_target_and_bad_unknown():
    with pytest.raises(InputError) as exc:
        calibrate_head_in_model(RM, unknown="mass")
    assert exc.value.field == "calibration.unknown"
    from woundroll.errors import ConvergenceError

    with pytest.raises(ConvergenceError, match="no head_radius"):
        calibrate_head_in_model(RM, target=400.0)


def test_cli_writes_an_instrument_file_that_reads_the_target(tmp_path):
    out = tmp_path / "rho-site.toml"
    res = CliRunner().invoke(
        app, ["calibrate-head", "--unknown", "head_length", "--write", str(out), "--json"]
    )
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)
    assert d["model"] == "2d" and d["unknown"] == "head_length"
    assert d["block_reading"] == pytest.approx(77.0, abs=1e-3)
    raw = tomllib.loads(out.read_text(encoding="utf-8"))
    assert raw["calibration_model"] == "2d"
    assert "calibrate-head" in raw["sources"]["head_length"]
    inst = load_instrument_file(str(out))
    assert inst.head_length == pytest.approx(d["head_length_m"], rel=1e-4)
    assert read_block(inst).reading == pytest.approx(77.0, abs=0.05)
    assert math.isclose(inst.head_radius, RM.head_radius)


def test_cli_bad_model_one_line_exit_2():
    res = CliRunner().invoke(app, ["calibrate-head", "--model", "2.5d"])
    assert res.exit_code == 2
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: --model:"), res.output
