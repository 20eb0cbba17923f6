"""Loading/unloading of the radial response (woundroll.materials.unloading) and its use by
the FD model (restitution), the pipeline and ``woundroll fit-stack --unloading``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.materials.radial_modulus import Pfeiffer
from woundroll.materials.unloading import (
    PfeifferUnloading,
    fit_stack_cycle,
    restitution_at_pressure,
    unloading_from_spec,
)

LOAD = Pfeiffer(K1=4.62e3, K2=123.88)  # PET1 (Table 2)
UNLOAD = PfeifferUnloading(K1=40e3, K2=400.0)
P_MAX = 1e6


def _cycle(n: int = 25) -> tuple[np.ndarray, np.ndarray]:
    eps_max = math.log1p(P_MAX / LOAD.K1) / LOAD.K2
    e_l = np.linspace(0.0, eps_max, n)
    eps_res = UNLOAD.residual_strain(eps_max, P_MAX)
    e_u = np.linspace(eps_max, eps_res + 0.05 * (eps_max - eps_res), n)[1:]
    p = np.concatenate([LOAD.pressure(e_l), UNLOAD.pressure(e_u, eps_max, P_MAX)])
    return np.concatenate([e_l, e_u]), p


def test_cycle_fit_recovers_the_laws():
    # exact synthetic data: the fits must return the constants (optimizer tolerance)
    eps, p = _cycle()
    fit = fit_stack_cycle(eps, p)
    assert fit.loading.law.K1 == pytest.approx(LOAD.K1, rel=1e-5)
    assert fit.loading.law.K2 == pytest.approx(LOAD.K2, rel=1e-6)
    assert fit.unloading.K1 == pytest.approx(UNLOAD.K1, rel=1e-5)
    assert fit.unloading.K2 == pytest.approx(UNLOAD.K2, rel=1e-6)
    # the measured energy ratio (trapezoids, 25 points a branch) against the law's
    assert fit.energy_ratio == pytest.approx(UNLOAD.energy_ratio(LOAD, P_MAX), rel=2e-2)


def test_energy_ratio_closed_form_and_limits():
    # unloading along the loading law gives back everything (to the 2001-point quadrature)
    same = PfeifferUnloading(LOAD.K1, LOAD.K2)
    assert same.energy_ratio(LOAD, P_MAX) == pytest.approx(1.0, abs=1e-5)
    r = UNLOAD.energy_ratio(LOAD, P_MAX)
    # the exponential branch's integral against a fine quadrature
    eps_max = math.log1p(P_MAX / LOAD.K1) / LOAD.K2
    eps_res = UNLOAD.residual_strain(eps_max, P_MAX)
    e = np.linspace(eps_res, eps_max, 200001)
    pu = UNLOAD.pressure(e, eps_max, P_MAX)
    w_u = float(np.sum(0.5 * (pu[1:] + pu[:-1]) * np.diff(e)))
    w_l = LOAD.K1 * (math.expm1(LOAD.K2 * eps_max) / LOAD.K2 - eps_max)
    assert r == pytest.approx(w_u / w_l, rel=1e-5)
    assert 0.0 < r < 1.0
    # stiffer unloading gives back less
    assert PfeifferUnloading(40e3, 800.0).energy_ratio(LOAD, P_MAX) < r


def test_restitution_and_spec():
    from woundroll.materials import Web

    web = Web(thickness=1e-4, width=0.15, E_theta=5.7e9, radial_modulus=LOAD)
    assert restitution_at_pressure(web, P_MAX) == 1.0  # no unloading law: elastic
    web_u = Web(
        thickness=1e-4, width=0.15, E_theta=5.7e9, radial_modulus=LOAD, radial_unloading=UNLOAD
    )
    e = restitution_at_pressure(web_u, P_MAX)
    assert e == pytest.approx(math.sqrt(UNLOAD.energy_ratio(LOAD, P_MAX)), rel=1e-12)
    assert unloading_from_spec({"K1": "40 kPa", "K2": 400}) == UNLOAD
    with pytest.raises(InputError) as ex:
        unloading_from_spec({"K1": "40 kPa"})
    assert ex.value.field == "web.radial_unloading.K2"
    with pytest.raises(InputError):
        unloading_from_spec({"K1": "40 kPa", "K2": -1})


def test_fit_stack_cli_unloading(tmp_path):
    eps, p = _cycle()
    f = tmp_path / "cycle.csv"
    f.write_text(
        "strain,pressure [kPa]\n"
        + "".join(f"{a:.10g},{b / 1e3:.10g}\n" for a, b in zip(eps, p, strict=True)),
        encoding="utf-8",
    )
    res = CliRunner().invoke(app, ["fit-stack", str(f), "--unloading", "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["unloading"]["K2"] == pytest.approx(400.0, rel=1e-4)
    loading_only = tmp_path / "load.csv"
    loading_only.write_text("strain,pressure\n0.01,100\n0.02,300\n0.03,900\n", encoding="utf-8")
    res = CliRunner().invoke(app, ["fit-stack", str(loading_only), "--unloading"])
    assert res.exit_code == 2


def test_pipeline_fd_uses_the_unloading_law():
    # Rho is a loading quantity (unchanged); the rebound readings fall below elastic
    import woundroll
    from woundroll.case import load_case

    base = ["contact.no_update=false"]
    # the PET1 preset carries a typical unloading law; "elastic" removes it
    el = woundroll.run(load_case("pet1-26.7N", [*base, 'web.radial_unloading="elastic"']))
    un = woundroll.run(
        load_case("pet1-26.7N", [*base, 'web.radial_unloading={K1="40 kPa", K2=400}'])
    )
    # elastic roll: R below 100 only by the plastic collision with the roll mass {9}
    assert el.hardness.restitution == 1.0
    assert 0 < un.hardness.restitution < 1
    assert un.hardness.fd.rebound_r < el.hardness.fd.rebound_r - 1.0
    assert un.hardness.fd.rho == pytest.approx(el.hardness.fd.rho, rel=1e-9)
    assert any("unloading" in n for n in un.notes)


def test_schmidt_hammer_rebound_from_a_given_roll_spring():
    # Schmidt R predicted through the hand-given roll spring path (the sphere needs the 3D
    # contact model): elastic -> 100; with the unloading law -> R = 100 sqrt(1 - (1-e^2) W/E0)
    # as the energy balance of the readout says (tested in instruments), here just < 100
    import woundroll
    from woundroll.case import load_case

    spring = [
        "tester.instrument='schmidt-n'",
        "tester.roll_spring.alpha=1e9",
        "tester.roll_spring.beta=1e5",
        "tester.roll_spring.effective_mass=0",
    ]
    el = woundroll.run(load_case("pet1-26.7N", [*spring, 'web.radial_unloading="elastic"']))
    un = woundroll.run(
        load_case("pet1-26.7N", [*spring, 'web.radial_unloading={K1="40 kPa", K2=400}'])
    )
    assert el.hardness.reading == pytest.approx(100.0, abs=1e-3)
    e = un.hardness.restitution
    assert e < 1.0
    # energy balance between the zero-velocity states (m_r = 0, x_gap = 0): the roll keeps
    # (1 - e^2) W of W = E_roll(d_max) {20}; tolerance: the FD time step (1e-4)
    inst = un.hardness.instrument
    d = un.hardness.energy.max_depth
    W = 1e9 * d**3 / 3 + 1e5 * d**2 / 2
    E0 = 0.5 * inst.spring_stiffness * inst.release_position**2
    assert un.hardness.reading == pytest.approx(100 * math.sqrt(1 - (1 - e * e) * W / E0), rel=1e-4)
