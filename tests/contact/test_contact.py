"""Verification of the 2D plane-strain contact model (woundroll.contact).

Every test compares a number with a closed form, a refined solution or an exact property,
with the tolerance and its reason stated next to the assertion.
"""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest

from woundroll.contact import (
    ContactOptions,
    ContactResult,
    fit_spring,
    indent,
    plot_slip_factor,
    slip_factor,
)
from woundroll.contact.plane_strain.fem import Assembler, element_basis, plane_strain_moduli
from woundroll.contact.plane_strain.mesh import build_mesh, graded_sizes
from woundroll.contact.plane_strain.solver import (
    _factorize,
    _hypoelastic_increment,
    _Roll,
    _solve_lcp,
)
from woundroll.errors import ConvergenceError, InputError
from woundroll.materials import Constant, Core, Pfeiffer, Web

# PET1 of the reference paper (Table 2)
R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
PET1 = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
RIGID = Core(outer_radius=R_CORE)
HEAD = {"head_radius": 0.01, "head_length": 0.02}


def pet_profile(n: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """Synthetic pre-impact profile: 30 kPa at the surface rising linearly to ~1 MPa at the core
    (the order of magnitude of Hakiel results for PET1; the winding model is not needed here)."""
    r = np.linspace(R_CORE, R_OUT, n)
    return r, -(30e3 + 1e6 * (R_OUT - r) / (R_OUT - R_CORE))


@pytest.fixture(scope="module")
def pet_default() -> ContactResult:
    r, s = pet_profile()
    return indent(PET1, RIGID, r, s, depth_max=1e-3, **HEAD)


def isotropic_web(E: float, nu: float) -> Web:
    """The linear isotropic limit: E_r = E_theta = E_z, one Poisson ratio, G = E / (2 (1 + nu))."""
    return Web(
        thickness=H,
        width=0.1,
        E_theta=E,
        E_z=E,
        radial_modulus=Constant(E),
        nu_theta_r=nu,
        nu_z_r=nu,
        nu_theta_z=nu,
        G_r_theta=E / (2 * (1 + nu)),
    )


# ---------------------------------------------------------------- constitutive law and mesh


def test_plane_strain_moduli_isotropic_limit() -> None:
    # isotropic plane strain: C11 = C22 = E (1-nu) / ((1+nu)(1-2nu)), C12 = E nu / ((1+nu)(1-2nu))
    E, nu = 7.0e6, 0.3
    web = isotropic_web(E, nu)
    C11, C12, C22, G = plane_strain_moduli(web, np.array([E]))
    lam = E / ((1 + nu) * (1 - 2 * nu))
    # exact algebra: only round-off allowed
    assert C11[0] == pytest.approx(lam * (1 - nu), rel=1e-12)
    assert C22[0] == pytest.approx(lam * (1 - nu), rel=1e-12)
    assert C12[0] == pytest.approx(lam * nu, rel=1e-12)
    assert G[0] == pytest.approx(E / (2 * (1 + nu)), rel=1e-12)


def test_plane_strain_moduli_match_inverted_3d_compliance() -> None:
    # general orthotropic data: compare with a direct inversion of the 3x3 compliance with
    # eps_z = 0 imposed (round-off only)
    web = Web(
        thickness=H,
        width=0.1,
        E_theta=5e9,
        E_z=3e9,
        radial_modulus=Constant(8e6),
        nu_theta_r=0.01,
        nu_z_r=0.02,
        nu_theta_z=0.35,
    )
    Er, Et, Ez = 8e6, 5e9, 3e9
    S = np.array(
        [
            [1 / Er, -0.01 / Et, -0.02 / Ez],
            [-0.01 / Et, 1 / Et, -0.35 / Et],
            [-0.02 / Ez, -0.35 / Et, 1 / Ez],
        ]
    )
    C3 = np.linalg.inv(S)  # plane strain: sigma = C3 eps with eps_z = 0 -> in-plane block
    C11, C12, C22, G = plane_strain_moduli(web, np.array([Er]))
    assert C11[0] == pytest.approx(C3[0, 0], rel=1e-9)
    assert C12[0] == pytest.approx(C3[0, 1], rel=1e-9)
    assert C22[0] == pytest.approx(C3[1, 1], rel=1e-9)
    assert G[0] == pytest.approx(2 * Er, rel=1e-12)  # Table 2 default G_rt = 2 E_r


def test_banded_assembly_matches_sparse_assembly() -> None:
    """The lower-triangle banded path and the full CSC path assemble the same K."""
    mesh = build_mesh(
        R_CORE,
        R_OUT,
        surface_size=4e-4,
        radial_growth=1.3,
        tangential_size=1e-3,
        fine_halfwidth=3e-3,
        tangential_growth=1.3,
    )
    roll = _Roll(
        PET1, Core(outer_radius=R_CORE, stiffness=1e9), *pet_profile(), mesh, ContactOptions()
    )
    asm = roll.assembler
    mod = roll.moduli(roll.sigma_pre)
    K = asm.csc(asm.values(*mod)).toarray()
    ab = asm.banded(asm.values_lower(*mod), lower_only=True)
    n, bw = asm.n_free, asm.bandwidth
    B = np.zeros((n, n))
    for k in range(bw + 1):
        B[np.arange(k, n), np.arange(n - k)] = ab[k, : n - k]
    B = np.tril(B) + np.tril(B, -1).T
    assert np.max(np.abs(K - B)) <= 1e-12 * np.max(np.abs(K))  # round-off only
    assert np.max(np.abs(K - K.T)) <= 1e-12 * np.max(np.abs(K))  # symmetric stiffness


def test_graded_sizes_fill_length_and_respect_growth() -> None:
    sizes = graded_sizes(0.0889, 1e-4, 1.25, "x")
    assert sizes.sum() == pytest.approx(0.0889, rel=1e-12)
    assert sizes[0] == pytest.approx(1e-4, rel=1e-9)
    assert np.all(sizes[1:] / sizes[:-1] <= 1.25 + 1e-9)


def test_mesh_is_graded_toward_the_contact() -> None:
    m = build_mesh(
        R_CORE,
        R_OUT,
        surface_size=1e-4,
        radial_growth=1.25,
        tangential_size=1e-4,
        fine_halfwidth=3e-3,
        tangential_growth=1.1,
    )
    assert m.r[-1] - m.r[-2] == pytest.approx(1e-4, rel=1e-9)  # one layer at the surface
    assert m.r[0] == R_CORE and m.r[-1] == pytest.approx(R_OUT, rel=1e-15)
    ds = np.diff(m.theta) * R_OUT
    assert ds[0] == pytest.approx(1e-4, rel=1e-9)
    assert m.theta[0] == 0.0 and m.theta[-1] == pytest.approx(math.pi, rel=1e-15)
    assert np.all(ds[1:] / ds[:-1] <= 1.1 + 1e-9)


# ---------------------------------------------------------------- FE against closed forms


@pytest.mark.parametrize("ratio", [1.0, 100.0, 1e4])
def test_orthotropic_ring_under_external_pressure(ratio: float) -> None:
    """Axisymmetric limit: annulus on a rigid core, uniform pressure p on the outside.

    With C12 = 0 (nu = 0), equilibrium gives u = A r^k + B r^-k, k = sqrt(C22 / C11).
    This checks the cylindrically orthotropic polar formulation (hoop term u_r / r) on the
    default tangential grading (``ContactOptions().tangential_growth``, 1.15 today: far
    elements up to ~24 deg; docs/contact.md generates both): the exact-sector
    element represents any axisymmetric field exactly in theta, so only the radial
    discretisation of r^k (k up to 100) is left."""
    E_r = 5e6
    web = Web(
        thickness=H,
        width=0.1,
        E_theta=ratio * E_r,
        radial_modulus=Constant(E_r),
        nu_theta_z=0.0,
        G_r_theta=E_r / 2,
    )
    mesh = build_mesh(
        R_CORE,
        R_OUT,
        surface_size=2e-4,
        radial_growth=1.1,
        tangential_size=1e-3,
        fine_halfwidth=2e-3,
        tangential_growth=ContactOptions().tangential_growth,
    )
    roll = _Roll(web, RIGID, np.array([R_CORE, R_OUT]), np.zeros(2), mesh, ContactOptions())
    C11, C12, C22, G = roll.moduli(roll.sigma_pre)
    lu = _factorize(roll, (C11, C12, C22, G))
    # consistent nodal loads of a uniform pressure on the circular outer boundary (linear
    # shape functions along the arc): p times the tributary arc, radial
    p = 1e4
    surf = roll.surface
    arc = np.diff(mesh.theta) * R_OUT
    trib = 0.5 * (np.concatenate([[0.0], arc]) + np.concatenate([arc, [0.0]]))
    F = np.zeros(2 * mesh.n_nodes)
    F[2 * surf] = -p * trib
    u = np.zeros_like(F)
    u[roll.free] = lu.solve(F[roll.free])
    k = math.sqrt(C22[0] / C11[0])
    a, b = R_CORE, R_OUT
    # u(a) = 0 -> u = A (r^k - a^2k r^-k); sigma_r(b) = C11 u'(b) = -p
    du_b = k * (b ** (k - 1) + a ** (2 * k) * b ** (-k - 1))
    A = -p / (C11[0] * du_b)
    u_exact = A * (b**k - a ** (2 * k) * b**-k)
    u_fe = u[2 * surf]
    # measured 0.02 % (E_t/E_r = 1, 100) and 0.16 % (1e4, k = 100): 0.5 % for the radial
    # discretisation (bilinear in r, 2e-4 m surface elements growing by 1.1)
    assert np.max(np.abs(u_fe / u_exact - 1)) < 0.005
    # every node on a ring moves the same: the tangential displacement is round-off
    assert np.max(np.abs(u[2 * surf + 1])) < 1e-9 * abs(u_exact)
    assert np.ptp(u_fe) < 1e-9 * abs(u_exact)


@pytest.mark.parametrize(
    ("element", "assumed_hoop", "zeros"),
    [("curved", True, 3), ("flat", True, 3), ("flat", False, 3), ("curved", False, 2)],
)
def test_element_rank(element: str, assumed_hoop: bool, zeros: int) -> None:
    """Each element stiffness (isotropic-like moduli) has exactly the rigid-motion null space:
    3 zero eigenvalues, so the assumed hoop strain adds no hourglass mode. The curved element
    with the full 2x2 hoop strain keeps only 2: one rigid translation (represented to first
    order in the element angle by bilinear polar components) costs hoop strain, the membrane
    locking that ``assumed_hoop`` removes."""
    mesh = build_mesh(
        0.1,
        0.2,
        surface_size=0.01,
        radial_growth=1.0,
        tangential_size=0.01,
        fine_halfwidth=0.05,
        tangential_growth=1.3,
    )
    basis = element_basis(mesh, element=element, assumed_hoop=assumed_hoop)
    for e in (0, 5, basis.A.shape[1] - 1):  # small, mid-size and 0.2 rad elements
        K = basis.A[0, e] + basis.A[2, e] + 0.3 * basis.A[1, e] + 0.35 * basis.A[3, e]
        w = np.linalg.eigvalsh(K) / np.abs(K).max()
        # round-off zeros are ~1e-16; the smallest genuine stiffness here is > 1e-5
        assert np.sum(np.abs(w) < 1e-12) == zeros
        assert np.all(w > -1e-12)


def test_element_angle_cap() -> None:
    """max_element_angle caps the grown tangential sizes; the rest of the half annulus is
    divided uniformly."""
    cap = math.radians(2)
    m = build_mesh(
        R_CORE,
        R_OUT,
        surface_size=1e-4,
        radial_growth=1.25,
        tangential_size=1e-4,
        fine_halfwidth=3e-3,
        tangential_growth=1.1,
        max_element_angle=cap,
    )
    dth = np.diff(m.theta)
    assert dth.max() <= cap * (1 + 1e-12)
    assert m.theta[-1] == pytest.approx(math.pi, rel=1e-15)
    assert np.all(dth[1:] / dth[:-1] <= 1.1 + 1e-9)
    free = build_mesh(
        R_CORE,
        R_OUT,
        surface_size=1e-4,
        radial_growth=1.25,
        tangential_size=1e-4,
        fine_halfwidth=3e-3,
        tangential_growth=1.1,
    )
    assert np.diff(free.theta).max() > 5 * cap  # the cap is active here
    sizes = graded_sizes(0.4, 1e-4, 1.1, "x", largest=5e-3)
    assert sizes.sum() == pytest.approx(0.4, rel=1e-12) and sizes.max() <= 5e-3 * (1 + 1e-12)


HERTZ_E, HERTZ_NU, HERTZ_R, HERTZ_ROLL = 10e6, 0.3, 0.01, 0.5


@pytest.fixture(scope="module")
def hertz() -> ContactResult:
    E, nu = HERTZ_E, HERTZ_NU
    web = isotropic_web(E, nu)
    opts = ContactOptions(
        n_steps=4, step_exponent=1.0, tangential_size=5e-5, surface_size=5e-5, fine_halfwidth=2e-3
    )
    return indent(
        web,
        Core(outer_radius=0.2),
        np.array([0.2, HERTZ_ROLL]),
        np.zeros(2),
        head_radius=HERTZ_R,
        head_length=1.0,
        depth_max=2e-4,
        options=opts,
    )


def test_hertz_half_width(hertz: ContactResult) -> None:
    """Linear isotropic limit: a = sqrt(4 P R_eff / (pi E*)), E* = E / (1 - nu^2), two
    cylinders 1/R_eff = 1/R_head + 1/R_roll. a < 1 mm << roll radius 0.5 m and depth 0.3 m,
    so the half-space idealisation holds."""
    R_eff = 1 / (1 / HERTZ_R + 1 / HERTZ_ROLL)
    E_star = HERTZ_E / (1 - HERTZ_NU**2)
    P = hertz.force_per_length[1:]
    a_hertz = np.sqrt(4 * P * R_eff / (math.pi * E_star))
    assert 0.3e-3 < a_hertz[0] and a_hertz[-1] < 1.5e-3  # the load range tested
    # 3 %: 7 to 15 surface elements per half-width, edge interpolated between nodes
    assert np.max(np.abs(hertz.half_width[1:] / a_hertz - 1)) < 0.03


def test_hertz_peak_pressure(hertz: ContactResult) -> None:
    R_eff = 1 / (1 / HERTZ_R + 1 / HERTZ_ROLL)
    E_star = HERTZ_E / (1 - HERTZ_NU**2)
    P = hertz.force_per_length[1:]
    a_hertz = np.sqrt(4 * P * R_eff / (math.pi * E_star))
    p0 = 2 * P / (math.pi * a_hertz)
    # 3 %: nodal force over tributary arc approximates the (smooth) pressure at the centre
    assert np.max(np.abs(hertz.peak_pressure[1:] / p0 - 1)) < 0.03


# ---------------------------------------------------------------- properties of the solution


def test_symmetry_whole_annulus_matches_half_model() -> None:
    """The whole-annulus model (no symmetry imposed) must be symmetric about the contact
    axis and reproduce the half model."""
    r, s = pet_profile()
    opts = {"n_steps": 6, "tangential_growth": 1.25}
    half = indent(PET1, RIGID, r, s, depth_max=5e-4, **HEAD, options=ContactOptions(**opts))
    full = indent(
        PET1, RIGID, r, s, depth_max=5e-4, **HEAD, options=ContactOptions(half_model=False, **opts)
    )
    # same discretisation of the same symmetric problem: agreement to solver round-off
    np.testing.assert_allclose(full.force, half.force, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(full.half_width, half.half_width, rtol=1e-6, atol=1e-12)
    # mirror pairs of element centres: sigma_r even, tau odd in theta
    key = np.round(full.element_r, 9), np.round(full.element_theta, 9)
    index = {(a, b): i for i, (a, b) in enumerate(zip(*key, strict=True))}
    pairs = np.array(
        [
            (i, index[(a, -b)])
            for i, (a, b) in enumerate(zip(*key, strict=True))
            if b > 0 and (a, -b) in index
        ]
    )
    assert len(pairs) > 0.4 * full.n_elements
    scale = np.max(np.abs(full.sigma_r - full.sigma_r_pre))
    i, j = pairs.T
    assert np.max(np.abs(full.sigma_r[i] - full.sigma_r[j])) < 1e-7 * scale
    assert np.max(np.abs(full.tau_r_theta[i] + full.tau_r_theta[j])) < 1e-7 * scale


def test_force_and_half_width_monotone(pet_default: ContactResult) -> None:
    assert np.all(np.diff(pet_default.force) > 0)
    assert np.all(np.diff(pet_default.half_width) >= 0)
    assert pet_default.delta[0] == 0 and pet_default.force[0] == 0
    assert pet_default.delta[-1] == pytest.approx(1e-3, rel=1e-15)


def test_no_update_is_softer(pet_default: ContactResult) -> None:
    r, s = pet_profile()
    frozen = indent(PET1, RIGID, r, s, depth_max=1e-3, update_modulus=False, **HEAD)
    # Pfeiffer stiffens with pressure, so freezing E_r at its pre-impact value must give a
    # much softer roll (the paper's Figure 8): at least a factor 2 at 1 mm here
    assert frozen.force[-1] < 0.5 * pet_default.force[-1]
    assert np.all(frozen.force[1:] < pet_default.force[1:])


def test_mesh_refinement_changes_force_less_than_2_percent(pet_default: ContactResult) -> None:
    """Halve the surface and tangential element sizes and take the square root of both growth
    ratios (about 4x the elements): F(d) must move by less than 2 % (project bar)."""
    r, s = pet_profile()
    R_eff = 1 / (1 / HEAD["head_radius"] + 1 / R_OUT)
    t_size = max(H / 4, math.sqrt(2 * R_eff * 1e-3) / 40)
    default = ContactOptions(n_steps=12)  # same steps on both meshes: only the mesh changes
    fine = ContactOptions(
        n_steps=12,
        surface_size=H / 2,
        tangential_size=t_size / 2,
        radial_growth=default.radial_growth**0.5,
        tangential_growth=default.tangential_growth**0.5,
    )
    base = indent(PET1, RIGID, r, s, depth_max=1e-3, **HEAD, options=default)
    refined = indent(PET1, RIGID, r, s, depth_max=1e-3, **HEAD, options=fine)
    assert refined.n_elements > 3 * base.n_elements
    assert base.n_elements == pet_default.n_elements
    d = np.linspace(0.2e-3, 1e-3, 9)
    change = np.interp(d, refined.delta, refined.force) / np.interp(d, base.delta, base.force) - 1
    assert np.max(np.abs(change)) < 0.02
    # the semi-contact width resolves to a few elements: 10 % (one element is 14 % of a)
    assert refined.semi_contact_width == pytest.approx(base.semi_contact_width, rel=0.10)


def test_fine_zone_width_converged() -> None:
    """Doubling the arc of the uniformly fine surface zone (default a_geo, about 6 contact
    half-widths here) changes F(d) by < 1 %: the contact is inside it with margin."""
    r, s = pet_profile()
    R_eff = 1 / (1 / HEAD["head_radius"] + 1 / R_OUT)
    a_geo = math.sqrt(2 * R_eff * 1e-3)
    base = indent(PET1, RIGID, r, s, depth_max=1e-3, **HEAD, options=ContactOptions(n_steps=12))
    wide = indent(
        PET1,
        RIGID,
        r,
        s,
        depth_max=1e-3,
        **HEAD,
        options=ContactOptions(n_steps=12, fine_halfwidth=2 * a_geo),
    )
    assert wide.n_elements > base.n_elements
    d = np.linspace(0.2e-3, 1e-3, 9)
    change = np.interp(d, wide.delta, wide.force) / np.interp(d, base.delta, base.force) - 1
    assert np.max(np.abs(change)) < 0.01


def test_load_step_refinement(pet_default: ContactResult) -> None:
    """Three times the depth increments (48 against the default 16) changes F by less than
    0.5 % at the default's own depths from 0.2 mm (measured 0.13 %; 0.04 % at 24 steps,
    0.01 % at 48 against 96: second order or better). Compared at the computed points:
    between them the coarser curve's straight chords, not the solution, differ (1.1 % at
    0.2 mm with 16 steps)."""
    r, s = pet_profile()
    finer = indent(PET1, RIGID, r, s, depth_max=1e-3, **HEAD, options=ContactOptions(n_steps=48))
    at = pet_default.delta >= 0.2e-3 - 1e-12
    d, f = pet_default.delta[at], pet_default.force[at]
    assert d.size >= 10
    change = np.interp(d, finer.delta, finer.force) / f - 1
    assert np.max(np.abs(change)) < 0.005


def test_forward_euler_converges_toward_midpoint() -> None:
    """Plain forward Euler (the brief's tangent update) is first order: its error to the
    converged force shrinks when the steps are doubled."""
    r, s = pet_profile()
    ref = indent(
        PET1,
        RIGID,
        r,
        s,
        depth_max=5e-4,
        **HEAD,
        options=ContactOptions(n_steps=48, tangential_growth=1.25),
    )
    errs = []
    for n in (12, 24):
        e = indent(
            PET1,
            RIGID,
            r,
            s,
            depth_max=5e-4,
            **HEAD,
            options=ContactOptions(n_steps=n, midpoint=False, tangential_growth=1.25),
        )
        errs.append(abs(e.force[-1] / ref.force[-1] - 1))
    assert errs[1] < 0.75 * errs[0]


def test_modulus_cap_softens_and_is_inactive_when_high() -> None:
    r, s = pet_profile()
    opts = {"n_steps": 6, "tangential_growth": 1.25}
    free = indent(PET1, RIGID, r, s, depth_max=5e-4, **HEAD, options=ContactOptions(**opts))
    capped = indent(
        PET1,
        RIGID,
        r,
        s,
        depth_max=5e-4,
        **HEAD,
        options=ContactOptions(max_modulus_ratio=0.01, **opts),
    )
    loose = indent(
        PET1,
        RIGID,
        r,
        s,
        depth_max=5e-4,
        **HEAD,
        options=ContactOptions(max_modulus_ratio=10.0, **opts),
    )
    assert capped.force[-1] < free.force[-1]
    # a cap of 10 E_theta is never reached (E_r peaks near 0.6 E_theta here): identical results
    assert loose.force[-1] == free.force[-1]


def test_elastic_core_is_softer_and_stiff_core_tends_to_rigid() -> None:
    r, s = pet_profile()
    opts = ContactOptions(n_steps=6, tangential_growth=1.25)
    rigid = indent(PET1, RIGID, r, s, depth_max=5e-4, **HEAD, options=opts)
    soft = indent(
        PET1, Core(outer_radius=R_CORE, stiffness=1e6), r, s, depth_max=5e-4, **HEAD, options=opts
    )
    stiff = indent(
        PET1, Core(outer_radius=R_CORE, stiffness=1e15), r, s, depth_max=5e-4, **HEAD, options=opts
    )
    assert soft.force[-1] < rigid.force[-1]
    # E_c = 1e15 Pa is 1e5 x stiffer than any E_r here: rigid to 1e-4
    assert stiff.force[-1] == pytest.approx(rigid.force[-1], rel=1e-4)


def test_slip_factor_vanishes_on_the_axis(pet_default: ContactResult) -> None:
    """tau_r_theta is odd in theta, so the slip factor is smallest next to the contact axis;
    away from it the shear under the head exceeds mu P (the paper's Figure 18 finding)."""
    res = pet_default
    near = R_OUT - res.element_r < 5e-4
    on_axis = near & (res.element_theta == res.element_theta[near].min())
    off_axis = near & (R_OUT * res.element_theta < 3 * res.semi_contact_width)
    assert res.slip_factor[on_axis].max() < 0.1 * res.slip_factor[off_axis].max()
    sf_half = indent(PET1, RIGID, *pet_profile(), depth_max=1e-3, friction=0.6, **HEAD)
    # SF = |tau| / (mu P): doubling mu halves it (same stresses)
    np.testing.assert_allclose(sf_half.slip_factor[near], 0.5 * res.slip_factor[near], rtol=1e-9)


def thin_stack_run(
    k1: float, k2: float, eps_max: float, n: int, midpoint: bool
) -> tuple[float, float, np.ndarray]:
    """A thin stack (1 mm wound on a 1 m rigid core, Pfeiffer K1 = ``k1``, K2 = ``k2``),
    its outer surface pushed in radially through stiff springs in ``n`` uniform steps to
    the strain ``eps_max``, driven by the increment function of :func:`indent`
    (``_hypoelastic_increment``, midpoint or forward Euler): the largest error of P over the
    elements against P = K1 (exp(K2 eps) - 1) at each element's strain, the mean P [Pa] and
    the elements' strains (docs/scripts/contact.py reads the same runs)."""
    web = Web(thickness=H, width=0.1524, E_theta=4950e6, radial_modulus=Pfeiffer(k1, k2))
    R_in, t = 1.0, 1e-3
    mesh = build_mesh(
        R_in,
        R_in + t,
        surface_size=1e-4,
        radial_growth=1.0,
        tangential_size=0.2,
        fine_halfwidth=0.2,
        tangential_growth=1.0,
    )
    roll = _Roll(
        web,
        Core(outer_radius=R_in),
        np.array([R_in, R_in + t]),
        np.zeros(2),
        mesh,
        ContactOptions(),
    )
    surf = roll.surface
    k_pen = 1e6 * web.E_theta
    spring = np.zeros(2 * mesh.n_nodes)
    spring[2 * surf] = k_pen
    roll.assembler = Assembler(roll.basis, roll.free, spring)
    rows = roll.assembler.free_index[2 * surf]
    u = np.zeros(2 * mesh.n_nodes)
    sig = np.zeros((mesh.n_elements, 3))
    delta = eps_max * t * np.arange(n + 1) / n
    for k in range(1, n + 1):
        df = np.zeros(roll.assembler.n_free)
        df[rows] = -k_pen * (delta[k] - delta[k - 1])

        def solve(mod: tuple, lu: object, df: np.ndarray = df) -> SimpleNamespace:
            du = np.zeros(2 * mesh.n_nodes)
            du[roll.free] = lu.solve(df)
            return SimpleNamespace(du=du, dsig=roll.stress_increment(mod, du))

        step = _hypoelastic_increment(roll, sig[:, 0], midpoint, solve)
        u += step.du
        sig += step.dsig
    eps = -roll.strain_increment(u)[:, 0]
    P = -sig[:, 0]
    return float(np.max(np.abs(P / (k1 * np.expm1(k2 * eps)) - 1))), float(P.mean()), eps


def test_hypoelastic_update_integrates_the_pfeiffer_law() -> None:
    """The incremental modulus update against the integrated law, in a thin-stack limit.

    Geometry: a 1 mm thick wound layer (10 elements of 0.1 mm) on a rigid core of radius
    1 m, plane strain, no pre-stress; its outer surface is pushed in radially by delta
    (displacement control, as the head in :func:`indent`, through springs 1e6 x stiffer than
    the stack). With Table 2's nu_tr = nu_zr = 0 the plane-strain stiffness has C11 = E_r,
    C12 = 0, so d sigma_r = E_r d eps_r whatever the hoop strain. Pfeiffer's tangent law {2},
    E_r = K2 (K1 + P) with P = -sigma_r and eps = -eps_r the compressive strain, integrates
    from P = 0 at eps = 0 to P(eps) = K1 (exp(K2 eps) - 1). Radial equilibrium
    d(r sigma_r)/dr = sigma_theta makes sigma_r vary through the thickness only by
    ~ sigma_theta t / R (t / R = 1e-3, sigma_theta ~ E_theta delta / R), so in this limit the
    stack is uniformly compressed, eps = delta / t. The test drives the same increment
    function as :func:`indent` (``_hypoelastic_increment``: moduli at the current total
    stress, midpoint or forward Euler) and compares every element's radial stress with the
    closed form at the element's own strain (only the time integration is tested), up to
    eps = 0.2 (PET2's K1, K2: the strain the stack reaches under a Rho-meter head).
    """
    K1, K2 = 20270.0, 26.24  # PET2, Table 2
    eps_max = 0.2

    def run(n: int, midpoint: bool) -> tuple[float, float]:
        err, p_mean, eps = thin_stack_run(K1, K2, eps_max, n, midpoint)
        # the thin-stack limit: uniform strain delta / t (1e-3: t / R)
        assert np.max(np.abs(eps / eps_max - 1)) < 1e-3
        return err, p_mean

    runs = {n: run(n, True) for n in (24, 48, 96)}
    mid = {n: r[0] for n, r in runs.items()}
    # measured 3.5 %, 0.96 %, 0.25 %: the law's exponent grows by K2 eps_max = 5.2 over the
    # path, 0.22 per increment at n = 24. Tolerances: 1.5 % at 48 and 0.4 % at 96 increments
    assert mid[48] < 0.015 and mid[96] < 0.004
    # second order: the error falls 4x per doubling (> 3x asserted)
    assert mid[48] < mid[24] / 3 and mid[96] < mid[48] / 3
    # the stack as a whole: P(delta / t) of the closed form, within the 96-step tolerance
    assert runs[96][1] == pytest.approx(K1 * math.expm1(K2 * eps_max), rel=0.004)
    euler = {n: run(n, False)[0] for n in (48, 96)}
    # forward Euler is first order (error x 0.55 per doubling here) and far less accurate
    assert euler[96] < 0.7 * euler[48] and euler[96] > 10 * mid[96]


# ---------------------------------------------------------------- fields at any depth


def test_at_depth_max_equals_the_final_fields(pet_default: ContactResult) -> None:
    res = pet_default
    st = res.at_depth(res.delta[-1])
    # the last increment itself: identical arrays, no arithmetic
    for name in ("sigma_r", "sigma_theta", "tau_r_theta", "slip_factor", "contact_pressure"):
        assert np.array_equal(getattr(st, name), getattr(res, name)), name
    assert st.half_width == res.semi_contact_width and st.force == res.force[-1]
    assert st.slip_extent() == res.slip_extent()
    assert np.array_equal(st.slip, res.slip)
    n = res.delta.size
    assert res.sigma_r_history.shape == (n, res.n_elements)
    assert res.contact_pressure_history.shape == (n, res.contact_s.size)
    # row 0 is the pre-impact state
    assert np.array_equal(res.sigma_r_history[0], res.sigma_r_pre)
    assert not np.any(res.tau_r_theta_history[0]) and not np.any(res.contact_pressure_history[0])


def test_at_depth_interpolates_between_increments(pet_default: ContactResult) -> None:
    res = pet_default
    k = 10
    exact = res.at_depth(res.delta[k])
    assert np.array_equal(exact.sigma_theta, res.sigma_theta_history[k])
    d = 0.25 * res.delta[k] + 0.75 * res.delta[k + 1]
    st = res.at_depth(d)
    w0, w1 = 0.25, 0.75
    for name, hist in (
        ("sigma_r", res.sigma_r_history),
        ("sigma_theta", res.sigma_theta_history),
        ("tau_r_theta", res.tau_r_theta_history),
        ("contact_pressure", res.contact_pressure_history),
    ):
        # linear interpolation in d (round-off of the weights only)
        want = w0 * hist[k] + w1 * hist[k + 1]
        np.testing.assert_allclose(
            getattr(st, name), want, rtol=1e-9, atol=1e-9 * np.abs(hist[k + 1]).max()
        )
    assert st.force == pytest.approx(w0 * res.force[k] + w1 * res.force[k + 1], rel=1e-12)
    assert st.half_width == pytest.approx(
        w0 * res.half_width[k] + w1 * res.half_width[k + 1], rel=1e-12
    )
    # the slip factor {23} is recomputed from the interpolated stresses, not interpolated
    np.testing.assert_array_equal(
        st.slip_factor, slip_factor(st.tau_r_theta, st.sigma_r, res.friction)
    )
    assert res.force[k] < st.force < res.force[k + 1]
    start = res.at_depth(0.0)
    assert start.force == 0.0 and start.half_width == 0.0
    assert np.array_equal(start.sigma_r, res.sigma_r_pre)
    assert res.at_depth("0.5 mm").force == pytest.approx(
        float(np.interp(5e-4, res.delta, res.force)), rel=1e-12
    )


@pytest.mark.parametrize(
    "depth", [-1e-9, 1.001e-3, float("nan"), float("inf"), "1 kPa", True, None]
)
def test_at_depth_outside_range_raises(pet_default: ContactResult, depth: object) -> None:
    with pytest.raises(InputError) as info:
        pet_default.at_depth(depth)  # type: ignore[arg-type]
    assert info.value.field == "depth"


# ---------------------------------------------------------------- fit, output, plots


def test_fit_spring_recovers_exact_quadratic() -> None:
    d = np.linspace(0, 1e-3, 11)
    alpha, beta, r2, res = fit_spring(d, 2e9 * d**2 + 3e4 * d)
    assert alpha == pytest.approx(2e9, rel=1e-9)
    assert beta == pytest.approx(3e4, rel=1e-9)
    assert r2 == pytest.approx(1.0, abs=1e-12) and res < 1e-9


def test_fit_quality_on_the_model(pet_default: ContactResult) -> None:
    res = pet_default
    assert res.fit_r2 > 0.999  # eq. 3 describes the computed F(d) well
    assert res.fit_max_rel_residual < 0.02
    fit = res.alpha * res.delta**2 + res.beta * res.delta
    assert np.max(np.abs(fit - res.force)) == pytest.approx(
        res.fit_max_rel_residual * res.force.max(), rel=1e-9
    )


def test_result_dict_and_plots(pet_default: ContactResult, tmp_path) -> None:
    d = pet_default.to_dict()
    for key in (
        "depth_m",
        "force_N",
        "half_width_m",
        "alpha_N_per_m2",
        "beta_N_per_m",
        "fit_r2",
        "semi_contact_width_m",
        "slip_region_depth_m",
    ):
        assert key in d
    json.dumps(d, allow_nan=False)  # strict JSON: no inf / NaN
    assert d["semi_contact_width_m"] == pet_default.half_width[-1]
    assert d["force_N"][-1] == pytest.approx(
        pet_default.force_per_length[-1] * HEAD["head_length"], rel=1e-12
    )
    with pytest.raises(ValueError):
        pet_default.force[0] = 1.0  # frozen result, read-only arrays
    fig = pet_default.plot(tmp_path / "fd.png")
    assert (tmp_path / "fd.png").stat().st_size > 1000 and len(fig.axes) == 2
    plot_slip_factor(pet_default, tmp_path / "sf.png")
    assert (tmp_path / "sf.png").stat().st_size > 1000


# ---------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"head_radius": 0.0}, "head_radius"),
        ({"head_radius": -0.01}, "head_radius"),
        ({"head_length": float("nan")}, "head_length"),
        ({"depth_max": 0.0}, "depth_max"),
        ({"depth_max": -1e-3}, "depth_max"),
        ({"depth_max": 0.006}, "depth_max"),  # more than half the head radius
        ({"friction": -0.1}, "friction"),
        ({"friction": "0.3 m"}, "friction"),
        ({"sigma_r": np.zeros(5)}, "sigma_r"),
        ({"sigma_r": np.full(200, np.nan)}, "sigma_r"),
        ({"radius": np.linspace(R_OUT, R_CORE, 200)}, "radius"),
        ({"radius": np.linspace(0.01, R_OUT, 200)}, "radius"),
        ({"options": ContactOptions}, "options"),
        ({"head_radius": "10 kPa"}, "head_radius"),
        ({"radius": ["a", "b"]}, "radius"),
    ],
)
def test_bad_input_raises_input_error(kwargs: dict, field: str) -> None:
    r, s = pet_profile()
    args = {"radius": r, "sigma_r": s, "depth_max": 1e-3, **HEAD}
    args.update(kwargs)
    with pytest.raises(InputError) as info:
        indent(PET1, RIGID, **args)
    assert info.value.field == field


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"n_steps": 0}, "options.n_steps"),
        ({"radial_growth": 0.9}, "options.radial_growth"),
        ({"tangential_size": -1.0}, "options.tangential_size"),
        ({"step_exponent": float("inf")}, "options.step_exponent"),
        ({"max_modulus_ratio": 0.0}, "options.max_modulus_ratio"),
        ({"midpoint": "yes"}, "options.midpoint"),
        ({"assumed_hoop": 1}, "options.assumed_hoop"),
        ({"element": "quadratic"}, "options.element"),
        ({"max_element_angle": 0.0}, "options.max_element_angle"),
        ({"max_element_angle": 2.0}, "options.max_element_angle"),
        ({"max_element_angle": float("nan")}, "options.max_element_angle"),
    ],
)
def test_bad_options(kwargs: dict, field: str) -> None:
    with pytest.raises(InputError) as info:
        ContactOptions(**kwargs)
    assert info.value.field == field


def test_units_strings_accepted() -> None:
    r, s = pet_profile()
    opts = ContactOptions(n_steps=3, tangential_growth=1.25)
    a = indent(
        PET1, RIGID, r, s, head_radius="10 mm", head_length="2 cm", depth_max="0.3 mm", options=opts
    )
    b = indent(PET1, RIGID, r, s, head_radius=0.01, head_length=0.02, depth_max=3e-4, options=opts)
    assert a.force[-1] == pytest.approx(b.force[-1], rel=1e-12)


def test_lcp_solver_exact_and_rejects_indefinite_flexibility() -> None:
    # 2x2 LCP with one contact open: lam = (-q0 / W00, 0) when q1 + W10 lam0 >= 0
    W = np.array([[2.0, 0.5], [0.5, 1.0]])
    lam = _solve_lcp(W, np.array([-1.0, 1.0]))
    np.testing.assert_allclose(lam, [0.5, 0.0], atol=1e-12)
    g = np.array([-1.0, 1.0]) + W @ lam
    assert np.all(g >= -1e-12) and abs(lam @ g) < 1e-12
    with pytest.raises(ConvergenceError):
        _solve_lcp(np.array([[1.0, 2.0], [2.0, 1.0]]), np.array([-1.0, -1.0]))


def test_coupled_with_the_winding_model() -> None:
    """PET1 wound at 26.7 N by woundroll.winding (Hakiel): the contact solve takes its
    profile as is, and a 10x thinner sampling of the same profile changes F by < 1 %
    (linear interpolation of sigma_r at element centres; the profile is smooth)."""
    from woundroll.winding.hakiel import wind
    from woundroll.winding.tension import TensionSchedule

    core = Core.tube(R_CORE, 0.0381, 200e9, 0.3)
    w = wind(PET1, core, R_OUT, TensionSchedule(web_stress=26.7 / (0.1524 * H)))
    opts = ContactOptions(n_steps=8, tangential_growth=1.25)
    full = indent(PET1, core, w.radius, w.sigma_r, depth_max=5e-4, **HEAD, options=opts)
    idx = np.unique(np.r_[np.arange(0, w.radius.size, 10), w.radius.size - 1])
    thin = indent(PET1, core, w.radius[idx], w.sigma_r[idx], depth_max=5e-4, **HEAD, options=opts)
    assert np.all(np.isfinite(full.force)) and np.all(np.diff(full.force) > 0)
    assert thin.force[-1] == pytest.approx(full.force[-1], rel=0.01)
    frozen = indent(
        PET1, core, w.radius, w.sigma_r, depth_max=5e-4, update_modulus=False, **HEAD, options=opts
    )
    assert frozen.force[-1] < full.force[-1]


def test_k1_zero_law_with_a_free_surface() -> None:
    """Table 3's K1 = 0: E_r = K2 P vanishes where the pre-impact pressure does (the free
    surface); the floor min_modulus_ratio * E_theta keeps the solve regular, and the result
    stays finite and monotone."""
    web = Web(thickness=H, width=0.1524, E_theta=4950e6, radial_modulus=Pfeiffer(0.0, 26.24))
    r = np.linspace(R_CORE, R_OUT, 300)
    s = -2e5 * (R_OUT - r) / (R_OUT - R_CORE)  # sigma_r = 0 at the surface
    res = indent(
        web,
        RIGID,
        r,
        s,
        depth_max=5e-4,
        **HEAD,
        options=ContactOptions(n_steps=8, tangential_growth=1.25),
    )
    assert np.all(np.isfinite(res.force)) and np.all(np.diff(res.force) > 0)
    assert np.all(np.isfinite(res.sigma_r)) and res.semi_contact_width > 0


def test_lcp_active_set_matches_nnls() -> None:
    """The contact LCP solver (Lawson-Hanson active set on the quadratic form, NumPy only)
    gives scipy's NNLS solution of the same problem: W = L L^T, min |L^T lam + L^-1 q|.
    Random SPD flexibilities with a mix of pressing (q < 0) and open (q > 0) nodes; the
    complementarity conditions hold to rounding (1e-9 of the problem's scale)."""
    import scipy.linalg as la
    from scipy.optimize import nnls

    from woundroll.contact.plane_strain.solver import _solve_lcp

    rng = np.random.default_rng(7)
    for m in (1, 2, 5, 17, 40):
        for _ in range(5):
            A = rng.normal(size=(m, m))
            W = A @ A.T + 0.1 * m * np.eye(m)
            q = rng.normal(size=m)
            lam = _solve_lcp(W, q)
            L = la.cholesky(W, lower=True)
            ref, _ = nnls(L.T, -la.solve_triangular(L, q, lower=True))
            scale = np.max(np.abs(ref)) + 1e-300
            assert np.max(np.abs(lam - ref)) < 1e-9 * scale
            g = q + W @ lam
            assert np.all(lam >= 0) and np.all(g >= -1e-9 * np.max(np.abs(q)))
            assert abs(lam @ g) < 1e-9 * np.max(np.abs(q)) * scale * m


def test_increments_whose_moduli_do_not_settle_are_split_through_the_cli() -> None:
    # contact.md assumption 2b's hard roll (K2 = 2000) with nu_z_r = 0.3: its E_r under the
    # head grows several-fold within one of the 16 default increments and the moduli do not
    # settle; the loading is solved again with 32 (plane_strain.solver.STEP_RETRIES). The
    # reading then agrees with an explicit 64-increment run within 0.5 % (measured 762.5
    # against 761.8 Rho FD, 0.09 %: both beyond the dial, shown as 100)
    import json

    from typer.testing import CliRunner

    from woundroll.app.cli import app

    args = ["run", "pet1-46.7N", "--json", "--set", "web.radial_modulus.K2=2000"]
    args += ["--set", "web.nu_z_r=0.3"]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 0, res.output
    fine = CliRunner().invoke(app, [*args, "--set", "contact.options.n_steps=64"])
    assert fine.exit_code == 0, fine.output
    got, ref = json.loads(res.stdout)["hardness"], json.loads(fine.stdout)["hardness"]
    assert got["rho_fd"] == pytest.approx(ref["rho_fd"], rel=5e-3)
    assert got["reading"] == 100.0 and got["rho_fd"] > 700
