"""Nip roller as a beam on the roll: verified against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.profile.nip import NipRoller, nip_hook, solve_nip

W = 0.61
EDGES = np.linspace(0.0, W, 62)


def _hetenyi_finite(x: np.ndarray, P: float, k: float, EI: float, length: float) -> np.ndarray:
    """Closed-form deflection of a free beam of length ``length`` on a Winkler foundation
    ``k`` with equal end loads P (Hetenyi 1946): the general solution of EI w'''' + k w = 0,
    w = e^(lam x) (C1 cos + C2 sin) + e^(-lam x) (C3 cos + C4 sin), with the end conditions
    w'' = 0 and EI w''' = +P at x = 0, -P at x = length (4 x 4 linear system)."""
    lam = (k / (4 * EI)) ** 0.25

    def basis(t: np.ndarray, d: int) -> np.ndarray:
        # d-th derivatives of e^(s lam t) cos(lam t), e^(s lam t) sin(lam t), s = +1, -1:
        # (d/dt)^d e^((s + i) lam t) = (lam (s + i))^d e^((s + i) lam t)
        out = []
        for s in (1.0, -1.0):
            c = (lam * (s + 1j)) ** d * np.exp((s + 1j) * lam * t)
            out += [c.real, c.imag]
        return np.array(out)

    A = np.array(
        [
            basis(np.array(0.0), 2),
            basis(np.array(0.0), 3) * EI,
            basis(np.array(length), 2),
            basis(np.array(length), 3) * EI,
        ]
    )
    C = np.linalg.solve(A, np.array([0.0, P, 0.0, -P]))
    return C @ basis(x, 0)


@pytest.mark.parametrize("lam_w", [1.0, 5.0])
def test_hetenyi_finite_beam_with_end_loads(lam_w: float) -> None:
    # finite free beam, bilateral linear foundation: closed form above. Tolerance 1e-4 of the
    # largest deflection covers the cubic Hermite discretisation (4 elements per sector)
    k = 1e8
    EI = k / (4 * (lam_w / W) ** 4)
    roller = NipRoller(EI=EI, line_load=1000.0)
    sol = solve_nip(EDGES, 0.0, k, roller, bilateral=True)
    exact = _hetenyi_finite(sol.node_z, 0.5 * 1000.0 * W, k, EI, W)
    assert np.max(np.abs(sol.deflection - exact)) < 1e-4 * np.max(np.abs(exact))
    # lam W = 1 is nearly a rigid beam: the load is uniform to within a few per cent
    if lam_w == 1.0:
        np.testing.assert_allclose(sol.load, 1000.0, rtol=0.05)


def test_stiff_roller_on_quadratic_foundation() -> None:
    # alpha d^2 + beta d = N under a rigid roller: d = (-beta + sqrt(beta^2 + 4 alpha N)) /
    # (2 alpha). A roller of EI = 1e9 N m^2 over 0.61 m bends the load distribution by
    # < 1e-3 here (the foundation is soft); tolerance 1e-3
    a, b, N = 1e13, 1e6, 1000.0
    sol = solve_nip(EDGES, a, b, NipRoller(EI=1e9, line_load=N))
    d = (-b + math.sqrt(b * b + 4 * a * N)) / (2 * a)
    np.testing.assert_allclose(sol.indentation, d, rtol=1e-3)
    np.testing.assert_allclose(sol.load, N, rtol=1e-3)
    assert sol.total == pytest.approx(N * W, rel=1e-8)


@pytest.mark.parametrize("refine", [2, 4])
def test_hetenyi_long_beam_with_end_loads(refine: int) -> None:
    # Hetenyi: semi-infinite beam on a Winkler foundation k, end load P:
    # w(x) = (2 P lam / k) exp(-lam x) cos(lam x), lam = (k / 4 EI)^(1/4).
    # With lam W = 20 the two ends do not interact (exp(-20) ~ 2e-9), so superposing the two
    # ends is exact to that level; tolerance 1e-4 of the end deflection covers the cubic
    # Hermite discretisation (measured 3e-6 with 2 elements per sector).
    k = 1e8
    lam = 20.0 / W
    roller = NipRoller(EI=k / (4 * lam**4), line_load=1000.0)
    P = 0.5 * 1000.0 * W
    sol = solve_nip(EDGES, 0.0, k, roller, refine=refine, bilateral=True)
    w0 = 2 * P * lam / k
    x = sol.node_z
    exact = w0 * (
        np.exp(-lam * x) * np.cos(lam * x) + np.exp(-lam * (W - x)) * np.cos(lam * (W - x))
    )
    assert np.max(np.abs(sol.deflection - exact)) < 1e-4 * w0
    assert sol.total == pytest.approx(2 * P, rel=1e-9)


def test_tensionless_foundation_carries_the_load_and_lifts_off() -> None:
    # a soft roller on a foundation with a CMD gap: equilibrium (sum of loads = bearing
    # forces) to 1e-6, no tension anywhere, and the sectors behind a 0.5 mm gap unloaded
    z = 0.5 * (EDGES[1:] + EDGES[:-1])
    gap = np.where(np.abs(z - 0.3) < 0.05, 5e-4, 0.0)
    roller = NipRoller.tube(200e9, 0.05, 0.04, 1500.0)
    sol = solve_nip(EDGES, 2e13, 5e7, roller, gap=gap)
    assert sol.total == pytest.approx(1500.0 * W, rel=1e-6)
    assert np.all(sol.load >= 0)
    assert np.all(sol.load[np.abs(z - 0.3) < 0.04] == 0)


def test_symmetric_input_gives_symmetric_load() -> None:
    z = 0.5 * (EDGES[1:] + EDGES[:-1])
    gap = 1e-4 * (1 + np.cos(2 * np.pi * (z - W / 2) / W))
    sol = solve_nip(EDGES, 1e13, 1e7, NipRoller.tube(200e9, 0.05, 0.04, 1000.0), gap=gap)
    np.testing.assert_allclose(sol.load, sol.load[::-1], rtol=1e-6, atol=1e-9 * sol.load.max())


def test_hook_uses_the_outer_radius_profile() -> None:
    # the hook's gap is max(r) - r: one sector standing 1 mm proud takes the largest load,
    # and the foundation still carries the whole bearing load
    r = np.full(61, 0.15)
    r[30] += 1e-3
    hook = nip_hook(EDGES, 0.0, 1e8, NipRoller.tube(200e9, 0.05, 0.04, 1000.0))
    load = hook(0, r, np.zeros(61))
    assert int(np.argmax(load)) == 30
    assert load[30] > 5 * np.median(load)
    assert np.sum(load) * (W / 61) == pytest.approx(1000.0 * W, rel=1e-8)


def test_zero_load() -> None:
    sol = solve_nip(EDGES, 0.0, 1e8, NipRoller(EI=1.0, line_load=0.0))
    assert np.all(sol.load == 0) and sol.total == 0


@pytest.mark.parametrize(
    ("kwargs", "fld"),
    [
        ({"alpha": -1.0}, "winding.nip.alpha"),
        ({"beta": np.nan}, "winding.nip.beta"),
        ({"alpha": 0.0, "beta": 0.0}, "winding.nip.foundation"),
        ({"gap": -1e-3}, "winding.nip.gap"),
        ({"refine": 0}, "winding.nip.refine"),
        ({"alpha": 1.0, "bilateral": True}, "winding.nip.alpha"),
    ],
)
def test_bad_input(kwargs: dict, fld: str) -> None:
    args = {"alpha": 0.0, "beta": 1e8} | kwargs
    with pytest.raises(InputError) as exc:
        solve_nip(EDGES, roller=NipRoller(EI=1.0, line_load=1.0), **args)
    assert exc.value.field == fld


def test_bad_roller() -> None:
    with pytest.raises(InputError) as exc:
        NipRoller(EI=-1.0, line_load=1.0)
    assert exc.value.field == "winding.nip.EI"
    with pytest.raises(InputError):
        NipRoller(EI=1.0, line_load=1.0, friction=3.0)


def test_roller_from_induced_tension() -> None:
    # Table 3 reading: mu N / h = 2.3 MPa with h = 76 um and mu = 0.3 -> N = 582.67 N/m
    from woundroll.profile.nip import roller_from_induced_tension

    r = roller_from_induced_tension(2.3e6, 76e-6, 0.3, EI=5e5)
    assert r.line_load == pytest.approx(2.3e6 * 76e-6 / 0.3, rel=1e-15)
    assert r.friction * r.line_load / 76e-6 == pytest.approx(2.3e6, rel=1e-14)
    with pytest.raises(InputError) as exc:
        roller_from_induced_tension(2.3e6, 76e-6, 0.0, EI=5e5)
    assert exc.value.field == "winding.nip.friction"
