"""Generator of docs/profile.md's numbers (docs/scripts/regenerate.py): the four bundled
``pet3-*`` cases through ``woundroll.run`` on today's defaults (the default roll model, the FD
reading as the instrument shows it), the amplitude study (three 31-sector runs), the default
layer grouping of the (r, z) winding against the 1D model on every bundled roll (uniform web,
1 sector: about 2 s a roll), the uniform Table 3 roll's Poisson coupling (15 and 61 sectors),
and the bundled profile's winding at 100 / 200 / 400 groups and against the whole stack
solved every increment (about a minute). Cost: about 5-6 min on a quiet 2-core machine
(13 min wall on a loaded one), most of it the Table 3 runs' contact stage."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

CASES = ("pet3-2.3MPa", "pet3-3.45MPa", "pet3-2.3MPa-nip", "pet3-3.45MPa-nip")


@cache
def _profile(name: str) -> Any:
    import woundroll

    return woundroll.run(woundroll.load_case(name)).profile


def table3() -> str:
    """Reading statistics on the scale, saturated and slack sectors, the correlation of the
    model's reading with the thickness, and the nip's contact, per case."""
    import numpy as np

    lines = [
        "| case | sectors | reading mean / SD (on the scale) | CoV (band) | min / max "
        "| saturated | slack | corr(reading, thickness) | nip: sectors touched, peak / mean |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name in CASES:
        p = _profile(name)
        st = p.rho_stats
        stats = (
            "fewer than two on the scale | | "
            if st is None
            else f"{st.mean:.1f} / {st.sd:.1f} | {100 * st.cov:.0f} % ({st.band}) | "
            f"{st.min:.1f} / {st.max:.1f}"
        )
        corr = float(np.corrcoef(p.rho, p.thickness)[0, 1])
        nip = "-"
        if p.nip_load is not None:
            mean = float(np.average(p.nip_load, weights=p.winding.dz))
            touched = 100 * float(np.mean(p.nip_load > 0))
            nip = f"{touched:.0f} %, {p.nip_load.max() / mean:.1f}" if mean > 0 else "none"
        lines.append(
            f"| `{name}` | {p.z.size} | {stats} | {int(p.saturated.sum())} | "
            f"{int(p.slack.sum())} | {corr:.2f} | {nip} |"
        )
    return "\n".join(lines)


def _scaled_profile(factor: float, into: str) -> str:
    """The bundled Table 3 profile with its deviations from the mean scaled by ``factor``,
    written as a CSV file (SI) in directory ``into``; its path."""
    from pathlib import Path

    from woundroll.materials.thickness_profile import bundled_profile

    prof = bundled_profile("table3_synthetic_pet")
    mean = prof.thickness.mean()
    scaled = mean + factor * (prof.thickness - mean)
    rows = [f"{float(x)!r},{float(h)!r}" for x, h in zip(prof.position, scaled, strict=True)]
    path = Path(into) / f"profile_x{factor:g}.csv"
    path.write_text("position [m],thickness [m]\n" + "\n".join(rows) + "\n")
    return str(path)


def amplitude() -> str:
    """pet3-2.3MPa with the profile's deviations scaled by 1, 0.5 and 0.25 (31 sectors)."""
    import tempfile

    import numpy as np

    import woundroll

    lines = [
        "| thickness SD / peak-to-peak | reading mean / CoV (on the scale) | min / max "
        "| saturated | slack sectors |",
        "|---|---|---|---|---|",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        for factor in (1.0, 0.5, 0.25):
            path = _scaled_profile(factor, tmp)
            case = woundroll.load_case(
                "pet3-2.3MPa", [f"winding.thickness_profile='{path}'", "profile.sectors=31"]
            )
            p = woundroll.run(case).profile
            th, st = p.thickness_stats, p.rho_stats
            ptp = 100 * (th.max - th.min) / th.mean
            stats = (
                "- | -"
                if st is None
                else f"{st.mean:.1f} / {100 * st.cov:.0f} % | {st.min:.1f} / {st.max:.1f}"
            )
            lines.append(
                f"| {100 * th.cov:.2f} % / {ptp:.1f} % (x {factor:g}) | {stats} | "
                f"{int(p.saturated.sum())} of {p.z.size} | {int(np.sum(p.slack))} |"
            )
    return "\n".join(lines)


def saturated() -> str:
    """How many sectors of pet3-2.3MPa the instrument shows at its scale's end."""
    p = _profile("pet3-2.3MPa")
    return f"{int(p.saturated.sum())} of {p.z.size} sectors saturate"


#: The bundled rolls of section 6's table: Table 2 (PET1, PET2; the studies' list) and
#: Table 3.
from woundroll.studies._common import TABLE2  # noqa: E402

ROLLS = (*TABLE2, "pet3-2.3MPa", "pet3-3.45MPa")


@cache
def _like_for_like(name: str) -> Any:
    """The bundled roll as a uniform web without the axial Poisson coupling (the (r, z) model
    is then plane stress like the 1D model): web, core, outer radius, tension schedule, its
    layer count, the 1D roll (layer by layer) and the (r, z) roll, 1 sector, default options
    (tests/winding/test_axisymmetric.py, ``_like_for_like``)."""
    from dataclasses import replace

    from woundroll.case import load_case
    from woundroll.winding.axisymmetric import wind_axisymmetric
    from woundroll.winding.hakiel import wind

    case = load_case(name)
    web = replace(case.web.build(), nu_z_r=0.0, nu_theta_z=0.0)
    core = case.core.build()
    r_out, ten = case.winding.final_radius(web, core), case.winding.schedule(web)
    n = int(round((r_out - core.outer_radius) / web.thickness))
    return n, wind(web, core, r_out, ten), wind_axisymmetric(web, core, r_out, ten, n_sectors=1)


def grouping() -> str:
    """Section 6's table: the default grouping of each bundled roll against the 1D model."""
    import numpy as np

    lines = [
        "| case | layers | groups (default) | P_core 1D [kPa] | P_core (r, z) [kPa] "
        "| max pointwise dev. | outermost group |",
        "|---|---|---|---|---|---|---|",
    ]
    for name in ROLLS:
        n, ref, res = _like_for_like(name)
        s1 = np.interp(res.radius[:, 0], ref.radius, ref.sigma_r)
        dev = np.abs(res.sigma_r[:, 0] / s1 - 1)
        pc1, pc = ref.core_pressure, float(res.core_pressure[0])
        lines.append(
            f"| `{name}` | {n:,} | {res.info['grouping_check']['groups']} | {pc1 / 1e3:.1f} "
            f"| {pc / 1e3:.1f} ({100 * (pc / pc1 - 1):+.1f} %) | {100 * dev[:-1].max():.2f} % "
            f"| {100 * dev[-1]:.2f} % |"
        )
    return "\n".join(lines)


def _tried(names: tuple[str, ...], groups: int) -> str:
    """The range of the deviations of ``groups`` groups from the fine grouping over ``names``."""
    v = [100 * _like_for_like(n)[2].info["grouping_check"]["tried"][groups] for n in names]
    lo, hi = min(v), max(v)
    return f"{lo:.2f} %" if f"{lo:.2f}" == f"{hi:.2f}" else f"{lo:.1f}-{hi:.1f} %"


def choice() -> str:
    """What ``choose_groups`` picks on the bundled rolls, and how far the coarser groupings
    are from the fine one."""
    table2 = ROLLS[:7]
    chk = {n: _like_for_like(n)[2].info["grouping_check"] for n in ROLLS}
    g2 = sorted({chk[n]["groups"] for n in table2})
    g2s = " / ".join(str(g) for g in g2)
    every = "every Table 2 roll" if len(g2) == 1 else "the Table 2 rolls"
    parts = [
        f"{g2s} groups on {every} (200 groups: {_tried(table2, 200)} off; "
        f"400: {_tried(table2, 400)})"
    ]
    for n in ROLLS[7:]:
        g = chk[n]["groups"]
        coarser = [k for k in sorted(chk[n]["tried"]) if k < g] or sorted(chk[n]["tried"])[:1]
        k = coarser[-1] if g != chk[n]["fine_groups"] else 200
        parts.append(
            f"{g} on {n}"
            + (
                f" ({k}: {100 * chk[n]['tried'][k]:.2f} %)"
                if k != g
                else f" ({100 * chk[n]['tried'][g]:.2f} %)"
            )
        )
    return ", ".join(parts[:-1]) + ", " + parts[-1]


def layers() -> str:
    """The layer count of the Table 3 roll and the fine grouping of the Table 2 and 3 rolls."""
    from woundroll.winding.axisymmetric import default_groups

    n3 = _like_for_like("pet3-2.3MPa")[0]
    n2 = _like_for_like("pet1-26.7N")[0]
    return f"{default_groups(n2)} for the Table 2 rolls, {default_groups(n3)} for Table 3"


def layer_count() -> str:
    """The layer count of the Table 3 roll."""
    return f"{_like_for_like('pet3-2.3MPa')[0]:,}"


#: The uniform Table 3 roll of tests/winding/test_axisymmetric.py: aluminium core
#: 10.16 cm, outer radius 20.32 cm, 76 um PET3 web 61 cm wide (Pfeiffer K1 = 0, K2 = 246.5).
R_CORE, R_OUT = 0.1016, 0.2032


@cache
def _uniform(n_sectors: int, web_stress: float, coupled: bool = True, shape: str = "power") -> Any:
    """The uniform Table 3 roll, (r, z) model, default grouping; with ``coupled`` Table 3's
    Poisson ratios (nu_z_r 0.01, nu_theta_z 0.3), else none (plane stress like the 1D
    model); and the 1D roll (layer by layer) beside it."""
    from woundroll.materials.radial_modulus import Pfeiffer
    from woundroll.materials.web import Core, Web
    from woundroll.winding.axisymmetric import wind_axisymmetric
    from woundroll.winding.hakiel import wind
    from woundroll.winding.tension import TensionSchedule

    nu = (0.01, 0.3) if coupled else (0.0, 0.0)
    web = Web(
        thickness=76e-6,
        width=0.61,
        E_theta=4999e6,
        radial_modulus=Pfeiffer(0.0, 246.5),
        nu_theta_r=0.01,
        nu_z_r=nu[0],
        nu_theta_z=nu[1],
    )
    core = Core.tube(R_CORE, 0.095, 69e9, 0.33)
    ten = TensionSchedule(web_stress=web_stress)
    res = wind_axisymmetric(web, core, R_OUT, ten, n_sectors=n_sectors, shape=shape)
    return res, wind(web, core, R_OUT, ten)


def _against_1d(res: Any, ref: Any, j: int) -> tuple[float, float]:
    """Sector ``j``'s largest |d sigma_r| against the 1D model / P_core, and the largest
    pointwise relative one in the outer 5 mm."""
    import numpy as np

    r = res.radius[:, j]
    s1 = np.interp(r, ref.radius, ref.sigma_r)
    dev = np.abs(res.sigma_r[:, j] - s1)
    outer = r > R_OUT - 0.005
    return float(dev.max() / ref.core_pressure), float(np.max(dev[outer] / np.abs(s1[outer])))


def sigma_z() -> str:
    """The axial stress at the core, mid-width, uniform Table 3 roll at 2.3 MPa."""
    res, _ = _uniform(15, 2.3e6)
    return f"{res.sigma_z[0, 7] / 1e6:+.1f} MPa"


def poisson_1d() -> str:
    """How far the coupled roll's sigma_r departs from the plane-stress 1D model."""
    res, ref = _uniform(15, 2.3e6)
    return f"{100 * _against_1d(res, ref, 7)[0]:.0f} %"


def edge() -> str:
    """The edge sector's core pressure over mid-width's, 61 sectors."""
    res, _ = _uniform(61, 2.3e6)
    return f"{100 * (res.core_pressure[0] / res.core_pressure[30] - 1):.0f} % higher"


def linear_shape() -> str:
    """Bilinear elements against the exact ring shapes, uniform roll, 15 sectors, mid-width."""
    import numpy as np

    a, _ = _uniform(15, 2.3e6)
    b, _ = _uniform(15, 2.3e6, shape="linear")
    core = abs(b.core_pressure[7] / a.core_pressure[7] - 1)
    outer = a.radius[:, 7] > R_OUT - 0.005
    surf = np.max(np.abs(b.sigma_r[outer, 7] / a.sigma_r[outer, 7] - 1))
    return (
        f"by {100 * core:.2f} % at the core and {100 * surf:.2f} % in the outer 5 mm "
        "(uniform Table 3 roll, 15 sectors, mid-width)"
    )


def poisson_row() -> str:
    """Section 6's row: Table 3's Poisson ratios against the 1D model, 15 sectors."""
    import numpy as np

    parts = [_against_1d(*_uniform(15, t), 7) for t in (2.3e6, 3.45e6)]
    sz = [_uniform(15, t)[0].sigma_z[0, 7] / 1e6 for t in (2.3e6, 3.45e6)]
    near = []
    for t in (2.3e6, 3.45e6):
        res, ref = _uniform(15, t)
        r = res.radius[:, 7]
        o = r > R_OUT - 0.005
        d = np.abs(res.sigma_r[o, 7] - np.interp(r[o], ref.radius, ref.sigma_r))
        near.append(100 * d.max() / ref.core_pressure)
    return (
        f"{100 * parts[0][0]:.1f} / {100 * parts[1][0]:.1f} % of P_core, largest near the core; "
        f"outer 5 mm pointwise {100 * parts[0][1]:.1f} / {100 * parts[1][1]:.1f} %, within "
        f"{max(near):.2f} % of P_core; sigma_z "
        f"at the core {sz[0]:+.2f} / {sz[1]:+.2f} MPa"
    )


def hakiel_row() -> str:
    """Section 6's row: uniform thickness without axial coupling against the 1D model,
    5 sectors (mid-width), default grouping."""
    parts = [_against_1d(*_uniform(5, t, coupled=False), 2) for t in (2.3e6, 3.45e6)]
    pc = [_uniform(5, t, coupled=False)[1].core_pressure / 1e3 for t in (2.3e6, 3.45e6)]
    return (
        f"max over the roll {100 * parts[0][0]:.2f} / {100 * parts[1][0]:.2f} % of P_core "
        f"({pc[0]:.1f} / {pc[1]:.1f} kPa); outer 5 mm pointwise {100 * parts[0][1]:.2f} / "
        f"{100 * parts[1][1]:.2f} % of the local sigma_r"
    )


@cache
def _bundled_winding(n_groups: int, **kw: Any) -> Any:
    """pet3-2.3MPa's (r, z) winding on the bundled profile, 61 sectors, ``n_groups`` graded
    groups, ``kw`` passed on (winding only, no contact: seconds; the whole stack every
    increment, ``window=None``, about a minute)."""
    from woundroll.case import load_case
    from woundroll.materials.thickness_profile import bundled_profile
    from woundroll.winding.axisymmetric import wind_axisymmetric

    case = load_case("pet3-2.3MPa")
    web, core = case.web.build(), case.core.build()
    r_out, ten = case.winding.final_radius(web, core), case.winding.schedule(web)
    prof = bundled_profile("table3_synthetic_pet")
    return wind_axisymmetric(web, core, r_out, ten, prof, n_sectors=61, n_groups=n_groups, **kw)


def _level_errors(lazy: Any, whole: Any) -> tuple[float, float, float, float]:
    """Largest |d sigma_r| / peak, pointwise where |sigma_r| > 1 % of the peak, the core
    pressure's largest relative change, and pointwise in the outer 24 groups (same mask)."""
    import numpy as np

    peak = np.abs(whole.sigma_r).max()
    d = np.abs(lazy.sigma_r - whole.sigma_r)
    big = np.abs(whole.sigma_r) > 0.01 * peak
    rel = np.where(big, d / np.where(big, np.abs(whole.sigma_r), 1.0), 0.0)
    core = np.abs(lazy.core_pressure / whole.core_pressure - 1).max()
    return float(d.max() / peak), float(rel.max()), float(core), float(rel[-24:].max())


def levels() -> str:
    """The levels of doubling depth against the whole stack solved every increment,
    pet3-2.3MPa on the bundled profile, 61 sectors, 400 groups; and with half the depth
    frozen (flush 8)."""
    whole = _bundled_winding(400, window=None)
    e = _level_errors(_bundled_winding(400), whole)
    half = _level_errors(_bundled_winding(400, flush=8), whole)
    return (
        f"largest |d sigma_r| {100 * e[0]:.3f} % of the peak, {100 * e[1]:.2f} % pointwise "
        f"where sigma_r exceeds 1 % of the peak, core pressure {100 * e[2]:.2f} %, and "
        f"{100 * e[3]:.3f} % pointwise in the outer 24 groups where the tester reads. The "
        "ratio of the frozen period to the depth sets the accuracy: freezing for half the "
        f"depth (16 / 8) makes the largest error {half[0] / e[0]:.1f} times larger"
    )


def groups_profile() -> str:
    """Core pressure of the thickest and the thinnest sector at 100 / 200 / 400 groups."""
    import numpy as np

    from woundroll.materials.thickness_profile import bundled_profile

    _, h = bundled_profile("table3_synthetic_pet").sector_average(61)
    thick, thin = int(np.argmax(h)), int(np.argmin(h))
    runs = [_bundled_winding(g) for g in (100, 200, 400)]
    pk = [w.core_pressure[thick] / 1e3 for w in runs]
    pn = [w.core_pressure[thin] / 1e3 for w in runs]
    slack = int(runs[-1].slack.sum())
    return (
        f"core pressure of the thickest sector {pk[0]:.0f} / {pk[1]:.0f} / {pk[2]:.0f} kPa at "
        f"100 / 200 / 400 groups ({100 * abs(pk[2] / pk[1] - 1):.2f} % between 200 and 400); "
        f"the thinnest sector {pn[0]:.1f} / {pn[1]:.1f} / {pn[2]:.1f} kPa: it is slack near "
        f"the surface ({slack} of the 61 sectors are at 400 groups, `slack` flags them)"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "table3": table3,
    "amplitude": amplitude,
    "saturated": saturated,
    "grouping": grouping,
    "choice": choice,
    "layers": layers,
    "layer_count": layer_count,
    "sigma_z": sigma_z,
    "poisson_1d": poisson_1d,
    "edge": edge,
    "linear_shape": linear_shape,
    "poisson_row": poisson_row,
    "hakiel_row": hakiel_row,
    "groups_profile": groups_profile,
    "levels": levels,
}
