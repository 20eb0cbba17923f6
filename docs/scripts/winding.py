"""Generators of docs/winding.md's numbers (docs/scripts/regenerate.py): the 1D winding model
(``woundroll.winding.hakiel.wind``) on the bundled PET1 26.7 N roll with 1 to 16 elements per
layer (the whole roll solved every increment, one load step) and with each modulus rule and
load-substep count, on the Table 3 film (K1 = 0), with layers lumped per increment on a 12 um
film, and the two new-layer variants on the Table 2 rolls and under layer refinement; today's
other defaults. Cost: about a minute on a quiet 2-core machine (the whole-roll reference
solves dominate)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from functools import cache
from typing import Any

SUBDIVISIONS = (1, 2, 4, 8, 16)
CASE = "pet1-26.7N"


@cache
def _roll() -> tuple[Any, Any, float, Any]:
    from woundroll.case import load_case

    case = load_case(CASE)
    web, core = case.web.build(), case.core.build()
    return web, core, case.winding.final_radius(web, core), case.winding.schedule(web)


@cache
def _core_pressure(subdivisions: int) -> float:
    from woundroll.winding.hakiel import WindingOptions, wind

    web, core, r_out, ten = _roll()
    opts = replace(WindingOptions(), subdivisions=subdivisions, window_layers=None, load_substeps=1)
    return float(wind(web, core, r_out, ten, options=opts).core_pressure)


def elements() -> str:
    """Core pressure against the elements per layer, the observed order of the last
    halvings and the default's distance from the Richardson limit."""
    from woundroll.winding.hakiel import WindingOptions

    default = WindingOptions().subdivisions
    web, core, r_out, _ = _roll()
    n = int(round((r_out - core.outer_radius) / web.thickness))
    p = [_core_pressure(s) for s in SUBDIVISIONS]
    head = " | ".join(f"{s}{' (default)' if s == default else ''}" for s in SUBDIVISIONS)
    cells = " | ".join(f"{x:,.0f}".replace(",", " ") for x in p)
    order = math.log2((p[-3] - p[-2]) / (p[-2] - p[-1]))
    limit = p[-1] + (p[-1] - p[-2]) / (2**order - 1)
    dev = 100 * abs(p[SUBDIVISIONS.index(default)] / limit - 1)
    return "\n".join(
        [
            f"`{CASE}`, {n:,} layers, the bundled core "
            f"(E_c = {core.stiffness / 1e9:.1f} GPa); core pressure, whole roll solved every "
            "increment, one load step:",
            "",
            f"| elements per layer | {head} |",
            "|---|" + "---|" * len(SUBDIVISIONS),
            f"| core pressure [Pa] | {cells} |",
            "",
            f"Observed order of the last two halvings {order:.1f}; {default} elements per layer "
            f"is {dev:.2f} % from the extrapolated limit.",
        ]
    )


def _profile_diff(a: Any, b: Any) -> float:
    """max |sigma_r(a) - sigma_r(b)| over b's radii, relative to b's core pressure (the
    measure of tests/winding/test_hakiel.py)."""
    import numpy as np

    return float(
        np.max(np.abs(np.interp(b.radius, a.radius, a.sigma_r) - b.sigma_r)) / b.core_pressure
    )


def k1_zero() -> str:
    """The Table 3 film (K1 = 0, 600 layers on the aluminium tube, 2.3 MPa): error against
    16 elements per layer and 8 load substeps (whole roll every increment) for 1-8 elements
    per layer, one load step, today's other defaults."""
    from woundroll.materials.radial_modulus import Pfeiffer
    from woundroll.materials.web import Core, Web
    from woundroll.winding.hakiel import WindingOptions, wind
    from woundroll.winding.tension import TensionSchedule

    web = Web(
        thickness=76e-6,
        width=0.61,
        E_theta=4999e6,
        radial_modulus=Pfeiffer(0.0, 246.5),
        nu_theta_r=0.01,
    )
    core = Core.tube(0.1016, 0.095, 69e9, 0.33)
    r_out, ten = 0.1016 + 600 * 76e-6, TensionSchedule(2.3e6)
    base = WindingOptions()
    ref = wind(
        web,
        core,
        r_out,
        ten,
        options=replace(base, subdivisions=16, load_substeps=8, window_layers=None),
    )
    errs = [
        _profile_diff(
            wind(web, core, r_out, ten, options=replace(base, subdivisions=s, window_layers=None)),
            ref,
        )
        for s in (1, 2, 4, 8)
    ]
    return ", ".join(f"{100 * e:.2f} % ({s})" for e, s in zip(errs, (1, 2, 4, 8), strict=True))


def lumping() -> str:
    """``layers_per_increment`` L on a 12 um film (2000 layers, 7.6 cm rigid core, Pfeiffer
    K1 = 10 kPa, K2 = 100, 1.5 MPa): error against a 4x grid with 4 load substeps."""
    from woundroll.materials.radial_modulus import Pfeiffer
    from woundroll.materials.web import Core, Web
    from woundroll.winding.hakiel import WindingOptions, wind
    from woundroll.winding.tension import TensionSchedule

    web = Web(thickness=12e-6, width=1.0, E_theta=5e9, radial_modulus=Pfeiffer(10e3, 100.0))
    core, r_out, ten = Core(0.076), 0.076 + 2000 * 12e-6, TensionSchedule(1.5e6)
    base = WindingOptions()
    ref = wind(
        web,
        core,
        r_out,
        ten,
        options=replace(
            base, subdivisions=4 * base.subdivisions, load_substeps=4, window_layers=None
        ),
    )
    ls = (1, 2, 4, 8, 16)
    errs = [
        _profile_diff(
            wind(web, core, r_out, ten, options=replace(base, layers_per_increment=n)), ref
        )
        for n in ls
    ]
    return ", ".join(f"{100 * e:.2f} % (L = {n})" for e, n in zip(errs, ls, strict=True))


def rules() -> str:
    """Core pressure of PET1 26.7 N for each modulus rule, one step per layer and 4, 16, 64
    load substeps (the reference: the midpoint rule at 64 substeps)."""
    from woundroll.winding.hakiel import WindingOptions, wind

    web, core, r_out, ten = _roll()
    subs = (1, 4, 16, 64)
    p = {
        (rule, n): float(
            wind(
                web,
                core,
                r_out,
                ten,
                options=replace(WindingOptions(), modulus_update=rule, load_substeps=n),
            ).core_pressure
        )
        for rule in ("explicit", "midpoint", "end")
        for n in subs
    }
    ref = p["midpoint", 64]

    def pa(x: float) -> str:
        return f"{x:,.0f}".replace(",", " ")

    lines = ["| rule | 1 step | 4 substeps | 16 | 64 |", "|---|---|---|---|---|"]
    for rule in ("explicit", "midpoint", "end"):
        first = f"{pa(p[rule, 1])} Pa ({100 * (p[rule, 1] / ref - 1):+.2f} %)"
        lines.append(f"| {rule} | {first} | " + " | ".join(pa(p[rule, n]) for n in subs[1:]) + " |")
    return "\n".join(lines)


#: The bundled Table 2 rolls (PET1, PET2): the studies' list.
from woundroll.studies._common import TABLE2  # noqa: E402


def _bundled(name: str) -> tuple[Any, Any, float, Any]:
    from woundroll.case import load_case

    case = load_case(name)
    web, core = case.web.build(), case.core.build()
    return web, core, case.winding.final_radius(web, core), case.winding.schedule(web)


def _mid_sigma_r(res: Any) -> float:
    """-sigma_r at the middle radius of the roll [Pa]."""
    import numpy as np

    r = np.asarray(res.radius)
    mid = 0.5 * (r[0] + r[-1])
    return float(-np.interp(mid, r, res.sigma_r))


def new_layer() -> str:
    """Core pressure and mid-roll sigma_r of the Table 2 rolls, laid-on against elastic new
    layer, default options otherwise."""
    from woundroll.winding.hakiel import WindingOptions, wind

    lines = [
        "| roll | laid on [kPa] | elastic [kPa] | difference "
        "| sigma_r at mid-roll, laid on / elastic [kPa] |",
        "|---|---|---|---|---|",
    ]
    for name in TABLE2:
        web, core, r_out, ten = _bundled(name)
        a = wind(web, core, r_out, ten, options=replace(WindingOptions(), new_layer="laid_on"))
        b = wind(web, core, r_out, ten, options=replace(WindingOptions(), new_layer="elastic"))
        pa, pb = float(a.core_pressure), float(b.core_pressure)
        lines.append(
            f"| {name} | {pa / 1e3:.1f} | {pb / 1e3:.1f} | {100 * (pb / pa - 1):+.1f} % "
            f"| {_mid_sigma_r(a) / 1e3:.1f} / {_mid_sigma_r(b) / 1e3:.1f} |"
        )
    return "\n".join(lines)


def surface_ratio() -> str:
    """E_theta / E_r at the free surface (zero pressure) of PET1 and PET2."""
    parts = []
    for label, name in (("PET1", "pet1-26.7N"), ("PET2", "pet2-26.7N")):
        web = _bundled(name)[0]
        e_r = float(web.radial_modulus.modulus_at_pressure(0.0))
        parts.append(f"{web.E_theta / e_r:,.0f} for {label}")
    return ", ".join(parts)


def layer_thickness() -> str:
    """PET1 26.7 N with the layer thickness halved three times at the same stresses: the
    two new-layer variants meet."""
    from woundroll.winding.hakiel import WindingOptions, wind

    web, core, r_out, ten = _bundled(CASE)
    lines = [
        "| h [um] | layers | laid on [Pa] | elastic [Pa] | difference |",
        "|---|---|---|---|---|",
    ]
    for k in range(4):
        w = replace(web, thickness=web.thickness / 2**k)
        n = int(round((r_out - core.outer_radius) / w.thickness))
        p = [
            float(
                wind(
                    w, core, r_out, ten, options=replace(WindingOptions(), new_layer=v)
                ).core_pressure
            )
            for v in ("laid_on", "elastic")
        ]
        lines.append(
            f"| {1e6 * w.thickness:g}{' (the web)' if k == 0 else ''} | {n:,} ".replace(",", " ")
            + f"| {p[0]:,.0f} | {p[1]:,.0f} | {100 * (p[1] / p[0] - 1):+.2f} % |".replace(",", " ")
        )
    return "\n".join(lines)


def _hakiel_tests() -> Any:
    """tests/winding/test_hakiel.py as a module (its rolls of the lazy-part test;
    records.test_module)."""
    import records

    return records.test_module("winding/test_hakiel.py")


def lazy() -> str:
    """The default (levels of doubling depth) against the whole roll solved every increment:
    largest |d sigma_r| / core pressure, on the rolls of test_default_deep_part_matches_exact_solve
    plus the benchmark film at 10,000 layers and PET1 with the other modulus rules."""
    from woundroll.materials.web import Core
    from woundroll.winding.hakiel import WindingOptions, wind
    from woundroll.winding.tension import TensionSchedule

    t = _hakiel_tests()
    cases = dict(t.LAZY_CASES)
    cases["film-10000"] = (
        t._film(),
        Core(0.076),
        0.076 + 10000 * 12e-6,
        TensionSchedule(1.5e6),
        {},
    )
    pet1 = cases["pet1"]
    for rule in ("explicit", "end"):
        cases[f"pet1 ({rule} rule)"] = (*pet1[:4], {"modulus_update": rule})
    lines = [
        "| roll | layers | default against exact |",
        "|---|---|---|",
    ]
    for name, (web, core, r_out, sched, extra) in cases.items():
        a = wind(web, core, r_out, sched, options=WindingOptions(**extra))
        b = wind(web, core, r_out, sched, options=WindingOptions(window_layers=None, **extra))
        n = int(round((r_out - core.outer_radius) / web.thickness))
        lines.append(f"| `{name}` | {n:,} | {100 * _profile_diff(a, b):.3f} % |")
    return "\n".join(lines)


# ---------------------------------------------------------------- after winding, modes, air
# whole runs of the bundled PET1 26.7 N case (woundroll.run, the Rho-meter, default roll
# model) with the case keys the page names, as ``woundroll run pet1-26.7N --set ...`` does


@cache
def _run(*overrides: str) -> Any:
    import woundroll

    return woundroll.run(woundroll.load_case("pet1-26.7N", list(overrides)))


def _pressures(res: Any) -> tuple[float, float, float]:
    """Core pressure, P at r = 6.7 cm and P 1 mm below the surface [kPa]."""
    import numpy as np

    w = res.winding
    r, p = w.radius, -w.sigma_r
    return (
        w.core_pressure / 1e3,
        float(np.interp(0.067, r, p)) / 1e3,
        float(np.interp(r[-1] - 1e-3, r, p)) / 1e3,
    )


_COOLED = ("storage.temperature_change=-20 K", "core.thermal_expansion=1.2e-5")


def storage_cooled() -> str:
    """PET1 26.7 N on a steel core cooled by 20 K: pressures and Rho before and after."""
    a, b = _run(), _run(*_COOLED)
    (c0, m0, s0), (c1, m1, s1) = _pressures(a), _pressures(b)
    return (
        f"the core pressure rises {c0:.1f} -> {c1:.1f} kPa (the PET's MD contracts more than "
        f"the steel core and grips it) while the body loosens, {m0:.1f} -> {m1:.1f} kPa at "
        f"r = 6.7 cm and {s0:.1f} -> {s1:.1f} kPa 1 mm below the surface (the stack contracts "
        f"more through its thickness than along the MD); Rho {a.hardness.shown:.1f} -> "
        f"{b.hardness.shown:.1f}. {b.winding.storage['iterations']} Picard iterations"
    )


_POWER = 'storage.radial_creep={law="power", n=0.2, tau="60 d"}'
_PRONY = 'storage.radial_creep={law="prony", c=[0.1, 0.2, 0.3], tau=["1 h", "1 d", "10 d"]}'


def creep() -> str:
    """PET1 26.7 N as wound and after 1, 30 and 365 days with the two example creep laws."""
    lines = [
        "| storage | core pressure [kPa] | P at r = 6.7 cm [kPa] | P 1 mm below the surface "
        "[kPa] | Rho |",
        "|---|---|---|---|---|",
    ]

    def row(label: str, res: Any) -> str:
        c, m, s = _pressures(res)
        return f"| {label} | {c:.1f} | {m:.1f} | {s:.1f} | {res.hardness.shown:.1f} |"

    lines.append(row("as wound", _run()))
    for law, name in (
        (_POWER, "power n = 0.2, tau = 60 d"),
        (_PRONY, "Prony c = 0.1, 0.2, 0.3 at 1 h, 1 d, 10 d"),
    ):
        for i, t in enumerate(("1 d", "30 d", "365 d")):
            label = f"{name}: {t}" if i == 0 else t
            lines.append(row(label, _run(law, f"storage.time={t}")))
    return "\n".join(lines)


_SURFACE = ("winding.friction=0.2", "winding.drum_friction=0.3", "winding.nip_saturation=1 kN/m")


def _reading(res: Any) -> str:
    """The reading, beyond the scale as the model gives it (marked), not clipped."""
    h = res.hardness
    off = " (off the scale)" if res.flags.get("reading_outside_range") else ""
    return f"{h.reading:.1f}{off}"


def _mode_cells(res: Any) -> str:
    w = res.winding
    return f"{w.wot[-1] / 1e6:.2f} | {w.core_pressure / 1e3:.0f} | {_reading(res)}"


def modes() -> str:
    """Centre and surface winding of PET1 26.7 N against the nip load."""
    lines = [
        "| nip load [N/m] | centre: WOT [MPa] | core p [kPa] | Rho | surface: WOT [MPa] "
        "| core p [kPa] | Rho |",
        "|---|---|---|---|---|---|---|",
    ]
    for n in (250, 500, 1000, 2000, 4000):
        nip = f"winding.nip_load={n} N/m"
        centre = _run(nip, "winding.friction=0.2")
        surface = _run(nip, "winding.mode=surface", *_SURFACE)
        lines.append(f"| {n} | {_mode_cells(centre)} | {_mode_cells(surface)} |")
    return "\n".join(lines)


def centre_surface() -> str:
    """Centre-surface winding at 500 N/m: differentials of 20, 100 and 1000 N/m, the last
    beyond the drum's hold (capped, with the drum_slip flag)."""
    import numpy as np

    from woundroll.case import load_case

    cells = {dt: _centre_surface_cells(dt) for dt in (20.0, 100.0, 1000.0)}
    res = cells[1000.0][0]
    case = load_case(
        "pet1-26.7N",
        [
            "winding.mode=center-surface",
            "winding.nip_load=500 N/m",
            "winding.tension_differential=20 N/m",
            *_SURFACE,
        ],
    )
    web = case.web.build()
    sched = case.winding.schedule(web)
    line = float(np.atleast_1d(sched.web_stress)[0]) * web.thickness
    hold = float(np.atleast_1d(sched.drum_limit(line))[0])
    beta = float(np.degrees(sched.drum_wrap))
    capped = "capped" if res.flags.get("drum_slip") else "NOT capped"
    return (
        f"a differential of 20 N/m gives WOT {cells[20.0][1]}, 100 N/m {cells[100.0][1]}; "
        f"1000 N/m exceeds the drum's hold ({hold:.1f} N/m at beta = {beta:.0f} deg) and is "
        f"{capped}: {cells[1000.0][1]}, with the warning"
    )


def _centre_surface_cells(dt: float) -> tuple[Any, str]:
    res = _run(
        "winding.mode=center-surface",
        "winding.nip_load=500 N/m",
        f"winding.tension_differential={dt:g} N/m",
        *_SURFACE,
    )
    w = res.winding
    return res, (
        f"{w.wot[-1] / 1e6:.2f} MPa (core {w.core_pressure / 1e3:.0f} kPa, Rho "
        f"{res.hardness.shown:.1f})"
    )


def _g(x: float) -> str:
    """Three significant figures, without an exponent for the page's ranges."""
    return f"{x:.3g}" if x >= 0.1 else f"{x:.2g}"


def air() -> str:
    """PET1 26.7 N (roughness 0.1 um) wound at speed, with and without a nip: the film at
    lay-on, the air kept per layer, the outer diameter and the core pressure without air,
    at winding and after the air has left, the leakage time and the 90 % leaving time."""
    lines = [
        "| nip | U | film | air per layer | D [mm] | core pressure [kPa] | tau / t_90 |",
        "|---|---|---|---|---|---|---|",
    ]
    for nip, u in ((0, 1), (0, 5), (300, 2), (300, 5), (300, 10), (1000, 10)):
        res = _run(f"winding.speed={u} m/s", "web.roughness=0.1 um", f"winding.nip_load={nip} N/m")
        a = res.winding.air
        kept = a["entrained_air_m"]
        d = [a[f"outer_diameter_{k}_m"] * 1e3 for k in ("no_air", "at_winding", "after")]
        p = [a[f"core_pressure_{k}_Pa"] / 1e3 for k in ("no_air", "at_winding", "after")]
        if kept == 0:
            dd, pp, times = f"{d[0]:.1f} (unchanged)", f"{p[0]:.1f} (unchanged)", "-"
        else:
            dd = " / ".join(f"{x:.1f}" for x in d)
            loose = " (loose)" if res.flags.get("air_loose") else ""
            pp = " / ".join(f"{abs(x):.1f}" for x in p) + loose  # abs: no "-0.0"
            times = f"{_g(a['air_leakage_time_s'])} / {_g(a['air_leaves_90_s'])} s"
        lines.append(
            f"| {'none' if nip == 0 else f'{nip} N/m'} | {u} m/s | "
            f"{_g(a['film_at_lay_on_m'] * 1e6)} um | "
            f"{'0' if kept == 0 else _g(kept * 1e6) + ' um'} | {dd} | {pp} | {times} |"
        )
    return "\n".join(lines)


def frozen_period() -> str:
    """test_default_deep_part_is_close_to_the_exact_solve's film (2,000 layers): the default
    and a finer setting (window 256 layers, flush interval 2) against the exact solve."""
    from woundroll.materials.web import Core
    from woundroll.winding.hakiel import WindingOptions, wind
    from woundroll.winding.tension import TensionSchedule

    t = _hakiel_tests()
    core, R, sched = Core(0.076), 0.076 + 2000 * 12e-6, TensionSchedule(1.5e6)
    exact = wind(t._film(), core, R, sched, options=WindingOptions(window_layers=None))
    d = WindingOptions()
    out = []
    for w, f in ((d.window_layers, d.flush_interval), (8, 2), (8, 4), (256, 2)):
        res = wind(
            t._film(), core, R, sched, options=WindingOptions(window_layers=w, flush_interval=f)
        )
        label = f"window {w}, flush interval {f}" + (
            " (default)" if (w, f) == (d.window_layers, d.flush_interval) else ""
        )
        out.append(f"{label}: {100 * _profile_diff(res, exact):.2g} %")
    return "; ".join(out)


def work() -> str:
    """Element evaluations per increment of the default on the benchmark film."""
    from woundroll.materials.web import Core
    from woundroll.winding.hakiel import wind
    from woundroll.winding.tension import TensionSchedule

    t = _hakiel_tests()
    cells = []
    for n in (500, 2000, 8000, 100_000):
        res = wind(t._film(), Core(0.076), 0.076 + n * 12e-6, TensionSchedule(1.5e6))
        st = res.stats
        ev = (st["element_evaluations_window"] + st["element_evaluations_refresh"]) / st[
            "increments"
        ]
        cells.append(f"{ev:.0f} at {n:,} layers")
    return "per increment " + ", ".join(cells)


# ---------------------------------------------------------------- docs/assumptions.md's
# sentences (the same problems as the tables above, as percentages)


def rules_prose() -> str:
    """One step per layer, explicit and end-of-increment rules against the midpoint
    reference (64 substeps), PET1 26.7 N."""
    from woundroll.winding.hakiel import WindingOptions, wind

    web, core, r_out, ten = _roll()

    def p(rule: str, n: int) -> float:
        opts = replace(WindingOptions(), modulus_update=rule, load_substeps=n)
        return float(wind(web, core, r_out, ten, options=opts).core_pressure)

    ref = p("midpoint", 64)
    return (
        f"explicit {100 * (p('explicit', 1) / ref - 1):+.1f} %, end-of-increment "
        f"{100 * (p('end', 1) / ref - 1):+.1f} %"
    )


def new_layer_prose() -> str:
    """Core pressure, elastic against laid-on new layer, the Table 2 rolls."""
    from woundroll.winding.hakiel import WindingOptions, wind

    out: dict[str, list[tuple[str, float]]] = {}
    for name in TABLE2:
        web, core, r_out, ten = _bundled(name)
        pa, pb = (
            float(
                wind(
                    web, core, r_out, ten, options=replace(WindingOptions(), new_layer=v)
                ).core_pressure
            )
            for v in ("laid_on", "elastic")
        )
        out.setdefault(name.split("-")[0].upper(), []).append(
            (name.split("-")[1].replace("N", ""), 100 * (pb / pa - 1))
        )
    return "; ".join(
        f"{m} {' / '.join(t for t, _ in v)} N: {' / '.join(f'{d:.1f}' for _, d in v)} %"
        for m, v in out.items()
    )


def layer_thickness_prose() -> str:
    """PET1 26.7 N, the layer thickness halved three times: elastic against laid on."""
    from woundroll.winding.hakiel import WindingOptions, wind

    web, core, r_out, ten = _bundled(CASE)
    cells = []
    for k in range(4):
        w = replace(web, thickness=web.thickness / 2**k)
        pa, pb = (
            float(
                wind(
                    w, core, r_out, ten, options=replace(WindingOptions(), new_layer=v)
                ).core_pressure
            )
            for v in ("laid_on", "elastic")
        )
        cells.append(f"{abs(100 * (pb / pa - 1)):.1f} % at {1e6 * w.thickness:g} um")
    return ", ".join(cells)


BLOCKS: dict[str, Callable[[], str]] = {
    "lazy": lazy,
    "new_layer": new_layer,
    "surface_ratio": surface_ratio,
    "layer_thickness": layer_thickness,
    "rules": rules,
    "elements": elements,
    "k1_zero": k1_zero,
    "lumping": lumping,
    "storage_cooled": storage_cooled,
    "creep": creep,
    "modes": modes,
    "centre_surface": centre_surface,
    "air": air,
    "frozen_period": frozen_period,
    "work": work,
    "rules_prose": rules_prose,
    "new_layer_prose": new_layer_prose,
    "layer_thickness_prose": layer_thickness_prose,
}
