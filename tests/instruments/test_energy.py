"""The energy model {19}-{22}: the cubic's root, its limits, its vectorisation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from woundroll.errors import InputError
from woundroll.instruments import energy_max_depth, get_instrument, impact_energy, rho_energy

RM = get_instrument("rho-meter")
K, XI, XG = RM.spring_stiffness, RM.release_position, RM.contact_position


def test_linear_spring_closed_form():
    # alpha = 0: {21} degenerates to (beta + k) d^2/2 + k x_gap d + k (x_gap^2 - x_in^2)/2 = 0;
    # textbook root (-b + sqrt(b^2 - 4ac)) / 2a. Both are exact: rel 1e-13 (rounding only).
    for beta in (1e3, 5.4e5, 1e8):
        a, b, c = 0.5 * (beta + K), K * XG, 0.5 * K * (XG**2 - XI**2)
        exact = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
        assert float(energy_max_depth(0.0, beta, K, XI, XG)) == pytest.approx(exact, rel=1e-13)
        rho = float(rho_energy(0.0, beta, RM))
        assert rho == pytest.approx(beta * exact / (3.76 * 9.81 * RM.mass), rel=1e-13)


def test_cubic_root_is_the_unique_positive_root():
    rng = np.random.default_rng(1)
    alpha = 10 ** rng.uniform(2, 13, 400)
    beta = 10 ** rng.uniform(1, 9, 400)
    d = energy_max_depth(alpha, beta, K, XI, XG)
    for al, be, dd in zip(alpha[:60], beta[:60], d[:60], strict=True):
        # printed form {21} (divided by alpha): numpy's companion-matrix roots
        coeffs = [1.0, 3 * (be + K) / (2 * al), 3 * K * XG / al, 3 * K * (XG**2 - XI**2) / (2 * al)]
        roots = np.roots(coeffs)
        pos = [r.real for r in roots if abs(r.imag) < 1e-12 * abs(r) and r.real > 0]
        assert len(pos) == 1
        assert dd == pytest.approx(pos[0], rel=1e-8)  # np.roots is only ~1e-10 accurate
    # energy balance {19}: residual relative to the initial energy, rounding level
    resid = 0.5 * K * (XG + d) ** 2 + alpha * d**3 / 3 + beta * d**2 / 2 - 0.5 * K * XI**2
    assert np.max(np.abs(resid)) / (0.5 * K * XI**2) < 1e-13


def test_vectorised_matches_scalar_root_finder():
    rng = np.random.default_rng(2)
    alpha = 10 ** rng.uniform(5, 11, 50)
    beta = 10 ** rng.uniform(3, 7, 50)
    d = energy_max_depth(alpha, beta, K, XI, XG)
    for al, be, dd in zip(alpha, beta, d, strict=True):
        ref = brentq(
            lambda x, al=al, be=be: (
                al * x**3 / 3 + (be + K) * x**2 / 2 + K * XG * x + K * (XG**2 - XI**2) / 2
            ),
            0.0,
            XI,
            xtol=1e-18,
            rtol=1e-14,
        )
        assert dd == pytest.approx(ref, rel=1e-12)


def test_extremes_no_nan_and_limits():
    d = energy_max_depth(
        np.array([0.0, 1e-6, 1e20, 0.0]), np.array([1e-9, 0.0, 0.0, 1e15]), K, XI, XG
    )
    assert np.all(np.isfinite(d)) and np.all(d > 0)
    # a roll with no stiffness lets the striker swing to +x_in: d = x_in - x_gap
    assert float(energy_max_depth(0.0, 0.0, K, XI, XG)) == pytest.approx(XI - XG, rel=1e-14)
    # contact before equilibrium (x_gap < 0) still has one positive root (energy balance)
    dn = float(energy_max_depth(3e8, 5e5, K, XI, -0.002))
    assert 0.5 * K * (-0.002 + dn) ** 2 + 1e8 * dn**3 + 2.5e5 * dn**2 == pytest.approx(
        0.5 * K * XI**2, rel=1e-13
    )


def test_rho_rises_with_alpha_and_beta():
    alphas = np.geomspace(1e6, 1e11, 50)
    assert np.all(np.diff(rho_energy(alphas, 5.4e5, RM)) > 0)
    betas = np.geomspace(1e3, 1e8, 50)
    assert np.all(np.diff(rho_energy(3.7e8, betas, RM)) > 0)


def test_bad_coefficients_rejected():
    with pytest.raises(InputError) as exc:
        rho_energy(np.array([1e8, -1.0]), 5e5, RM)
    assert exc.value.field == "roll_spring.alpha"
    with pytest.raises(InputError) as exc:
        rho_energy(1e8, np.nan, RM)
    assert exc.value.field == "roll_spring.beta"


def test_impact_energy_result_consistent():
    res = impact_energy(RM, (3.7e8, 5.4e5))
    assert res.rho == pytest.approx(float(rho_energy(3.7e8, 5.4e5, RM)), rel=1e-14)
    assert res.peak_force == pytest.approx(
        3.7e8 * res.max_depth**2 + 5.4e5 * res.max_depth, rel=1e-14
    )


@pytest.mark.parametrize("x_gap", [0.0024, 0.0, -0.004])
def test_tabulated_law_energy_root_is_exact(x_gap):
    # a straight line given as a table must give the closed-form root of the quadratic
    # (rounding only: rel 1e-12), also when contact happens before equilibrium (x_gap < 0)
    from woundroll.instruments import TabulatedLaw

    inst = RM.with_overrides(contact_position=x_gap)
    beta = 5.4e5
    d_tab = np.linspace(0.0, 5e-3, 501)
    law = TabulatedLaw(d_tab, beta * d_tab)
    a, b, c = 0.5 * (beta + K), K * x_gap, 0.5 * K * (x_gap**2 - XI**2)
    exact = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
    assert impact_energy(inst, law).max_depth == pytest.approx(exact, rel=1e-12)


@pytest.mark.parametrize("x_gap", [2.4e-3, 0.0, -1e-3])
def test_chunked_matches_whole_array_form(x_gap):
    """The cache-chunked evaluation (issue 14: >= 1e7 per second, benchmarks/bench_impact.py)
    is the same iteration as the straightforward whole-array form: equal to rounding (4 ulp)
    across chunk boundaries (a size that is not a multiple of the chunk), with zeros in alpha
    and beta, and with broadcasting."""
    from woundroll.instruments.impact import _CHUNK, _energy_max_depth_whole_array

    rng = np.random.default_rng(3)
    n = 2 * _CHUNK + 17
    a = 10 ** rng.uniform(5, 12, n)
    b = 10 ** rng.uniform(2, 8, n)
    a[:3] = 0.0
    b[3:6] = 0.0
    args = (2800.0, 8e-3, x_gap)
    d = energy_max_depth(a, b, *args)
    ref = _energy_max_depth_whole_array(a, b, *args)
    assert d.shape == (n,)
    np.testing.assert_allclose(d, ref, rtol=1e-15)
    grid = energy_max_depth(a[:5, None], b[None, :7], *args)
    assert grid.shape == (5, 7)
    np.testing.assert_allclose(grid, _energy_max_depth_whole_array(a[:5, None], b[:7], *args))
    assert np.ndim(energy_max_depth(1e8, 1e4, *args)) == 0
