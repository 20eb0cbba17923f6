"""The 3D loadings extend past their first depth (``stop`` / ``extend_to``) as plane strain does.

:func:`woundroll.contact.solid3d.solver.indent3d` and
:func:`woundroll.contact.layered.roll3d.indent_layered3d` go on past ``depth_max`` by the same
step law until ``stop`` says so; :func:`woundroll.contact.roll_stiffness` then solves the 3D
model once where it solved it twice (docs/contact.md, "3D model"). Coarse meshes: these
check the loading's bookkeeping, not the physics (the mesh study does that).
"""

from __future__ import annotations

import dataclasses
import json
from typing import Any

import numpy as np
import pytest

from woundroll.contact.heads import Head
from woundroll.contact.layered.roll3d import Layered3DOptions, indent_layered3d
from woundroll.contact.solid3d.linsolve import pardiso_available
from woundroll.contact.solid3d.solver import Contact3DOptions, indent3d
from woundroll.contact.spring import FIT_REACH
from woundroll.errors import InputError
from woundroll.materials import Core, Pfeiffer, Web

#: a solver reproducible to the bit (the default mixed precision is to ~1e-12)
EXACT_SOLVER = "pardiso" if pardiso_available() else "splu"

R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
PET1 = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
RIGID = Core(outer_radius=R_CORE)
SPHERE = Head("sphere", 0.0125)
#: one mesh whatever the depth: every size given (the default sizes follow depth_max)
MESH = {
    "tangential_size": 5e-4,
    "fine_halfwidth": 3.2e-3,
    "axial_size": 5e-4,
    "fine_halflength": 3.2e-3,
    "surface_size": 3e-4,
    "radial_growth": 1.6,
    "tangential_growth": 1.6,
    "axial_growth": 1.6,
    "locality_cut": True,
}
#: the first depth, its increments, and the depth past which the test's ``stop`` ends
FIRST, STEPS, STOP_AT = 2e-4, 4, 4.5e-4
#: the depth the loading stops at: the first past STOP_AT by d_k = FIRST (k / STEPS)^1.5
K_STOP = 7
DEEP = FIRST * (K_STOP / STEPS) ** 1.5


def pet_profile(n: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """The synthetic PET1 profile of test_contact3d.py (30 kPa at the surface to ~1 MPa)."""
    r = np.linspace(R_CORE, R_OUT, n)
    return r, -(30e3 + 1e6 * (R_OUT - r) / (R_OUT - R_CORE))


def stop_past(depth: float, calls: list[int] | None = None):  # noqa: ANN201
    """``stop(delta, force)``: True once the depth reaches ``depth``."""

    def stop(delta: np.ndarray, force: np.ndarray) -> bool:
        assert delta.size == force.size and delta[0] == 0.0
        if calls is not None:
            calls.append(delta.size)
        return bool(delta[-1] >= depth)

    return stop


def test_extended_loading_is_the_direct_solve_to_its_depth() -> None:
    """Loaded to FIRST by 4 increments and on by the same law (d_k = FIRST (k/4)^1.5) until
    the stop at k = 7, against a direct solve to d_7 in 7 increments on the same mesh: the
    same depths (to rounding), the same gap tolerance (1e-3 of the same first increment),
    the same arithmetic. F(d), a(d), the fields at the last depth and the work counters
    agree to 1e-9 (rounding of the depths; measured 2e-14 on F, 4e-14 on sigma_r). PARDISO
    in double precision: the two solves order the unknowns differently (the surface nodes
    the contact may reach come last, found from each one's depth_max), which the default's
    single-precision factorisation turns into differences of its refinement tolerance (6e-6
    on F), and this test is of the loading's arithmetic, not of the solver."""
    r, s = pet_profile()
    opts = Contact3DOptions(n_steps=STEPS, n_fine=5, solver=EXACT_SOLVER, **MESH)
    calls: list[int] = []
    ext = indent3d(
        PET1,
        RIGID,
        r,
        s,
        head=SPHERE,
        depth_max=FIRST,
        options=opts,
        stop=stop_past(STOP_AT, calls),
        extend_to=1e-3,
    )
    direct = indent3d(
        PET1,
        RIGID,
        r,
        s,
        head=SPHERE,
        depth_max=DEEP,
        options=dataclasses.replace(opts, n_steps=K_STOP),
    )
    assert calls == list(range(2, K_STOP + 2))  # after every increment, the origin included
    assert ext.mesh_shape == direct.mesh_shape and ext.n_dof == direct.n_dof
    np.testing.assert_allclose(ext.delta, direct.delta, rtol=1e-12)
    np.testing.assert_allclose(ext.force, direct.force, rtol=1e-9)
    np.testing.assert_allclose(ext.half_width, direct.half_width, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(ext.half_length, direct.half_length, rtol=1e-9, atol=1e-12)
    scale = float(np.max(np.abs(direct.sigma_r - direct.sigma_r_pre)))
    np.testing.assert_allclose(ext.sigma_r, direct.sigma_r, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(
        ext.surface_pressure, direct.surface_pressure, rtol=0, atol=1e-9 * direct.peak_pressure[-1]
    )
    assert ext.sigma_r_history.shape == direct.sigma_r_history.shape
    assert ext.at_depth(0.9 * DEEP).force == pytest.approx(direct.at_depth(0.9 * DEEP).force)
    assert ext.stats["factorisations"] == direct.stats["factorisations"]


def test_stop_before_the_first_depth_keeps_its_increments() -> None:
    """A hard roll stops before depth_max: the curve is the first increments of the full
    solve (the same arithmetic: equal to the last bit), and extend_to changes nothing there;
    without ``stop`` ``extend_to`` is ignored (as in 2D). PARDISO in double precision: the
    default's single-precision factorisation is reproducible to ~1e-12, not to the bit (MKL
    picks its kernels by the arrays' memory alignment), and this test is of the loading's
    arithmetic, not of the solver."""
    r, s = pet_profile()
    opts = Contact3DOptions(n_steps=STEPS, n_fine=5, solver=EXACT_SOLVER, **MESH)
    kw = {"head": SPHERE, "depth_max": DEEP, "options": dataclasses.replace(opts, n_steps=K_STOP)}
    full = indent3d(PET1, RIGID, r, s, **kw)
    early = indent3d(PET1, RIGID, r, s, stop=stop_past(FIRST), extend_to=1e-3, **kw)
    assert early.delta.size == STEPS + 1 and early.delta[-1] == pytest.approx(FIRST)
    np.testing.assert_array_equal(early.force, full.force[: STEPS + 1])
    assert early.stats["factorisations"] < full.stats["factorisations"]
    ignored = indent3d(PET1, RIGID, r, s, extend_to=1e-3, **kw)
    np.testing.assert_array_equal(ignored.force, full.force)


def test_extend_to_beyond_the_reach_names_its_field() -> None:
    r, s = pet_profile()
    opts = Contact3DOptions(n_steps=2, n_fine=5, **MESH)
    with pytest.raises(InputError) as e:  # half the sphere's radius: 6.25 mm
        indent3d(
            PET1, RIGID, r, s, head=SPHERE, depth_max=FIRST, options=opts,
            stop=stop_past(1.0), extend_to=7e-3,
        )  # fmt: skip
    assert e.value.field == "extend_to"


@pytest.mark.slow  # 15 s on the loaded 2-core machine
def test_extended_layered_loading_is_the_direct_solve() -> None:
    """The layered 3D roll (mu 0.3: the interfaces slip near the head) shares the loading:
    extended past its first depth it is the direct solve to the stop's depth on the same
    mesh and layered zone (1.5 mm of 5-layer shells), to 1e-7 (the interface passes stop at
    a relative change of 1e-5, from the same start: equal to rounding, measured 1e-12)."""
    r, s = pet_profile()
    base = Contact3DOptions(n_steps=2, n_fine=4, **MESH)
    lopts = Layered3DOptions(base=base, layered_depth=1.5e-3, layers_per_shell=5)
    kw = {"head": SPHERE, "friction": 0.3}
    ext = indent_layered3d(
        PET1, RIGID, r, s, depth_max=FIRST, options=lopts, stop=stop_past(3e-4), extend_to=1e-3,
        **kw,
    )  # fmt: skip
    k = ext.delta.size - 1
    assert k == 3  # FIRST (3/2)^1.5 = 3.7e-4, the first depth past 3e-4
    direct = indent_layered3d(
        PET1,
        RIGID,
        r,
        s,
        depth_max=float(ext.delta[-1]),
        options=dataclasses.replace(lopts, base=dataclasses.replace(base, n_steps=k)),
        **kw,
    )
    np.testing.assert_allclose(ext.delta, direct.delta, rtol=1e-12)
    np.testing.assert_allclose(ext.force, direct.force, rtol=1e-7)
    assert ext.stats["interface_passes"] == direct.stats["interface_passes"]


# ------------------------------------------------------------------ roll_stiffness, the CLI

COARSE = Contact3DOptions(
    n_fine=5, n_steps=8, radial_growth=1.6, tangential_growth=1.6, axial_growth=1.6
)


def _counted(monkeypatch: pytest.MonkeyPatch, entry: Any, extends: bool) -> list[float]:
    """The '3d' registry entry ``entry`` with its solve wrapped to count the calls (their
    first depths); ``extends`` False: as before the 3D loading could be extended."""
    from woundroll.contact import models

    depths: list[float] = []

    def solve(*args, **kw):  # noqa: ANN002, ANN003, ANN202
        depths.append(kw["depth_max"])
        if not extends:
            kw.pop("stop", None), kw.pop("extend_to", None)
        return entry.solve(*args, **kw)

    counted = dataclasses.replace(entry, solve=solve, extends=extends)
    monkeypatch.setitem(models.ROLL_MODELS, "3d", counted)
    return depths


@pytest.mark.slow  # three coarse 3D solves of PET2 53.4 N: ~15 s on the loaded machine
def test_roll_stiffness_solves_3d_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """PET2 53.4 N under the Rho-meter (coarse mesh), first depth 1 mm (as before the
    guide): without the extension roll_stiffness solved the 3D model twice (1 mm, then
    1.1 x 1.25 d_max); with it once, the curve going on past 1 mm until the stop. The two
    springs differ by the meshes (sized for 1 mm here, for the deeper depth there) and the
    steps: the striker's depth within 2 % (measured 0.8 %; alpha 1 %, beta 5 %)."""
    import sys
    from pathlib import Path

    from woundroll.contact import models, roll_stiffness
    from woundroll.instruments import get_instrument

    sys.path.insert(0, str(Path(__file__).parent))
    from test_real_profiles import real_roll

    web, core, r, s = real_roll("pet2-53.4N")
    rho = get_instrument("rho-meter")
    kw = {"model": "3d", "options3d": COARSE, "start_depth": 1e-3}
    entry = models.ROLL_MODELS["3d"]
    twice = _counted(monkeypatch, entry, extends=False)
    before = roll_stiffness(web, core, r, s, rho, **kw)
    assert len(twice) == 2 and twice[0] == 1e-3
    once = _counted(monkeypatch, entry, extends=True)
    after = roll_stiffness(web, core, r, s, rho, **kw)
    assert once == [1e-3]
    assert after.contact.delta[-1] >= FIT_REACH * after.impact_depth  # extended past 1 mm
    assert not after.extrapolated
    assert after.impact_depth == pytest.approx(before.impact_depth, rel=0.02)


def test_cli_reads_a_table2_roll_with_the_3d_model() -> None:
    """``woundroll run pet2-53.4N --set contact.model='3d'`` (coarse mesh, ~5 s): one solve,
    its first depth from the guide (1.7 mm), reaching past the fit window; a reading on the
    scale."""
    from typer.testing import CliRunner

    from woundroll.app.cli import app

    sets = [
        "contact.model='3d'",
        "contact.options3d.n_fine=5",
        "contact.options3d.n_steps=8",
        "contact.options3d.radial_growth=1.6",
        "contact.options3d.tangential_growth=1.6",
        "contact.options3d.axial_growth=1.6",
    ]
    args = ["run", "pet2-53.4N", "--json"]
    for x in sets:
        args += ["--set", x]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    c = out["contact"]
    assert c["model"] == "3d"
    assert c["depth_max_m"] > 1e-3  # the guide's first depth
    assert c["depth_max_m"] >= FIT_REACH * c["impact_depth_m"]  # the window inside
    assert 10.0 < out["hardness"]["reading"] < 100.0


class _FirstSolve(Exception):
    """Raised by the stand-in 3D solve: the test wants its first depth only."""


@pytest.mark.parametrize(("case", "guided"), [("pet2-53.4N", True), ("pet1-26.7N", False)])
def test_the_guide_sizes_the_first_3d_solve(
    monkeypatch: pytest.MonkeyPatch, case: str, guided: bool
) -> None:
    """The '3d' entry's first depth is where the CMD-spreading spring's curve would stop,
    STOP_MARGIN x FIT_REACH x its d_max, when that is deeper than FIRST_DEPTH (PET2 53.4 N:
    1.7 mm; the 3D curve stops at 1.76 mm), else FIRST_DEPTH (PET1 26.7 N: 0.9 mm guided,
    1 mm used). No 3D solve here: the stand-in stops at the first call."""
    import sys
    from pathlib import Path

    from woundroll.contact import models, roll_stiffness
    from woundroll.contact.spring import FIRST_DEPTH, FIT_REACH, STOP_MARGIN
    from woundroll.instruments import get_instrument

    sys.path.insert(0, str(Path(__file__).parent))
    from test_real_profiles import real_roll

    web, core, r, s = real_roll(case)
    rho = get_instrument("rho-meter")
    guide = roll_stiffness(web, core, r, s, rho, model="2d+cmd-spread")
    expected = STOP_MARGIN * FIT_REACH * guide.impact_depth
    assert (expected > FIRST_DEPTH) is guided
    depths: list[float] = []

    def solve(*args, **kw):  # noqa: ANN002, ANN003, ANN202
        depths.append(kw["depth_max"])
        raise _FirstSolve

    entry = dataclasses.replace(models.ROLL_MODELS["3d"], solve=solve)
    monkeypatch.setitem(models.ROLL_MODELS, "3d", entry)
    with pytest.raises(_FirstSolve):
        roll_stiffness(web, core, r, s, rho, model="3d")
    assert depths == [pytest.approx(max(expected, FIRST_DEPTH), rel=1e-12)]
    depths.clear()
    with pytest.raises(_FirstSolve):  # a given first depth is kept (no guide)
        roll_stiffness(web, core, r, s, rho, model="3d", start_depth=5e-4)
    assert depths == [5e-4]


@pytest.mark.parametrize("depth", [1.0e-3, 1.2641e-3, 1.446e-3, 1.712e-3, 2.1e-3])
def test_a_cmd_node_sits_on_the_cylinders_end(depth: float) -> None:
    """Whatever depth the mesh is sized for, a CMD node lies on the Rho-meter cylinder's
    sharp end (within 1e-12 of L/2, inside it: the head reaches it), so the load-carrying
    length does not move with depth_max (it moved by up to an element, F(d) by up to 4 %,
    docs/contact.md "Mesh"); the elements stay no larger than the default size."""
    import math

    from woundroll.contact.solid3d.solver import _mesh_under_the_head
    from woundroll.instruments import get_instrument

    head = Head.from_instrument(get_instrument("rho-meter"))
    opts = Contact3DOptions()
    mesh = _mesh_under_the_head(PET1, RIGID, R_OUT, head, depth, opts)
    half = 0.5 * float(head.length)
    k = int(np.argmin(np.abs(mesh.z - half)))
    assert mesh.z[k] <= half and mesh.z[k] == pytest.approx(half, rel=1e-11)
    assert np.isfinite(head.lift(0.0, mesh.z[k]))
    a_y = head.footprint(depth, R_OUT)[0]
    size = min(half / 12.0, a_y / 2.0)
    assert np.all(np.diff(mesh.z[: k + 1]) <= size * (1 + 1e-12))
    assert math.isclose(float(np.ptp(np.diff(mesh.z[: k + 1]))), 0.0, abs_tol=1e-12)
