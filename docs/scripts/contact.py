"""Generators of docs/contact.md's numbers (docs/scripts/regenerate.py runs them): the mesh
and step convergence of the 2D contact model on the rolls the pipeline runs, and the
semi-contact width's convergence, on today's defaults (``ContactOptions()``). The cases,
depths, head and refinements are those of tests/contact/test_real_profiles.py (imported
from there, so that the page shows what the tests measure). Cost: about 40 2D contact
solves, a few minutes on a quiet 2-core machine."""

from __future__ import annotations

import importlib.util
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]


@cache
def _test_module(name: str) -> Any:
    """tests/contact/<name>.py as a module: the page shows the tests' own problems."""
    path = ROOT / "tests" / "contact" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"docs_{name}", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _tests() -> Any:
    """tests/contact/test_real_profiles.py (its cases and helpers)."""
    return _test_module("test_real_profiles")


@cache
def _solve(name: str, options: Any) -> Any:
    t = _tests()
    return t.solve(name, (t.CASES | t.MORE_CASES)[name], options)


def _variants(name: str) -> dict[str, Any]:
    """The refinements of the slow full study, labelled as the page shows them."""
    from woundroll.contact import ContactOptions

    t = _tests()
    base = ContactOptions()
    depth = (t.CASES | t.MORE_CASES)[name]
    ref = t.refinements(name, depth, base, angles=(3.0, 1.0))
    v = {
        f"tangential growth {base.tangential_growth:g} -> {base.tangential_growth**0.5:.3f}": ref[
            "tangential_growth"
        ],
        "element angle capped at 3 deg": ref["max_element_angle 3 deg"],
        "element angle capped at 1 deg": ref["max_element_angle 1 deg"],
        "surface ring h / 2 -> h / 4": ref["surface_size"],
        f"radial growth {base.radial_growth:g} -> {base.radial_growth**0.5:.3f}": ref[
            "radial_growth"
        ],
        "fine tangential size / 2": ref["tangential_size"],
        "fine zone doubled": ref["fine_halfwidth"],
        f"increments {base.n_steps} -> {2 * base.n_steps}": ContactOptions(
            n_steps=2 * base.n_steps
        ),
    }
    merged: dict[str, Any] = {}
    for label, opts in v.items():
        if "angle" not in label:
            merged.update({k: x for k, x in opts.__dict__.items() if x != getattr(base, k)})
    v["all of these at once"] = ContactOptions(**{**base.__dict__, **merged})
    return v


def refinement() -> str:
    """Each mesh parameter refined alone from the defaults, the steps doubled, and all at
    once: largest change of F(d) over 0.2-1 depth_max, four bundled rolls."""
    from woundroll.contact import ContactOptions

    t = _tests()
    cases = t.CASES | t.MORE_CASES
    names = list(cases)
    label = {n: f"{n} ({1e3 * d:g} mm)" for n, d in cases.items()}
    base = {n: _solve(n, ContactOptions()) for n in names}
    lines = [
        "| refinement | " + " | ".join(label[n] for n in names) + " |",
        "|---|" + "---|" * len(names),
        "| F at depth_max, default mesh [N] | "
        + " | ".join(f"{base[n].force[-1]:.2f}" for n in names)
        + " |",
        "| elements, default mesh | " + " | ".join(f"{base[n].n_elements}" for n in names) + " |",
    ]
    variants = {n: _variants(n) for n in names}
    for row in variants[names[0]]:
        cells = []
        for n in names:
            res = _solve(n, variants[n][row])
            cells.append(f"{100 * t.max_change(res, base[n], cases[n]):.3f} %")
        lines.append(f"| {row} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def width() -> str:
    """The semi-contact width of PET1 26.7 N at 1 mm against the surface ring (h / 1, 2, 4)
    and the fine tangential size (t, t / 2, t / 4), with Richardson in the ring size."""
    import math

    t = _tests()
    name, depth = "pet1-26.7N", t.CASES["pet1-26.7N"]
    web, _, radius, _ = t.real_roll(name)
    r_eff = 1.0 / (1.0 / t.rho_meter_head()["head_radius"] + 1.0 / radius[-1])
    t_size = max(web.thickness / 4, math.sqrt(2.0 * r_eff * depth) / 40)
    a = {
        (r, k): 1e3 * _solve(name, t.width_options(web.thickness, t_size, r, k)).half_width[-1]
        for r in (1, 2, 4)
        for k in (1, 2, 4)
    }
    lines = ["| surface ring | t | t / 2 | t / 4 |", "|---|---|---|---|"]
    for r in (1, 2, 4):
        ring = "h (one ring per layer)" if r == 1 else f"h / {r}" + (" (default)" if r == 2 else "")
        lines.append(f"| {ring} | " + " | ".join(f"{a[r, k]:.3f}" for k in (1, 2, 4)) + " |")
    # Richardson from the rings h / 2 and h / 4 at each tangential size, with the order
    # observed from the three rings
    rich = []
    for k in (1, 2, 4):
        a1, a2, a4 = a[1, k], a[2, k], a[4, k]
        ratio = (a2 - a1) / (a4 - a2) if a4 != a2 else float("inf")
        p = math.log2(ratio) if ratio > 1 else float("nan")
        rich.append("" if not math.isfinite(p) else f"{a4 + (a4 - a2) / (2**p - 1):.2f}")
    lines.append("| Richardson in the ring size | " + " | ".join(rich) + " |")
    return "\n".join(lines)


def width_default() -> str:
    """The default mesh's semi-contact width at PET1 26.7 N, 1 mm."""
    from woundroll.contact import ContactOptions

    a = 1e3 * _solve("pet1-26.7N", ContactOptions()).half_width[-1]
    return f"{a:.3f} mm"


def fields() -> str:
    """F, the largest radial pressure and the peak nodal contact pressure at depth_max on
    PET1 and PET2 26.7 N for the default step count, 3x and 6x it."""
    from woundroll.contact import ContactOptions

    t = _tests()
    n0 = ContactOptions().n_steps
    steps = (n0, 3 * n0, 6 * n0)
    lines = [
        "| roll (depth) | steps | F [N] | largest radial pressure [MPa] "
        "| peak nodal contact pressure [MPa] |",
        "|---|---|---|---|---|",
    ]
    for name, depth in t.CASES.items():
        for n in steps:
            r = _solve(name, ContactOptions(n_steps=n))
            lines.append(
                f"| {name} ({1e3 * depth:g} mm) | {n}{' (default)' if n == n0 else ''} "
                f"| {r.force[-1]:.2f} | {-r.sigma_r.min() / 1e6:.2f} "
                f"| {r.contact_pressure_history[-1].max() / 1e6:.2f} |"
            )
    return "\n".join(lines)


@cache
def _own(name: str, update: bool) -> Any:
    """The 2D contact on the winding model's own profile of a bundled roll, a 10 mm head
    2 cm long, to 1 mm, with or without the E_r update; default options."""
    from woundroll.contact import indent

    web, core, radius, sigma_r = _tests().real_roll(name)
    return indent(
        web,
        core,
        radius,
        sigma_r,
        depth_max=1e-3,
        head_radius=10e-3,
        head_length=0.02,
        update_modulus=update,
    )


def _e(x: float) -> str:
    """``x`` in the docs' short scientific form, 3 digits: 2.03e8, not 2.03e+08."""
    m, _, e = f"{x:.2e}".partition("e")
    return f"{m}e{int(e)}"


def own_profile() -> str:
    """The sentence on PET1 26.7 N and 46.7 N with the winding model's profile."""
    a, b = _own("pet1-26.7N", True), _own("pet1-26.7N", False)
    c, d = _own("pet1-46.7N", True), _own("pet1-46.7N", False)
    return (
        f"F = {a.force[-1]:.0f} N, alpha = {_e(a.alpha)} N/m^2, beta = {_e(a.beta)} "
        f"N/m, R^2 = {a.fit_r2:.4f}, a = {1e3 * a.half_width[-1]:.2f} mm; no update: "
        f"F = {b.force[-1]:.0f} N, a = {1e3 * b.half_width[-1]:.1f} mm. At 46.7 N: "
        f"F = {c.force[-1]:.0f} N (update) and {d.force[-1]:.0f} N (no update)"
    )


def memory() -> str:
    """The size of the stress histories a result keeps, PET1 26.7 N on the default mesh."""
    from woundroll.contact import ContactOptions

    r = _solve("pet1-26.7N", ContactOptions())
    n_rows, n_el = r.sigma_r_history.shape
    mb = 3 * n_rows * n_el * 8 / 1e6
    return f"3 x {n_rows} x {n_el} floats, {mb:.1f} MB, at the default mesh (PET1 26.7 N)"


def _contact_tests() -> Any:
    """tests/contact/test_contact.py (its Hertz problem)."""
    return _test_module("test_contact")


@cache
def _hertz() -> tuple[float, float, float, float]:
    """Hertz line contact, the test's problem (its ``hertz`` fixture's arguments): the
    range of the closed-form half-width [m] and the largest deviations of the half-width
    and the peak pressure from the closed forms [%]."""
    import math

    import numpy as np

    from woundroll.contact import ContactOptions, indent
    from woundroll.materials.web import Core

    t = _contact_tests()
    E, nu, R, roll = t.HERTZ_E, t.HERTZ_NU, t.HERTZ_R, t.HERTZ_ROLL
    opts = ContactOptions(
        n_steps=4, step_exponent=1.0, tangential_size=5e-5, surface_size=5e-5, fine_halfwidth=2e-3
    )
    res = indent(
        t.isotropic_web(E, nu),
        Core(outer_radius=0.2),
        np.array([0.2, roll]),
        np.zeros(2),
        head_radius=R,
        head_length=1.0,
        depth_max=2e-4,
        options=opts,
    )
    r_eff = 1 / (1 / R + 1 / roll)
    e_star = E / (1 - nu**2)
    p = res.force_per_length[1:]
    a = np.sqrt(4 * p * r_eff / (math.pi * e_star))
    da = 100 * np.max(np.abs(res.half_width[1:] / a - 1))
    dp = 100 * np.max(np.abs(res.peak_pressure[1:] / (2 * p / (math.pi * a)) - 1))
    return float(a[0]), float(a[-1]), float(da), float(dp)


def hertz_width() -> str:
    """The half-width row of the verification table (a cell)."""
    lo, hi, da, _ = _hertz()
    return f"a = {1e3 * lo:.2f}-{1e3 * hi:.2f} mm: within {da:.1f} %"


def hertz_pressure() -> str:
    """The peak-pressure row of the verification table (a cell)."""
    return f"within {_hertz()[3]:.2f} %"


@cache
def _ring() -> tuple[list[float], float, float, float]:
    """The orthotropic ring on a rigid core under external pressure (the test's problem,
    tests/contact/test_contact.py::test_orthotropic_ring_under_external_pressure): the
    surface u_r against u = A r^k + B r^-k for E_t/E_r = 1, 100, 1e4 on the default
    tangential grading, and the tangential displacement and the spread of u_r."""
    import math

    import numpy as np

    from woundroll.contact import ContactOptions
    from woundroll.materials.radial_modulus import Constant
    from woundroll.materials.web import Web

    t = _contact_tests()
    growth = ContactOptions().tangential_growth
    errs, rest = [], 0.0
    for ratio in (1.0, 100.0, 1e4):
        E_r = 5e6
        web = Web(
            thickness=t.H,
            width=0.1,
            E_theta=ratio * E_r,
            radial_modulus=Constant(E_r),
            nu_theta_z=0.0,
            G_r_theta=E_r / 2,
        )
        mesh = t.build_mesh(
            t.R_CORE,
            t.R_OUT,
            surface_size=2e-4,
            radial_growth=1.1,
            tangential_size=1e-3,
            fine_halfwidth=2e-3,
            tangential_growth=growth,
        )
        roll = t._Roll(
            web, t.RIGID, np.array([t.R_CORE, t.R_OUT]), np.zeros(2), mesh, ContactOptions()
        )
        C11, C12, C22, G = roll.moduli(roll.sigma_pre)
        lu = t._factorize(roll, (C11, C12, C22, G))
        p = 1e4
        surf = roll.surface
        arc = np.diff(mesh.theta) * t.R_OUT
        trib = 0.5 * (np.concatenate([[0.0], arc]) + np.concatenate([arc, [0.0]]))
        F = np.zeros(2 * mesh.n_nodes)
        F[2 * surf] = -p * trib
        u = np.zeros_like(F)
        u[roll.free] = lu.solve(F[roll.free])
        k = math.sqrt(C22[0] / C11[0])
        a, b = t.R_CORE, t.R_OUT
        du_b = k * (b ** (k - 1) + a ** (2 * k) * b ** (-k - 1))
        A = -p / (C11[0] * du_b)
        u_exact = A * (b**k - a ** (2 * k) * b**-k)
        u_fe = u[2 * surf]
        errs.append(100 * float(np.max(np.abs(u_fe / u_exact - 1))))
        rest = max(
            rest,
            float(np.max(np.abs(u[2 * surf + 1]))) / abs(u_exact),
            float(np.ptp(u_fe)) / abs(u_exact),
        )
    far = math.degrees(float(np.max(np.diff(mesh.theta))))
    return errs, rest, growth, far


def ring() -> str:
    """The ring row's result cell."""
    errs, rest, _, _ = _ring()
    return (
        "surface u_r within "
        + ", ".join(f"{e:.3f} %" for e in errs)
        + f"; u_theta and the spread of u_r around the ring {rest:.0e} of u_r"
    )


def ring_grading() -> str:
    """The ring row's mesh: the default tangential growth and the largest far element."""
    _, _, growth, far = _ring()
    return f"growth {growth:g}, far elements up to {far:.0f} deg"


@cache
def _synthetic(head_radius: float, update: bool = True) -> Any:
    """The test's synthetic PET1 profile (30 kPa at the surface rising to ~1 MPa at the
    core, rigid core), a head ``head_radius`` 2 cm long, to 1 mm; default options."""
    from woundroll.contact import indent

    t = _contact_tests()
    r, s = t.pet_profile()
    return indent(
        t.PET1,
        t.RIGID,
        r,
        s,
        depth_max=1e-3,
        head_radius=head_radius,
        head_length=0.02,
        update_modulus=update,
    )


def synthetic() -> str:
    """The example's numbers: the 10 mm head with and without the update."""
    a, b = _synthetic(0.01), _synthetic(0.01, False)
    return (
        f"F = {a.force[-1]:.0f} N, alpha = {_e(a.alpha)} N/m^2, beta = {_e(a.beta)} N/m, "
        f"R^2 = {a.fit_r2:.5f}, max residual {100 * a.fit_max_rel_residual:.1f} % of F_max, "
        f"a = {1e3 * a.half_width[-1]:.2f} mm; without the update F = {b.force[-1]:.0f} N and "
        f"a = {1e3 * b.half_width[-1]:.2f} mm"
    )


def update_row() -> str:
    """The verification table's cell: F at 1 mm without and with the update."""
    a, b = _synthetic(0.01), _synthetic(0.01, False)
    return f"F(1 mm) = {b.force[-1]:.0f} N vs {a.force[-1]:.0f} N"


def head_sweep() -> str:
    """F and a against the head radius on the synthetic profile."""
    radii = (5e-3, 10e-3, 15e-3, 30e-3)
    res = [_synthetic(r) for r in radii]
    return (
        "("
        + ", ".join(f"{x.force[-1]:.0f}" for x in res)
        + " N for R_h = "
        + ", ".join(f"{1e3 * r:g}" for r in radii)
        + " mm) while a grows ("
        + ", ".join(f"{1e3 * x.half_width[-1]:.2f}" for x in res)
        + " mm)"
    )


def head() -> str:
    """The head of the study: the bundled Rho-meter preset's."""
    h = _tests().rho_meter_head()
    return f"radius {1e3 * h['head_radius']:.3f} mm, length {1e2 * h['head_length']:.2f} cm"


BLOCKS: dict[str, Callable[[], str]] = {
    "head": head,
    "synthetic": synthetic,
    "head_sweep": head_sweep,
    "update_row": update_row,
    "ring": ring,
    "ring_grading": ring_grading,
    "hertz_width": hertz_width,
    "hertz_pressure": hertz_pressure,
    "memory": memory,
    "own_profile": own_profile,
    "fields": fields,
    "refinement": refinement,
    "width": width,
    "width_default": width_default,
}
