"""The 3D model's linear solvers (woundroll.contact.solid3d.linsolve): each solves the 3D
stiffness to its stated residual, the mixed-precision PARDISO refines to MIXED_RTOL and falls
back to double precision where the refinement stalls, and a 3D curve is the same with
either PARDISO (the accuracy the default gives up: none beyond MIXED_RTOL)."""

from __future__ import annotations

import functools

import numpy as np
import pytest
import scipy.sparse as sp

from woundroll.contact.heads import Head
from woundroll.contact.solid3d import linsolve
from woundroll.contact.solid3d.solver import Contact3DOptions, build_roll3d, indent3d
from woundroll.materials import Core, Pfeiffer, Web

R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
PET1 = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
RIGID = Core(outer_radius=R_CORE)
COARSE = {"n_fine": 5, "radial_growth": 1.6, "tangential_growth": 1.6, "axial_growth": 1.6}

needs_pardiso = pytest.mark.skipif(
    not linsolve.pardiso_available(), reason="PARDISO (pypardiso, mkl) not installed"
)


def pet_profile(n: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """The synthetic PET1 profile of test_contact3d.py (30 kPa at the surface to ~1 MPa)."""
    r = np.linspace(R_CORE, R_OUT, n)
    return r, -(30e3 + 1e6 * (R_OUT - r) / (R_OUT - R_CORE))


@functools.cache
def stiffness() -> sp.csr_matrix:
    """The upper triangle of a 3D roll's stiffness (coarse mesh, PET1 test roll, E_r from
    the wound-in pressure: moduli from ~0.4 MPa to 5.7 GPa)."""
    r, s = pet_profile()
    roll = build_roll3d(
        PET1, RIGID, r, s, head=Head("cylinder", 0.0078, 0.0254), depth_max=5e-4,
        options=Contact3DOptions(**COARSE),
    )  # fmt: skip
    return roll.asm.upper(roll.moduli(roll.sigma_pre)).tocsr()


def full(upper: sp.csr_matrix) -> sp.csr_matrix:
    return (upper + upper.T - sp.diags(upper.diagonal())).tocsr()


def relative_residual(K: sp.csr_matrix, x: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.linalg.norm(b - K @ x, axis=0) / np.linalg.norm(b, axis=0)))


@pytest.mark.parametrize(
    ("name", "bound"),
    [
        # double precision: round-off of a factorisation (measured ~1e-13 here)
        pytest.param("pardiso", 1e-10, marks=needs_pardiso),
        # single-precision factor, refined: MIXED_RTOL by construction
        pytest.param("pardiso-mixed", linsolve.MIXED_RTOL, marks=needs_pardiso),
        ("splu", 1e-10),
    ],
)
def test_each_solver_solves_the_3d_stiffness_to_its_residual(name: str, bound: float) -> None:
    U = stiffness()
    K = full(U)
    solver = linsolve.make_solver(name, U)
    solver.factor(U.data)
    b = np.random.default_rng(1).standard_normal((U.shape[0], 3))
    assert relative_residual(K, solver.solve(b), b) <= bound
    x1 = solver.solve(b[:, 0])  # one right-hand side, as the contact passes solve
    assert x1.shape == (U.shape[0],)
    assert relative_residual(K, x1[:, None], b[:, :1]) <= bound


@needs_pardiso
def test_auto_is_the_mixed_precision_pardiso() -> None:
    assert isinstance(linsolve.make_solver("auto", stiffness()), linsolve._PardisoMixed)
    assert type(linsolve.make_solver("pardiso", stiffness())) is linsolve._Pardiso
    # an iteration whose own tolerance is near MIXED_RTOL (the layered roll's friction)
    # asks "auto" for double precision
    assert type(linsolve.make_solver("auto", stiffness(), mixed=False)) is linsolve._Pardiso


@needs_pardiso
def test_mixed_precision_refinement_gains_orders(monkeypatch: pytest.MonkeyPatch) -> None:
    """The single-precision solve alone leaves a residual of single precision's order;
    each refinement step in double gains about three orders (measured on PET1 26.7 N's
    stiffness: 5.4e-4, 7.6e-7, 1.5e-9), so asking for 1e-4 of the raw residual takes at
    most two steps, and asking for nothing more than the raw residual takes none."""
    U = stiffness()
    K = full(U)
    mixed = linsolve.make_solver("pardiso-mixed", U)
    mixed.factor(U.data)
    b = np.random.default_rng(2).standard_normal((U.shape[0], 1))
    raw = relative_residual(K, linsolve._Pardiso.solve(mixed, b), b)
    assert 1e-9 < raw < 1e-2  # single precision, not double
    monkeypatch.setattr(linsolve, "MIXED_RTOL", 2 * raw)
    mixed.solve(b)
    assert mixed.refinement_steps == 0
    monkeypatch.setattr(linsolve, "MIXED_RTOL", 1e-4 * raw)
    x = mixed.solve(b)
    assert 1 <= mixed.refinement_steps <= 2
    assert relative_residual(K, x, b) <= 1e-4 * raw
    assert mixed.double_fallbacks == 0


def stiff_half_chain(n: int, stiff: float) -> sp.csr_matrix:
    """The upper triangle of a chain of n nodes whose first half is ``stiff`` times
    stiffer (a web's E_theta beside a soft E_r, exaggerated): condition ~n^2 x stiff."""
    k = np.ones(n + 1)
    k[: n // 2] = stiff
    return sp.diags([k[:-1] + k[1:], -k[1:-1]], [0, 1], format="csr")


@needs_pardiso
@pytest.mark.parametrize(
    ("n", "stiff", "where"),
    [
        # single precision factorises, its refinement stalls (raw residual ~0.4)
        (100_000, 1e6, "refinement"),
        # single precision loses a pivot (PARDISO error -4)
        (200_000, 1e8, "factorisation"),
    ],
)
def test_mixed_precision_falls_back_to_double(n: int, stiff: float, where: str) -> None:
    """A matrix too ill-conditioned for single precision is factorised again in double
    precision and still meets the residual; the solver's later matrices (a loading's next
    increments share their conditioning) are factorised in double precision directly, by
    the same double-precision solver (one analysis), and solve exactly."""
    U = stiff_half_chain(n, stiff)
    K = full(U)
    mixed = linsolve.make_solver("pardiso-mixed", U)
    mixed.factor(U.data)
    assert (mixed.double is not None) == (where == "factorisation")
    b = np.random.default_rng(3).standard_normal((n, 1))
    x = mixed.solve(b)
    assert mixed.double_fallbacks == 1
    assert relative_residual(K, x, b) <= 1e-8  # double precision's, at this condition
    first = mixed.double
    U2 = stiff_half_chain(n, 2.0 * stiff)  # the next matrix of the same pattern
    mixed.factor(U2.data)
    assert mixed.double is first and mixed.double_fallbacks == 1
    assert mixed.double_factorisations == 2
    steps = mixed.refinement_steps
    x2 = mixed.solve(b)
    assert relative_residual(full(U2), x2, b) <= 1e-8
    assert mixed.refinement_steps == steps  # no single-precision attempt on it


@needs_pardiso
def test_a_3d_curve_is_the_same_with_either_pardiso() -> None:
    """The default (mixed precision) against double precision throughout on a coarse 3D
    curve: forces within MIXED_RTOL (3e-5, each solve's residual bound; measured 1.1e-5
    here: the contact's first pass on the single-precision flexibility lands within ~1e-6 of
    the forces and is accepted within the gap tolerance, and the lagged predictor carries
    that into the next increment's moduli; 4e-8 when both took the same passes on cached
    whole-solve columns) and the stats report the refinement."""
    r, s = pet_profile()
    head = Head("cylinder", 0.0078, 0.0254)
    runs = {
        name: indent3d(
            PET1,
            RIGID,
            r,
            s,
            head=head,
            depth_max=5e-4,
            options=Contact3DOptions(n_steps=8, solver=name, **COARSE),
        )  # fmt: skip
        for name in ("pardiso", "auto")
    }
    f0, f1 = runs["pardiso"].force[1:], runs["auto"].force[1:]
    assert np.max(np.abs(f1 / f0 - 1)) < linsolve.MIXED_RTOL
    st = runs["auto"].stats
    assert st["refinement_steps"] > 0 and st["double_fallbacks"] == 0
    assert 0 < st["largest_refined_residual"] <= linsolve.MIXED_RTOL
    assert runs["pardiso"].stats["refinement_steps"] == 0


def surface_dofs(U: sp.csr_matrix, m: int = 40) -> np.ndarray:
    """``m`` unknowns spread over the matrix (as the contact's surface nodes are over the
    unknowns' numbering)."""
    return np.linspace(5, U.shape[0] - 5, m).astype(np.int64)


@pytest.mark.parametrize(
    ("name", "mark", "bound"),
    [
        # double precision, a partial solve on the marked unknowns (ordered last)
        pytest.param("pardiso", True, 1e-10, marks=needs_pardiso),
        pytest.param("pardiso", False, 1e-10, marks=needs_pardiso),
        # single precision: the flexibility is a contact iteration's model, its residual is
        # computed by the refined solves; single precision's relative error (~1e-6)
        pytest.param("pardiso-mixed", True, 1e-4, marks=needs_pardiso),
        pytest.param("pardiso-mixed", False, 1e-4, marks=needs_pardiso),
        ("splu", False, 1e-10),
    ],
)
def test_flexibility_is_the_block_of_the_inverse(name: str, mark: bool, bound: float) -> None:
    """``flexibility(dofs)`` is K^-1[dofs, dofs], from PARDISO's partial solve where the
    unknowns were marked before the factorisation (sparse right-hand sides, selected
    solution components: only the factor's last block), else from whole solves; against
    whole double-precision solves of the same unit loads. A partial solve on unknowns not
    all marked falls back to whole solves (the last case of each PARDISO)."""
    U = stiffness()
    K = full(U).tocsc()
    dofs = surface_dofs(U)
    solver = linsolve.make_solver(name, U)
    if mark:
        solver.mark(dofs)
    solver.factor(U.data)
    B = np.zeros((U.shape[0], dofs.size))
    B[dofs, np.arange(dofs.size)] = 1.0
    exact = sp.linalg.spsolve(K, B)[dofs]
    W = solver.flexibility(dofs)
    assert np.max(np.abs(W - exact)) / np.max(np.abs(exact)) <= bound
    if mark:  # a subset of the marked unknowns, and one unknown beyond them
        sub = dofs[::3]
        Ws = solver.flexibility(sub)
        assert np.max(np.abs(Ws - exact[::3, ::3])) / np.max(np.abs(exact)) <= bound
        extra = np.append(dofs[:4], dofs[0] + 1)
        B2 = np.zeros((U.shape[0], extra.size))
        B2[extra, np.arange(extra.size)] = 1.0
        exact2 = sp.linalg.spsolve(K, B2)[extra]
        W2 = solver.flexibility(extra)
        assert np.max(np.abs(W2 - exact2)) / np.max(np.abs(exact2)) <= bound
    # whole solves still solve the whole system on the reordered factorisation
    b = np.random.default_rng(4).standard_normal(U.shape[0])
    tol = 1e-10 if name != "pardiso-mixed" else linsolve.MIXED_RTOL
    assert relative_residual(full(U), solver.solve(b)[:, None], b[:, None]) <= tol


@needs_pardiso
def test_marking_comes_before_the_factorisation() -> None:
    U = stiffness()
    solver = linsolve.make_solver("pardiso", U)
    solver.factor(U.data)
    with pytest.raises(RuntimeError, match="before the first factor"):
        solver.mark(surface_dofs(U))


@needs_pardiso
def test_double_fallback_keeps_the_marked_unknowns() -> None:
    """A matrix the single-precision factorisation loses a pivot on (PARDISO error -4) is
    factorised in double precision with the same marked unknowns: its flexibility is still
    a partial solve, exact to double precision's error at this condition."""
    n, stiff = 200_000, 1e8
    U = stiff_half_chain(n, stiff)
    dofs = np.array([10, 50_000, 120_000, 199_990])
    mixed = linsolve.make_solver("pardiso-mixed", U)
    mixed.mark(dofs)
    mixed.factor(U.data)
    assert mixed.double is not None and np.array_equal(mixed.double.marked, dofs)
    B = np.zeros((n, dofs.size))
    B[dofs, np.arange(dofs.size)] = 1.0
    exact = sp.linalg.spsolve(full(U).tocsc(), B)[dofs]
    W = mixed.flexibility(dofs)
    assert np.max(np.abs(W - exact)) / np.max(np.abs(exact)) <= 1e-6
