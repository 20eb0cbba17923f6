"""The layered roll in 3D (woundroll.contact.layered.roll3d): the continuum when stuck, N
plates when free, slip along the force in theta and z, refinement.

Coarse meshes keep the default suite fast; each tolerance says why it is what it is
(docs/contact.md, "The layered roll in 3D").
"""

from __future__ import annotations

import numpy as np
import pytest

from woundroll.contact.heads import Head
from woundroll.contact.layered.roll3d import (
    Layered3DOptions,
    Layered3DState,
    _LayeredRoll3D,
    indent_layered3d,
    layered_mesh3d,
)
from woundroll.contact.solid3d.fem import orthotropic_moduli
from woundroll.contact.solid3d.solver import Contact3DOptions, Roll3D
from woundroll.errors import InputError
from woundroll.materials import Core, Pfeiffer, Web
from woundroll.materials.radial_modulus import Constant

# --------------------------------------------------------------- a coarse PET1 test roll

R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
PET1 = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
RIGID = Core(outer_radius=R_CORE)
GROW = {"radial_growth": 1.6, "tangential_growth": 1.6, "axial_growth": 1.6}


def pet_profile(n: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """The synthetic PET1 profile of test_contact3d.py (30 kPa at the surface to ~1 MPa)."""
    r = np.linspace(R_CORE, R_OUT, n)
    return r, -(30e3 + 1e6 * (R_OUT - r) / (R_OUT - R_CORE))


def pet_roll(
    mu: float,
    head: Head,
    *,
    interfaces: bool = True,
    n_steps: int = 2,
    layers_per_shell: int | None = 5,
    layered_depth: float = 1.5e-3,
    state: list[Layered3DState] | None = None,
    depth_max: float = 3e-4,
    gap_tol: float | None = None,
) -> float:
    r, s = pet_profile()
    base = Contact3DOptions(n_steps=n_steps, n_fine=4, locality_cut=True, **GROW)
    opts = Layered3DOptions(
        base=base,
        layered_depth=layered_depth,
        layers_per_shell=layers_per_shell,
        interfaces=interfaces,
        gap_tol=gap_tol,
    )
    res = indent_layered3d(
        PET1, RIGID, r, s, head=head, depth_max=depth_max, friction=mu, options=opts, state=state
    )
    return float(res.force[-1])


SPHERE = Head("sphere", 0.0125)


# ------------------------------------------------------------------ the continuum when stuck


def test_uncut_layered_roll_is_the_3d_roll() -> None:
    """With no interface the doubled numbering is the 3D model's: the stiffness matrices of
    the two assemblers are equal to rounding (same elements, same DOF order)."""
    r, s = pet_profile()
    base = Contact3DOptions(n_fine=4, locality_cut=True, **GROW)
    lopts = Layered3DOptions(base=base, layered_depth=1e-3, layers_per_shell=5)
    mesh, cut, _, _ = layered_mesh3d(PET1, RIGID, R_OUT, SPHERE, 3e-4, lopts)
    plain = Roll3D(PET1, RIGID, r, s, mesh, base)
    uncut = _LayeredRoll3D(PET1, RIGID, r, s, mesh, base, cut[:0], 1.0)
    D = orthotropic_moduli(PET1, PET1.E_r(plain.sigma_pre))
    Kp, Ku = plain.asm.matrix(D), uncut.asm.matrix(D)
    assert Kp.shape == Ku.shape
    assert abs(Kp - Ku).max() <= 1e-12 * abs(Kp).max()
    np.testing.assert_array_equal(plain.sr, uncut.sr)


@pytest.mark.slow  # 16 s on the loaded 2-core machine
def test_high_friction_is_the_continuum_on_the_same_mesh() -> None:
    """mu = 1e6: every interface sticks, the equations are the continuum's on the same
    mesh. The head contact is solved to a gap tolerance (1e-3 of the first depth step in
    the 3D model: the two runs then differ by 4e-4, each within it); at 1e-6 the forces
    agree to 3.8e-6 (measured), the ADMM's stopping tolerance (1e-5 of the largest
    displacement increment): asserted 2e-5."""
    stuck = pet_roll(1.0, SPHERE, interfaces=False, gap_tol=1e-6)
    high = pet_roll(1e6, SPHERE, gap_tol=1e-6)
    assert high == pytest.approx(stuck, rel=2e-5)


# ---------------------------------------------------------------- N plates when free (slab)

# The setting of tests/contact/test_layered_plates.py (derived there): N = 9 sheets of
# h = 0.1 mm on a Winkler core of radius 20 m that holds the innermost nodes tangentially,
# a stiff near-isotropic web; here a 3D slab 2 mm wide with u_z = 0 on both CMD faces and a
# head longer than the slab (plane strain: the 3D model's own 2D check), so the closed form
# of a beam on a Winkler foundation applies: K = 2 k / beta, stuck EI = E'(9h)^3/3,
# frictionless EI = 8 E'h^3/12 + E'h^3/3, ratio 243^(1/4) = 3.948.
N, R_W, E_T, NU, W = 9, 20.0, 5e9, 0.3, 2e-3
E_P = E_T / (1 - NU**2)
STIFF = Web(
    thickness=H,
    width=W,
    E_theta=E_T,
    radial_modulus=Constant(E_T),
    G_r_theta=E_T / 2.6,
    nu_theta_z=NU,
)
EI_SLIP = (N - 1) * E_P * H**3 / 12 + E_P * H**3 / 3
EI_STICK = E_P * (N * H) ** 3 / 3
K_W = 4 * EI_SLIP / 5e-3**4
WINKLER = Core(outer_radius=R_W, stiffness=K_W * R_W)


def beam_stiffness(EI: float) -> float:
    return 2 * K_W / (K_W / (4 * EI)) ** 0.25


#: The slab's mesh grading, 1.3 rather than the 3D default 1.6 (MESH_GROWTH): the closed
#: forms are a continuous beam whose deflection decays over 1/beta ~ 5 mm along the hoop,
#: and 1.6 coarsens the hoop elements too fast to resolve it. Measured (stuck / frictionless
#: against the closed forms): growth 1.6 +3.7 % / +3.3 %, 1.3 +1.4 % / +0.8 %, 1.14 +0.7 % /
#: -0.2 % (the mesh error falls with the grading; same on the commit before the layered
#: set-up's split, dc46381^).
SLAB_GROWTH = {"radial_growth": 1.3, "tangential_growth": 1.3, "axial_growth": 1.3}


def slab(mu: float, interfaces: bool = True) -> float:
    """Secant stiffness F / (W d) [N/m^2] of the slab pressed 0.02 mm deep."""
    r = np.linspace(R_W, R_W + N * H, 50)
    s = np.full(r.size, -1e3)  # 1 kPa wound-in: the interfaces closed
    base = Contact3DOptions(
        n_steps=2,
        cmd_edges="fixed",
        axial_size=W / 6,
        surface_size=5e-5,  # the mesh builder's check only: the shells are the sheets
        locality_cut=True,
        tangential_size=5e-5,
        fine_halfwidth=2e-4,
        **SLAB_GROWTH,
    )
    opts = Layered3DOptions(
        base=base, layered_depth=(N - 1) * H, layers_per_shell=1, interfaces=interfaces
    )
    res = indent_layered3d(
        STIFF,
        WINKLER,
        r,
        s,
        head=Head("cylinder", 1e-3, 2 * W),
        depth_max=2e-5,
        friction=mu,
        options=opts,
    )
    return float(res.force[-1] / W / res.delta[-1])


@pytest.mark.slow
def test_frictionless_sheets_bend_as_separate_plates() -> None:
    # measured (n_steps 2, growth 1.3: SLAB_GROWTH): stuck +1.44 %, frictionless +0.81 %
    # against the closed forms, ratio 3.973 against 3.948 (n_steps 4: +1.44 %, +0.88 %,
    # 3.970), mu = 1e6 equal to the stuck stack to 3e-5. Tolerance 2 % as in 2D (the
    # ring's hoop stiffness, the head's finite contact, the coarser 3D hoop mesh)
    stuck, free = slab(1.0, interfaces=False), slab(1e-6)
    assert stuck == pytest.approx(beam_stiffness(EI_STICK), rel=0.02)
    assert free == pytest.approx(beam_stiffness(EI_SLIP), rel=0.02)
    assert stuck / free == pytest.approx((EI_STICK / EI_SLIP) ** 0.25, rel=0.02)


# ------------------------------------------------------- slip along the force, in theta and z


@pytest.mark.slow  # 18 s on the loaded 2-core machine
def test_slip_runs_along_the_force_and_z_matters() -> None:
    """A sphere presses the coarse PET1 roll with mu = 0.1: the interfaces slip in a ring
    around the head, so some pairs slip mostly along the CMD (z). Every slipping pair's
    force is on the rim of its disc (|T| = mu P A, to the ADMM tolerance: 1e-3) and points
    along its slip (the angle between them below 0.05 rad); no pair's force leaves its
    disc; and the roll is softer than the stuck one."""
    st: list[Layered3DState] = []
    slipping = pet_roll(0.1, SPHERE, state=st)
    x = st[0]
    w = x.slip_increment
    nw = np.hypot(w[:, 0], w[:, 1])
    T = x.shear
    nT = np.hypot(T[:, 0], T[:, 1])
    assert np.all(nT <= x.limit * (1 + 1e-9) + 1e-12)
    slip = nw > 1e-6 * np.max(nw)
    assert np.sum(slip) > 10
    assert np.any(slip & (np.abs(w[:, 1]) > 2 * np.abs(w[:, 0])))  # along the CMD
    assert np.any(slip & (np.abs(w[:, 0]) > 2 * np.abs(w[:, 1])))  # along the hoop
    big = nw > 1e-2 * np.max(nw)
    assert nT[big] == pytest.approx(x.limit[big], rel=1e-3)
    cos = np.einsum("ij,ij->i", T[big], w[big]) / (nT[big] * nw[big])
    assert np.all(cos > np.cos(0.05))
    stuck = pet_roll(1.0, SPHERE, interfaces=False)
    assert slipping < stuck


# ---------------------------------------------------------------------------- refinement


@pytest.mark.slow
def test_layers_per_shell_refinement_converges() -> None:
    """The same 1.2 mm zone in shells of 4, 2 and 1 layers (cylinder head, mu 0.3). One
    sheet per shell is the model itself; lumping sheets glues layers that would slip, so
    the force falls monotonically toward it (as in 2D). Measured: the steps 14.7 N then
    12.9 N (observed order 0.19, slower than 2D's 0.49: in 3D the lumped sheets glue the
    CMD slip too). Bounds: monotone, each step smaller than the last."""
    head = Head("cylinder", 0.00635, 0.0254)
    f = [
        pet_roll(0.3, head, layers_per_shell=n, layered_depth=1.2e-3, n_steps=3) for n in (4, 2, 1)
    ]
    print("layers per shell 4, 2, 1:", f)
    assert f[0] > f[1] > f[2]
    assert abs(f[2] - f[1]) < abs(f[1] - f[0])


# ---------------------------------------------------------------------------- bad input


def test_bad_input_names_the_field() -> None:
    r, s = pet_profile()
    with pytest.raises(InputError) as e:
        indent_layered3d(PET1, RIGID, r, s, head=SPHERE, depth_max=3e-4, friction=0.0)
    assert e.value.field == "friction"
    with pytest.raises(InputError) as e:
        indent_layered3d(
            PET1,
            RIGID,
            r,
            s,
            head=SPHERE,
            depth_max=3e-4,
            options=Layered3DOptions(layered_depth=0.2),
        )
    assert e.value.field == "layered_depth"
    with pytest.raises(InputError) as e:
        Layered3DOptions(layers_per_shell=0)
    assert e.value.field == "layers_per_shell"
    with pytest.raises(InputError) as e:
        Layered3DOptions(base=Contact3DOptions(slip="reduced-shear"))
    assert e.value.field == "slip"


@pytest.mark.parametrize(
    ("sets", "field"),
    [
        (["contact.model=3d", "contact.layered_depth=2 mm"], "contact.layered_depth"),
        (["contact.model=layered-3d", "contact.layers_per_shell=0"], "contact.layers_per_shell"),
        (["contact.model=layered-3d", "contact.shear_ratio=1.0"], "contact.shear_ratio"),
    ],
)
def test_case_keys_for_layered3d(sets: list[str], field: str) -> None:
    from woundroll.case import load_case

    with pytest.raises(InputError) as e:
        case = load_case("pet1-26.7N", sets)
        case.contact.model_options()
    assert e.value.field == field


def test_case_gives_the_layered3d_options() -> None:
    from woundroll.case import load_case

    case = load_case(
        "pet1-26.7N",
        [
            "contact.model=layered-3d",
            "contact.layered_depth=2 mm",
            "contact.layers_per_shell=4",
            "contact.options3d.n_fine=5",
        ],
    )
    opts = case.contact.model_options()
    assert isinstance(opts, Layered3DOptions)
    assert opts.layered_depth == pytest.approx(2e-3)
    assert opts.layers_per_shell == 4
    assert opts.base.n_fine == 5
