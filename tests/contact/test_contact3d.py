"""The 3D contact model (woundroll.contact.solid3d.solver): element, heads, Hertz, the 2D limit.

Coarse meshes keep the default suite fast; each tolerance says why it is what it is. The
mesh-refinement study of the real rolls is ``slow`` (docs/contact.md, 3D section).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from woundroll.contact import indent
from woundroll.contact.heads import Head
from woundroll.contact.solid3d import linsolve
from woundroll.contact.solid3d.fem import D_PAIRS, lumped_mass, orthotropic_moduli, ring_matrices
from woundroll.contact.solid3d.mesh import build_mesh3d
from woundroll.contact.solid3d.solver import Contact3DOptions, indent3d
from woundroll.errors import InputError
from woundroll.materials import Constant, Core, Pfeiffer, Web

R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
PET1 = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
RIGID = Core(outer_radius=R_CORE)


def pet_profile(n: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """The synthetic PET1 profile of test_contact.py (30 kPa at the surface to ~1 MPa)."""
    r = np.linspace(R_CORE, R_OUT, n)
    return r, -(30e3 + 1e6 * (R_OUT - r) / (R_OUT - R_CORE))


def isotropic_web(E: float, nu: float, width: float) -> Web:
    G = E / (2 * (1 + nu))
    return Web(
        thickness=H,
        width=width,
        E_theta=E,
        E_z=E,
        radial_modulus=Constant(E),
        nu_theta_r=nu,
        nu_z_r=nu,
        nu_theta_z=nu,
        G_r_theta=G,
        G_r_z=G,
    )


# ------------------------------------------------------------------ material and element


def moduli_and_inverse() -> tuple[np.ndarray, np.ndarray, tuple[float, float, float]]:
    """The moduli of an orthotropic web (all nine) and ``numpy.linalg.inv`` of its 3x3
    normal compliance, with (E_r, E_theta, E_z) (docs/scripts/contact_checks.py shows it)."""
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
    return orthotropic_moduli(web, np.array([Er]))[:, 0], np.linalg.inv(S), (Er, Et, Ez)


def test_orthotropic_moduli_invert_the_compliance() -> None:
    D, C, (Er, Et, _) = moduli_and_inverse()
    for (p, q), v in zip(D_PAIRS[:6], D[:6], strict=True):
        assert v == pytest.approx(C[p, q], rel=1e-9)  # round-off of a 3x3 inversion
    assert D[6] == pytest.approx(2 * Er) and D[7] == pytest.approx(2 * Er)  # Table 2 default
    assert D[8] == pytest.approx(Et / (2 * 1.35))


def element_matrix(dr: float) -> np.ndarray:
    """The 24x24 stiffness of one brick ``dr`` thick at r = 0.1 m (nine distinct moduli)."""
    M = ring_matrices(np.array([0.1, 0.1 + dr]))[0]
    dth, dz = 0.01, 0.002
    D = np.array([1.0, 3, 2, 0.3, 0.2, 0.4, 0.7, 0.9, 1.1])
    f = np.array([1.0, 1 / dth, 1 / dz])
    c = (D[:, None, None] * f[None, :, None] * f[None, None, :] * dth * dz).ravel()
    return (c @ M).reshape(24, 24)


@pytest.mark.parametrize("dr", [1e-4, 1e-2])
def test_element_has_exactly_the_rigid_body_null_space(dr: float) -> None:
    """Six zero eigenvalues (rigid motions) and no more: the assumed hoop strain and the
    mid-line shear sampling add no hourglass mode (thin surface brick and a fat one)."""
    K = element_matrix(dr)
    assert np.abs(K - K.T).max() <= 1e-12 * np.abs(K).max()
    ev = np.linalg.eigvalsh(K) / np.abs(K).max()
    assert np.sum(np.abs(ev) < 1e-10) == 6  # round-off level
    assert ev[6] > 1e-7


def quarter_mass() -> tuple[float, float]:
    """The lumped mass of a graded quarter mesh and rho pi/2 (R^2 - r^2) W/2 [kg]."""
    mesh = build_mesh3d(
        0.05,
        0.1,
        z_max=0.02,
        theta_max=math.pi,
        surface_size=0.005,
        radial_growth=1.2,
        tangential_size=0.01,
        fine_halfwidth=0.02,
        tangential_growth=1.3,
        axial_size=0.005,
        fine_halflength=0.01,
        axial_growth=1.3,
    )
    m = lumped_mass(mesh, 1400.0)
    exact = 1400.0 * math.pi / 2 * (0.1**2 - 0.05**2) * 0.02  # half annulus x z_max
    return float(m[::3].sum()), exact


def test_lumped_mass_is_the_mass_of_the_quarter() -> None:
    total, exact = quarter_mass()
    assert total == pytest.approx(exact, rel=1e-12)


# ------------------------------------------------------------------------------ heads


def test_head_lifts() -> None:
    sphere = Head("sphere", 0.025)
    assert sphere.lift(0.003, 0.004) == pytest.approx(0.025 - math.sqrt(0.025**2 - 0.005**2))
    assert math.isinf(sphere.lift(0.03, 0.0))
    cyl = Head("cylinder", 0.006, 0.0254, edge_radius=0.002)
    # flat part: the circle of the cylinder; rounded end: the cross-section shrinks
    assert cyl.lift(0.001, 0.005) == pytest.approx(0.006 - math.sqrt(0.006**2 - 0.001**2))
    assert cyl.lift(0.0, 0.0127 - 0.002) == pytest.approx(0.0)
    assert cyl.lift(0.0, 0.0127) == pytest.approx(0.002)
    assert math.isinf(cyl.lift(0.0, 0.013))
    punch = Head("punch", 0.005, edge_radius=0.001)
    assert punch.lift(0.002, 0.002) == 0.0
    assert punch.lift(0.005, 0.0) == pytest.approx(0.001)


def test_head_errors_name_the_field() -> None:
    with pytest.raises(InputError) as e:
        Head("cone", 0.01)
    assert e.value.field == "head.shape"
    with pytest.raises(InputError) as e:
        Head("cylinder", 0.01)
    assert e.value.field == "head.length"
    with pytest.raises(InputError) as e:
        Head("punch", 0.01, edge_radius=0.02)
    assert e.value.field == "head.edge_radius"


def test_heads_from_the_instrument_files() -> None:
    from woundroll.instruments import get_instrument

    assert Head.from_instrument(get_instrument("schmidt-n")).shape == "sphere"
    rho = Head.from_instrument(get_instrument("rho-meter"))
    assert rho.shape == "cylinder" and rho.length == pytest.approx(0.0254)


# ----------------------------------------------------------------------- verification


@pytest.fixture(scope="module")
def hertz() -> tuple:
    """A rigid sphere on a thick isotropic body of large radius (a half-space to the contact)."""
    E, nu, R_roll, Rh, t = 10e6, 0.3, 2.0, 0.01, 0.1
    web = isotropic_web(E, nu, width=0.2)
    core = Core(outer_radius=R_roll - t)
    grow = {"radial_growth": 1.5, "tangential_growth": 1.5, "axial_growth": 1.5}
    res = indent3d(
        web,
        core,
        np.array([R_roll - t, R_roll]),
        np.zeros(2),
        head=Head("sphere", Rh),
        depth_max=2e-4,
        options=Contact3DOptions(n_steps=2, n_fine=6, step_exponent=1.0, **grow),
    )
    return res, E / (1 - nu**2), 1.0 / math.sqrt((1 / Rh + 1 / R_roll) / Rh)


def test_sphere_on_isotropic_half_space_matches_hertz(hertz: tuple) -> None:
    """F = 4/3 E* sqrt(R) d^1.5, a = sqrt(R d) (R: the geometric mean of the principal
    radii, 1/R1 = 1/R_h + 1/R_roll and R2 = R_h, within 0.5 % of the elliptic solution).
    Tolerance 2 % (the issue's bar): 6 elements per contact radius (measured: F +0.9 %,
    a +1 %; with 8 elements +1.0 %, +1.0 %), 70 contact radii of body under the head."""
    res, E_star, R = hertz
    d = res.delta[-1]
    assert res.force[-1] == pytest.approx(4 / 3 * E_star * math.sqrt(R) * d**1.5, rel=0.02)
    a = math.sqrt(R * d)
    assert res.half_width[-1] == pytest.approx(a, rel=0.02)
    assert res.half_length[-1] == pytest.approx(a, rel=0.02)


def test_linear_material_factorises_once(hertz: tuple) -> None:
    assert hertz[0].stats["factorisations"] == 1


def test_plane_strain_slab_is_the_2d_model() -> None:
    """A head as long as the roll on a slab with u_z = 0 faces is plane strain: the 3D model
    must give the 2D model's force per length. Same increments and the same midpoint rule
    (trial predictor) in both, PET1 with the hypoelastic update; the 3D mesh is coarser
    than the 2D default in the hoop (a_y / 10), hence 2 % (the issue's bar). The formulation
    is checked on a finer grading (1.3: 0.3 % at 1 mm, bar 1 %); the default grading (1.6)
    meets the 2 % bar at every depth (measured 1.3 % at 1 mm)."""
    r, s = pet_profile()
    web = PET1
    grow = {"radial_growth": 1.3, "tangential_growth": 1.3, "axial_growth": 1.3}
    opts = Contact3DOptions(
        n_steps=6, predictor="trial", cmd_edges="fixed", axial_size=web.width / 6, **grow
    )
    head = Head("cylinder", 0.01, 2 * web.width)
    r3 = indent3d(web, RIGID, r, s, head=head, depth_max=1e-3, options=opts)
    default = indent3d(
        web, RIGID, r, s, head=head, depth_max=1e-3,
        options=Contact3DOptions(
            n_steps=6, predictor="trial", cmd_edges="fixed", axial_size=web.width / 6
        ),
    )  # fmt: skip
    from woundroll.contact import ContactOptions

    r2 = indent(
        web,
        RIGID,
        r,
        s,
        head_radius=0.01,
        head_length=web.width,
        depth_max=1e-3,
        options=ContactOptions(n_steps=6, predictor=False),
    )
    np.testing.assert_allclose(r3.delta, r2.delta, rtol=1e-12)
    assert np.max(np.abs(r3.force[2:] / r2.force[2:] - 1)) < 0.02
    assert r3.force[-1] / r2.force[-1] == pytest.approx(1.0, abs=0.01)
    assert np.max(np.abs(default.force[2:] / r2.force[2:] - 1)) < 0.02


def updated_and_frozen():  # noqa: ANN201
    """A sphere pressed 0.4 mm into the PET1 test roll with E_r updated and frozen."""
    r, s = pet_profile()
    head = Head("sphere", 0.0125)
    grow = {"radial_growth": 1.5, "tangential_growth": 1.5, "axial_growth": 1.5}
    opts = Contact3DOptions(n_steps=4, n_fine=5, locality_cut=True, **grow)
    up = indent3d(PET1, RIGID, r, s, head=head, depth_max=4e-4, options=opts)
    frozen = indent3d(
        PET1, RIGID, r, s, head=head, depth_max=4e-4, update_modulus=False, options=opts
    )
    return up, frozen


def test_update_stiffens_and_no_update_is_softer() -> None:
    up, frozen = updated_and_frozen()
    assert np.all(np.diff(up.force) > 0) and np.all(np.diff(frozen.force) > 0)
    assert frozen.force[-1] < 0.8 * up.force[-1]  # E_r grows with the pressure {2}
    assert frozen.stats["factorisations"] == 1


# ----------------------------------------------------------------------------- errors


@pytest.mark.parametrize(
    ("head", "kw", "field"),
    [
        (Head("cylinder", 0.006, 0.2), {}, "head.length"),
        (Head("sphere", 0.01), {"depth_max": 6e-3}, "depth_max"),
        (
            Head("sphere", 0.01),
            {"options": Contact3DOptions(tangential_size=5e-3)},
            "options.tangential_size",
        ),
    ],
)
def test_bad_input_names_the_field(head: Head, kw: dict, field: str) -> None:
    r, s = pet_profile()
    with pytest.raises(InputError) as e:
        indent3d(PET1, RIGID, r, s, head=head, **{"depth_max": 5e-4, **kw})
    assert e.value.field == field


def test_bad_options_are_rejected() -> None:
    with pytest.raises(InputError) as e:
        Contact3DOptions(n_fine=2)  # too coarse to resolve the contact
    assert e.value.field == "options.n_fine"
    with pytest.raises(InputError) as e:
        Contact3DOptions(solver="magic")
    assert e.value.field == "options.solver"


# ------------------------------------------------------------------ pipeline, refinement


COARSE3D = [
    "contact.options3d.n_fine=5",
    "contact.options3d.radial_growth=1.6",
    "contact.options3d.tangential_growth=1.6",
    "contact.options3d.axial_growth=1.6",
]


@pytest.mark.slow
def test_schmidt_hammer_reads_a_roll_through_the_3d_model() -> None:
    """The registry's default for a spherical head sends the Schmidt tip to the 3D
    model: a reading from winder settings without a hand-given roll spring (coarse mesh:
    this checks the coupling, the mesh study checks the numbers)."""
    import woundroll
    from woundroll.contact.solid3d.solver import Contact3DResult

    res = woundroll.run(
        woundroll.load_case(
            "pet2-53.4N", ["tester.instrument='schmidt-n'", "contact.no_update=false", *COARSE3D]
        )
    )
    assert isinstance(res.contact.contact, Contact3DResult)
    assert res.contact.contact.head["shape"] == "sphere"
    r = res.hardness.to_dict()
    assert 10.0 < r["reading"] <= 100.0
    assert res.contact.alpha >= 0 and res.contact.beta > 0


@functools.cache
def _rho_meter_pet2(options: Contact3DOptions):  # noqa: ANN202
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parent))
    from test_real_profiles import real_roll

    web, core, radius, sigma_r = real_roll("pet2-26.7N")
    head = Head("cylinder", 6.565e-3, 25.4e-3)
    return indent3d(web, core, radius, sigma_r, head=head, depth_max=2.1e-3, options=options)


def _refined(base: Contact3DOptions, name: str) -> Contact3DOptions:
    kw = dict(base.__dict__)
    if name.endswith("growth"):
        kw[name] = kw[name] ** 0.5
    elif name == "n_fine":
        kw[name] = 2 * kw[name]
    elif name == "n_steps":
        kw[name] = 2 * kw[name]
    elif name == "axial_size":  # the cylinder's default, min(L / 24, a_y / 2), halved
        a_y = math.sqrt(2.1e-3 * 2 / (1 / 6.565e-3 + 1 / 0.1334))
        kw[name] = 0.5 * min(25.4e-3 / 24, a_y / 2)
    return Contact3DOptions(**kw)


@pytest.mark.slow
@pytest.mark.parametrize(
    "name",
    ["radial_growth", "tangential_growth", "axial_growth", "n_fine", "axial_size", "n_steps"],
)
def test_mesh_refinement_moves_the_rho_meter_curve_by_less_than_1_percent(name: str) -> None:
    """PET2 26.7 N (Hakiel profile), Rho-meter head, 2.1 mm: each mesh parameter refined
    alone from the default moves F(d) over 0.2-1 depth_max by < 1 % (the issue's bar), the
    increments 12 -> 24 too (the lagged predictor; measured 0.52 % at 0.4 depth_max, mostly
    the linear interpolation between the 12 increments' depths, 0.07 % at depth_max; the
    rate predictor's 24 -> 48 moved F by 1.12 % at 0.2 depth_max, docs/contact.md)."""
    base = Contact3DOptions()
    ref = _rho_meter_pet2(base)
    fine = _rho_meter_pet2(_refined(base, name))
    d = np.linspace(0.2, 1.0, 9) * 2.1e-3
    f0 = np.interp(d, ref.delta, ref.force)
    f1 = np.interp(d, fine.delta, fine.force)
    assert np.max(np.abs(f1 / f0 - 1)) < 0.01


def test_model_dispatch_errors_name_the_field() -> None:
    from woundroll.contact import roll_stiffness
    from woundroll.instruments import get_instrument

    r, s = pet_profile()
    sn = get_instrument("schmidt-n")
    with pytest.raises(InputError, match="takes a cylinder head") as e:  # 2D: no sphere
        roll_stiffness(PET1, RIGID, r, s, sn, model="2d")
    assert e.value.field == "contact.model"
    with pytest.raises(InputError) as e:
        roll_stiffness(PET1, RIGID, r, s, sn, model="4d")
    assert e.value.field == "contact.model"


def reduced_shear_runs():  # noqa: ANN201
    """A sphere on the PET1 test roll without slip, with the reduced-shear slip at mu 1e9
    (nothing slips) and at mu 0.3 (docs/scripts/contact_checks.py shows them)."""
    r, s = pet_profile()
    head = Head("sphere", 0.0125)
    grow = {"radial_growth": 1.6, "tangential_growth": 1.6, "axial_growth": 1.6}
    base = {"n_steps": 3, "n_fine": 5, "locality_cut": True, **grow}
    kw = {"head": head, "depth_max": 3e-4}
    plain = indent3d(PET1, RIGID, r, s, options=Contact3DOptions(**base), **kw)
    slip = Contact3DOptions(**base, slip="reduced-shear")
    sticky = indent3d(PET1, RIGID, r, s, friction=1e9, options=slip, **kw)
    slipping = indent3d(PET1, RIGID, r, s, friction=0.3, options=slip, **kw)
    return plain, sticky, slipping


def test_reduced_shear_slip_softens_and_vanishes_without_slip() -> None:
    """Slip emulation (Figure 19): with mu so large that no element slips the curve is the
    no-slip curve exactly; with mu = 0.3 the slipped elements lose 99 % of G_rt, G_rz and
    the roll is softer."""
    plain, sticky, slipping = reduced_shear_runs()
    assert sticky.stats["slipped_elements"] == 0
    np.testing.assert_allclose(sticky.force, plain.force, rtol=1e-12)
    assert slipping.stats["slipped_elements"] > 0
    assert slipping.force[-1] < plain.force[-1]


def _reuse_case(**kw):  # noqa: ANN202
    r, s = pet_profile()
    base = {"n_steps": 4, "n_fine": 5, "locality_cut": True}
    grow = {"radial_growth": 1.5, "tangential_growth": 1.5, "axial_growth": 1.5}
    opts = Contact3DOptions(**base, **grow, **kw)
    return indent3d(PET1, RIGID, r, s, head=Head("sphere", 0.0125), depth_max=4e-4, options=opts)


def test_reused_factorisation_falls_back_to_the_fresh_answer() -> None:
    """Modified Newton (``reuse_factorisation``) with too few conjugate-gradient iterations
    allowed: each increment's K is factorised afresh, and F(d) is the plain curve within the
    contact solve's own tolerance. Both solve each increment's contact until the gaps are
    within 1e-3 of the first increment's depth, along different passes (the fallback's first
    pass uses the flexibility of the last factorisation, the plain solve that of its own):
    the forces then agree to ~1e-3 of the first increment's, 2e-4 measured."""
    fresh = _reuse_case()
    again = _reuse_case(reuse_factorisation=True, pcg_max_iterations=1)
    assert again.stats["pcg_refactorisations"] == fresh.stats["factorisations"] - 1
    np.testing.assert_allclose(again.force[1:], fresh.force[1:], rtol=1e-3)


@pytest.mark.slow
def test_reused_factorisation_gives_the_fresh_answer() -> None:
    """Conjugate gradients on the current K, preconditioned by the first increment's
    factorisation, solve the same systems to the relative residual 1e-10, so F(d) is the
    fresh-factorisation curve within the contact iteration's own tolerance (1e-3 of the
    first increment's depth; the passes differ: the reused solve's contact flexibility is the
    first factorisation's; measured 6.1e-6). Up to 252 iterations per solve (the stale K
    is a poor preconditioner under the head, docs/contact.md; 134 on the rate predictor,
    whose increments had no trial solve): 400 allowed, so that none falls back."""
    fresh = _reuse_case()
    reused = _reuse_case(reuse_factorisation=True, pcg_max_iterations=400)
    assert reused.stats["factorisations"] == 1 and reused.stats["pcg_iterations"] > 0
    np.testing.assert_allclose(reused.force[1:], fresh.force[1:], rtol=1e-3)


@functools.cache
def _cylinder(n_steps: int, predictor: str, solver: str = "auto"):  # noqa: ANN202
    r, s = pet_profile()
    opts = Contact3DOptions(
        n_steps=n_steps,
        predictor=predictor,
        n_fine=5,
        radial_growth=1.6,
        tangential_growth=1.6,
        axial_growth=1.6,
        solver=solver,
    )
    head = Head("cylinder", 0.0078, 0.0254)
    return indent3d(PET1, RIGID, r, s, head=head, depth_max=5e-4, options=opts)


def _cylinder_force(n_steps: int, predictor: str) -> float:
    return float(_cylinder(n_steps, predictor).force[-1])


def test_lagged_predictor_is_second_order_in_the_increments() -> None:
    """The default predictor (a trial solve on the last increment's factorisation) keeps
    the midpoint rule's second order: F(depth_max) of a cylinder 0.5 mm into the PET1 test
    roll (coarse mesh) changes by 80.5, 19.5, 5.6, 1.4 N from 4 to 64 increments, ratios
    4.1, 3.5, 3.9 (second order: 4); asserted 3-5.5 on 4 / 8 / 16. The stress-rate
    predictor is first order where the contact spreads (ratio 2.0 on 4 / 8 / 16) and its
    change from 8 to 16 increments (87 N) is 4.5 times the lagged one's."""
    lagged = [_cylinder_force(n, "lagged") for n in (4, 8, 16)]
    e1, e2 = abs(lagged[1] - lagged[0]), abs(lagged[2] - lagged[1])
    assert 3.0 <= e1 / e2 <= 5.5
    rate = [_cylinder_force(n, "rate") for n in (8, 16)]
    assert abs(rate[1] - rate[0]) > 3.0 * e2


def test_contact_is_solved_in_a_pass_on_the_partial_solves_flexibility() -> None:
    """With PARDISO the contact's flexibility is the factorised K's own (a partial solve on
    the reachable surface's radial unknowns, ordered last): each contact solve takes one
    pass as a rule, so an increment (a lagged trial and the solve at the midpoint moduli)
    costs 2-3 whole solves (measured 16 on 8 increments; on cached columns of earlier
    factorisations it took 20-30). SuperLU's whole-solve columns give the same curve within
    the contact's gap tolerance (1e-3 of the first increment's depth; measured 6.8e-5)."""
    res = _cylinder(8, "lagged")
    st = res.stats
    if linsolve.pardiso_available():
        assert st["partial_solves"] >= st["factorisations"] - 1
        assert st["rhs_solved"] <= 3 * 8
    ref = _cylinder(8, "lagged", "splu")
    assert ref.stats["partial_solves"] == 0
    np.testing.assert_allclose(res.force[1:], ref.force[1:], rtol=1e-3)


def test_candidates_beyond_the_marked_zone_take_whole_solves(monkeypatch) -> None:  # noqa: ANN001
    """A contact that outgrows the marked zone (here: a zone of one node) is solved on
    cached whole-solve columns instead, to the same curve within the contact's gap
    tolerance (1e-3 of the first increment's depth; measured 6.8e-5, 221 right-hand sides
    against 16)."""
    from woundroll.contact.solid3d import solver as solver3d

    ref = _cylinder(8, "lagged")

    def one_node(self, d):  # noqa: ANN001, ANN202
        zone = np.zeros(self.cos_t.size, dtype=bool)
        zone[0] = True
        return zone

    monkeypatch.setattr(solver3d._Loading3D, "reachable_at", one_node)
    small = _cylinder.__wrapped__(8, "lagged")
    if linsolve.pardiso_available():
        assert small.stats["partial_solves"] < ref.stats["partial_solves"]
        assert small.stats["rhs_solved"] > ref.stats["rhs_solved"]
    np.testing.assert_allclose(small.force[1:], ref.force[1:], rtol=1e-3)
