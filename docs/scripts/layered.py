"""Generators of docs/contact.md's numbers on the layered roll and the other explanations
(frozen shear, a lower G/E_r) (docs/scripts/regenerate.py runs them).

The verification numbers are the tests' own problems (tests/contact/test_layered.py's PET1
test roll, test_layered_plates.py's nine-sheet stack), the readings are the pipeline's
(``woundroll.studies.layered.layered_study`` on PET1 26.7 N and PET2 53.4 N at H = 8.89 and
2 cm, default options, the bundled Rho-meter). Cost: about 6-8 CPU min on a quiet 2-core
machine (16 layered pipeline runs of 10-60 s each, a few 2D runs, ~20 small layered solves).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
MUS = (1e4, 0.5, 0.3, 0.1)


def _test_module(name: str) -> Any:
    """tests/contact/<name>.py as a module: the page shows the tests' own problems."""
    import records

    return records.test_module(f"contact/{name}.py")


@cache
def _roll(mu: float, interfaces: bool = True, layers_per_shell: int = 1) -> Any:
    """The PET1 test roll (test_layered.py) pressed 1 mm, default layered options."""
    from woundroll.contact.layered.solver import LayeredOptions, indent_layered

    t = _test_module("test_layered")
    r, s = t.pet_profile()
    opts = LayeredOptions(interfaces=interfaces, layers_per_shell=layers_per_shell)
    return indent_layered(
        t.PET1, t.RIGID, r, s, depth_max=1e-3, friction=mu, options=opts, **t.HEAD
    )


@cache
def _continuum_2d() -> Any:
    """The 2D model on its own mesh and step control, same roll, 1 mm."""
    from woundroll.contact import indent

    t = _test_module("test_layered")
    r, s = t.pet_profile()
    return indent(t.PET1, t.RIGID, r, s, depth_max=1e-3, **t.HEAD)


def test_roll() -> str:
    """The mu table's setting (inline): sheets, zone depth, steps."""
    import math

    from woundroll.contact.layered.solver import LAYERED_DEPTH

    t = _test_module("test_layered")
    res = _roll(0.3)
    r_eff = 1.0 / (1.0 / t.HEAD["head_radius"] + 1.0 / t.R_OUT)
    zone = LAYERED_DEPTH * math.sqrt(2.0 * r_eff * 1e-3)
    return (
        f"{round(zone / t.H)} sheets, layered zone {1e3 * zone:.1f} mm, {len(res.delta) - 1} steps"
    )


def mu_table() -> str:
    """Force at 1 mm on the PET1 test roll against mu; the continuum on the same mesh."""
    cont = float(_roll(0.3, interfaces=False).force[-1])
    lines = ["| mu | force [N] | against the continuum |", "|---|---|---|"]
    for mu in MUS:
        f = float(_roll(mu).force[-1])
        label = "1e4 (stick)" if mu == 1e4 else f"{mu:g}"
        lines.append(f"| {label} | {f:.1f} | {100 * (f / cont - 1):+.1f} % |")
    return "\n".join(lines)


def stick_row() -> str:
    """Verification cell: every interface sticks against the continuum on the same mesh."""
    a, b = float(_roll(1e4).force[-1]), float(_roll(0.3, interfaces=False).force[-1])
    return f"{a:.3f} N vs {b:.3f} N ({abs(a / b - 1):.0e})"


def own_mesh_row() -> str:
    """Verification cell: the stuck layered roll against the 2D model's own mesh."""
    a, b = float(_roll(1e4).force[-1]), float(_continuum_2d().force[-1])
    return f"{a:.1f} vs {b:.1f} N ({100 * abs(a / b - 1):.2f} %)"


@cache
def _plates() -> tuple[float, float, float, float]:
    t = _test_module("test_layered_plates")
    stuck, free = t.stack(1.0, interfaces=False), t.stack(1e-6)
    return stuck, free, t.beam_stiffness(t.EI_STICK), t.beam_stiffness(t.EI_SLIP)


def plates_free() -> str:
    stuck, free, k_stick, k_slip = _plates()
    return f"{free:.3e} vs {k_slip:.3e} N/m^2 ({100 * (free / k_slip - 1):+.1f} %)"


def plates_stuck() -> str:
    stuck, free, k_stick, k_slip = _plates()
    return f"{stuck:.3e} vs {k_stick:.3e} N/m^2 ({100 * (stuck / k_stick - 1):+.1f} %)"


def plates_ratio() -> str:
    stuck, free, k_stick, k_slip = _plates()
    return f"{stuck / free:.3f} vs {k_stick / k_slip:.3f}"


def layers_per_shell() -> str:
    """1, 2, 4 layers per shell at mu 0.3 on the PET1 test roll, 1 mm (inline)."""
    f = [float(_roll(0.3, layers_per_shell=k).force[-1]) for k in (1, 2, 4)]
    return (
        f"1 -> {f[0]:.1f} N, 2 -> {f[1]:.1f} N ({100 * (f[1] / f[0] - 1):+.1f} %), "
        f"4 -> {f[2]:.1f} N ({100 * (f[2] / f[0] - 1):+.1f} %)"
    )


def refinement() -> str:
    """The slow tests' refinements (test_layered.py): load steps 4/8/16 on 5 sheets and
    4/2/1 layers per shell on 8 layers, mu 0.3, 0.5 mm, with the observed orders."""
    from woundroll.contact.layered.solver import ContactOptions, LayeredOptions

    t = _test_module("test_layered")
    steps = [
        t.run(
            0.3, LayeredOptions(base=ContactOptions(newton=False, n_steps=n), layered_depth=5 * t.H)
        )
        for n in (4, 8, 16)
    ]
    lps = [
        t.run(
            0.3,
            LayeredOptions(
                base=ContactOptions(newton=False, n_steps=4),
                layered_depth=8 * t.H,
                layers_per_shell=k,
            ),
        )
        for k in (4, 2, 1)
    ]
    return (
        "4/8/16 load steps "
        + " / ".join(f"{f:.2f}" for f in steps)
        + f" N, observed order {t._order(steps):.2f}; 4/2/1 layers per shell (8 layers) "
        + " / ".join(f"{f:.1f}" for f in lps)
        + f" N, monotone toward one sheet per layer, observed order {t._order(lps):.2f}"
    )


# ------------------------------------------------------------- readings of the rolls


@cache
def _study() -> Any:
    """``woundroll study layered`` on PET1 26.7 N, PET2 53.4 N and its 2 cm pile."""
    from woundroll.studies.layered import layered_study

    return layered_study(cases=("pet1-26.7N", "pet2-53.4N"), pile_heights=(0.02,))


def _rows() -> list[dict[str, Any]]:
    return list(_study().rows)


COLS = (
    ("2d", "rho_2d"),
    ("layered mu 0.1 / 0.3 / 0.5", None),
    ("2d, G frozen", "rho_2d_shear_frozen"),
    ("2d, G = 1 E_r", "rho_2d_shear_ratio1"),
    ("2d, G = 0.5 E_r", "rho_2d_shear_ratio0.5"),
    ("layered mu 0.3, G frozen", "rho_layered_mu0.3_shear_frozen"),
)
LAYERED = ("rho_layered_mu0.1", "rho_layered_mu0.3", "rho_layered_mu0.5")


def _label(row: dict[str, Any]) -> str:
    name = {"pet1-26.7N": "PET1 26.7 N", "pet2-53.4N": "PET2 53.4 N"}[row["case"]]
    if row["case"] == "pet2-53.4N":
        name += f", H {100 * row['pile_height_m']:.3g} cm"
    return name


def readings() -> str:
    """Rho FD side by side: the continuum, the layered roll, the other explanations."""
    rows = _rows()
    lines = [
        "| roll | " + " | ".join(c for c, _ in COLS) + " |",
        "|---|" + "---|" * len(COLS),
    ]

    def cells(get: Callable[[str], float], fmt: str) -> str:
        out = []
        for _, key in COLS:
            if key is None:
                out.append(" / ".join(format(get(k), fmt) for k in LAYERED))
            else:
                out.append(format(get(key), fmt))
        return " | ".join(out)

    for row in rows:
        lines.append(f"| {_label(row)} | " + cells(lambda k, r=row: r[k], ".1f") + " |")
    tall = next(r for r in rows if r["series"] == "table2" and r["case"] == "pet2-53.4N")
    low = next(r for r in rows if r["series"] == "pile-height")
    lines.append(
        f"| pile-height ratio H {100 * low['pile_height_m']:.3g} / "
        f"{100 * tall['pile_height_m']:.3g} cm | " + cells(lambda k: low[k] / tall[k], ".2f") + " |"
    )
    return "\n".join(lines)


def effects() -> str:
    """The paragraph under the readings: how much each explanation lowers each roll."""
    rows = _rows()
    p1 = next(r for r in rows if r["case"] == "pet1-26.7N")
    p2 = next(r for r in rows if r["series"] == "table2" and r["case"] == "pet2-53.4N")
    low = next(r for r in rows if r["series"] == "pile-height")

    def d(row: dict[str, Any], key: str) -> float:
        return 100 * (row[key] / row["rho_2d"] - 1)

    def ratio(key: str) -> float:
        return low[key] / p2[key]

    fr = [ratio(k) for k in (*LAYERED, "rho_2d_shear_frozen", "rho_layered_mu0.3_shear_frozen")]
    return (
        "Every explanation lowers the readings. The layered model (mu 0.3) lowers soft PET2 "
        + ("more" if d(p2, "rho_layered_mu0.3") < d(p1, "rho_layered_mu0.3") else "less")
        + f" than hard PET1 ({d(p2, 'rho_layered_mu0.3'):.0f} % against "
        f"{d(p1, 'rho_layered_mu0.3'):.0f} %); frozen shear lowers PET1 by "
        f"{-d(p1, 'rho_2d_shear_frozen'):.0f} % and PET2 by {-d(p2, 'rho_2d_shear_frozen'):.0f} % "
        f"(E_r grows most under the head of the hard roll); a lower ratio lowers both "
        f"({d(p1, 'rho_2d_shear_ratio1'):.0f} / {d(p2, 'rho_2d_shear_ratio1'):.0f} % at 1, "
        f"{d(p1, 'rho_2d_shear_ratio0.5'):.0f} / {d(p2, 'rho_2d_shear_ratio0.5'):.0f} % at 0.5). "
        f"None brings the pile-height ratio near the tests' ~1 (the continuum: "
        f"{ratio('rho_2d'):.2f}): friction and frozen shear leave it at "
        f"{min(fr):.2f}-{max(fr):.2f}, a lower G/E_r gives {ratio('rho_2d_shear_ratio1'):.2f} "
        f"at 1 and {ratio('rho_2d_shear_ratio0.5'):.2f} at 0.5"
    )


def _rho(case: str, *over: str) -> float:
    import woundroll

    res = woundroll.run(woundroll.load_case(case, [*over, "contact.no_update=false"]))
    return float(res.hardness.to_dict()["rho_fd"])


def shear08() -> str:
    """2d with G_r_theta = 0.8 E_r (inline): the three rolls and the pile ratio."""
    import woundroll
    from woundroll.studies.layered import _PILE_OVERRIDE, PILE_CASE

    r_core = woundroll.load_case(PILE_CASE).core.build().outer_radius
    over = ("contact.model='2d'", "contact.shear_ratio=0.8")
    p1 = _rho("pet1-26.7N", *over)
    p2 = _rho(PILE_CASE, *over)
    p2h = _rho(PILE_CASE, _PILE_OVERRIDE.format(r=r_core + 0.02), *over)
    return (
        f"PET1 26.7 N {p1:.1f}, PET2 53.4 N {p2:.1f} at 8.89 cm and {p2h:.1f} at 2 cm "
        f"(ratio {p2h / p2:.2f})"
    )


def pile_ratios() -> str:
    """The pile-height ratios (2 / 8.89 cm) of the layered roll, frozen shear and a lower
    G/E_r, for the bullet under "Which model reads a roll" (inline)."""
    rows = _rows()
    tall = next(r for r in rows if r["series"] == "table2" and r["case"] == "pet2-53.4N")
    low = next(r for r in rows if r["series"] == "pile-height")

    def q(key: str) -> float:
        return low[key] / tall[key]

    lay = [q(k) for k in LAYERED]
    lower = [q("rho_2d_shear_ratio1"), q("rho_2d_shear_ratio0.5")]
    return (
        f'(`contact.model = "layered"`: {min(lay):.2f}-{max(lay):.2f} over mu 0.1-0.5), '
        f"frozen shear ({q('rho_2d_shear_frozen'):.2f}) or a lower G/E_r "
        f"({min(lower):.2f}-{max(lower):.2f})"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "test_roll": test_roll,
    "mu_table": mu_table,
    "stick_row": stick_row,
    "own_mesh_row": own_mesh_row,
    "plates_free": plates_free,
    "plates_stuck": plates_stuck,
    "plates_ratio": plates_ratio,
    "layers_per_shell": layers_per_shell,
    "refinement": refinement,
    "readings": readings,
    "effects": effects,
    "shear08": shear08,
    "pile_ratios": pile_ratios,
}

if __name__ == "__main__":
    import sys

    for name in sys.argv[1:] or list(BLOCKS):
        print(f"--- {name}\n{BLOCKS[name]()}", flush=True)
