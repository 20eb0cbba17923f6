"""Convergence of the contact model on the rolls the pipeline runs (woundroll.contact).

The pre-impact profiles come from the winding model (``woundroll.winding.hakiel.wind``) on
the bundled cases, and the head is the Rho-meter's bundled preset
(``get_instrument("rho-meter")``: radius 7.820 mm since its calibration, length 2.54 cm;
docs/contact.md prints the head it uses, generated). The depths are fixed inputs, near the
``depth_max`` the pipeline's depth search ends at for these cases (1.25 x the impact's
maximum depth): 1.0 mm (PET1 26.7 N), 2.1 mm (PET2 26.7 N), 1.54 mm (PET2 80 N), 0.73 mm
(PET1 46.7 N).

Each mesh parameter is refined alone from the defaults and F(d) over 0.2-1 depth_max must
move by less than 2 % (the project's discretisation bar). The defect these tests pin: the
earlier default (straight-edged elements with full hoop-strain integration) locked in the
far field, where the hoop-stiff roll (E_theta / E_r ~ 1e4 at the surface) bends
inextensionally, and was 7 % (PET1) and 18 % (PET2) too stiff; refining the tangential
growth alone moved F by that much. ``test_flat_element_without_assumed_hoop_locks`` keeps
that failure visible.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest

from woundroll.contact import ContactOptions, ContactResult, indent
from woundroll.contact.plane_strain.solver import FINE_ZONE

CASES = {"pet1-26.7N": 1.0e-3, "pet2-26.7N": 2.1e-3}
MORE_CASES = {"pet2-80N": 1.54e-3, "pet1-46.7N": 0.73e-3}
BAR = 0.02  # the project's 2 % bar for discretisation changes of F(d)


@cache
def real_roll(name: str) -> tuple:
    """Web, core and the Hakiel pre-impact profile (radius, sigma_r) of a bundled case."""
    from woundroll.case import load_case
    from woundroll.winding.hakiel import wind

    case = load_case(name)
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    return web, core, np.asarray(w.radius), np.asarray(w.sigma_r)


@cache
def rho_meter_head() -> dict[str, float]:
    from woundroll.instruments import get_instrument

    ins = get_instrument("rho-meter")
    return {"head_radius": ins.head_radius, "head_length": ins.head_length}


def solve(name: str, depth: float, options: ContactOptions) -> ContactResult:
    web, core, radius, sigma_r = real_roll(name)
    return indent(web, core, radius, sigma_r, depth_max=depth, **rho_meter_head(), options=options)


def refinements(
    name: str, depth: float, base: ContactOptions, angles: tuple[float, ...] = (3.0,)
) -> dict[str, ContactOptions]:
    """Each mesh parameter refined alone from ``base`` (sizes halved, growth ratios
    square-rooted, fine zone doubled, far-field element angle capped)."""
    web, _, radius, _ = real_roll(name)
    h = web.thickness
    r_eff = 1.0 / (1.0 / rho_meter_head()["head_radius"] + 1.0 / radius[-1])
    a_geo = math.sqrt(2.0 * r_eff * depth)
    t_size = max(h / 4, a_geo / 40)  # the defaults of ContactOptions
    out = {
        "tangential_growth": {"tangential_growth": base.tangential_growth**0.5},
        "radial_growth": {"radial_growth": base.radial_growth**0.5},
        "surface_size": {"surface_size": h / 4},  # the default is h / 2
        "tangential_size": {"tangential_size": t_size / 2},
        "fine_halfwidth": {"fine_halfwidth": 2 * FINE_ZONE * a_geo},  # the default doubled
    }
    for deg in angles:
        out[f"max_element_angle {deg:g} deg"] = {"max_element_angle": math.radians(deg)}
    return {k: ContactOptions(**{**base.__dict__, **v}) for k, v in out.items()}


def max_change(res: ContactResult, ref: ContactResult, depth: float) -> float:
    """Largest relative change of F(d) over 0.2-1 depth_max (interpolated between steps)."""
    d = np.linspace(0.2 * depth, depth, 9)
    return float(
        np.max(np.abs(np.interp(d, res.delta, res.force) / np.interp(d, ref.delta, ref.force) - 1))
    )


# slow: a refined-mesh contact solve per case (~25 s together); the mesh convergence tests of
# tests/contact/test_convergence.py stay in the default suite
@pytest.mark.slow
@pytest.mark.parametrize("name", list(CASES))
def test_default_mesh_converged_on_real_profiles(name: str) -> None:
    """Default mesh vs each parameter refined alone (8 depth increments on both: the mesh
    error does not depend on the steps; the step study is the next test). Measured changes:
    at most 0.15 % (PET1) and 0.07 % (PET2), from the radial growth; the far-field
    parameters (tangential growth, element angle) 0.01 %."""
    depth = CASES[name]
    base_opts = ContactOptions(n_steps=8)
    base = solve(name, depth, base_opts)
    for label, opts in refinements(name, depth, base_opts).items():
        res = solve(name, depth, opts)
        assert res.n_elements > base.n_elements, label  # it is a refinement
        assert max_change(res, base, depth) < BAR, label


@pytest.mark.parametrize("name", list(CASES))
def test_default_steps_converged_on_real_profiles(name: str) -> None:
    """16 (default) vs 48 depth increments on the default mesh: measured 0.69 % (PET1),
    0.44 % (PET2), most of it the chords between the coarser depths (at the computed
    depths 0.13 %, test_contact.test_load_step_refinement); at 24: 0.46 %, 0.05 %. Bar 2 %."""
    depth = CASES[name]
    base = solve(name, depth, ContactOptions())
    finer = solve(name, depth, ContactOptions(n_steps=48))
    assert max_change(finer, base, depth) < BAR


def test_flat_element_without_assumed_hoop_locks() -> None:
    """The earlier element (straight edges, hoop strain at all four Gauss points) on PET2:
    square-rooting the tangential growth moves F by ~10 % (membrane locking in the far
    field; 127.7 -> 115.0 N at 24 steps); the default element moves < 0.1 % (measured
    0.001 %). The 5 % threshold sits between the two."""
    name, depth = "pet2-26.7N", CASES["pet2-26.7N"]
    g = ContactOptions().tangential_growth
    for element, hoop, locks in (("flat", False, True), ("curved", True, False)):
        coarse = solve(name, depth, ContactOptions(n_steps=6, element=element, assumed_hoop=hoop))
        fine = solve(
            name,
            depth,
            ContactOptions(n_steps=6, element=element, assumed_hoop=hoop, tangential_growth=g**0.5),
        )
        change = max_change(fine, coarse, depth)
        assert (change > 0.05) if locks else (change < 0.001), element


@pytest.mark.slow
@pytest.mark.parametrize("name", list(CASES | MORE_CASES))
def test_full_convergence_study_on_real_profiles(name: str) -> None:
    """The whole study from the defaults (16 increments, fine zone a_geo / 2, tangential
    growth 1.15 since session 12), four cases: every parameter alone (element angle capped
    at 3 and 1 deg), the step count doubled, and everything refined at once (~5x the
    elements). Measured: at most 0.17 % for any mesh parameter (radial growth, PET1
    46.7 N), 0.93 % for the steps (PET1 46.7 N; the chords between the coarser depths),
    1.1 % all at once. With the earlier defaults (24 increments): 0.18 %, 0.68 %, 0.41 %."""
    depth = (CASES | MORE_CASES)[name]
    base_opts = ContactOptions()
    base = solve(name, depth, base_opts)
    variants = refinements(name, depth, base_opts, angles=(3.0, 1.0))
    variants["n_steps"] = ContactOptions(n_steps=2 * base_opts.n_steps)
    merged: dict = {}
    for label, opts in variants.items():
        if not label.startswith("max_element_angle"):
            merged.update({k: v for k, v in opts.__dict__.items() if v != getattr(base_opts, k)})
    variants["all at once"] = ContactOptions(**{**base_opts.__dict__, **merged})
    for label, opts in variants.items():
        res = solve(name, depth, opts)
        assert max_change(res, base, depth) < BAR, label


def width_options(h: float, t_size: float, radial: int, tangential: int) -> ContactOptions:
    """The surface ring h / radial thick, the fine tangential size t_size / tangential."""
    return ContactOptions(surface_size=h / radial, tangential_size=t_size / tangential)


def test_semi_contact_width_converged_on_default_mesh() -> None:
    """Issue 14 item 8: the semi-contact width a (it sets the active mass {14}-{18}) within
    2 % of a refined mesh on PET1 26.7 N at 1 mm, as F is. The contact edge is decided by
    the surface ring: refined radially (ring h / 1, 2, 4) and tangentially (t, t / 2, t / 4)
    the width rises with the ring and falls with t. On the bundled head (7.820 mm) and
    today's defaults: default mesh (ring h / 2) 0.597 mm against 0.596 mm on (h / 4, t / 2);
    one ring per layer 0.540 mm, 9 % low, which this test would fail. The whole 3 x 3 study
    with its Richardson estimate is generated in docs/contact.md (``contact.width``). The
    issue's independent FE reference, 0.518 mm, is for the former 6.565 mm head and is not
    compared here (docs/history.md has that study)."""
    name, depth = "pet1-26.7N", CASES["pet1-26.7N"]
    web, _, radius, _ = real_roll(name)
    r_eff = 1.0 / (1.0 / rho_meter_head()["head_radius"] + 1.0 / radius[-1])
    t_size = max(web.thickness / 4, math.sqrt(2.0 * r_eff * depth) / 40)
    # the default increments resolve the width; far fewer (8) make it markedly smaller (the
    # edge follows the pressure tail, which the step error moves)
    default = solve(name, depth, ContactOptions())
    refined = solve(name, depth, width_options(web.thickness, t_size, 4, 2))
    old = solve(name, depth, width_options(web.thickness, t_size, 1, 1))
    a_ref = refined.half_width[-1]
    assert default.half_width[-1] == pytest.approx(a_ref, rel=BAR)
    assert abs(old.half_width[-1] / a_ref - 1) > 0.05  # one ring per layer: ~11 % low
    # F hardly moves with the ring (0.04 %): the width, not the force, needed the ring
    assert default.force[-1] == pytest.approx(old.force[-1], rel=0.002)
