"""Generators of docs/contact.md's numbers on the 3D model and the fast path
``2d+cmd-spread`` (docs/scripts/regenerate.py runs them).

The 3D curves and readings are the stored references
(``tests/contact/data/contact3d_reference.json``, made by
``tests/contact/data/make_contact3d_reference.py`` with the default 3D options and the
Hertz-calibrated head of 6.565 mm; ~1 CPU min a roll to recompute, checked against the code
by tests/contact/test_cmd_spread.py's slow tests); the 2D, corrected and pipeline numbers
are run live with that head, through the tests' own helpers
(tests/contact/test_cmd_spread.py, test_contact3d.py). Live 3D solves: the tests' coarse
Hertz sphere and plane-strain slab, and one 3D reading with the reduced-shear slip (PET2
53.4 N). Cost: about 3-4 CPU min (the slip reading ~1.5 min, ~25 2D pipeline runs).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
REF_FILE = ROOT / "tests" / "contact" / "data" / "contact3d_reference.json"
#: the validation table's rows: reference key, label (the fit rolls marked)
ROLLS = (
    "pet1-26.7N",
    "pet1-33.4N",
    "pet1-40N",
    "pet1-46.7N",
    "pet2-26.7N",
    "pet2-53.4N",
    "pet2-80N",
    "pet2-53.4N-H2cm",
    "pet2-53.4N-H4cm",
    "pet2-53.4N-H6cm",
)


def _test_module(name: str) -> Any:
    """tests/contact/<name>.py as a module: the page shows the tests' own problems."""
    import records

    return records.test_module(f"contact/{name}.py")


def _head(t: Any) -> str:
    """The override of the head the 3D references were computed with (the tests' own)."""
    return getattr(t, "REF_HEAD", "tester.head_radius='6.565 mm'")


@cache
def _ref() -> dict[str, Any]:
    return json.loads(REF_FILE.read_text())


@cache
def _run(key: str, model: str) -> Any:
    """The pipeline on reference roll ``key`` with ``model`` and the reference head."""
    import woundroll

    t = _test_module("test_cmd_spread")
    c3 = _ref()["cases"][key]["3d"]
    over = [*c3["overrides"], "contact.no_update=false", f"contact.model='{model}'", _head(t)]
    return woundroll.run(woundroll.load_case(c3["case"], over))


def _pile(key: str) -> float:
    return 100 * _ref()["cases"][key]["3d"]["pile_height_m"]


def _row(key: str) -> dict[str, float]:
    """3D (stored) and live corrected / plane-strain readings of one roll."""
    import numpy as np

    ref = _ref()["cases"][key]["3d"]
    cs = _run(key, "2d+cmd-spread")
    ps = _run(key, "2d")
    hc, hp = cs.hardness.to_dict(), ps.hardness.to_dict()
    sp = cs.contact.cmd_spread
    d_imp = hc["impact_depth_m"]
    curve = ref["curve"]
    return {
        "H": _pile(key),
        "rho3": ref["rho_fd"],
        "rhoc": hc["rho_fd"],
        "rho2": hp["rho_fd"],
        "e3": ref["rho_energy"],
        "ec": hc["rho_energy"],
        "d3": 1e3 * ref["delta_max_m"],
        "dc": 1e3 * d_imp,
        "leff": float(np.interp(d_imp, sp.corrected.delta, sp.length_ratio)),
        "a3": 1e3 * float(np.interp(ref["delta_max_m"], curve["delta_m"], curve["half_width_m"])),
        "ac": 1e3 * cs.contact.semi_contact_width,
    }


def validation() -> str:
    """The fast path's validation table: 3D (stored) against 2d+cmd-spread and 2d (live)."""
    fit = _test_module("test_cmd_spread").FIT_SET
    lines = [
        "| roll | H [cm] | Rho FD 3D | Rho FD 2D + CMD spread | diff. | Rho FD plane strain "
        "| diff. | Rho energy 3D / corrected | impact depth 3D / corrected [mm] "
        "| L_eff/L at that depth |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for key in ROLLS:
        r = _row(key)
        name = _ref()["cases"][key]["3d"]["case"] + (" (fit)" if key in fit else "")
        lines.append(
            f"| {name} | {r['H']:.2f} | {r['rho3']:.1f} | {r['rhoc']:.1f} "
            f"| {100 * (r['rhoc'] / r['rho3'] - 1):+.1f} % | {r['rho2']:.1f} "
            f"| {100 * (r['rho2'] / r['rho3'] - 1):+.1f} % | {r['e3']:.1f} / {r['ec']:.1f} "
            f"| {r['d3']:.2f} / {r['dc']:.2f} | {r['leff']:.2f} |"
        )
    return "\n".join(lines)


def validation_summary() -> str:
    """The sentence under the table: the largest validation miss, plane strain's misses,
    the pile heights through each model."""
    fit = _test_module("test_cmd_spread").FIT_SET
    rows = {k: _row(k) for k in ROLLS}
    val = {k: abs(r["rhoc"] / r["rho3"] - 1) for k, r in rows.items() if k not in fit}
    worst = max(val, key=lambda k: val[k])
    ps = [abs(r["rho2"] / r["rho3"] - 1) for r in rows.values()]
    piles = ("pet2-53.4N-H2cm", "pet2-53.4N-H4cm", "pet2-53.4N-H6cm", "pet2-53.4N")

    def col(c: str) -> str:
        return " / ".join(f"{rows[k][c]:.1f}" for k in piles)

    return (
        f"Largest difference on the {len(val)} validation rolls {100 * val[worst]:.1f} % "
        f"({_ref()['cases'][worst]['3d']['case']} at H = {rows[worst]['H']:g} cm); the "
        f"plane strain misses by {100 * min(ps):.0f}-{100 * max(ps):.0f} %. The pile-height "
        f"dependence follows the 3D model: the corrected path reads {col('rhoc')} Rho for "
        f"H = 2 / 4 / 6 / 8.89 cm against the 3D model's {col('rho3')} (plane strain "
        f"{col('rho2')}): the thin roll's plane-strain basin is shorter (the core is close), "
        f"so it gets less spread (L_eff / L = {rows['pet2-53.4N-H2cm']['leff']:.2f} against "
        f"{rows['pet2-53.4N']['leff']:.2f}), as in 3D"
    )


def width_3d() -> str:
    """The semi-contact width at the impact depth: 3D (stored curve) against the corrected
    path's (the 2D solution's)."""
    parts = []
    for key in ("pet1-26.7N", "pet2-26.7N"):
        r = _row(key)
        parts.append((key, r["a3"], r["ac"]))
    lo = min(a3 / ac - 1 for _, a3, ac in parts)
    hi = max(a3 / ac - 1 for _, a3, ac in parts)
    return f"the 3D a at the impact depth is {100 * lo:.0f}-{100 * hi:.0f} % larger: " + ", ".join(
        f"{a3:.2f} against {ac:.2f} mm on {k}" for k, a3, ac in parts
    )


@cache
def _vs2d() -> tuple[list[float], list[float], list[float]]:
    """PET2 26.7 N: the stored 3D F(d) at every third depth, the live 2D curve there."""
    import numpy as np

    c = _ref()["cases"]["pet2-26.7N"]["3d"]["curve"]
    d = np.asarray(c["delta_m"])
    f3 = np.asarray(c["force_N"])
    idx = list(range(3, len(d), 3))
    if idx[-1] != len(d) - 1:
        idx.append(len(d) - 1)
    c2 = _run("pet2-26.7N", "2d").contact.contact
    f2 = np.interp(d[idx], c2.delta, c2.force)
    return list(d[idx]), list(f3[idx]), list(f2)


def _sig3(x: float) -> str:
    """``x`` to three significant digits, trailing zeros kept: 28.0, 1.77, 101."""
    import math

    return f"{x:.{max(0, 2 - math.floor(math.log10(abs(x))))}f}"


def vs2d() -> str:
    """The 3D against the 2D table on PET2 26.7 N."""
    d, f3, f2 = _vs2d()
    lines = [
        "| depth [mm] | " + " | ".join(f"{1e3 * x:.2f}" for x in d) + " |",
        "|---|" + "---|" * len(d),
        "| F 3D [N] | " + " | ".join(_sig3(x) for x in f3) + " |",
        "| F 2D (plane strain x head length) [N] | " + " | ".join(_sig3(x) for x in f2) + " |",
        "| ratio | " + " | ".join(f"{a / b:.2f}" for a, b in zip(f3, f2, strict=True)) + " |",
    ]
    return "\n".join(lines)


def vs2d_ratio() -> str:
    """The range of the 3D / 2D ratio over the table (inline)."""
    _, f3, f2 = _vs2d()
    r = [a / b for a, b in zip(f3, f2, strict=True)]
    return f"{min(r):.1f}-{max(r):.1f} times"


def _ratio_range(key: str) -> tuple[float, float]:
    """3D / plane strain over 0.25-1 x the curve's depth (stored 3D, live 2D)."""
    import numpy as np

    c = _ref()["cases"][key]["3d"]["curve"]
    d, f3 = np.asarray(c["delta_m"]), np.asarray(c["force_N"])
    c2 = _run(key, "2d").contact.contact
    sel = d > 0.25 * d[-1]
    r = f3[sel] / np.interp(d[sel], c2.delta, c2.force)
    return float(r.min()), float(r.max())


def ez8() -> str:
    """PET1 26.7 N with E_z = E_theta / 8 (stored 3D curve, ``extra``) against plane strain
    and the correction without a CMD-stiffness factor; E_z = E_theta beside it."""
    t = _test_module("test_cmd_spread")
    f3, fc, f2 = t._extra_curves("pet1-26.7N-Ez/8")
    r = f3 / f2
    lo, hi = _ratio_range("pet1-26.7N")
    c = fc / f3
    return (
        f"3D / plane strain = {r.min():.2f}-{r.max():.2f} over 0.25-1 x the depth, against "
        f"{lo:.2f}-{hi:.2f} with E_z = E_theta; the spread without a factor reads F(d) to "
        f"{c.min():.3f}-{c.max():.3f} of the 3D model"
    )


def longer_head() -> str:
    """The 50.8 mm head: corrected / 3D and plane strain / 3D (stored 3D, ``extra``)."""
    t = _test_module("test_cmd_spread")
    out = []
    for key, label in (
        ("pet2-53.4N-L50.8mm", "PET2 53.4 N"),
        ("pet1-26.7N-L50.8mm", "PET1 26.7 N"),
    ):
        f3, fc, f2 = t._extra_curves(key)
        depth = 1e3 * _ref()["extra"][key]["curve"]["delta_m"][-1]
        c, p = fc / f3, f2 / f3
        out.append(
            f"{label} to {depth:g} mm, corrected / 3D = {c.min():.3f}-{c.max():.3f} "
            f"(plane strain / 3D = {p.min():.2f}-{p.max():.2f})"
        )
    return "; ".join(out)


def limits() -> str:
    """L_eff / L at the impact depth of PET2 53.4 N for the Rho-meter head, 10x and 1000x
    as long (the spread does not depend on L)."""
    from dataclasses import replace

    import numpy as np

    from woundroll.contact.plane_strain.cmd_spread import apply_cmd_spread

    res = _run("pet2-53.4N", "2d+cmd-spread")
    c = res.contact.contact
    d = res.hardness.to_dict()["impact_depth_m"]
    L = c.head_length
    ratios = []
    for k in (1, 10, 1000):
        long = replace(c, head_length=k * L, force=np.asarray(c.force) * k)
        sp = apply_cmd_spread(long)
        ratios.append(float(np.interp(d, sp.corrected.delta, sp.length_ratio)))
    return (
        f"on PET2 53.4 N at the impact's depth ({1e3 * d:.2f} mm) L_eff / L = {ratios[0]:.2f} "
        f"for the Rho-meter's {1e3 * L:.1f} mm head, {ratios[1]:.3f} for a head 10 times as "
        f"long, {ratios[2]:.4f} for 1000 times"
    )


def hertz3d() -> str:
    """The 3D Hertz sphere row (the test's fixture problem): F and a against the closed form."""
    import math

    t = _test_module("test_contact3d")
    res, e_star, R = t.hertz.__wrapped__()
    d = res.delta[-1]
    f = res.force[-1] / (4 / 3 * e_star * math.sqrt(R) * d**1.5) - 1
    a = math.sqrt(R * d)
    return (
        f"F {100 * f:+.1f} %, a {100 * (res.half_width[-1] / a - 1):+.1f} % (hoop) and "
        f"{100 * (res.half_length[-1] / a - 1):+.1f} % (CMD)"
    )


def slab() -> str:
    """The plane-strain slab row (the test's problem): 3D force per length against 2D."""
    import numpy as np

    from woundroll.contact import ContactOptions, indent
    from woundroll.contact.heads import Head
    from woundroll.contact.solid3d.solver import Contact3DOptions, indent3d

    t = _test_module("test_contact3d")
    r, s = t.pet_profile()
    web = t.PET1
    opts = Contact3DOptions(
        n_steps=6, predictor="trial", cmd_edges="fixed", axial_size=web.width / 6
    )
    r3 = indent3d(
        web, t.RIGID, r, s, head=Head("cylinder", 0.01, 2 * web.width), depth_max=1e-3, options=opts
    )
    r2 = indent(
        web,
        t.RIGID,
        r,
        s,
        head_radius=0.01,
        head_length=web.width,
        depth_max=1e-3,
        options=ContactOptions(n_steps=6, predictor=False),
    )
    dev = np.abs(np.asarray(r3.force[2:]) / np.asarray(r2.force[2:]) - 1)
    return (
        f"within {100 * dev.max():.1f} % beyond the first increment, "
        f"{100 * abs(r3.force[-1] / r2.force[-1] - 1):.2f} % at 1 mm"
    )


@cache
def _slip3d() -> Any:
    return _run_slip("pet2-53.4N")


def _run_slip(key: str) -> Any:
    import woundroll

    t = _test_module("test_cmd_spread")
    c3 = _ref()["cases"][key]["3d"]
    over = [
        *c3["overrides"],
        "contact.no_update=false",
        "contact.model='3d'",
        "contact.slip='reduced-shear'",
        _head(t),
    ]
    return woundroll.run(woundroll.load_case(c3["case"], over))


def slip3d() -> str:
    """PET2 53.4 N in 3D with the reduced-shear slip (live) against the stored no-slip 3D."""
    res = _slip3d()
    h = res.hardness.to_dict()
    ref = _ref()["cases"]["pet2-53.4N"]["3d"]
    return (
        f"**Rho FD {h['rho_fd']:.1f}** (energy {h['rho_energy']:.1f}; max depth "
        f"{1e3 * h['impact_depth_m']:.2f} mm, a = {1e3 * res.contact.semi_contact_width:.1f} "
        f"mm) against {ref['rho_fd']:.1f} (energy {ref['rho_energy']:.1f}) without slip"
    )


def basin() -> str:
    """lambda, lambda / a and the spread s over the fit window (0.25-1.25 x the impact
    depth) of the corrected path on the ten reference rolls (inline)."""
    import numpy as np

    lam, ratio, spread = [], [], []
    for key in ROLLS:
        res = _run(key, "2d+cmd-spread")
        sp = res.contact.cmd_spread
        d = np.asarray(sp.corrected.delta)
        d_imp = res.hardness.to_dict()["impact_depth_m"]
        sel = (d >= 0.25 * d_imp) & (d <= 1.25 * d_imp)
        a = np.asarray(sp.plane_strain.half_width)[sel]
        lam += list(np.asarray(sp.decay_length)[sel])
        ratio += list(np.asarray(sp.decay_length)[sel] / a)
        spread += list(np.asarray(sp.spread)[sel])
    return (
        f"lambda = {1e3 * min(lam):.0f}-{1e3 * max(lam):.0f} mm, {min(ratio):.0f}-"
        f"{max(ratio):.0f} times the contact half-width a, over 0.25-1.25 x the impact depth "
        f"of the ten reference rolls, where the spread s past each end is "
        f"{1e3 * min(spread):.0f}-{1e3 * max(spread):.0f} mm"
    )


def constants() -> str:
    """The fitted constants of the fast path (inline; their definition in the code)."""
    from woundroll.contact.plane_strain.cmd_spread import BASIN_FACTOR, END_FACTOR

    return f"c_b = {BASIN_FACTOR:g}, c_a = {END_FACTOR:g}"


def ref_cost() -> str:
    """The CPU time each stored 3D reference took when it was made (inline)."""
    cpu = [c["3d"]["cpu_s"] for c in _ref()["cases"].values()]
    return f"{min(cpu):.0f}-{max(cpu):.0f} CPU s a roll when they were made"


def sector_cost() -> str:
    """What a 3D reading costs a profile sector (the registry table, inline): the CPU
    seconds of the default-mesh rolls of the record studies3d.slip (no slip emulation)."""
    import records

    rec = records.load("studies3d.slip")
    runs = {k: v for k, v in rec["cpu_s"].items() if k.endswith(" default none")}
    rolls = sorted({k.split("-")[0].upper() for k in runs})
    return (
        f"{min(runs.values()):.0f}-{max(runs.values()):.0f} CPU s a sector (the "
        f"{'/'.join(rolls)} rolls on the default mesh, measured {rec['measured']} by "
        "`docs/scripts/records.py studies3d.slip`)"
    )


def pile_effect() -> str:
    """How much more the 2 cm pile reads than 8.89 cm, 2D (live) and 3D (stored) (inline)."""
    ref = _ref()["cases"]
    low, tall = "pet2-53.4N-H2cm", "pet2-53.4N"

    def rho2(key: str) -> float:
        return float(_run(key, "2d").hardness.to_dict()["rho_fd"])

    d2 = rho2(low) / rho2(tall) - 1
    d3 = ref[low]["3d"]["rho_fd"] / ref[tall]["3d"]["rho_fd"] - 1
    return f"2D reads {100 * d2:+.0f} %, 3D {100 * d3:+.0f} %"


def mesh_growth() -> str:
    """The 3D mesh's default growth away from the contact zone (inline; a default of
    ``Contact3DOptions``)."""
    from woundroll.contact.solid3d.solver import Contact3DOptions

    o = Contact3DOptions()
    g = {o.radial_growth, o.tangential_growth, o.axial_growth}
    if len(g) == 1:
        return f"growth {o.radial_growth:g} in all three directions"
    return (
        f"growth {o.radial_growth:g} radially, {o.tangential_growth:g} along the hoop and "
        f"{o.axial_growth:g} along the CMD"
    )


def validation_max() -> str:
    """The registry table's cell: how many validation rolls, and the largest miss (inline)."""
    fit = _test_module("test_cmd_spread").FIT_SET
    val = [abs(_row(k)["rhoc"] / _row(k)["rho3"] - 1) for k in ROLLS if k not in fit]
    return f"{len(val)} more rolls within {100 * max(val):.1f} % of 3D"


BLOCKS: dict[str, Callable[[], str]] = {
    "vs2d": vs2d,
    "vs2d_ratio": vs2d_ratio,
    "validation": validation,
    "validation_summary": validation_summary,
    "width_3d": width_3d,
    "ez8": ez8,
    "longer_head": longer_head,
    "limits": limits,
    "hertz3d": hertz3d,
    "slab": slab,
    "slip3d": slip3d,
    "basin": basin,
    "constants": constants,
    "ref_cost": ref_cost,
    "pile_effect": pile_effect,
    "sector_cost": sector_cost,
    "mesh_growth": mesh_growth,
    "validation_max": validation_max,
}

if __name__ == "__main__":
    import sys

    for name in sys.argv[1:] or list(BLOCKS):
        print(f"--- {name}\n{BLOCKS[name]()}", flush=True)
