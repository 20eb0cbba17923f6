"""The impact in time on the 2D FE roll (woundroll.contact.dynamic)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.contact import roll_stiffness
from woundroll.contact.dynamic import DynamicOptions, element_mass, impact_dynamic
from woundroll.contact.mesh import build_mesh
from woundroll.errors import InputError
from woundroll.instruments import RollSpring, TabulatedLaw, impact_energy, impact_fd
from woundroll.materials import Core, Web
from woundroll.materials.radial_modulus import Constant
from woundroll.winding.hakiel import WindingOptions, wind


@pytest.fixture(scope="module")
def pet1():
    """PET1 wound at 26.7 N (Hakiel profile), the Rho-meter, and its quasi-static spring."""
    case = load_case("pet1-26.7N")
    web, core = case.web.build(), case.core.build()
    r_out = case.winding.final_radius(web, core)
    w = wind(
        web,
        core,
        r_out,
        case.winding.schedule(web),
        options=WindingOptions.from_dict(case.winding.options, "winding.options"),
    )
    inst = case.tester_setup.instrument
    st = roll_stiffness(web, core, w.radius, w.sigma_r, inst)
    return web, core, w.radius, w.sigma_r, inst, st


def _run(pet1, **kw):
    web, core, r, s, inst, st = pet1
    density = kw.pop("density", None)
    return impact_dynamic(
        web,
        core,
        r,
        s,
        inst,
        density=density,
        contact_time=2.1e-3,
        depth_scale=1.25 * st.impact_depth,
        options=DynamicOptions(**kw),
    )


def test_mass_matrix_sums_to_the_annulus_mass():
    # the row sums of the consistent mass are the lumped masses; their total is
    # rho * area of the half annulus per unit length (exact quadrature: round-off)
    mesh = build_mesh(
        0.05,
        0.1,
        surface_size=1e-3,
        radial_growth=1.2,
        tangential_size=1e-3,
        fine_halfwidth=5e-3,
        tangential_growth=1.2,
    )
    M = element_mass(mesh)
    total_r = M[:, 0::2, 0::2].sum()
    assert total_r == pytest.approx(0.5 * math.pi * (0.1**2 - 0.05**2), rel=1e-12)
    assert M[:, 1::2, 1::2].sum() == pytest.approx(total_r, rel=1e-12)
    assert np.all(M.sum(axis=2) > 0)  # lumped masses positive


def test_massless_roll_matches_the_fd_model_on_the_same_curve(pet1):
    # the thin/light limit of the 1.5D models: with no roll inertia the FE impact is the
    # striker on the quasi-static F(d) of the same mesh; the FD model with that curve
    # (tabulated, m_r = 0) must agree. Tolerances: 0.5 % (the dynamic hypoelastic path vs
    # 24 quasi-static increments, time steps of both), e within 0.5 % of 1 (elastic roll,
    # first-order numerical damping of gamma = 0.6).
    web, core, r, s, inst, st = pet1
    c = st.contact
    fd = impact_fd(inst, RollSpring(TabulatedLaw(c.delta, c.force), 0.0))
    en = impact_energy(inst, TabulatedLaw(c.delta, c.force))
    dyn = _run(pet1, density=1e-3, steps_per_contact=200)
    assert dyn.rho == pytest.approx(fd.rho, rel=5e-3)
    assert dyn.impulse == pytest.approx(fd.impulse, rel=5e-3)
    assert dyn.max_depth == pytest.approx(en.max_depth, rel=5e-3)  # energy conservation {19}
    assert dyn.contact_time == pytest.approx(fd.contact_time, rel=1e-2)
    assert dyn.restitution == pytest.approx(1.0, abs=5e-3)
    assert dyn.energy_roll_left < 1e-3 * dyn.energy_in


def test_energy_balance_and_time_step_convergence(pet1):
    # every joule is accounted for: striker kinetic + spring, roll kinetic, work of the
    # roll's internal forces, and the loss (numerical damping of gamma = 0.6 plus the
    # discrete impact of nodes entering contact), which is first order in dt
    runs = [_run(pet1, steps_per_contact=n) for n in (100, 200, 400)]
    e0 = runs[0].energy_in
    for d in runs:
        total = d.energy_striker + d.energy_roll_kinetic + d.energy_roll_internal
        # the loss grows monotonically and stays a few % of the impact energy
        loss = (e0 + 0.5 * 2800.0 * 0.0024**2) - total
        assert np.all(loss > -1e-6 * e0)
        assert loss[-1] < 0.05 * e0
        assert d.energy_contact_loss == pytest.approx(loss[-1], abs=1e-6 * e0)
    losses = [d.energy_contact_loss for d in runs]
    assert losses[2] < 0.75 * losses[1] < 0.75 * 0.75 * losses[0]  # ~ halves per halving
    rho = [d.rho for d in runs]
    # Rho converges: successive differences shrink, the last below 0.5 %
    assert abs(rho[2] - rho[1]) < abs(rho[1] - rho[0])
    assert abs(rho[2] - rho[1]) < 5e-3 * rho[2]
    imp = [d.impulse for d in runs]
    assert abs(imp[2] - imp[1]) < 2e-3 * imp[2]


def test_hard_roll_is_an_elastic_bounce():
    # closed-form limit: on a very stiff, light elastic roll the contact is short and the
    # striker bounces back with its impact speed; the impulse is 2 m v_c plus the
    # striker spring's impulse k x_gap t_contact (tolerance 1 %: the contact lasts ~0.1 ms,
    # wave loss into the light roll)
    from woundroll.instruments import get_instrument

    inst = get_instrument("rho-meter")
    web = Web(thickness=1e-4, width=0.15, E_theta=5e9, radial_modulus=Constant(5e9), density=1.0)
    core = Core(0.0445)
    r = np.array([0.0445, 0.1334])
    s = np.zeros(2)
    d = impact_dynamic(
        web,
        core,
        r,
        s,
        inst,
        contact_time=1e-4,
        depth_scale=2e-5,
        options=DynamicOptions(steps_per_contact=100),
    )
    m, v = inst.mass, inst.impact_speed
    expected = 2 * m * v + inst.spring_stiffness * inst.contact_position * d.contact_time
    assert d.impulse == pytest.approx(expected, rel=1e-2)
    assert d.restitution == pytest.approx(1.0, abs=1e-2)


def test_bad_options():
    with pytest.raises(InputError) as e:
        DynamicOptions(mass="diagonal")
    assert e.value.field.endswith("mass")
    with pytest.raises(InputError):
        DynamicOptions(steps_per_contact=5)
    with pytest.raises(InputError):
        DynamicOptions(newmark_gamma=0.4)


def test_case_with_contact_dynamic_reports_hardness_dynamic(tmp_path):
    import json

    import woundroll
    from woundroll.case import load_case

    case = load_case(
        "pet1-26.7N",
        ["contact.dynamic=true", "contact.dynamic_options.steps_per_contact=100"],
    )
    res = woundroll.run(case)
    d = json.loads(res.to_json())["hardness"]
    dyn = d["dynamic"]
    for key in ("rho", "impulse_Ns", "contact_time_s", "delta_max_m"):
        assert np.isfinite(dyn[key]) and dyn[key] > 0
    n = len(dyn["time_s"])
    assert n > 50
    for key in ("deceleration_m_per_s2", "position_m", "velocity_m_per_s", "contact_force_N"):
        assert len(dyn[key]) == n
    at = dyn["at_peak"]
    assert len(at["depth_below_surface_m"]) == len(at["radial_pressure_Pa"]) > 10
    # the rebound is elastic without an unloading law, and the readout says so
    assert dyn["rebound"].startswith("elastic")
    # beside the 1.5D models (same striker, same roll): within 25 % of the FD reading
    assert dyn["rho"] == pytest.approx(d["rho_fd"], rel=0.25)
    files = res.write(tmp_path)
    assert tmp_path / "dynamic.png" in files and (tmp_path / "dynamic.png").stat().st_size > 0


@pytest.mark.parametrize(
    ("overrides", "field"),
    [
        (["contact.dynamic=true", "contact.dynamic_options.mass='diagonal'"], "mass"),
        (["contact.dynamic=true", "contact.dynamic_options.colour=1"], "colour"),
        (
            ["contact.dynamic=true", "tester.roll_spring.alpha=1e8", "tester.roll_spring.beta=1e5"],
            "contact.dynamic",
        ),
    ],
)
def test_case_errors_name_the_field(overrides, field):
    from woundroll.case import load_case

    with pytest.raises(InputError) as e:
        load_case("pet1-26.7N", overrides)
    assert field in e.value.field
