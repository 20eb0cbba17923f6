"""What the plane-strain contact solve keeps between the passes of an increment gives the
numbers of computing it afresh, bit for bit (issue 23 item 3, docs/performance.md "The
contact stage, per sector").

Kept: the contact columns' flexibility on the factor (``_Factor.flexibility``), the
increment's contact geometry and right-hand sides (``_ContactGeometry``), the secant
modulus's start-of-increment strain (``_Roll.secant_modulus``). Each is only a reuse of
numbers already computed from equal inputs, so the tolerance is zero: the whole loading
(forces, contact widths, stresses, factorisations) must be identical with every reuse
defeated. The rolls: the Table 3 web wound by the 1D model (K1 = 0, the profile's sectors'
law), taut and with a slack surface (the striker then sinks to the model's reach).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_step_control import table3_roll

from woundroll.contact import roll_stiffness
from woundroll.contact.plane_strain import solver as solver_mod
from woundroll.instruments import get_instrument


def _solve(roll: tuple, start: float) -> object:
    web, core, r, s = roll
    return roll_stiffness(web, core, r, s, get_instrument("rho-meter"), start_depth=start)


def _defeat_reuse(monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """Every kept quantity computed afresh; counts how often each would have been reused."""
    calls = {"geometry": 0, "flexibility": 0, "secant": 0}
    geometry = solver_mod._ContactGeometry

    def fresh_geometry(cls, roll, *args):  # type: ignore[no-untyped-def]
        calls["geometry"] += 1
        return geometry(roll, *args)

    flexibility = solver_mod._Factor.flexibility

    def fresh_flexibility(self, *args, **kw):  # type: ignore[no-untyped-def]
        calls["flexibility"] += 1
        self._flex = None
        return flexibility(self, *args, **kw)

    secant = solver_mod._Roll.secant_modulus

    def fresh_secant(self, start, end):  # type: ignore[no-untyped-def]
        calls["secant"] += 1
        self._start_strain = None
        return secant(self, start, end)

    monkeypatch.setattr(geometry, "of", classmethod(fresh_geometry))
    monkeypatch.setattr(solver_mod._Factor, "flexibility", fresh_flexibility)
    monkeypatch.setattr(solver_mod._Roll, "secant_modulus", fresh_secant)
    return calls


@pytest.mark.parametrize("slack_depth, start", [(None, 1e-3), (3e-3, float("inf"))])
def test_kept_quantities_give_the_numbers_of_a_fresh_computation(
    monkeypatch: pytest.MonkeyPatch, slack_depth: float | None, start: float
) -> None:
    roll = table3_roll(slack_depth)
    kept = _solve(roll, start)
    with monkeypatch.context() as m:
        calls = _defeat_reuse(m)
        fresh = _solve(roll, start)
    # the passes did ask again (more passes than increments): the reuse was exercised
    n_incr = kept.contact.delta.size - 1
    assert calls["geometry"] > n_incr and calls["flexibility"] > n_incr
    assert calls["secant"] > n_incr
    a, b = kept.contact, fresh.contact
    assert np.array_equal(a.delta, b.delta)
    assert np.array_equal(a.force, b.force)  # tolerance 0: the same numbers reused
    assert np.array_equal(a.half_width, b.half_width)
    assert a.factorisations == b.factorisations
    assert (kept.alpha, kept.beta) == (fresh.alpha, fresh.beta)


def test_a_different_candidate_set_is_not_taken_from_the_factor() -> None:
    """The flexibility kept on a factor is used for the same columns only: other columns
    on the same factor give their own (here: a fresh factor's) numbers."""
    rng = np.random.default_rng(3)
    n, bw = 40, 3
    # a banded SPD matrix in LAPACK lower storage (Fortran order, as the solver builds it)
    ab = np.zeros((bw + 1, n), order="F")
    ab[0] = 10.0 + rng.random(n)
    for d in range(1, bw + 1):
        ab[d, : n - d] = 0.5 * rng.random(n - d)
    from scipy.linalg.lapack import dpbtrf

    cb, info = dpbtrf(ab.copy(order="F"), lower=1)
    assert info == 0
    B1 = rng.random((6, 3))
    B2 = B1.copy()
    B2[2, 1] += 1.0
    f = solver_mod._Factor(banded=cb)
    G1, _, _ = f.flexibility(np.arange(6), B1, n)
    G2, _, _ = f.flexibility(np.arange(6), B2, n)
    G2_fresh, _, _ = solver_mod._Factor(banded=cb).flexibility(np.arange(6), B2, n)
    G1_again, _, _ = f.flexibility(np.arange(6), B1.copy(), n)  # equal, not the same array
    assert np.array_equal(G2, G2_fresh) and not np.array_equal(G1, G2)
    assert np.array_equal(G1, G1_again)
    with pytest.raises(ValueError):
        G1_again[0, 0] = 0.0  # shared by the passes: read-only
