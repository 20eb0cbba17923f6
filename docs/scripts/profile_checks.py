"""Generators of docs/profile.md section 6's verification table (docs/scripts/regenerate.py
runs them): each cell is the measurement of a test, on today's defaults, beside the tolerance
that test asserts. The problems (webs, core, bands, closed forms, beams) are imported from the
test modules themselves (tests/winding/test_axisymmetric.py, tests/profile/test_nip.py,
tests/materials/test_thickness_profile.py), so the page shows what the tests measure.
Cost: about 40 (r, z) windings of 1-61 sectors, a few minutes on a quiet 2-core machine,
most of it the slow Table 3 grouping check (61 sectors, 200 and 400 groups)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]


def _test_module(rel: str) -> Any:
    """tests/<rel>.py as a module: the page shows the tests' own problems."""
    import records

    return records.test_module(f"{rel}.py")


def _ax() -> Any:
    return _test_module("winding/test_axisymmetric")


def _ten(T: float = 2.3e6) -> Any:
    from woundroll.winding.tension import TensionSchedule

    return TensionSchedule(web_stress=T)


def _wind(*args: Any, **kw: Any) -> Any:
    from woundroll.winding.axisymmetric import wind_axisymmetric

    return wind_axisymmetric(*args, **kw)


def _pct(x: float, digits: int = 2) -> str:
    return f"{100 * x:.{digits}f}"


def _sci(x: float) -> str:
    """A round-off-sized relative number: one significant digit, or 0 when exact."""
    return "0 (exact)" if x == 0 else f"{x:.0e}".replace("e-0", "e-")


# ---------------------------------------------------------------- closed forms


def _altmann_errors(E_r: float) -> tuple[float, float]:
    """test_constant_modulus_matches_altmann_closed_form: largest sigma_r error (relative)
    and sigma_theta error (of T) at the test's sample points."""
    import numpy as np

    t = _ax()
    from woundroll.materials.radial_modulus import Constant

    web, T = t.plane_web(Constant(E_r)), 2.3e6
    res = _wind(web, t.CORE, t.R_OUT, _ten(T), n_sectors=3, n_groups=200)
    R = t.R_CORE + res.n_layers * t.H
    idx = np.arange(0, 190, 17)
    ref = np.array(
        [t.altmann(E_r, web.E_theta, 0.01, t.CORE.stiffness, T, R, res.radius[i, 1]) for i in idx]
    )
    err_r = np.abs(res.sigma_r[idx, 1] / ref[:, 0] - 1).max()
    err_t = (np.abs(res.sigma_theta[idx, 1] - ref[:, 1]) / T).max()
    return float(err_r), float(err_t)


def altmann_stiff() -> str:
    r, th = _altmann_errors(1.25e9)
    return f"sigma_r {_pct(r)} %, sigma_theta {_pct(th)} % of T"


def altmann_soft() -> str:
    r, th = _altmann_errors(50e6)
    return f"sigma_r {_pct(r)} %, sigma_theta {_pct(th)} % of T"


def continuous_grouping() -> str:
    """test_constant_modulus_converges_under_layer_grouping, extended to 200 groups, and the
    offset of the discrete-layer closed form from the continuous one at the same radius."""
    import math

    import numpy as np

    t = _ax()
    from woundroll.materials.radial_modulus import Constant
    from woundroll.winding.closed_form import linear_orthotropic

    E_r = 5e6
    web = t.table3_web(Constant(E_r))
    errs, offset = [], 0.0
    for G in (50, 100, 200):
        res = _wind(web, t.CORE, t.R_OUT, _ten(), n_sectors=1, n_groups=G, grouping="uniform")
        i = G // 2
        R = t.R_CORE + res.n_layers * t.H
        ref = t.altmann(E_r, web.E_theta, 0.01, t.CORE.stiffness, 2.3e6, R, res.radius[i, 0])[0]
        errs.append(abs(res.sigma_r[i, 0] / ref - 1))
        if G == 200:
            r, sr, _ = linear_orthotropic(
                t.R_CORE,
                t.H,
                np.full(res.n_layers, 2.3e6),
                E_r,
                web.E_theta,
                t.CORE.stiffness,
                0.01,
            )
            offset = abs(np.interp(res.radius[i, 0], r, sr) / ref - 1)
    g = math.sqrt(web.E_theta / E_r)
    return (
        " / ".join(f"{100 * e:.2f}" for e in errs)
        + f" %, tending to the {100 * offset:.2f} % offset between a discrete-layer build and"
        f" the continuous integral (g = {g:.1f})"
    )


def discrete_closed_form() -> str:
    """test_constant_modulus_matches_discrete_layer_closed_form at 100 / 200 / 400 / every
    layer (uniform groups, 1 sector): max |d sigma_r| / P_core below the outer 5 mm."""
    import numpy as np

    t = _ax()
    from woundroll.materials.radial_modulus import Constant
    from woundroll.winding.closed_form import linear_orthotropic

    out = []
    for E_r, label, groups in (
        (5e6, "5 MPa", (100, 200, 400, 1337)),
        (50e6, "50 MPa", (100, 200, 400, 1337)),
        (1.25e9, "1.25 GPa", (100, 200)),
    ):
        web = t.table3_web(Constant(E_r))
        r, sr, _ = linear_orthotropic(
            t.R_CORE, t.H, np.full(1337, 2.3e6), E_r, web.E_theta, t.CORE.stiffness, 0.01
        )
        errs = []
        for G in groups:
            a = _wind(web, t.CORE, t.R_OUT, _ten(), n_sectors=1, n_groups=G, grouping="uniform")
            sel = a.radius[:, 0] < t.R_OUT - 0.005
            ref = np.interp(a.radius[sel, 0], r, sr)
            errs.append(np.max(np.abs(a.sigma_r[sel, 0] - ref)) / abs(sr[0]))
        out.append(f"{label}: " + " / ".join(f"{100 * e:.2g}" for e in errs) + " %")
    return "; ".join(out) + " (of P_core)"


# ---------------------------------------------------------------- uniform web, (r, z) model


def sectors_vs_column() -> str:
    """test_uniform_thickness_without_axial_poisson_is_the_1d_model."""
    import numpy as np

    t = _ax()
    web = t.plane_web()
    many = _wind(web, t.CORE, t.R_OUT, _ten(), n_sectors=61, n_groups=60, window=None)
    one = _wind(web, t.CORE, t.R_OUT, _ten(), n_sectors=1, n_groups=60)
    rel = np.max(np.abs(many.sigma_r / np.repeat(one.sigma_r, 61, axis=1) - 1))
    smax = np.max(np.abs(many.sigma_r))
    axial = max(np.max(np.abs(many.tau_rz)), np.max(np.abs(many.sigma_z))) / smax
    return (
        f"sigma_r identical to {_sci(rel)} (relative); sigma_z, tau_rz {_sci(axial)} of the"
        " peak sigma_r"
    )


def symmetry() -> str:
    """test_uniform_roll_sigma_z_and_tau_rz_symmetry_and_free_edges."""
    import numpy as np

    t = _ax()
    res = _wind(t.table3_web(), t.CORE, 0.15, _ten(), n_sectors=15)
    tmax = np.max(np.abs(res.tau_rz))
    mid_tau = np.max(np.abs(res.tau_rz[:, 7])) / tmax
    odd = np.max(np.abs(res.tau_rz + res.tau_rz[:, ::-1])) / tmax
    even = np.max(np.abs(res.sigma_z - res.sigma_z[:, ::-1])) / tmax
    mid, edge = np.abs(res.sigma_z[:, 7]).max(), np.abs(res.sigma_z[:, 0]).max()
    rr = np.concatenate([[t.R_CORE], 0.5 * (res.radius[1:, 0] + res.radius[:-1, 0]), [0.15]])
    dr = np.diff(rr)[:, None]
    Fz = np.sum(res.sigma_z * res.radius * dr, axis=0)
    Fa = np.sum(np.abs(res.sigma_z) * res.radius * dr, axis=0)
    return (
        f"tau_rz odd in z ({_sci(odd)} of its peak), zero in the middle sector "
        f"({_sci(mid_tau)} of its peak), sigma_z even ({_sci(even)}); "
        f"sigma_z at the edge sector {edge / mid:.2f} of mid-width; net axial force across "
        f"each CMD section {_sci(np.max(np.abs(Fz)) / np.max(Fa))} of int abs(sigma_z) r dr"
    )


def axial_properties() -> str:
    """test_E_z_and_nu_theta_z_enter_sigma_z."""
    import numpy as np

    t = _ax()
    kw: dict[str, Any] = dict(n_sectors=5, n_groups=40)
    base = _wind(t.table3_web(), t.CORE, 0.13, _ten(), **kw)
    soft = _wind(t.table3_web(E_z=0.5e9), t.CORE, 0.13, _ten(), **kw)
    nu = _wind(t.table3_web(nu_theta_z=0.1), t.CORE, 0.13, _ten(), **kw)
    off = _wind(t.plane_web(), t.CORE, 0.13, _ten(), **kw)
    s0 = np.abs(base.sigma_z).max()
    d_soft = np.abs(soft.sigma_z - base.sigma_z).max() / s0
    d_nu = np.abs(nu.sigma_z - base.sigma_z).max() / s0
    d_off = np.abs(off.sigma_z).max() / s0
    return (
        f"E_z 0.5 GPa changes sigma_z by {100 * d_soft:.0f} %, nu_theta_z 0.3 -> 0.1 by "
        f"{100 * d_nu:.0f} % of its peak ({s0 / 1e3:.0f} kPa); without axial coupling "
        f"sigma_z = {_sci(d_off)} of it"
    )


def cmd_mesh() -> str:
    """test_cmd_mesh_convergence: a smooth +1 % band, 15 / 31 / 61 sectors, 80 groups."""
    t = _ax()
    core, top = [], []
    for ns in (15, 31, 61):
        a = _wind(t.table3_web(), t.CORE, 0.13, _ten(), t._band(0.01), n_sectors=ns, n_groups=80)
        core.append(-a.sigma_r_core[ns // 2] / 1e3)
        top.append(-a.sigma_r[-8, ns // 2] / 1e3)

    def rate(v: list[float]) -> float:
        return abs(v[0] - v[1]) / abs(v[1] - v[2])

    q = rate(core)
    extra = core[2] + (core[2] - core[1]) / (q - 1)
    return (
        "core pressure at the band centre "
        + " / ".join(f"{v:.1f}" for v in core)
        + f" kPa (differences fall {q:.1f}x per halving: second order is 4x; extrapolated "
        f"{extra:.1f}, 61 sectors within {100 * abs(core[2] / extra - 1):.1f} %); outer-group "
        "sigma_r " + " / ".join(f"{v:.2f}" for v in top) + f" kPa ({rate(top):.1f}x)"
    )


def lazy_deep_part() -> str:
    """test_lazy_deep_part_matches_the_exact_solve (a -1 % lane, 15 sectors, 60 groups) and
    test_deep_levels_match_the_exact_solve_on_the_bundled_profile (9 sectors, 160 groups)."""
    import numpy as np

    from woundroll.materials.thickness_profile import bundled_profile

    t = _ax()
    kw: dict[str, Any] = dict(n_sectors=15, n_groups=60)
    a = _wind(t.table3_web(), t.CORE, 0.13, _ten(), t._band(-0.01), **kw)
    b = _wind(t.table3_web(), t.CORE, 0.13, _ten(), t._band(-0.01), window=None, **kw)
    e = [
        np.max(np.abs(getattr(a, n) - getattr(b, n))) / np.max(np.abs(getattr(b, n)))
        for n in ("sigma_r", "sigma_theta", "sigma_z")
    ]
    kw = dict(n_sectors=9, n_groups=160)
    prof = bundled_profile()
    exact = _wind(t.table3_web(), t.CORE, t.R_OUT, _ten(), prof, window=None, **kw)
    lev = _wind(t.table3_web(), t.CORE, t.R_OUT, _ten(), prof, **kw)
    d = t._deep_part_errors(lev, exact)
    return (
        f"-1 % lane, 15 sectors, 60 groups: {_pct(e[0])} / {_pct(e[1])} / {_pct(e[2])} % "
        f"(sigma_r / sigma_theta / sigma_z) of the peak; bundled profile, 9 sectors, 160 "
        f"groups, R 20.32 cm: {_pct(d[0])} / {_pct(d[1])} / {_pct(d[2])} % of the peak, core "
        f"pressure {_pct(d[3])} %"
    )


def near_surface() -> str:
    """test_group_convergence_helper's case (bundled profile, 21 sectors, R 15 cm) at 100 ->
    200 and 200 -> 400 graded groups."""
    from woundroll.materials.thickness_profile import bundled_profile
    from woundroll.winding.axisymmetric import group_convergence

    t = _ax()
    cells = []
    for G in (100, 200):
        out = group_convergence(
            t.table3_web(), t.CORE, 0.15, _ten(), bundled_profile(), n_sectors=21, n_groups=G
        )
        cells.append(
            f"{G} -> {int(out['n_groups_fine'])}: core {_pct(out['core_stress_change'])} %, WOT "
            f"{_pct(out['wot_change'])} %, outer 5 mm sigma_r "
            f"{_pct(out['surface_stress_change'])} % of its peak "
            f"({_pct(out['surface_stress_change_pointwise'])} % pointwise)"
        )
    return "; ".join(cells)


def near_surface_table3() -> str:
    """test_table3_grouping_converged_near_the_surface (slow): 61 sectors, R 20.32 cm,
    200 -> 400 graded groups."""
    from woundroll.materials.thickness_profile import bundled_profile
    from woundroll.winding.axisymmetric import group_convergence

    t = _ax()
    out = group_convergence(t.table3_web(), t.CORE, t.R_OUT, _ten(), bundled_profile())
    return (
        f"{int(out['n_groups'])} -> {int(out['n_groups_fine'])}: outer 5 mm sigma_r "
        f"{_pct(out['surface_stress_change'])} % of its peak, core "
        f"{_pct(out['core_stress_change'])} %, WOT {_pct(out['wot_change'])} %"
    )


def slack_flag() -> str:
    """test_slack_flag_marks_a_thin_lane: a -3 % lane, 15 sectors, 60 groups."""
    import numpy as np

    t = _ax()
    res = _wind(t.table3_web(), t.CORE, 0.13, _ten(), t._band(-0.03), n_sectors=15, n_groups=60)
    flagged = np.flatnonzero(res.slack)
    span = (
        f"sector {flagged[0] + 1}"
        if flagged.size == 1
        else f"sectors {flagged[0] + 1}-{flagged[-1] + 1}"
    )
    return (
        f"a -3 % lane (15 sectors): {span} of 15 flagged (zero WOT in the outer groups of the "
        "middle one), the outer three sectors on each side taut and not flagged"
        if res.slack[7] and not (res.slack[:3].any() or res.slack[-3:].any())
        else f"a -3 % lane (15 sectors): flagged {list(flagged + 1)}"
    )


def allocation() -> str:
    """test_allocation_closed_forms: the closed forms, and the total force on 50 random
    sectors."""
    import numpy as np

    from woundroll.winding.axisymmetric import allocate_tension

    w = np.full(4, 1e-4)
    s, _ = allocate_tension(np.full(4, 0.15), w, 100.0, 5e9)
    eq = np.max(np.abs(s / (100.0 / w.sum()) - 1))
    s1, _ = allocate_tension(np.array([0.15, 0.15, 0.16, 0.15]), w, 100.0, 5e9)
    one = abs(s1[2] / (100.0 / w[2]) - 1)
    rng = np.random.default_rng(3)
    rho = 0.15 + 2e-6 * rng.random(50)
    ww = 1e-6 * (1 + rng.random(50))
    s2, _ = allocate_tension(rho, ww, 5.0, 5e9)
    tot = abs(np.sum(s2 * ww) / 5.0 - 1)
    return (
        f"total force on 50 random sectors exact to {_sci(tot)} (relative); equal "
        f"radii {_sci(eq)}, a single taut sector {_sci(one)}"
    )


# ---------------------------------------------------------------- nip beam, sector averages


def _nip() -> Any:
    return _test_module("profile/test_nip")


def hetenyi_long() -> str:
    """test_hetenyi_long_beam_with_end_loads (lam W = 20), 2 and 4 elements per sector."""
    import numpy as np

    from woundroll.profile.nip import NipRoller, solve_nip

    n = _nip()
    k, lam = 1e8, 20.0 / n.W
    roller = NipRoller(EI=k / (4 * lam**4), line_load=1000.0)
    P = 0.5 * 1000.0 * n.W
    out = []
    for refine in (2, 4):
        sol = solve_nip(n.EDGES, 0.0, k, roller, refine=refine, bilateral=True)
        w0 = 2 * P * lam / k
        x = sol.node_z
        exact = w0 * (
            np.exp(-lam * x) * np.cos(lam * x) + np.exp(-lam * (n.W - x)) * np.cos(lam * (n.W - x))
        )
        out.append(np.max(np.abs(sol.deflection - exact)) / w0)
    return f"{out[0]:.1e} / {out[1]:.1e} of w(0) (2 / 4 elements per sector)"


def hetenyi_finite() -> str:
    """test_hetenyi_finite_beam_with_end_loads at lam W = 1, 5 and 20."""
    import numpy as np

    from woundroll.profile.nip import NipRoller, solve_nip

    n = _nip()
    out = []
    for lam_w in (1.0, 5.0, 20.0):
        k = 1e8
        EI = k / (4 * (lam_w / n.W) ** 4)
        sol = solve_nip(n.EDGES, 0.0, k, NipRoller(EI=EI, line_load=1000.0), bilateral=True)
        exact = n._hetenyi_finite(sol.node_z, 0.5 * 1000.0 * n.W, k, EI, n.W)
        out.append(np.max(np.abs(sol.deflection - exact)) / np.max(np.abs(exact)))
    return " / ".join(f"{e:.1e}" for e in out) + " of the largest deflection"


def stiff_roller() -> str:
    """test_stiff_roller_on_quadratic_foundation."""
    import math

    import numpy as np

    from woundroll.profile.nip import NipRoller, solve_nip

    n = _nip()
    a, b, N = 1e13, 1e6, 1000.0
    sol = solve_nip(n.EDGES, a, b, NipRoller(EI=1e9, line_load=N))
    d = (-b + math.sqrt(b * b + 4 * a * N)) / (2 * a)
    err = max(np.max(np.abs(sol.indentation / d - 1)), np.max(np.abs(sol.load / N - 1)))
    return f"indentation and load within {err:.1e}"


def load_balance() -> str:
    """test_tensionless_foundation_carries_the_load_and_lifts_off."""
    import numpy as np

    from woundroll.profile.nip import NipRoller, solve_nip

    n = _nip()
    z = 0.5 * (n.EDGES[1:] + n.EDGES[:-1])
    gap = np.where(np.abs(z - 0.3) < 0.05, 5e-4, 0.0)
    sol = solve_nip(n.EDGES, 2e13, 5e7, NipRoller.tube(200e9, 0.05, 0.04, 1500.0), gap=gap)
    return f"sum of loads = bearing forces to {_sci(abs(sol.total / (1500.0 * n.W) - 1))}"


def sector_averages() -> str:
    """test_sector_average_exact_for_linear_profile and ..._conserves_the_integral."""
    import numpy as np

    from woundroll.materials.thickness_profile import ThicknessProfile, bundled_profile

    x = np.linspace(0.0, 0.6, 13)
    z, h = ThicknessProfile(x, 70e-6 + 1e-5 * x).sector_average(7)
    lin = np.max(np.abs(h / (70e-6 + 1e-5 * z) - 1))
    prof = bundled_profile()
    exact = np.trapezoid(prof.thickness, prof.position)
    cons = max(
        abs(np.sum(prof.sector_average(m)[1]) * prof.extent / m / exact - 1)
        for m in (1, 7, 61, 200)
    )
    return f"linear profile exact ({_sci(lin)}), integral conserved ({_sci(cons)})"


BLOCKS: dict[str, Callable[[], str]] = {
    "altmann_stiff": altmann_stiff,
    "altmann_soft": altmann_soft,
    "continuous_grouping": continuous_grouping,
    "discrete_closed_form": discrete_closed_form,
    "sectors_vs_column": sectors_vs_column,
    "symmetry": symmetry,
    "axial_properties": axial_properties,
    "cmd_mesh": cmd_mesh,
    "lazy_deep_part": lazy_deep_part,
    "near_surface": near_surface,
    "near_surface_table3": near_surface_table3,
    "slack_flag": slack_flag,
    "allocation": allocation,
    "hetenyi_long": hetenyi_long,
    "hetenyi_finite": hetenyi_finite,
    "stiff_roller": stiff_roller,
    "load_balance": load_balance,
    "sector_averages": sector_averages,
}
