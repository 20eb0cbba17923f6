"""The linear orthotropic closed form, and the numerical model against it."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from woundroll.errors import InputError
from woundroll.materials import Constant, Core, Web
from woundroll.winding.closed_form import linear_orthotropic
from woundroll.winding.hakiel import WindingOptions, wind
from woundroll.winding.tension import Taper, TensionSchedule

H = 50e-6
RC = 0.05
E_T = 5e9
E_R = 2e6
T0 = 2e6
N_LAYERS = 300


def _web(nu: float = 0.0) -> Web:
    return Web(thickness=H, width=0.5, E_theta=E_T, radial_modulus=Constant(E_R), nu_theta_r=nu)


CASES = {
    "rigid": (Core(RC), Taper(), 0.0),
    "rigid-taper": (Core(RC), Taper("linear", 0.3), 0.0),
    "compliant": (Core.tube(RC, RC - 0.005, 70e9, 0.33), Taper(), 0.01),
    "compliant-taper": (Core(RC, stiffness=0.2e9), Taper("hyperbolic", 0.5), 0.01),
}


@pytest.mark.parametrize("name", list(CASES))
def test_numerical_model_matches_closed_form(name: str) -> None:
    """Constant E_r: the numerical model equals the summed power-law increments.

    Tolerance 0.1 % (core pressure; profile relative to the core pressure): the brief's
    bar. The element relation is the exact power-law solution, so the agreement is in
    fact to rounding; 0.1 % would still catch a wrong core condition (the rigid and the
    compliant cores differ by >10 % here, next test) or a wrong layer pressure.
    """
    core, taper, nu = CASES[name]
    web = _web(nu)
    R = RC + N_LAYERS * H
    sched = TensionSchedule(T0, taper=taper)
    res = wind(web, core, R, sched, options=WindingOptions(subdivisions=3))
    wot = sched.wound_on_tension(RC + H * np.arange(N_LAYERS), RC, R, H)
    r, sr, st = linear_orthotropic(RC, H, wot, E_R, E_T, core.stiffness, nu)
    ns = 3
    assert np.allclose(res.radius[::ns], r, rtol=1e-12)
    p_ref = -sr[0]
    assert res.core_pressure == pytest.approx(p_ref, rel=1e-3)
    assert np.max(np.abs(res.sigma_r[::ns] - sr)) <= 1e-3 * p_ref
    assert np.max(np.abs(res.sigma_theta[::ns] - st)) <= 1e-3 * np.max(np.abs(st))


@pytest.mark.parametrize("new_layer", ["laid_on", "elastic"])
def test_levels_of_the_deep_part_are_exact_for_constant_moduli(new_layer: str) -> None:
    """2,000 layers with the default lazy deep part (levels of doubling depth, up to 8 of
    them here): with constant E_r the frozen moduli are the true ones, so any error in the
    bookkeeping of the levels (pending increments, their frozen shapes, the hoop-stress
    flux, the boundaries moving with the surface) would show. Asserted to 1e-9 (rounding
    over 2,000 increments; measured ~1e-12), for both ways a new layer enters.
    """
    n = 2000
    core, taper, nu = CASES["compliant-taper"]
    web = _web(nu)
    R = RC + n * H
    sched = TensionSchedule(T0, taper=taper)
    res = wind(web, core, R, sched, options=WindingOptions(new_layer=new_layer))
    assert res.options["window_layers"] is not None
    wot = sched.wound_on_tension(RC + H * np.arange(n), RC, R, H)
    r, sr, st = linear_orthotropic(RC, H, wot, E_R, E_T, core.stiffness, nu, new_layer)
    p_ref = -sr[0]
    assert np.max(np.abs(res.sigma_r[::2] - sr)) <= 1e-9 * p_ref
    assert np.max(np.abs(res.sigma_theta[::2] - st)) <= 1e-9 * np.max(np.abs(st))


def test_elastic_new_layer_lowers_core_pressure_by_one_layer_shift() -> None:
    """Constant E_r: with the load on the new layer's outer face each increment is the
    laid-on one scaled by phi(s)/phi(s + h) < 1, so the core pressure is lower, by at most
    1 - (r_c / (r_c + h))^k ~ k h / r_c (5 % here; measured 3.1 %: the core term of phi
    grows the other way); asserted between 1 % and k h / r_c. The elastic surface keeps the
    last layer's pressure T h / R.
    """
    wot = np.full(N_LAYERS, T0)
    _, sr_on, _ = linear_orthotropic(RC, H, wot, E_R, E_T)
    r, sr_el, _ = linear_orthotropic(RC, H, wot, E_R, E_T, new_layer="elastic")
    assert 1e-2 < 1 - sr_el[0] / sr_on[0] < math.sqrt(E_T / E_R) * H / RC
    assert sr_on[-1] == 0.0
    assert sr_el[-1] == pytest.approx(-T0 * H / r[-1], rel=1e-12)


def test_core_condition_moves_core_pressure() -> None:
    """The compliant core lowers the core pressure: checks the tests above can fail."""
    wot = np.full(N_LAYERS, T0)
    _, sr_rigid, _ = linear_orthotropic(RC, H, wot, E_R, E_T)
    _, sr_soft, _ = linear_orthotropic(RC, H, wot, E_R, E_T, core_stiffness=0.2e9)
    assert -sr_soft[0] < 0.9 * -sr_rigid[0]


def test_closed_form_equals_continuous_integral() -> None:
    """Thin layers: the layer sum tends to the integral (Altmann's continuous form).

    sigma_r(r) = -(1/r) int_r^R T phi(r)/phi(s) ds, rigid core (c = 0). The sum is a
    left Riemann sum of that integral, error O(h) ~ h k / r relative: < 0.5 % here.
    """
    h = 5e-6
    n = 4000
    R = RC + n * h
    r, sr, _ = linear_orthotropic(RC, h, np.full(n, T0), E_R, E_T)
    k = math.sqrt(E_T / E_R)

    def phi(x: float) -> float:
        return (x / RC) ** k + (RC / x) ** k

    for ri in (RC, RC + 0.3 * n * h, RC + 0.9 * n * h):
        val, _ = quad(lambda s, ri=ri: phi(ri) / phi(s), ri, R, limit=200)
        expected = -T0 * val / ri
        got = np.interp(ri, r, sr)
        assert got == pytest.approx(expected, rel=5e-3)


def test_single_layer_on_rigid_core() -> None:
    """One layer: its pressure T h / r_c acts on the core, hoop stress T (exact)."""
    r, sr, st = linear_orthotropic(RC, H, [T0], E_R, E_T)
    assert sr[0] == pytest.approx(-T0 * H / RC, rel=1e-14)
    assert st[0] == st[1] == T0


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"core_radius": 0.0}, "core_radius"),
        ({"thickness": -1e-6}, "thickness"),
        ({"E_r": 0.0}, "E_r"),
        ({"wot": []}, "wot"),
        ({"core_stiffness": 0.0}, "core_stiffness"),
        ({"new_layer": "glued"}, "new_layer"),
    ],
)
def test_bad_input(kwargs: dict, field: str) -> None:
    args = {"core_radius": RC, "thickness": H, "wot": [T0], "E_r": E_R, "E_theta": E_T}
    args.update(kwargs)
    with pytest.raises(InputError) as err:
        linear_orthotropic(**args)
    assert err.value.field == field
