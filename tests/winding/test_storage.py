"""Temperature and moisture after winding (woundroll.winding.storage): the finite
differences against the closed form of a cylindrically orthotropic annulus on an elastic
core, their convergence rate, a uniform expansion that leaves the roll unstressed, zero
change equal to today's run, warnings and bad input."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.materials.radial_modulus import Constant
from woundroll.materials.web import Core, Web
from woundroll.winding.hakiel import wind
from woundroll.winding.storage import (
    StorageChange,
    apply_storage,
    closed_form_linear,
    solve_increment,
)
from woundroll.winding.tension import TensionSchedule

runner = CliRunner()

# a PET-like roll cooled by 20 K on a steel core (expansion coefficients of the PET preset)
DT = -20.0
ARGS = dict(
    E_theta=5e9,
    nu_theta_r=0.01,
    eps_r=6e-5 * DT,
    eps_theta=1.7e-5 * DT,
    core_stiffness=3e9,
    core_strain=1.2e-5 * DT,
)


def _error(n: int, E_r: float = 2e8) -> float:
    a, b = 0.05, 0.2
    r = np.linspace(a, b, n)
    s = solve_increment(r, np.full(n, E_r), **ARGS)
    c = closed_form_linear(r, a, b, E_r, **ARGS)
    return float(np.max(np.abs(s - c)) / np.max(np.abs(c)))


def test_constant_modulus_matches_the_closed_form():
    # 1601 nodes on a 15 cm annulus, g = 5: relative error measured 3.4e-5 (second-order
    # FD); 1e-4 leaves a factor 3
    assert _error(1601) < 1e-4


def test_second_order_convergence():
    errs = [_error(n) for n in (101, 201, 401, 801)]
    orders = [math.log2(e0 / e1) for e0, e1 in zip(errs, errs[1:], strict=False)]
    # measured 1.88, 1.94, 1.97: the three-point stencils are second order
    assert orders[-1] == pytest.approx(2.0, abs=0.1), orders
    assert all(o > 1.8 for o in orders), orders


def test_uniform_expansion_leaves_the_roll_unstressed():
    # web (r and theta) and core expand alike: no stress change (to round-off)
    args = dict(ARGS, eps_r=1e-3, eps_theta=1e-3, core_strain=1e-3)
    r = np.linspace(0.05, 0.2, 201)
    s = solve_increment(r, np.full(201, 2e8), **args)
    assert np.max(np.abs(s)) < 1e-6 * 5e9 * 1e-3


@pytest.fixture(scope="module")
def linear_roll():
    web = Web(
        thickness=1e-4,
        width=0.15,
        E_theta=5e9,
        radial_modulus=Constant(2e8),
        alpha_r=6e-5,
        alpha_theta=1.7e-5,
        beta_r=0.1,
        beta_theta=0.05,
        nu_theta_r=0.01,
    )
    core = Core.tube(0.0445, 0.0381, 200e9, 0.3)
    core = replace(core, thermal_expansion=1.2e-5)
    w = wind(web, core, 0.09, TensionSchedule(web_stress=2e7))
    return web, core, w


def storage_against_closed_form(web, core, w):  # noqa: ANN001, ANN201
    """The linear roll cooled by DT and wetted by 1 %: (storage result, the closed form's
    sigma_r change, the relative error of the result's against it);
    docs/scripts/winding_checks.py shows it."""
    change = StorageChange(temperature_change=DT, moisture_change=0.01)
    res = apply_storage(w, web, core, change)
    eps_r, eps_theta = change.free_strains(web)
    c = closed_form_linear(
        w.radius,
        w.radius[0],
        w.radius[-1],
        2e8,
        5e9,
        0.01,
        eps_r,
        eps_theta,
        core.stiffness,
        1.2e-5 * DT,
    )
    return res, c, float(np.max(np.abs(res.delta_sigma_r - c)) / np.max(np.abs(c)))


def test_linear_roll_after_storage_matches_the_closed_form(linear_roll):
    w = linear_roll[2]
    res, c, err = storage_against_closed_form(*linear_roll)
    # the winding's mesh (455 layers, 911 nodes): relative error measured 2.4e-5; 1e-4
    assert err < 1e-4
    # a constant law needs no Picard iteration beyond the check
    assert res.iterations <= 2
    np.testing.assert_allclose(
        res.winding.sigma_r, w.sigma_r + np.r_[c[:-1], 0.0], atol=1e-4 * np.max(np.abs(c))
    )


def test_zero_change_returns_the_wound_in_state_bit_for_bit(linear_roll):
    web, core, w = linear_roll
    res = apply_storage(w, web, core, StorageChange())
    assert res.winding is w
    assert not res.warnings


def test_zero_change_run_equals_todays_run(tmp_path):
    from woundroll.case import load_case
    from woundroll.case.schema import StorageSpec
    from woundroll.pipeline import run

    base = run("pet1-26.7N")
    case = load_case("pet1-26.7N").model_copy(update={"storage": StorageSpec()})
    after = run(case)
    np.testing.assert_array_equal(after.winding.sigma_r, base.winding.sigma_r)
    np.testing.assert_array_equal(after.winding.sigma_theta, base.winding.sigma_theta)
    assert after.hardness.reading == base.hardness.reading
    assert after.flags["storage_overstress"] is False


def test_hoop_stress_beyond_strength_is_flagged(linear_roll):
    web, core, w = linear_roll
    weak = replace(web, tensile_strength=2.2e7)
    res = apply_storage(w, weak, core, StorageChange(temperature_change=-200.0))
    assert res.overstressed
    assert any("tensile_strength" in m or "pulled apart" in m for m in res.warnings)


def test_non_number_names_the_field():
    with pytest.raises(InputError) as exc:
        StorageChange(temperature_change="warm")  # type: ignore[arg-type]
    assert exc.value.field == "storage.temperature_change"


@pytest.mark.parametrize(
    ("line", "field"),
    [
        ('temperature_change = "warm"', "storage.temperature_change"),
        ('moisture_change = "lots"', "storage.moisture_change"),
    ],
)
def test_cli_bad_storage_exit_2_one_line(tmp_path, line, field):
    text = (
        '[web]\npreset = "PET1"\n[core]\nrigid = true\nouter_radius = "4.45 cm"\n'
        '[winding]\nouter_radius = "5 cm"\ntension = "26.7 N"\n'
        f"[storage]\n{line}\n"
    )
    path = tmp_path / "bad.toml"
    path.write_text(text)
    res = runner.invoke(app, ["run", str(path), "-q"])
    assert res.exit_code == 2, res.output
    errors = [x for x in res.output.splitlines() if x.strip() and not x.startswith("warning")]
    assert len(errors) == 1 and errors[0].startswith(f"error: {field}"), res.output


def test_run_flags_overstress_and_notes_the_change(tmp_path):
    # winding only (no tester): heated by 150 K, PET's hoop stress passes a 5 MPa strength
    from woundroll.pipeline import run

    path = tmp_path / "hot.toml"
    path.write_text(
        '[web]\npreset = "PET1"\ntensile_strength = "5 MPa"\n'
        '[core]\nrigid = true\nouter_radius = "4.45 cm"\n'
        '[winding]\nouter_radius = "6 cm"\ntension = "26.7 N"\n'
        '[storage]\ntemperature_change = "150 K"\n'
    )
    res = run(path)
    assert res.flags["storage_overstress"] is True
    assert any(w.startswith("storage:") for w in res.warnings)
    assert any(n.startswith("storage:") for n in res.notes)
    assert res.to_dict()["winding"]["storage"]["temperature_change_K"] == 150.0


def test_temperature_change_in_the_units_a_mill_uses():
    # a change of 1 degC is 1 K; of 1 degF, 5/9 K (a change, not a temperature: no offset)
    from woundroll.case import load_case

    def dt(text: str) -> float:
        return load_case(
            "pet1-26.7N", [f"storage.temperature_change='{text}'"]
        ).storage.temperature_change

    assert dt("-20 K") == dt("-20 degC") == dt("-20 °C") == -20.0
    assert dt("-36 degF") == pytest.approx(-20.0, rel=1e-15)
    assert dt("9 °F") == pytest.approx(5.0, rel=1e-15)
