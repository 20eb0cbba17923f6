"""Generators of docs/contact.md's numbers (docs/scripts/regenerate.py runs them): the mesh
and step convergence of the 2D contact model on the rolls the pipeline runs, and the
semi-contact width's convergence, on today's defaults (``ContactOptions()``). The cases,
depths, head and refinements are those of tests/contact/test_real_profiles.py (imported
from there, so that the page shows what the tests measure). Cost: about 40 2D contact
solves, a few minutes on a quiet 2-core machine."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]


def _test_module(name: str) -> Any:
    """tests/contact/<name>.py as a module: the page shows the tests' own problems."""
    import records

    return records.test_module(f"contact/{name}.py")


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


# ------------------------------------------------------- step control and verification


@cache
def _thin_stack(
    k1: float, k2: float, eps_max: float, n: int, midpoint: bool
) -> tuple[float, float]:
    """The thin stack of tests/contact/test_contact.py::
    test_hypoelastic_update_integrates_the_pfeiffer_law (1 mm wound on a 1 m rigid core,
    outer surface pushed in radially through stiff springs, uniform steps to ``eps_max``),
    driven by the same increment function as ``indent``: the largest error of P over the
    elements against P = K1 (exp(K2 eps) - 1) at each element's strain, and the mean P."""
    err, p_mean, _eps = _contact_tests().thin_stack_run(k1, k2, eps_max, n, midpoint)
    return err, p_mean


#: Table 2's Pfeiffer constants of PET2 and PET1 (K1 [Pa], K2 [-]), as in the test
PET2_LAW, PET1_LAW = (20270.0, 26.24), (4.62e3, 123.88)


def thin_stack() -> str:
    """The paragraph's errors: PET2 to eps 0.2, midpoint and forward Euler at 24/48/96
    uniform steps; PET1 to eps 0.08, midpoint at 24-192."""
    mid = [_thin_stack(*PET2_LAW, 0.2, n, True)[0] for n in (24, 48, 96)]
    eul = [_thin_stack(*PET2_LAW, 0.2, n, False)[0] for n in (24, 48, 96)]
    p1 = [_thin_stack(*PET1_LAW, 0.08, n, True)[0] for n in (24, 48, 96, 192)]

    def pc(xs: list[float]) -> str:
        return ", ".join(f"{100 * x:.2g} %" for x in xs)

    return (
        f"the largest error of P over the elements is {pc(mid)} for 24, 48, 96 midpoint "
        f"steps (second order), {pc(eul)} for forward Euler (first order). With PET1's "
        f"constants to eps = 0.08 (K2 eps = {PET1_LAW[1] * 0.08:.1f}) the midpoint errors are "
        f"{pc(p1)} for 24 to 192 steps"
    )


def thin_stack_row() -> str:
    """The verification table's cell."""
    import math

    mid = [_thin_stack(*PET2_LAW, 0.2, n, True)[0] for n in (24, 48, 96)]
    eul = [_thin_stack(*PET2_LAW, 0.2, n, False)[0] for n in (48, 96)]
    k1, k2 = PET2_LAW
    mean = _thin_stack(*PET2_LAW, 0.2, 96, True)[1] / (k1 * math.expm1(k2 * 0.2)) - 1
    return (
        "midpoint " + ", ".join(f"{100 * x:.2g} %" for x in mid) + " at 24, 48, 96 steps; "
        "Euler " + ", ".join(f"{100 * x:.2g} %" for x in eul) + " at 48, 96; the stack's mean "
        f"P vs P(delta/t) at 96 steps: {100 * abs(mean):.2f} %"
    )


@cache
def _pet(options: Any = None, **kw: Any) -> Any:
    """The test's PET1 roll on the synthetic profile, R_h 10 mm, 2 cm, 1 mm."""
    from woundroll.contact import indent

    t = _contact_tests()
    r, s = t.pet_profile()
    return indent(t.PET1, t.RIGID, r, s, depth_max=1e-3, **t.HEAD, options=options)


def _change(a: Any, b: Any, d: Any) -> float:
    import numpy as np

    return float(
        np.max(np.abs(np.interp(d, a.delta, a.force) / np.interp(d, b.delta, b.force) - 1))
    )


def mesh_row() -> str:
    """The mesh-refinement row (tests/contact/test_contact.py's refinement, 12 steps)."""
    import math

    import numpy as np

    from woundroll.contact import ContactOptions

    t = _contact_tests()
    R_eff = 1 / (1 / t.HEAD["head_radius"] + 1 / t.R_OUT)
    t_size = max(t.H / 4, math.sqrt(2 * R_eff * 1e-3) / 40)
    default = ContactOptions(n_steps=12)
    fine = ContactOptions(
        n_steps=12,
        surface_size=t.H / 2,
        tangential_size=t_size / 2,
        radial_growth=default.radial_growth**0.5,
        tangential_growth=default.tangential_growth**0.5,
    )
    base, ref = _pet(default), _pet(fine)
    d = np.linspace(0.2e-3, 1e-3, 9)
    da = abs(ref.semi_contact_width / base.semi_contact_width - 1)
    return (
        f"mesh refinement (sizes / 2, growth ratios square-rooted: {base.n_elements} -> "
        f"{ref.n_elements} elements), PET1, synthetic profile, R_h 10 mm, 1 mm | F(d) changes "
        f"<= {100 * _change(ref, base, d):.2f} %, a by {100 * da:.1f} %"
    )


def fine_zone_row() -> str:
    """The fine-zone row: the uniformly fine arc doubled."""
    import math

    import numpy as np

    from woundroll.contact import ContactOptions

    t = _contact_tests()
    R_eff = 1 / (1 / t.HEAD["head_radius"] + 1 / t.R_OUT)
    a_geo = math.sqrt(2 * R_eff * 1e-3)
    base = _pet(ContactOptions(n_steps=12))
    wide = _pet(ContactOptions(n_steps=12, fine_halfwidth=2 * a_geo))
    d = np.linspace(0.2e-3, 1e-3, 9)
    return f"F(d) changes <= {100 * _change(wide, base, d):.3f} %"


def step_row() -> str:
    """The step-refinement row: the default steps against three times as many, at the
    default's own depths from 0.2 mm."""
    import numpy as np

    from woundroll.contact import ContactOptions

    n0 = ContactOptions().n_steps
    base, fine = _pet(ContactOptions()), _pet(ContactOptions(n_steps=3 * n0))
    at = base.delta >= 0.2e-3 - 1e-12
    ch = np.interp(base.delta[at], fine.delta, fine.force) / base.force[at] - 1
    worst = 100 * float(np.max(np.abs(ch)))
    return f"step refinement {n0} -> {3 * n0} increments | F(d) changes <= {worst:.2f} %"


def synthetic_extremes() -> str:
    """The largest radial pressure and E_r / E_t under the 10 mm head (inline)."""
    a = _synthetic(0.01)
    t = _contact_tests()
    P = -float(a.sigma_r.min())
    E_r = float(t.PET1.radial_modulus.modulus_at_pressure(P))
    return f"P up to {P / 1e6:.0f} MPa, E_r = K2 P up to {E_r / t.PET1.E_theta:.1f} E_t"


def _step_tests() -> Any:
    return _test_module("test_step_control")


def window() -> str:
    """The slack-ramped Table 3 roll's reading (tests/contact/test_step_control.py, started
    at the model's reach as the profile does for slack sectors) at 24, 48 and 192 steps."""
    t = _step_tests()
    roll = t.table3_roll(3e-3)
    rho = [t.table3_rho(roll, float("inf"), f"n_steps={n}") for n in (24, 48, 192)]
    return " / ".join(f"{x:.2f}" for x in rho) + " Rho at 24, 48 and 192 steps"


def step_accuracy() -> str:
    """The defaults against the references of tests/contact/test_step_control.py: the
    Table 2 rolls against the 48-step explicit midpoint, the taut and slack Table 3 rolls
    against 96 steps at step_tol 0.05 %."""
    t = _step_tests()
    t2 = []
    for name in t.TABLE2:
        rho = t.reading(name)[0]
        ref = t.reading(name, "n_steps=48", "predictor=false")[0]
        t2.append(abs(rho / ref - 1))
    t3 = []
    for slack, start in ((None, 1e-3), (3e-3, float("inf"))):
        roll = t.table3_roll(slack)
        t3.append(abs(t.table3_rho(roll, start) / t.table3_rho(roll, start, *t.REFERENCE) - 1))
    return (
        f"the seven Table 2 rolls read within {100 * max(t2):.2g} % of the 48-step explicit "
        f"midpoint; the test's taut and slack Table 3 rolls within {100 * t3[0]:.2g} % and "
        f"{100 * t3[1]:.2g} % of 96 steps at `step_tol` 0.05 %"
    )


# ------------------------------------------------------------------ 2D slip emulation


def _slip_tests() -> Any:
    """tests/contact/test_slip2d.py (PET2 53.4 N, Rho-meter head, 1.5 mm)."""
    return _test_module("test_slip2d")


@cache
def _slip(friction: float = 0.3, **options: Any) -> Any:
    from woundroll.contact import ContactOptions

    kw = {"slip": "reduced-shear", **options}
    if kw["slip"] == "none":
        kw.pop("slip")
    return _slip_tests().solve(ContactOptions(**kw), friction=friction)


def slip_steps() -> str:
    """F at the test's depth with the slipping share, 12 / 24 / 48 / 96 steps (inline)."""
    t = _slip_tests()
    f = [float(_slip(n_steps=n).force[-1]) for n in (12, 24, 48, 96)]
    return (
        f"F at {1e3 * t.DEPTH:g} mm on PET2 53.4 N: "
        + ", ".join(f"{x:.1f}" for x in f)
        + " N at 12, 24, 48, 96 steps"
    )


def slip_cost() -> str:
    """Passes and factorisations of the default slip solve (inline)."""
    from woundroll.contact import ContactOptions

    res = _slip()
    n = len(res.delta) - 1
    return (
        f"{res.slip_passes / n:.1f} passes per increment on average instead of one "
        f"(PET2 53.4 N to {1e3 * _slip_tests().DEPTH:g} mm, {ContactOptions().n_steps} "
        f"increments: {res.slip_passes} passes, {res.factorisations} factorisations)"
    )


def slip_checks() -> str:
    """The slow tests' measurements: slip / no slip at every depth (8 steps), the largest
    SF outside the zone, the step and surface-ring refinements of the default curve."""
    import numpy as np

    from woundroll.contact import ContactOptions

    t = _slip_tests()
    plain = _slip(slip="none", n_steps=8)
    soft = _slip(n_steps=8)
    ratio = np.asarray(soft.force[1:]) / np.asarray(plain.force[1:])
    sf = np.asarray(soft.slip_factor)[~np.asarray(soft.slipped)]
    base = _slip()
    d = np.linspace(0.2, 1.0, 9) * t.DEPTH
    n0 = ContactOptions().n_steps

    def change(fine: Any) -> float:
        f = np.interp(d, fine.delta, fine.force) / np.interp(d, base.delta, base.force)
        return 100 * float(np.max(np.abs(f - 1)))

    steps = change(_slip(n_steps=3 * n0))
    ring = change(_slip(surface_size=t.real_roll("pet2-53.4N")[0].thickness / 4))
    return (
        f"F(d) with slip is below F(d) without at every depth ({ratio.min():.2f}-"
        f"{ratio.max():.2f} of it on PET2 53.4 N, 8 steps) and falls with the fraction "
        f"(0.1 > 0.01) and with mu (0.6 > 0.3); no element outside the converged zone has "
        f"SF >= 1 (max {sf.max():.3f}); 1 pass per increment raises ConvergenceError; `slow`: "
        f"{n0} -> {3 * n0} steps moves F(d) by {steps:.1f} %, the surface ring halved by "
        f"{ring:.1f} %"
    )


def locking() -> str:
    """The curved element with the full hoop integration against the default (assumed hoop
    strain): F at depth_max on PET2 26.7 N, the study's case (inline)."""
    from woundroll.contact import ContactOptions

    t = _tests()
    name = "pet2-26.7N"
    full = _solve(name, ContactOptions(assumed_hoop=False))
    base = _solve(name, ContactOptions())
    return (
        f"`assumed_hoop=False`: {full.force[-1]:.1f} N instead of {base.force[-1]:.1f} N, "
        f"{name} at {1e3 * t.CASES[name]:g} mm"
    )


def semi_width_reading() -> str:
    """PET1 26.7 N read with the model's semi-contact width and with the paper's accepted
    a = 0.6 cm (the pipeline, bundled case; inline)."""
    import woundroll

    runs = []
    for over in ([], ["tester.semi_contact_width='6 mm'"]):
        res = woundroll.run(woundroll.load_case("pet1-26.7N", over))
        runs.append(res)
    a, b = (r.hardness.to_dict() for r in runs)
    return (
        f"PET1 26.7 N reads {a['rho_fd']:.1f} Rho (FD) with the model's a of "
        f"{1e3 * runs[0].contact.semi_contact_width:.2f} mm at the impact depth, and "
        f"{b['rho_fd']:.1f} Rho with a = 0.6 cm, m_r = {1e3 * b['effective_mass_kg']:.1f} g: "
        f"the FD reading does depend on a, through the active mass; the energy model has no "
        f"mass and reads {a['rho_energy']:.1f} and {b['rho_energy']:.1f}"
    )


def fine_zone_margin() -> str:
    """The contact half-width at the deepest depth solved against a_geo on the study's
    Table 2 rolls (tests/contact/test_real_profiles.py's cases; inline)."""
    import math

    from woundroll.contact import ContactOptions

    t = _tests()
    out = {}
    for name, depth in (t.CASES | t.MORE_CASES).items():
        res = _solve(name, ContactOptions())
        r_eff = 1.0 / (1.0 / t.rho_meter_head()["head_radius"] + 1.0 / res.outer_radius)
        frac = res.half_width[-1] / math.sqrt(2.0 * r_eff * depth)
        mat = name.split("-")[0].upper()
        out[mat] = max(out.get(mat, 0.0), frac)
    return " and ".join(f"{v:.2f} a_geo on the {k} rolls" for k, v in sorted(out.items()))


# ---------------------------------------------------------------------------------------
# assumptions 10 and 11 (live: three and two 2D solves of test_real_profiles' rolls)


def _e1(x: float) -> str:
    """One significant digit in e-notation without a padded exponent: 4e-6."""
    m, e = f"{x:.0e}".split("e")
    return f"{m}e{int(e)}"


def core_tube() -> str:
    """Assumption 10: the plane-stress tube's E_c against the plane-strain one on the
    bundled steel core, and what either change does to F(d) under the head (PET1 26.7 N)."""
    import dataclasses

    from woundroll.contact import ContactOptions, indent

    t = _tests()
    web, core, radius, sigma_r = t.real_roll("pet1-26.7N")
    depth = t.CASES["pet1-26.7N"]
    a, b, E, nu = core.inner_radius, core.outer_radius, core.E, core.nu
    e_strain = E / ((1 + nu) * ((1 - 2 * nu) * b**2 + a**2) / (b**2 - a**2))

    def solve(c: Any) -> Any:
        return indent(
            web, c, radius, sigma_r, depth_max=depth, **t.rho_meter_head(), options=ContactOptions()
        )

    base = _solve("pet1-26.7N", ContactOptions())
    strain = t.max_change(solve(dataclasses.replace(core, stiffness=e_strain)), base, depth)
    rigid = t.max_change(solve(dataclasses.replace(core, stiffness=float("inf"))), base, depth)
    return (
        f"{e_strain / 1e9:.1f} GPa instead of {core.stiffness / 1e9:.1f} GPa for the bundled "
        f"steel core (radii {1e3 * a:.1f}/{1e3 * b:.1f} mm). Under the head it does not "
        f"matter: that change moves F by {_e1(strain)} (PET1 26.7 N, Rho-meter head, "
        f"{1e3 * depth:g} mm), a rigid core by {_e1(rigid)} (the core is "
        f"{1e3 * (radius[-1] - b):.0f} mm below the surface"
    )


def stack_strain() -> str:
    """Assumption 11: the stack's nominal strain under the head at the test rolls' depths,
    from the largest contact pressure and Pfeiffer's law {2} (eps = ln(1 + P/K1) / K2)."""
    import math

    from woundroll.contact import ContactOptions

    t = _tests()
    out = []
    for name, label in (("pet1-26.7N", "PET1"), ("pet2-26.7N", "PET2")):
        res = _solve(name, ContactOptions())
        law = t.real_roll(name)[0].radial_modulus
        p = float(res.peak_pressure[-1])
        eps = math.log(1 + p / law.K1) / law.K2
        out.append(
            f"{eps:.2f} ({label}, P ~ {p / 1e6:.2g} MPa, Rho-meter head at "
            f"{1e3 * t.CASES[name]:g} mm)"
        )
    return "eps ~ " + " and ~ ".join(out)


def model_ratio() -> str:
    """3D against plane strain on the seven Table 2 rolls, from the cached 3D references
    (tests/contact/data/contact3d_reference.json: both models' readings, the same head)."""
    import json

    from woundroll.studies._common import TABLE2

    ref = json.loads((ROOT / "tests" / "contact" / "data" / "contact3d_reference.json").read_text())
    ratios = [ref["cases"][n]["3d"]["rho_fd"] / ref["cases"][n]["2d"]["rho_fd"] for n in TABLE2]
    return f"{min(ratios):.2f}-{max(ratios):.2f} times"


# ---------------------------------------------------------------------------------------
# measured record (docs/scripts/records.py): the probes of "Which model reads a roll" and
# assumption 2b (3D and 61-sector profile runs)


def _records() -> Any:
    import records

    return records


#: the hard roll of assumption 2b: PET1 46.7 N with a 16x higher K2, Poisson ratios varied
HARD = ("web.radial_modulus.K2=2000",)
HARD_RATIOS = (
    ("nu_tr_0", "web.nu_theta_r=0"),
    ("nu_tr_0.25", "web.nu_theta_r=0.25"),
    ("nu_tr_0.3", "web.nu_theta_r=0.3"),
    ("nu_zr_0.3", "web.nu_z_r=0.3"),
)


def _probe_runs() -> list[Any]:
    Run = _records().Run
    return [
        Run("pet3_uniform", "pet3-2.3MPa"),
        Run("pet3_profile", "pet3-2.3MPa"),
        *[Run(f"hard_{k}", "pet1-46.7N", (*HARD, o)) for k, o in HARD_RATIOS],
    ]


def _probe_measure(run: Any) -> dict[str, Any]:
    import numpy as np

    from woundroll.case import load_case
    from woundroll.instruments.definitions import beyond_scale
    from woundroll.pipeline import run as run_case

    if run.id == "pet3_uniform":  # the Table 3 roll without its thickness profile
        out = {}
        for model in ("2d", "2d+cmd-spread", "3d"):
            case = load_case(run.case, [*run.overrides, f"contact.model='{model}'"])
            case = case.model_copy(
                update={"winding": case.winding.model_copy(update={"thickness_profile": None})}
            )
            out[model] = float(run_case(case).hardness.fd.rho)
        return out
    if run.id == "pet3_profile":  # the Table 3 profile: sectors beyond the dial
        p2 = run_case(load_case(run.case, list(run.overrides))).profile
        cs = run_case(load_case(run.case, [*run.overrides, "contact.model='2d+cmd-spread'"]))
        pc = cs.profile
        return {
            "sectors": float(len(p2.z)),
            "saturated_2d_fd": float(np.sum(p2.saturated)),
            "saturated_cmd_spread_energy": float(np.sum(beyond_scale(pc.rho_energy, pc.scale))),
        }
    from woundroll.errors import ConvergenceError

    try:
        res = run_case(load_case(run.case, list(run.overrides)))
    except ConvergenceError as exc:  # recorded: the page says so
        return {"converged": False, "error": str(exc)}
    return {"rho_fd": float(res.hardness.fd.rho)}


MEASUREMENTS: dict[str, Any] = {
    "probes": _records().Measurement(
        models=_records().SOLID,
        about="docs/contact.md's probes: uniform PET3 in each model, the Table 3 profile's "
        "saturated sectors, the hard roll of assumption 2b",
        runs=_probe_runs,
        measure=_probe_measure,
        spot=("hard_nu_tr_0.3",),
        rtol=1e-3,
        reason=(
            "deterministic on one machine; the readings go through iterative contact and "
            "impact solves whose platform rounding is far below 1e-3"
        ),
        cost="uniform PET3 in three models (one 3D), two 61-sector profile runs, four 2D "
        "runs: about 1 CPU min",
    ),
}


def _measured() -> str:
    rec = _records().load("contact.probes")
    return f"measured {rec['measured']} by `docs/scripts/records.py contact.probes`"


def probe_rows() -> str:
    """The uniform PET3 row of the model table (record contact.probes)."""
    r = _records().results("contact.probes")["pet3_uniform"]
    return (
        f"| uniform PET3, 2.3 MPa | {r['2d']:.1f} | {r['2d+cmd-spread']:.1f} | {r['3d']:.1f} | "
        "the Table 3 roll read on the 0-100 scale |"
    )


def probe_pet3() -> str:
    """The Table 3 bullet (record contact.probes)."""
    res = _records().results("contact.probes")
    u, p = res["pet3_uniform"], res["pet3_profile"]
    past = "past" if u["2d"] > 100 else "below"
    return (
        f"the uniform PET3 roll reads {u['2d']:.1f} in plane strain ({past} the dial's 100), "
        f"{u['3d']:.1f} in 3D; on the real Table 3 profile {p['saturated_2d_fd']:.0f} of "
        f"{p['sectors']:.0f} sectors saturate in plane strain (FD reading), against "
        f"{p['saturated_cmd_spread_energy']:.0f} through the CMD-spreading path read by the "
        f"energy model ({_measured()})"
    )


def hard_roll() -> str:
    """Assumption 2b's hard roll (record contact.probes)."""
    res = _records().results("contact.probes")

    def cell(k: str) -> str:
        r = res[f"hard_{k}"]
        return f"{r['rho_fd']:.0f}" if "rho_fd" in r else f"no reading ({r['error']})"

    return (
        f"That roll now reads {cell('nu_tr_0')}, {cell('nu_tr_0.25')}, {cell('nu_tr_0.3')} Rho "
        f"(FD) at nu_tr = 0, 0.25, 0.3; at nu_zr = 0.3: {cell('nu_zr_0.3')} ({_measured()})"
    )


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
    "thin_stack": thin_stack,
    "thin_stack_row": thin_stack_row,
    "mesh_row": mesh_row,
    "fine_zone_row": fine_zone_row,
    "step_row": step_row,
    "synthetic_extremes": synthetic_extremes,
    "window": window,
    "step_accuracy": step_accuracy,
    "slip_steps": slip_steps,
    "slip_cost": slip_cost,
    "slip_checks": slip_checks,
    "locking": locking,
    "semi_width_reading": semi_width_reading,
    "fine_zone_margin": fine_zone_margin,
    "core_tube": core_tube,
    "model_ratio": model_ratio,
    "stack_strain": stack_strain,
    # rendered from the measured record contact.probes (MEASUREMENTS)
    "probe_rows": probe_rows,
    "probe_pet3": probe_pet3,
    "hard_roll": hard_roll,
}

if __name__ == "__main__":
    import sys

    for name in sys.argv[1:] or list(BLOCKS):
        print(f"--- {name}\n{BLOCKS[name]()}", flush=True)
