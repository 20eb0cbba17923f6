"""Generators of docs/studies.md's layered section ("Layered: the layered roll beside the
continuum"): the table of `woundroll study layered` and the bullets under it.

The 88 runs of the study (``woundroll.studies.layered.study_jobs``: the same list the
command runs) and the uniform PET3 roll are too slow for ``make docs`` (about 15 CPU min);
they are a measured record (docs/scripts/records.py ``layered_study.table``,
docs/data/layered_study.table.json) that the blocks here render. So are the bullets' other
runs (``checks``: the zone deepened, the paper's slip fraction, the reduced-shear fraction
fitted to the layered roll by bisection) and the layered roll in 3D (``roll3d``: readings on
the coarse 3D mesh; ``head3d``: the pressure under the head and the CMD spread; ``lps3d``:
finer shells). The 2d readings at G = 0.8 E_r (three 2d runs, ~5 CPU s) are live.
Re-measure with::

    PYTHONPATH=src .venv/bin/python docs/scripts/records.py layered_study.table
    PYTHONPATH=src .venv/bin/python docs/scripts/records.py layered_study.checks  # after table
    PYTHONPATH=src .venv/bin/python docs/scripts/records.py layered_study.roll3d  # and the rest
    .venv/bin/python docs/scripts/regenerate.py layered_study
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import records
from records import Measurement, Run

#: The uniform PET3 roll: the Table 3 case without its thickness profile.
PET3 = "pet3-2.3MPa"
PET3_ID = "pet3-2.3MPa-uniform"


def _run_id(case: str, pile_height_m: float | None, model: str) -> str:
    roll = case if pile_height_m is None else f"{case}@{100 * pile_height_m:g}cm"
    return f"{roll}/{model}"


def table_runs() -> list[Run]:
    """The study's 88 runs (its own list) and the uniform PET3 roll under every model."""
    from woundroll.studies.layered import study_jobs, study_models

    runs = [
        Run(
            _run_id(j.case, j.pile_height_m, j.model),
            j.case,
            j.overrides,
            (("series", j.series), ("model", j.model)),
        )
        for j in study_jobs()
    ]
    runs += [
        Run(
            f"{PET3_ID}/{name}",
            PET3,
            ("contact.no_update=false", *over),
            (("series", "pet3-uniform"), ("model", name), ("thickness_profile", None)),
        )
        for name, over in study_models()
    ]
    return runs


def measure_reading(run: Run) -> dict[str, Any]:
    """Rho FD, the FD impact depth and the pile height of one run (the study's own job;
    the PET3 runs with the case's thickness profile removed: a uniform roll)."""
    from woundroll.studies.layered import _job

    if ("thickness_profile", None) not in run.params:
        got = _job(run.case, run.overrides)
        return {
            "rho_fd": got["rho_fd"],
            "impact_depth_m": got["delta_max_m"],
            "pile_height_m": got["pile_height_m"],
        }
    from woundroll.case import load_case
    from woundroll.pipeline import run as run_pipeline

    case = load_case(run.case, list(run.overrides))
    case = case.model_copy(
        update={"winding": case.winding.model_copy(update={"thickness_profile": None})}
    )
    res = run_pipeline(case)
    assert res.hardness is not None
    h = res.hardness.to_dict()
    return {
        "rho_fd": float(h["rho_fd"]),
        "impact_depth_m": float(h["impact_depth_m"]),
        "pile_height_m": float(res.winding.radius[-1] - res.winding.radius[0]),
    }


# ------------------------------------------------------------- the bullets' other runs

#: The reduced-shear emulation (2d) and its bisection on ``contact.slip_shear_fraction``.
EMULATION = ("contact.model='2d'", "contact.slip='reduced-shear'", "contact.friction=0.3")
#: Bracket of the fraction [-] and the bracket width where the bisection stops [-].
FIT_BRACKET = (0.01, 1.0)
FIT_WIDTH = 0.005
#: The rolls the fraction is fitted to (a Table 2 roll of each material): (case, the table
#: record's run it is fitted to).
FIT_ROLLS = (("pet1-26.7N", "pet1-26.7N/layered_mu0.3"), ("pet2-53.4N", "pet2-53.4N/layered_mu0.3"))
#: The paper's fraction (the case key's default) read on PET2 53.4 N.
PAPER_FRACTION = 0.01
#: Zone depths of the zone caveat [mm] (the default, 1 a_geo, is the table's mu 0.3 column).
ZONE_DEPTHS_MM = (11.3, 15.0)
#: Its rolls: (case, pile height [m] or None for the Table 2 roll, depths [mm]).
ZONE_ROLLS: tuple[tuple[str, float | None, tuple[float, ...]], ...] = (
    ("pet1-26.7N", None, ZONE_DEPTHS_MM[:1]),
    ("pet2-53.4N", None, ZONE_DEPTHS_MM),
    ("pet2-53.4N", 0.02, ZONE_DEPTHS_MM),
)


#: The zone-depth ladder (layered, mu 0.3): (case, pile height [m] or None for the case's
#: own, depths [mm]); each ends near the deepest zone the model takes (a continuum of at
#: least a tenth of the wound thickness must stay below it).
ZONE_LADDER: tuple[tuple[str, float | None, tuple[float, ...]], ...] = (
    ("pet2-53.4N", None, (4.0, 8.0, 12.0, 20.0, 30.0, 45.0, 70.0)),
    ("pet2-53.4N", 0.02, (4.0, 8.0, 12.0, 17.0)),
    ("pet1-26.7N", None, (12.0, 30.0, 70.0)),
)


def zone_runs() -> list[Run]:
    """The layered roll (mu 0.3) with its zone of sheets deepened toward the whole pile."""
    base = ("contact.no_update=false", "contact.model='layered'", "contact.friction=0.3")
    return [
        Run(
            f"zone/{_run_id(case, h, f'{d:g}mm')}",
            case,
            (
                *(_pile_overrides(h) if h is not None else ()),
                *base,
                f"contact.layered_depth='{d:g} mm'",
            ),
        )
        for case, h, depths in ZONE_LADDER
        for d in depths
    ] + [
        # the deepest PET1 zone stuck (mu 1e4): the continuum on the layered mesh, so that
        # a fall of the ladder is the sheets' slip, not the zone's mesh
        Run(
            f"zone/pet1-26.7N/{ZONE_LADDER[-1][2][-1]:g}mm_stuck",
            "pet1-26.7N",
            (
                "contact.no_update=false",
                "contact.model='layered'",
                "contact.friction=10000.0",
                f"contact.layered_depth='{ZONE_LADDER[-1][2][-1]:g} mm'",
            ),
        )
    ]


def _pile_overrides(h: float) -> tuple[str, ...]:
    """The study's overrides of :data:`PILE_CASE` wound to pile height ``h`` [m]."""
    from woundroll.studies.layered import study_rolls

    return study_rolls((), (h,))[0][3]


def _table_rho(run_id: str) -> float | None:
    """Rho FD of run ``run_id`` in the table record (None before it is measured)."""
    try:
        return float(records.results("layered_study.table")[run_id]["rho_fd"])
    except (SystemExit, KeyError):
        return None


def checks_runs() -> list[Run]:
    """The zone-depth runs (layered, mu 0.3), the paper's fraction on PET2 and the
    reduced-shear fits (each with its target, from the table record, in its params, so
    that a re-measured table makes the fits stale)."""
    base = ("contact.no_update=false", "contact.model='layered'", "contact.friction=0.3")
    runs = []
    for case, h, depths in ZONE_ROLLS:
        over = _pile_overrides(h) if h is not None else ()
        for d in depths:
            runs.append(
                Run(
                    f"zone/{_run_id(case, h, f'{d:g}mm')}",
                    case,
                    (*over, *base, f"contact.layered_depth='{d:g} mm'"),
                )
            )
    runs.append(
        Run(
            "paper_fraction/pet2-53.4N",
            "pet2-53.4N",
            (
                "contact.no_update=false",
                *EMULATION,
                f"contact.slip_shear_fraction={PAPER_FRACTION}",
            ),
        )
    )
    off = _pile_overrides(0.02)
    for case, target in FIT_ROLLS:
        runs.append(
            Run(
                f"fit/{case}",
                case,
                ("contact.no_update=false", *EMULATION),
                (
                    ("target_run", target),
                    ("target_rho_fd", _table_rho(target)),
                    ("off_roll", ("pet2-53.4N", off)),
                ),
            )
        )
    return runs


def _emulated_rho(case: str, overrides: tuple[str, ...], fraction: float) -> float:
    from woundroll.studies.layered import _job

    over = (*overrides, f"contact.slip_shear_fraction={fraction!r}")
    return float(_job(case, over)["rho_fd"])


def measure_check(run: Run) -> dict[str, Any]:
    """A zone or paper-fraction run: its reading; a fit run: the bisection of the fraction
    until the bracket is :data:`FIT_WIDTH` wide (Rho grows with the fraction), the reading at
    the bracket's middle, and that fraction's reading on the off-roll (PET2's 2 cm pile)."""
    if not run.id.startswith("fit/"):
        return measure_reading(run)
    target = run.param("target_rho_fd")
    if target is None:
        raise SystemExit(f"{run.id}: measure layered_study.table first (the fit's target)")
    lo, hi = FIT_BRACKET
    r_lo = _emulated_rho(run.case, run.overrides, lo)
    r_hi = _emulated_rho(run.case, run.overrides, hi)
    if not r_lo < target < r_hi:
        raise SystemExit(f"{run.id}: target {target} outside [{r_lo}, {r_hi}] over {FIT_BRACKET}")
    n = 2
    while hi - lo > FIT_WIDTH:
        mid = 0.5 * (lo + hi)
        n += 1
        if _emulated_rho(run.case, run.overrides, mid) < target:
            lo = mid
        else:
            hi = mid
    f = 0.5 * (lo + hi)
    off_case, off_over = run.param("off_roll")
    return {
        "slip_shear_fraction": f,
        "rho_fd": _emulated_rho(run.case, run.overrides, f),
        "target_rho_fd": target,
        "off_roll_rho_fd": _emulated_rho(off_case, (*off_over, *run.overrides), f),
        "evaluations": float(n + 2),
    }


# ------------------------------------------------------------- the layered roll in 3D

#: The 3D table's first rolls (the pressure under the head, finer shells): (case, pile height
#: [m] or None for the case's own).
ROLLS_3D: tuple[tuple[str, float | None], ...] = (
    ("pet1-26.7N", None),
    ("pet1-26.7N", 0.02),
    ("pet2-53.4N", None),
    ("pet2-53.4N", 0.02),
)


def _models_3d() -> dict[str, tuple[str, ...]]:
    """The 3D columns of `woundroll study layered-3d` (its coarse mesh, one definition:
    ``woundroll.studies.layered.COARSE_3D``): ``{name: overrides}``."""
    from woundroll.studies.layered import study_models

    return {n: o for n, o in study_models(explanations=(), three_d=True) if "3d" in n}


#: The friction of the 3D table's layered-3d column (the others: the mu sweep's rows).
MU_3D = 0.3
LAYERED_3D = f"layered-3d_mu{MU_3D:g}"
#: Sheets a shell of the ladder's thick shells: the coarse mesh's surface ring on PET2 53.4 N
#: (what layered-3d's ``layers_per_shell=None`` gives there; :func:`lps_ladder3d` checks it).
LPS_RING = 9
#: The depth both 3D models are pressed to for the pressure under the head [m], and where
#: it is read: depths on the column under the head's centre [m], depths of the CMD spread [m].
HEAD_DEPTH = 1.4e-3
PRESSURE_DEPTHS = (0.25e-3, 0.5e-3, 1e-3, 2e-3, 4e-3, 8e-3, 16e-3)
SPREAD_DEPTHS = (0.0, 1e-3, 3e-3)
#: The fraction of the centre-plane value that marks the CMD spread [-].
SPREAD_LEVEL = 0.1


def _wound_to(case: str, h: float | None) -> tuple[str, ...]:
    """Overrides that wind ``case`` to pile height ``h`` [m] (none for the case's own)."""
    if h is None:
        return ()
    from woundroll.case import load_case
    from woundroll.studies.layered import _PILE_OVERRIDE

    return (_PILE_OVERRIDE.format(r=load_case(case).core.build().outer_radius + h),)


def roll3d_runs() -> list[Run]:
    """PET1's 2 cm pile in 2d, layered, 3d and layered-3d (the other rolls' 2d and layered
    are the table's); the 3d and
    layered-3d (mu :data:`MU_3D`) runs of `woundroll study layered-3d` (its own list, the
    8.89 cm pile left out: it is the Table 2 roll) and of the uniform PET3 roll; the mu
    sweep (layered-3d at the study's other frictions) on PET2 53.4 N at both pile heights."""
    from woundroll.studies.layered import study_jobs

    runs = [
        Run(
            _run_id("pet1-26.7N", 0.02, name),
            "pet1-26.7N",
            (*_wound_to("pet1-26.7N", 0.02), "contact.no_update=false", *over),
        )
        for name, over in (
            ("2d", ("contact.model='2d'",)),
            ("layered_mu0.3", ("contact.model='layered'", "contact.friction=0.3")),
            ("3d", _models_3d()["3d"]),
            (LAYERED_3D, _models_3d()[LAYERED_3D]),
        )
    ]
    sweep = [_run_id(c, h, "")[:-1] for c, h in ROLLS_3D if c == "pet2-53.4N"]
    for j in study_jobs(explanations=(), three_d=True):
        roll = _run_id(j.case, j.pile_height_m, "")[:-1]
        if "3d" not in j.model or roll == "pet2-53.4N@8.89cm":
            continue
        if j.model in ("3d", LAYERED_3D) or roll in sweep:
            runs.append(Run(_run_id(j.case, j.pile_height_m, j.model), j.case, j.overrides))
    runs += [
        Run(
            f"{PET3_ID}/{name}",
            PET3,
            ("contact.no_update=false", *over),
            (("thickness_profile", None),),
        )
        for name, over in _models_3d().items()
        if name in ("3d", LAYERED_3D)
    ]
    # the coarse mesh's own offset: 3d on the default 3D mesh
    runs += [
        Run(f"{c}/3d_default_mesh", c, ("contact.no_update=false", "contact.model='3d'"))
        for c in ("pet1-26.7N", "pet2-53.4N")
    ]
    # and layered-3d's (its ratio to 3d on the default mesh)
    runs += [
        Run(
            f"{c}/{LAYERED_3D}_default_mesh",
            c,
            ("contact.no_update=false", "contact.model='layered-3d'", f"contact.friction={MU_3D}"),
        )
        for c in ("pet1-26.7N", "pet2-53.4N")
    ]
    return runs


#: The rolls of the layers-per-shell ladder (case, pile height [m] or None for its own):
#: the soft roll the default was chosen on, a hard one and a short pile.
LPS_ROLLS: tuple[tuple[str, float | None], ...] = (
    ("pet2-53.4N", None),
    ("pet1-26.7N", None),
    ("pet2-53.4N", 0.02),
)


def lps_runs() -> list[Run]:
    """layered-3d at the default sheets a shell and at one on :data:`LPS_ROLLS`, and PET2
    53.4 N at 8.89 cm also with :data:`LPS_RING` sheets a shell (the 3D surface ring): the
    layers-per-shell ladder. The default's readings are the roll3d record's runs again (the
    same inputs); measured here so that the ladder's CPU times come from one code version
    (roll3d's predate the 3D solver's PARDISO settings, which cut a run's CPU by ~30 %)."""
    n0 = _lps_default()
    runs = []
    for case, h in LPS_ROLLS:
        shells = (LPS_RING, n0, 1) if (case, h) == LPS_ROLLS[0] else (n0, 1)
        runs += [
            Run(
                _run_id(case, h, f"layered-3d_lps{n}"),
                case,
                (
                    *_wound_to(case, h),
                    "contact.no_update=false",
                    *_models_3d()[LAYERED_3D],
                    f"contact.layers_per_shell={n}",
                ),
            )
            for n in shells
        ]
    return runs


def head_runs() -> list[Run]:
    """PET2 53.4 N (H 8.89 cm) pressed :data:`HEAD_DEPTH` deep by both 3D models."""
    return [
        Run(
            f"pet2-53.4N/{name}@{1e3 * HEAD_DEPTH:g}mm",
            "pet2-53.4N",
            (*over, f"contact.depth_max='{1e3 * HEAD_DEPTH:g} mm'"),
        )
        for name, over in (
            ("3d", _models_3d()["3d"]),
            ("layered-3d", _models_3d()[LAYERED_3D]),
            ("layered-3d_lps1", (*_models_3d()[LAYERED_3D], "contact.layers_per_shell=1")),
        )
    ]


def measure_head(run: Run) -> dict[str, Any]:
    """The force at :data:`HEAD_DEPTH`, the contact-induced radial pressure -sigma_r on the
    element column under the head's centre (nearest theta = 0 and z = 0) at
    :data:`PRESSURE_DEPTHS` (linear in depth between element centres), and the CMD
    half-width where -sigma_r on the hoop line nearest theta = 0 falls to
    :data:`SPREAD_LEVEL` of its centre-plane value, at :data:`SPREAD_DEPTHS` (at 0 the
    head's contact pressure on the surface line; deeper, the element layer nearest the depth;
    linear in z between points)."""
    import numpy as np

    from woundroll.case import load_case
    from woundroll.pipeline import run as run_pipeline

    res = run_pipeline(load_case(run.case, list(run.overrides)))
    assert res.contact is not None
    c = res.contact.contact
    r_out = float(res.winding.radius[-1])
    depth = r_out - np.asarray(c.element_r)
    theta = np.asarray(c.element_theta)
    z = np.asarray(c.element_z)
    p = -np.asarray(c.sigma_r)
    on_line = np.isclose(theta, theta.min(), rtol=0, atol=1e-12)
    column = on_line & np.isclose(z, z[on_line].min(), rtol=0, atol=1e-12)
    order = np.argsort(depth[column])
    d_col, p_col = depth[column][order], p[column][order]
    out: dict[str, Any] = {
        "depth_m": float(c.delta[-1]),
        "force_N": float(c.force[-1]),
        "pressure_depths_m": list(PRESSURE_DEPTHS),
        "spread_depths_m": list(SPREAD_DEPTHS),
    }
    # one key a number (the spot check's tolerance applies to numbers, not to lists)
    for k, d in enumerate(PRESSURE_DEPTHS):
        out[f"pressure_{k}_Pa"] = float(np.interp(d, d_col, p_col))

    def half_width(zz: Any, pp: Any, where: str) -> float:
        level = SPREAD_LEVEL * pp[0]
        k = int(np.argmax(pp < level))  # first point below the level
        if k == 0:
            raise SystemExit(f"{run.id}: the pressure {where} never falls to the level")
        return float(zz[k - 1] + (level - pp[k - 1]) * (zz[k] - zz[k - 1]) / (pp[k] - pp[k - 1]))

    layers = np.unique(depth[on_line])
    widths = []
    for d in SPREAD_DEPTHS:
        if d == 0.0:  # the head's contact pressure on the surface line theta = 0
            widths.append(
                half_width(np.asarray(c.surface_z), np.asarray(c.surface_pressure)[0], "at 0")
            )
            continue
        # the element layer nearest d (h-layered3d's reading; the coarse mesh's layers are
        # ~1 mm thick there)
        layer = layers[np.argmin(np.abs(layers - d))]
        row = on_line & np.isclose(depth, layer, rtol=0, atol=1e-12)
        zo = np.argsort(z[row])
        widths.append(half_width(z[row][zo], p[row][zo], f"at {1e3 * d:g} mm"))
    for k, w in enumerate(widths):
        out[f"spread_half_width_{k}_m"] = w
    return out


MEASUREMENTS: dict[str, Measurement] = {
    "table": Measurement(
        models=records.LAYERED,
        about="`woundroll study layered` (88 runs) and the uniform PET3 roll, Rho FD",
        runs=table_runs,
        measure=measure_reading,
        spot=("pet2-53.4N@2cm/2d", "pet2-53.4N@2cm/layered_mu0.1"),
        rtol=1e-3,
        reason=(
            "deterministic solves; 1e-3 covers platform rounding of the contact Newton "
            "iterations and the FD step control, and is below the 0.1 Rho the page shows"
        ),
        cost="about 14 CPU min: 2d runs ~1 CPU s, layered 9-31 CPU s (measured at load 5-7)",
    ),
    "checks": Measurement(
        models=records.LAYERED,
        about=(
            "the layered zone deepened (mu 0.3), the paper's slip fraction, and the "
            "reduced-shear fraction fitted to the layered roll by bisection"
        ),
        runs=checks_runs,
        measure=measure_check,
        spot=("paper_fraction/pet2-53.4N", "fit/pet2-53.4N"),
        rtol=1e-3,
        reason=(
            "deterministic solves (as the table); a fit's fraction moves only if a reading "
            "crosses its target at a bisection step, a change of code the check should catch"
        ),
        cost="about 6 CPU min: five deep-zone layered runs (30-75 CPU s), two fits of 12 2d runs",
    ),
    "zone": Measurement(
        models=records.LAYERED,
        about="the layered roll (mu 0.3) with its zone of sheets deepened toward the whole pile",
        runs=zone_runs,
        measure=measure_reading,
        spot=("zone/pet2-53.4N@2cm/4mm",),
        rtol=1e-3,
        reason="deterministic solves (as the table)",
        cost="about 15 CPU min: 10-30 CPU s a run at 4-12 mm, ~2-3 CPU min at 70 mm",
    ),
    "roll3d": Measurement(
        models=records.LAYERED_SOLID,
        about="the layered roll in 3D beside 3d (coarse 3D mesh, mu 0.3), Rho FD",
        runs=roll3d_runs,
        measure=measure_reading,
        spot=("pet1-26.7N@2cm/2d", "pet1-26.7N@2cm/3d"),
        rtol=1e-3,
        reason=(
            "deterministic solves (as the table); the 3D head contact's gap tolerance moves "
            "a force by ~4e-4 between two runs of the same equations (docs/contact.md)"
        ),
        cost=(
            "about 35 CPU min: layered-3d 37-107 CPU s a roll on the coarse mesh, 3d 4-12 CPU "
            "s; on the default 3D mesh 3d 19-41 CPU s, layered-3d ~8-20 CPU min"
        ),
    ),
    "head3d": Measurement(
        models=records.LAYERED_SOLID,
        about=(
            "PET2 53.4 N pressed 1.4 mm by 3d and layered-3d: the pressure under the head "
            "and the CMD spread"
        ),
        runs=head_runs,
        measure=measure_head,
        spot=("pet2-53.4N/3d@1.4mm",),
        rtol=1e-3,
        reason="as roll3d: the head contact's gap tolerance (~4e-4) under the 1e-3",
        cost="about 4 CPU min (layered-3d 50 CPU s at two sheets a shell, ~2.5 min at one)",
    ),
    "lps3d": Measurement(
        models=records.LAYERED_SOLID,
        about=f"layered-3d at 2 (the default) and 1 sheet a shell on PET2 53.4 N (8.89 and 2 "
        f"cm) and PET1 26.7 N, and PET2 53.4 N at 8.89 cm with {LPS_RING} (coarse mesh, mu 0.3)",
        runs=lps_runs,
        measure=measure_reading,
        spot=(),
        rtol=1e-3,
        reason="no spot run: each run costs ~5 CPU min, beyond the slow suite's budget",
        cost="about 11 CPU min: 0.5-1 CPU min a run at 2 sheets a shell, 2-3 at one",
    ),
}


# ------------------------------------------------------------- rendering


def _rec(name: str) -> dict[str, dict[str, Any]]:
    return records.results(f"layered_study.{name}")


def _rho(run_id: str, name: str = "table") -> float:
    return float(_rec(name)[run_id]["rho_fd"])


def _by(name: str, key: str = "rho_fd") -> dict[str, Any]:
    """``{run id: number}`` of record ``name``."""
    return {i: v[key] for i, v in _rec(name).items()}


def _pct(a: float, b: float) -> float:
    """a against b [%]."""
    return 100.0 * (a / b - 1.0)


def _wrap(text: str) -> str:
    """A bullet wrapped as the page's prose is (95 columns, two-space continuation)."""
    import textwrap

    return textwrap.fill(
        text, width=95, subsequent_indent="  ", break_long_words=False, break_on_hyphens=False
    )


def _span(xs: list[float], fmt: str = ".1f") -> str:
    lo, hi = min(xs), max(xs)
    return format(lo, fmt) if format(lo, fmt) == format(hi, fmt) else f"{lo:{fmt}}-{hi:{fmt}}"


def _measured(name: str) -> str:
    rec = records.load(f"layered_study.{name}")
    return f"measured {rec['measured']} by `docs/scripts/records.py layered_study.{name}`"


#: The study's columns: (record model name, page header).
COLUMNS = (
    ("2d", "2d"),
    ("layered_mu0.1", "layered mu 0.1"),
    ("layered_mu0.3", "mu 0.3"),
    ("layered_mu0.5", "mu 0.5"),
    ("2d_shear_frozen", "2d, G frozen"),
    ("2d_shear_ratio1", "2d, G = 1 E_r"),
    ("2d_shear_ratio0.5", "2d, G = 0.5 E_r"),
    ("layered_mu0.3_shear_frozen", "layered mu 0.3, G frozen"),
)
LAYERED = ("layered_mu0.1", "layered_mu0.3", "layered_mu0.5")
PET1 = ("pet1-26.7N", "pet1-33.4N", "pet1-40N", "pet1-46.7N")
PET2 = ("pet2-26.7N", "pet2-53.4N", "pet2-80N")


def _label(case: str) -> str:
    """``pet2-53.4N`` -> ``PET2 53.4 N``."""
    web, tension = case.split("-", 1)
    return f"{web.upper()} {tension[:-1]} N"


def _rolls() -> list[tuple[str, str]]:
    """The table's rows: (label, roll id in the record) in the study's order; the Table 2
    roll that is the pile series' tallest pile is read in the series."""
    from woundroll.studies.layered import PILE_CASE, study_rolls

    rolls = []
    for case, series, h, _ in study_rolls():
        if series == "table2" and case != PILE_CASE:
            rolls.append((_label(case), case))
        elif series == "pile-height":
            rolls.append((_label(case), _run_id(case, h, "")[:-1]))
    return rolls


def _pile_pair() -> tuple[str, str]:
    """Roll ids of the lowest and the tallest pile of the series."""
    from woundroll.studies.layered import DEFAULT_PILE_HEIGHTS, PILE_CASE

    hs = sorted(DEFAULT_PILE_HEIGHTS)
    return _run_id(PILE_CASE, hs[0], "")[:-1], _run_id(PILE_CASE, hs[-1], "")[:-1]


def _heights() -> tuple[float, float]:
    """Pile heights of the pair [cm], as wound."""
    lo, hi = _pile_pair()
    t = _rec("table")
    return 100 * t[f"{lo}/2d"]["pile_height_m"], 100 * t[f"{hi}/2d"]["pile_height_m"]


def _ratio(model: str) -> float:
    lo, hi = _pile_pair()
    return _rho(f"{lo}/{model}") / _rho(f"{hi}/{model}")


def heights() -> str:
    """The pile heights of the study's series (inline; its constants, no run)."""
    from woundroll.studies.layered import DEFAULT_PILE_HEIGHTS

    return "H = " + ", ".join(f"{100 * h:g}" for h in DEFAULT_PILE_HEIGHTS) + " cm"


def provenance() -> str:
    """How the table was measured (inline)."""
    rec = records.load("layered_study.table")
    cpu = rec["cpu_s"]
    return (
        f"{_measured('table')}, {sum(cpu.values()) / 60:.0f} CPU min at load {rec['load_1min']:g}"
    )


def study_cost() -> str:
    """The study's size and cost (inline)."""
    from woundroll.studies.layered import study_jobs

    jobs = study_jobs()
    cpu = records.load("layered_study.table")["cpu_s"]
    ids = [_run_id(j.case, j.pile_height_m, j.model) for j in jobs]
    lay = [cpu[i] for i, j in zip(ids, jobs, strict=True) if j.model.startswith("layered")]
    return (
        f"{len(jobs)} runs, {len(lay)} of them layered ({min(lay):.0f}-{max(lay):.0f} CPU s "
        f"each; {sum(cpu[i] for i in ids) / 60:.0f} CPU min in all)"
    )


def table() -> str:
    """Rho FD of every roll and model of the study, the pile ratio, the uniform PET3 roll."""
    t = _rec("table")
    lines = [
        "| roll | H [cm] | " + " | ".join(h for _, h in COLUMNS) + " |",
        "|---|---|" + "---|" * len(COLUMNS),
    ]
    for label, roll in _rolls():
        h = 100 * t[f"{roll}/2d"]["pile_height_m"]
        cells = [f"{t[f'{roll}/{m}']['rho_fd']:.1f}" for m, _ in COLUMNS]
        lines.append(f"| {label} | {h:.2f} | " + " | ".join(cells) + " |")
    lo, hi = _heights()
    lines.append(
        f"| ratio H {lo:.3g} / {hi:.3g} cm | | "
        + " | ".join(f"{_ratio(m):.2f}" for m, _ in COLUMNS)
        + " |"
    )
    h3 = 100 * t[f"{PET3_ID}/2d"]["pile_height_m"]
    cells = [f"{t[f'{PET3_ID}/{m}']['rho_fd']:.1f}" for m, _ in COLUMNS]
    lines.append(f"| PET3 uniform, 2.3 MPa | {h3:.2f} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def pet3_cost() -> str:
    """CPU time of the uniform PET3 roll's layered runs (inline)."""
    cpu = records.load("layered_study.table")["cpu_s"]
    xs = [cpu[f"{PET3_ID}/{m}"] for m, _ in COLUMNS if m.startswith("layered")]
    return f"{min(xs):.0f}-{max(xs):.0f} CPU s"


def soft() -> str:
    """The bullet on soft PET2 reading below the continuum."""
    lo, _ = _pile_pair()
    d = {r: _pct(_rho(f"{r}/layered_mu0.3"), _rho(f"{r}/2d")) for r in (*PET1, *PET2, lo)}
    every = all(
        _rho(f"{r}/{m}") < _rho(f"{r}/2d") for _, r in [*_rolls(), ("", PET3_ID)] for m in LAYERED
    )
    p1 = [d[r] for r in PET1]
    p2 = [d[r] for r in (*PET2, lo)]
    more = max(p2) < min(p1)
    growing = all(b < a for a, b in zip(p1, p1[1:], strict=False))
    spread = {
        r: max(_rho(f"{r}/{m}") for m in LAYERED) - min(_rho(f"{r}/{m}") for m in LAYERED)
        for r in ("pet2-53.4N", "pet1-26.7N")
    }
    drop = {r: _rho(f"{r}/2d") - _rho(f"{r}/layered_mu0.3") for r in spread}
    hardly = all(spread[r] < drop[r] / 3 for r in spread)
    verdict = "yes, in the right direction" if every and more else "in part"
    tensions = " / ".join(r.split("-", 1)[1][:-1] for r in PET2)
    h_lo, _ = _heights()

    def mu_span(r: str) -> str:
        return _span([_rho(f"{r}/{m}") for m in LAYERED])

    text = (
        f"- **Soft PET2 below the continuum: {verdict}.** Interlayer friction lowers "
        f"{'every' if every else 'not every'} reading; at mu 0.3 soft PET2 "
        f"({' / '.join(f'{d[r]:+.0f}' for r in PET2)} % at {tensions} N; {d[lo]:+.0f} % at a "
        f"{h_lo:.3g} cm pile) {'more' if more else 'not always more'} than hard PET1 "
        f"({max(p1):+.0f} to {min(p1):+.0f} %{', growing with tension' if growing else ''}), "
        "as the paper's PET2 tests read below its models. The answer "
        f"{'hardly depends' if hardly else 'depends'} on mu over 0.1-0.5 (PET2 53.4 N "
        f"{mu_span('pet2-53.4N')}, PET1 26.7 N {mu_span('pet1-26.7N')}, against "
        f"{_rho('pet2-53.4N/2d'):.1f} and {_rho('pet1-26.7N/2d'):.1f} in 2d)"
        + (
            ": most interfaces under the head slip at any of these mu, and what carries the "
            "load is the sheets' own stiffness."
            if hardly
            else "."
        )
    )
    return _wrap(text)


#: A pile-height ratio within this of 1 reads "nearly the same at every pile height" [-].
NEARLY = 0.1


def pile() -> str:
    """The bullet on pile-height independence."""
    q = {m: _ratio(m) for m, _ in COLUMNS}
    lay = [q[m] for m in LAYERED]
    none = min(q.values()) > 1 + NEARLY
    larger = min(q["2d_shear_ratio1"], q["2d_shear_ratio0.5"]) > q["2d"]
    lo, hi = _heights()
    text = (
        f"- **Pile-height independence: {'no' if none else 'in part'}.** The ratio of the "
        f"{lo:.3g} cm to the {hi:.3g} cm reading is {_span(lay, '.2f')} with friction "
        f"(continuum {q['2d']:.2f}). Frozen shear gives {q['2d_shear_frozen']:.2f} "
        f"({q['layered_mu0.3_shear_frozen']:.2f} with friction), a lower G/E_r makes it "
        f"{'larger' if larger else 'not larger'} ({q['2d_shear_ratio1']:.2f} at 1, "
        f"{q['2d_shear_ratio0.5']:.2f} at 0.5). "
        + (
            "No explanation tested in plane strain reads nearly the same at every pile height "
            f"(every ratio is at least {min(q.values()):.2f}). "
            if none
            else f"The lowest ratio is {min(q.values()):.2f}. "
        )
        + "(The paper's own words, shared/reference/NOTES.md, say models and tests read "
        '"very close to each other for various pile heights", which may mean close to each '
        "other rather than independent of H; its figures are lost.)"
    )
    return _wrap(text)


def shear08() -> str:
    """2d at G_r_theta = 0.8 E_r on PET1 26.7 N and the PET2 pile pair (inline; live: three
    2d runs, ~10 CPU s)."""
    from woundroll.studies.layered import _job

    over = ("contact.no_update=false", "contact.model='2d'", "contact.shear_ratio=0.8")
    lo, hi = _pile_pair()
    by_id = {r.id: r for r in table_runs()}

    def rho(roll: str) -> float:
        r = by_id[f"{roll}/2d"]
        return float(_job(r.case, (*r.overrides, *over))["rho_fd"])

    p1, p2, p2h = rho("pet1-26.7N"), rho(hi), rho(lo)
    h_lo, h_hi = _heights()
    return (
        f"PET1 26.7 N {p1:.1f}, PET2 53.4 N {p2:.1f} / {p2h:.1f} at {h_hi:.3g} / {h_lo:.3g} cm "
        f"(ratio {p2h / p2:.2f})"
    )


def pet3() -> str:
    """The bullet on the uniform PET3 roll and the dial's scale."""
    from woundroll.instruments.definitions import READING_RANGES

    low, top = READING_RANGES["rho"]
    lay = [_rho(f"{PET3_ID}/{m}") for m in LAYERED]
    c = _rho(f"{PET3_ID}/2d")
    on = max(lay) <= top
    verdict = "yes for uniform PET3" if on and c > top else ("yes" if on else "no")
    text = (
        f"- **Readings on the scale: {verdict}.** The layered roll reads the uniform PET3 roll "
        f"at 2.3 MPa {_span(lay)} (mu 0.1-0.5) against {c:.1f} in 2d, "
        f"{'inside' if on else 'beyond'} the dial's {low:g}-{top:g}."
    )
    return _wrap(text)


def _ladder(case: str, h: float | None) -> list[tuple[float, float]]:
    """(zone depth [mm], Rho FD) of one roll of :data:`ZONE_LADDER`."""
    z = _by("zone")
    depths = next(d for c, hh, d in ZONE_LADDER if (c, hh) == (case, h))
    return [(d, z[f"zone/{_run_id(case, h, f'{d:g}mm')}"]) for d in depths]


def zone_ladder() -> str:
    """The zone-depth ladder: Rho FD against the depth of the zone of sheets."""
    depths = sorted({d for _, _, ds in ZONE_LADDER for d in ds})
    lines = [
        "| roll | 2d | default zone | " + " | ".join(f"{d:g} mm" for d in depths) + " |",
        "|---|---|---|" + "---|" * len(depths),
    ]
    for case, h, _ in ZONE_LADDER:
        roll = _run_id(case, h, "")[:-1]
        got = dict(_ladder(case, h))
        cells = [f"{got[d]:.2f}" if d in got else "" for d in depths]
        cm = (
            100 * _rec("table")[f"{roll}/2d"]["pile_height_m"]
            if f"{roll}/2d" in _rec("table")
            else None
        )
        label = _label(case) + (f", H {cm:.3g} cm" if cm is not None else "")
        lines.append(
            f"| {label} | {_rho(f'{roll}/2d'):.2f} | {_rho(f'{roll}/layered_mu0.3'):.2f} | "
            + " | ".join(cells)
            + " |"
        )
    return "\n".join(lines)


def zone_provenance() -> str:
    """How the zone ladder was measured (inline)."""
    rec = records.load("layered_study.zone")
    cpu = rec["cpu_s"]
    return (
        f"{_measured('zone')}, {min(cpu.values()):.0f}-{max(cpu.values()):.0f} CPU s a run "
        f"at load {rec['load_1min']:g}"
    )


def zone_summary() -> str:
    """docs/contact.md's sentence on the ladder (inline)."""
    tall, p1 = _ladder("pet2-53.4N", None), _ladder("pet1-26.7N", None)
    (d_a, r_a), (d_b, r_b) = tall[-2], tall[-1]
    cpu = records.load("layered_study.zone")["cpu_s"]
    deep = cpu[f"zone/pet2-53.4N/{d_b:g}mm"]
    shallow = cpu[f"zone/pet2-53.4N/{tall[0][0]:g}mm"]
    return (
        f"PET2 53.4 N reads {r_b:.2f} at a {d_b:g} mm zone ({abs(_pct(r_b, r_a)):.1f} % from "
        f"{d_a:g} mm; {_pct(r_b, _rho('pet2-53.4N/layered_mu0.3')):+.0f} % against the default "
        f"zone), PET1 26.7 N {p1[-1][1]:.2f} ({_pct(p1[-1][1], p1[-2][1]):+.0f} % from "
        f"{p1[-2][0]:g} mm); the {d_b:g} mm run cost {deep:.0f} CPU s against {shallow:.0f} at "
        f"{tall[0][0]:g} mm ({_measured('zone')})"
    )


def zone_converged() -> str:
    """The bullet on the zone ladder: where the reading converges, and the pile ratio of
    the rolls layered all the way down (every claim computed)."""
    tall = _ladder("pet2-53.4N", None)
    low = _ladder("pet2-53.4N", 0.02)
    p1 = _ladder("pet1-26.7N", None)
    (d_a, r_a), (d_b, r_b) = tall[-2], tall[-1]
    last_step = abs(_pct(r_b, r_a))
    default_t, default_l = (
        _rho("pet2-53.4N/layered_mu0.3"),
        _rho(f"{_pile_pair()[0]}/layered_mu0.3"),
    )
    q_deep = low[-1][1] / tall[-1][1]
    q_default = default_l / default_t
    q_2d = _rho(f"{_pile_pair()[0]}/2d") / _rho("pet2-53.4N/2d")
    stuck = _by("zone")[f"zone/pet1-26.7N/{p1[-1][0]:g}mm_stuck"]
    text = (
        "- **The zone of sheets all the way down.** Deepening the zone toward the whole pile "
        f"(a continuum of at least a tenth of the wound thickness stays below it): PET2 53.4 N "
        f"at 8.89 cm reads {' -> '.join(f'{r:.1f}' for _, r in tall)} at "
        f"{' / '.join(f'{d:g}' for d, _ in tall)} mm, the last step {d_a:g} -> {d_b:g} mm "
        f"{last_step:.1f} %, {_pct(r_b, default_t):+.0f} % against the default zone and "
        f"{_pct(r_b, _rho('pet2-53.4N/2d')):+.0f} % against `2d`; at 2 cm "
        f"{' -> '.join(f'{r:.1f}' for _, r in low)} ({low[-1][0]:g} mm: the whole pile but "
        f"its inner tenth); PET1 26.7 N {' -> '.join(f'{r:.1f}' for _, r in p1)} at "
        f"{' / '.join(f'{d:g}' for d, _ in p1)} mm"
        + (", not converged" if abs(_pct(p1[-1][1], p1[-2][1])) > 5 else "")
        + f" (stuck, mu 1e4, the {p1[-1][0]:g} mm zone reads {stuck:.2f} against `2d`'s "
        f"{_rho('pet1-26.7N/2d'):.2f}: the fall is the sheets' slip, not the zone's mesh). "
        "With both PET2 rolls layered this deep "
        f"the pile-height ratio is {q_deep:.2f} (default zone {q_default:.2f}, 2d {q_2d:.2f}; "
        "the paper's tests about 1)."
    )
    return _wrap(text)


def zone() -> str:
    """The bullet on the layered zone's depth (the checks record)."""
    z = _by("checks")
    lo, hi = _pile_pair()
    d1, d2 = ZONE_DEPTHS_MM
    p1 = (_rho("pet1-26.7N/layered_mu0.3"), z[f"zone/pet1-26.7N/{d1:g}mm"])
    p2 = (_rho(f"{hi}/layered_mu0.3"), z[f"zone/pet2-53.4N/{d1:g}mm"])
    q = [
        _ratio("layered_mu0.3"),
        z[f"zone/{lo}/{d1:g}mm"] / z[f"zone/pet2-53.4N/{d1:g}mm"],
        z[f"zone/{lo}/{d2:g}mm"] / z[f"zone/pet2-53.4N/{d2:g}mm"],
    ]
    p2_deep = z[f"zone/pet2-53.4N/{d2:g}mm"]
    lowers = p1[1] < p1[0] and p2[1] < p2[0] and p2_deep < p2[1]
    converged = abs(p2_deep / p2[1] - 1) < 0.01
    little = max(q) - min(q) < 0.05
    text = (
        "- **Caveat: the layered zone is "
        + ("converged in depth to 1 %" if converged else "not converged in depth")
        + '** (docs/contact.md, "Zone depth"): deepening it from the default (1 a_geo) to '
        f"{d1:g} mm {'lowers' if lowers else 'moves'} PET1 26.7 N {p1[0]:.1f} -> {p1[1]:.1f} "
        f"and PET2 53.4 N {p2[0]:.1f} -> {p2[1]:.1f}"
        + (
            ", so the layered columns are upper bounds of a roll that is sheets all the way down"
            if lowers
            else ""
        )
        + f"; at these depths the pile-height ratio moves {'little' if little else 'with it'} "
        f"({q[0]:.2f} at the default, {q[1]:.2f} at {d1:g} mm, {q[2]:.2f} at {d2:g} mm; PET2 "
        f"53.4 N reads {p2_deep:.1f} at {d2:g} mm)."
    )
    return _wrap(text)


def fit() -> str:
    """The bullet on the reduced-shear emulation fitted to the layered roll."""
    c = _rec("checks")
    f1, f2 = c["fit/pet1-26.7N"], c["fit/pet2-53.4N"]
    lo, _ = _pile_pair()
    layered_lo = _rho(f"{lo}/layered_mu0.3")
    e2 = _pct(f2["off_roll_rho_fd"], layered_lo)
    e1 = _pct(f1["off_roll_rho_fd"], layered_lo)
    per_material = abs(e1) > 2 * abs(e2)
    paper = c["paper_fraction/pet2-53.4N"]["rho_fd"]
    h_lo, h_hi = _heights()
    z = _by("checks")
    deeper_lowers = (
        z[f"zone/pet2-53.4N/{ZONE_DEPTHS_MM[0]:g}mm"] < f2["target_rho_fd"]
        and z[f"zone/pet1-26.7N/{ZONE_DEPTHS_MM[0]:g}mm"] < f1["target_rho_fd"]
    )
    text = (
        "- **The reduced-shear emulation carries the layered answer"
        + (", per material.**" if per_material else ".**")
        + ' The cheap emulation (`contact.slip = "reduced-shear"` in 2d, mu 0.3) fitted by '
        "bisection on `contact.slip_shear_fraction` (to a bracket "
        f"{FIT_WIDTH:g} wide) to the layered roll (mu 0.3, default zone): PET1 26.7 N "
        f"({f1['target_rho_fd']:.2f}) f = {f1['slip_shear_fraction']:.2f}, PET2 53.4 N at "
        f"{h_hi:.3g} cm ({f2['target_rho_fd']:.2f}) f = {f2['slip_shear_fraction']:.2f}. Off its "
        f"fit roll, PET2's f reads the {h_lo:.3g} cm pile {f2['off_roll_rho_fd']:.2f} against "
        f"the layered {layered_lo:.2f} ({e2:+.1f} %); PET1's f there reads "
        f"{f1['off_roll_rho_fd']:.2f} ({e1:+.0f} %)"
        + (": the fraction is a material's, not a universal one" if per_material else "")
        + f" (the paper's {PAPER_FRACTION:g} reads PET2 {paper:.1f}, "
        + ("below" if paper < f2["target_rho_fd"] else "above")
        + " the layered roll's "
        + f"{f2['target_rho_fd']:.1f}). Fitted at the default zone depth, which is not "
        "converged (above)"
        + (": a deeper zone would lower both fractions." if deeper_lowers else ".")
    )
    return _wrap(text)


def _reading3d(roll: str, model: str) -> dict[str, Any]:
    """A run of the 3D table: 2d and layered from the table record where it has the roll,
    else from roll3d; layered-3d at other shells from lps3d."""
    rid = f"{roll}/{model}"
    for name in ("table", "roll3d", "lps3d"):
        got = _rec(name).get(rid)
        if got is not None:
            return got
    raise KeyError(rid)


def _rolls3d() -> list[tuple[str, str]]:
    """(label, roll id) of the 3D table's rows: the study's rolls (Table 2, then the pile
    series with its tallest pile the Table 2 roll), PET1's 2 cm pile, the uniform PET3."""
    rows = []
    for label, roll in _rolls():
        if roll == _pile_pair()[1]:
            roll = roll.split("@")[0]  # the tallest pile is the Table 2 roll (8.89 cm)
        rows.append((label, roll))
    rows.append((_label("pet1-26.7N"), _run_id("pet1-26.7N", 0.02, "")[:-1]))
    rows.append(("PET3 uniform, 2.3 MPa", PET3_ID))
    out = []
    for label, roll in rows:
        cm = 100 * _reading3d(roll, "3d")["pile_height_m"]
        out.append((f"{label}, H {cm:.3g} cm", roll))
    return out


def _rho3d(roll: str, model: str) -> float:
    return float(_reading3d(roll, model)["rho_fd"])


def provenance3d() -> str:
    """How the 3D table was measured (inline)."""
    names = ("roll3d", "lps3d", "head3d")
    dates = sorted({records.load(f"layered_study.{n}")["measured"] for n in names})
    return (
        f"measured {' and '.join(dates)} by `docs/scripts/records.py "
        + " ".join(f"layered_study.{n}" for n in names)
        + "`"
    )


def table3d() -> str:
    """Rho FD of every roll in 2d, layered, 3d and layered-3d (mu :data:`MU_3D`, coarse 3D
    mesh), layered-3d against 3d, and the pile ratio."""
    models = ("2d", f"layered_mu{MU_3D:g}", "3d", LAYERED_3D)
    lines = [
        "| roll | 2d | layered | 3d | layered-3d | layered-3d / 3d |",
        "|---|---|---|---|---|---|",
    ]
    for label, roll in _rolls3d():
        cells = [f"{_rho3d(roll, m):.1f}" for m in models]
        cells.append(f"{_pct(_rho3d(roll, LAYERED_3D), _rho3d(roll, '3d')):+.1f} %")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    lo, hi = (roll.split("@")[0] if "@8.89" in roll else roll for roll in _pile_pair())
    lo_cm, hi_cm = _heights()
    lines.append(
        f"| PET2 pile ratio {lo_cm:.3g} / {hi_cm:.3g} cm | "
        + " | ".join(f"{_rho3d(lo, m) / _rho3d(hi, m):.2f}" for m in models)
        + " | |"
    )
    return "\n".join(lines)


def _frictions() -> tuple[float, ...]:
    from woundroll.studies.layered import FRICTIONS

    return FRICTIONS


def mu3d() -> str:
    """The mu sweep on PET2 53.4 N at both pile heights: layered and layered-3d."""
    lo, hi = (roll.split("@")[0] if "@8.89" in roll else roll for roll in _pile_pair())
    mus = _frictions()
    lines = [
        "| roll | "
        + " | ".join(f"layered mu {m:g}" for m in mus)
        + " | "
        + " | ".join(f"layered-3d mu {m:g}" for m in mus)
        + " |",
        "|---|" + "---|" * (2 * len(mus)),
    ]
    label = dict(_rolls3d())
    label = {v: k for k, v in label.items()}
    for roll in (hi, lo):
        cells = [f"{_rho3d(roll, f'layered_mu{m:g}'):.1f}" for m in mus]
        cells += [f"{_rho3d(roll, f'layered-3d_mu{m:g}'):.1f}" for m in mus]
        lines.append(f"| {label[roll]} | " + " | ".join(cells) + " |")
    lo_cm, hi_cm = _heights()
    cells = [
        f"{_rho3d(lo, f'{k}_mu{m:g}') / _rho3d(hi, f'{k}_mu{m:g}'):.2f}"
        for k in ("layered", "layered-3d")
        for m in mus
    ]
    lines.append(f"| pile ratio {lo_cm:.3g} / {hi_cm:.3g} cm | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def cost3d() -> str:
    """CPU time of the 3D table's runs (inline)."""
    cpu = records.load("layered_study.roll3d")["cpu_s"]
    d3 = [v for k, v in cpu.items() if k.endswith("/3d")]
    l3 = [v for k, v in cpu.items() if "/layered-3d" in k and not k.endswith("_default_mesh")]
    return (
        f"3d {min(d3):.0f}-{max(d3):.0f} CPU s a roll, layered-3d {min(l3):.0f}-{max(l3):.0f}"
        f" (at load {records.load('layered_study.roll3d')['load_1min']:g})"
    )


def study3d_cost() -> str:
    """The whole `woundroll study layered-3d`'s CPU time from the records' run times: the
    2d and layered runs from the table record, each 3D run from roll3d (a layered-3d run at
    another mu costed as the same roll's at mu 0.3 where it was not measured) (inline)."""
    from woundroll.studies.layered import study_jobs

    table = records.load("layered_study.table")["cpu_s"]
    r3 = records.load("layered_study.roll3d")["cpu_s"]
    total = 0.0
    for j in study_jobs(explanations=(), three_d=True):
        rid = _run_id(j.case, j.pile_height_m, j.model)
        roll = rid.rsplit("/", 1)[0].replace("@8.89cm", "")
        if "3d" not in j.model:
            total += table[rid]
        else:
            total += r3.get(
                f"{roll}/{j.model}", r3[f"{roll}/{LAYERED_3D}"] if "layered" in j.model else 0.0
            )
    return f"about {total / 60:.0f} CPU min"


def mesh_offset3d() -> str:
    """The study's coarse 3D mesh against the default one, 3d and layered-3d on two rolls,
    and the two models' ratio on each mesh (inline)."""
    parts = []
    for model, name in (("3d", "3d"), (LAYERED_3D, "layered-3d")):
        rolls = []
        for c in ("pet1-26.7N", "pet2-53.4N"):
            fine, coarse = _rho3d(c, f"{model}_default_mesh"), _rho3d(c, model)
            rolls.append(
                f"{_label(c)} {coarse:.1f} against {fine:.1f} ({_pct(coarse, fine):+.1f} %)"
            )
        parts.append(f"{name} {'; '.join(rolls)}")
    ratio = []
    for c in ("pet1-26.7N", "pet2-53.4N"):
        fine = _pct(_rho3d(c, f"{LAYERED_3D}_default_mesh"), _rho3d(c, "3d_default_mesh"))
        coarse = _pct(_rho3d(c, LAYERED_3D), _rho3d(c, "3d"))
        ratio.append(
            f"{_label(c)} {fine:+.1f} % on the default mesh, {coarse:+.1f} % on the coarse"
        )
    return "; ".join(parts) + "; layered-3d against 3d: " + ", ".join(ratio)


def cost_ratio3d() -> str:
    """CPU time of layered-3d against 3d on the same roll and mesh (inline)."""
    cpu = records.load("layered_study.roll3d")["cpu_s"]
    rolls = [k[: -len("/3d")] for k in cpu if k.endswith("/3d")]
    x = [cpu[f"{r}/{LAYERED_3D}"] / cpu[f"{r}/3d"] for r in rolls if f"{r}/{LAYERED_3D}" in cpu]
    return f"{_span(x, '.1f')}x over {len(x)} rolls ({_measured('roll3d')})"


def head3d_table() -> str:
    """The pressure under the head and the CMD spread of both 3D models (PET2 53.4 N
    pressed :data:`HEAD_DEPTH`)."""
    head = _rec("head3d")
    depths = " / ".join(f"{1e3 * d:g}" for d in PRESSURE_DEPTHS)
    where = " / ".join("the surface" if d == 0 else f"{1e3 * d:g} mm" for d in SPREAD_DEPTHS)
    lines = [
        f"| | force [N] | p at {depths} mm depth [MPa] | CMD {100 * SPREAD_LEVEL:g} % "
        f"half-width at {where} deep [mm] |",
        "|---|---|---|---|",
    ]
    for name, label in (
        ("3d", "3d"),
        ("layered-3d", f"layered-3d (mu {MU_3D:g}), {_lps_default()} sheets a shell"),
        ("layered-3d_lps1", f"layered-3d (mu {MU_3D:g}), 1 sheet a shell"),
    ):
        r = head[f"pet2-53.4N/{name}@{1e3 * HEAD_DEPTH:g}mm"]
        p_ = " / ".join(f"{r[f'pressure_{k}_Pa'] / 1e6:.2f}" for k in range(len(PRESSURE_DEPTHS)))
        w = " / ".join(
            f"{1e3 * r[f'spread_half_width_{k}_m']:.1f}" for k in range(len(SPREAD_DEPTHS))
        )
        lines.append(f"| {label} | {r['force_N']:.1f} | {p_} | {w} |")
    return "\n".join(lines)


def text3d_all() -> str:
    """The paragraph on the whole 3D table and the mu sweep: every claim computed."""
    from woundroll.instruments.definitions import READING_RANGES

    low, top = READING_RANGES["rho"]
    rows = _rolls3d()
    vs3 = [_pct(_rho3d(r, LAYERED_3D), _rho3d(r, "3d")) for _, r in rows]
    vs2 = [_pct(_rho3d(r, LAYERED_3D), _rho3d(r, "2d")) for _, r in rows]
    below3 = all(v < 0 for v in vs3)
    above2 = sum(v > 0 for v in vs2)
    lo, hi = (roll.split("@")[0] if "@8.89" in roll else roll for roll in _pile_pair())
    series = [r for _, r in rows if r.startswith("pet2-53.4N@")] + [hi]
    series = sorted(series, key=lambda r: _reading3d(r, "3d")["pile_height_m"])
    falls = all(
        _rho3d(a, LAYERED_3D) > _rho3d(b, LAYERED_3D)
        for a, b in zip(series, series[1:], strict=False)
    )
    mus = _frictions()
    q = {m: _rho3d(lo, f"layered-3d_mu{m:g}") / _rho3d(hi, f"layered-3d_mu{m:g}") for m in mus}
    keeps = min(q.values()) > 1 + NEARLY
    m0, m1 = mus[0], mus[-1]

    def span_mu(kind: str, roll: str) -> float:
        return _pct(_rho3d(roll, f"{kind}_mu{m1:g}"), _rho3d(roll, f"{kind}_mu{m0:g}"))

    d3, d2 = span_mu("layered-3d", hi), span_mu("layered", hi)
    p3 = {m: _rho3d(PET3_ID, m) for m in ("2d", f"layered_mu{MU_3D:g}", "3d", LAYERED_3D)}
    on = p3[LAYERED_3D] <= top
    text = (
        f"Over the study's rolls, the layered roll in 3D (mu {MU_3D:g}, {_lps_default()} sheets a "
        "shell) reads "
        + ("below" if below3 else "not always below")
        + f" the 3D continuum (by {_span([-v for v in vs3], '.1f')} %) and above `2d` on "
        f"{above2} of {len(rows)} rolls (from {min(vs2):+.0f} to {max(vs2):+.0f} %). Along "
        "PET2's pile series it "
        + ("falls with every taller pile" if falls else "does not fall steadily with the pile")
        + f", and the 2 cm / 8.89 cm ratio is {_span(list(q.values()), '.2f')} at mu "
        f"{m0:g}-{m1:g}"
        + (" (the paper's tests: about 1)" if keeps else "")
        + ". Friction matters "
        + ("less" if abs(d3) < abs(d2) else "no less")
        + f" in 3D than in plane strain: raising mu from {m0:g} to {m1:g} moves the 8.89 cm "
        f"roll's reading {d3:+.1f} % in layered-3d against {d2:+.1f} % in the 2D layered "
        f"roll. The uniform PET3 roll at 2.3 MPa reads {p3[LAYERED_3D]:.1f} in layered-3d "
        f"({p3['3d']:.1f} in 3d, {p3['2d']:.1f} in 2d), "
        + ("inside" if on else "beyond")
        + f" the dial's {low:g}-{top:g}."
    )
    import textwrap

    return textwrap.fill(text, width=95, break_long_words=False, break_on_hyphens=False)


def verdict() -> str:
    """docs/contact.md's bullet on the layered rolls and the default (every claim from the
    records)."""
    lo, hi = _pile_pair()
    pet2 = [r for r in (*PET2, lo)]
    below = [_pct(_rho(f"{r}/layered_mu0.3"), _rho(f"{r}/2d")) for r in pet2]
    q2 = [_ratio(m) for m in LAYERED]
    rows = _rolls3d()
    above2 = sum(_rho3d(r, LAYERED_3D) > _rho3d(r, "2d") for _, r in rows)
    hi3 = hi.split("@")[0] if "@8.89" in hi else hi
    q3 = _rho3d(lo, LAYERED_3D) / _rho3d(hi3, LAYERED_3D)
    tall, low = _ladder("pet2-53.4N", None), _ladder("pet2-53.4N", 0.02)
    p1 = _ladder("pet1-26.7N", None)
    pile_ok = min(*q2, q3, low[-1][1] / tall[-1][1]) < 1 + NEARLY
    pet1_ok = abs(_pct(p1[-1][1], _rho("pet1-26.7N/2d"))) < 10
    text = (
        '- Interlayer friction (the layered rolls, docs/studies.md "Layered") '
        + ("could change" if pile_ok and pet1_ok else "does not change")
        + " the choice: in plane strain it reads the PET2 rolls "
        + f"{_span([-b for b in below], '.0f')} % below `2d` (mu 0.3) but keeps the "
        + f"pile-height ratio ({_span(q2, '.2f')} over mu "
        f"0.1-0.5; {low[-1][1] / tall[-1][1]:.2f} with the sheets all the way down); in 3D "
        f"(`layered-3d`, mu 0.3) it reads above `2d` on {above2} of {len(rows)} rolls, pile "
        f"ratio {q3:.2f}; with the sheets all the way down (a {p1[-1][0]:g} mm zone) PET1 26.7 N "
        f"reads {p1[-1][1]:.1f} against `2d`'s {_rho('pet1-26.7N/2d'):.1f}"
        + (", far from the paper's PET1 agreement" if not pet1_ok else "")
        + ": the sheets slip outside a cone under the head wherever the head's stress "
        "dominates the wound-in pressure, which a line load's does through the whole pile and a "
        'finite head\'s does not (docs/contact.md "Zone depth"); the default zone stays 1 a_geo.'
    )
    import textwrap

    return textwrap.fill(
        text, width=95, subsequent_indent="  ", break_long_words=False, break_on_hyphens=False
    )


def text3d() -> str:
    """The paragraph under the 3D table: pile ratio, level, pressure under the head."""
    tall, low = (_run_id("pet2-53.4N", h, "")[:-1] for h in (None, 0.02))

    def rho(roll: str, m: str) -> float:
        return float(_reading3d(roll, m)["rho_fd"])

    one = "layered-3d_lps1"
    variants = ("3d", LAYERED_3D)
    q = {m: rho(low, m) / rho(tall, m) for m in (*variants, "2d")}
    q3 = [q[m] for m in variants]
    keeps = min(q3) > 1 + NEARLY
    above_one = _pct(rho(tall, one), rho(tall, "2d"))
    above_default = _pct(rho(tall, LAYERED_3D), rho(tall, "2d"))
    stays_above = above_one > 10.0
    h_lo = 100 * _reading3d(low, "3d")["pile_height_m"]
    h_hi = 100 * _reading3d(tall, "3d")["pile_height_m"]
    head = _rec("head3d")
    c, lay = (
        head[f"pet2-53.4N/3d@{1e3 * HEAD_DEPTH:g}mm"],
        head[f"pet2-53.4N/layered-3d@{1e3 * HEAD_DEPTH:g}mm"],
    )
    top = [k for k, d in enumerate(PRESSURE_DEPTHS) if d <= 2e-3]
    dp = [-_pct(lay[f"pressure_{k}_Pa"], c[f"pressure_{k}_Pa"]) for k in top]
    wc, wl = ([r[f"spread_half_width_{k}_m"] for k in range(len(SPREAD_DEPTHS))] for r in (c, lay))
    as_far = max(abs(a / b - 1) for a, b in zip(wl, wc, strict=True)) < 0.15
    where = " / ".join("the surface" if d == 0 else f"{1e3 * d:g} mm" for d in SPREAD_DEPTHS)
    text = (
        "In 3D as in plane strain, friction between the sheets "
        + ("neither removes" if keeps and stays_above else "does not both remove")
        + f" the pile-height dependence (PET2's {h_lo:.3g} cm / {h_hi:.3g} cm ratio is "
        f"{_span(q3, '.2f')} in every 3D variant, {q['2d']:.2f} in 2d; the paper's tests read "
        "about 1) "
        + ("nor brings" if keeps and stays_above else "and bring")
        + f" the reading down to the plane-strain level: the 3D layered roll reads "
        f"{above_default:.0f} % above `2d` on PET2 at {h_hi:.3g} cm, and {above_one:.0f} % at "
        'one sheet a shell (docs/contact.md "The layered roll in 3D"). Under '
        f"the head (PET2 53.4 N, H {h_hi:.3g} cm, pressed {1e3 * HEAD_DEPTH:g} mm) the sheets "
        f"carry {-_pct(lay['force_N'], c['force_N']):.0f} % less force and lower the pressure "
        f"{_span(dp, '.0f')} % in the top {1e3 * PRESSURE_DEPTHS[top[-1]]:g} mm, and spread "
        f"the load along the CMD {'about as far as' if as_far else 'not as far as'} the "
        f"continuum (the {100 * SPREAD_LEVEL:g} % point at "
        f"{' / '.join(f'{1e3 * w:.1f}' for w in wl)} mm against "
        f"{' / '.join(f'{1e3 * w:.1f}' for w in wc)} mm at {where} deep)"
        + (": interlayer slip does not make the load local." if as_far else ".")
    )
    import textwrap

    return textwrap.fill(text, width=95, break_long_words=False, break_on_hyphens=False)


def _lps_default() -> int:
    from woundroll.contact.layered.roll3d import LAYERS_PER_SHELL_3D

    return LAYERS_PER_SHELL_3D


def _coarse_shells(case_name: str) -> int:
    """Layers in the 3D surface ring (layered-3d's shells at ``layers_per_shell=None``) on
    the study's coarse 3D mesh (``COARSE_3D``) for the bundled case's roll, solved to the
    spring fit's reach (``FIT_REACH`` x its layered-3d impact depth, as the pipeline solves
    it)."""
    from woundroll.case import load_case
    from woundroll.contact.heads import Head
    from woundroll.contact.layered.roll3d import Layered3DOptions, layered_mesh3d
    from woundroll.contact.spring import FIT_REACH
    from woundroll.instruments import get_instrument
    from woundroll.studies.layered import COARSE_3D

    case = load_case(case_name, list(COARSE_3D))
    web, core = case.web.build(), case.core.build()
    r_out = case.winding.final_radius(web, core)
    depth = FIT_REACH * _reading3d(case_name, LAYERED_3D)["impact_depth_m"]
    head = Head.from_instrument(get_instrument("rho-meter"))
    opts = Layered3DOptions(base=case.contact.contact3d_options(), layers_per_shell=None)
    return layered_mesh3d(web, core, r_out, head, depth, opts)[3]


def lps_ladder3d() -> str:
    """Layers per shell in layered-3d on PET2 53.4 N at 8.89 cm (coarse mesh): the 3D
    surface ring's, the default and one sheet a shell (inline)."""
    from woundroll.contact.layered.roll3d import LAYERS_PER_SHELL_3D

    roll = "pet2-53.4N"
    lps = _rec("lps3d")
    cpu = records.load("layered_study.lps3d")["cpu_s"]
    ring = _coarse_shells(roll)
    rows = [
        lps[f"{roll}/layered-3d_lps{LPS_RING}"]["rho_fd"],
        _rho3d(roll, LAYERED_3D),
        lps[f"{roll}/layered-3d_lps1"]["rho_fd"],
    ]
    r1 = rows[-1]
    cost = cpu[f"{roll}/layered-3d_lps1"] / cpu[f"{roll}/layered-3d_lps{LAYERS_PER_SHELL_3D}"]
    return (
        f"{' / '.join(f'{v:.1f}' for v in rows)} Rho at {LPS_RING} (the 3D surface ring"
        + ("" if ring == LPS_RING else f"; the ring holds {ring} sheets on today's mesh")
        + f") / {LAYERS_PER_SHELL_3D} (the default) / 1 sheets a shell: the surface ring's "
        f"shells read {_pct(rows[0], r1):+.0f} % and the default {_pct(rows[1], r1):+.1f} % "
        f"above one sheet a shell, which costs {cost:.1f} x the default and reads "
        f"{_pct(r1, _rho3d(roll, '3d')):+.0f} % against `3d` and "
        f"{_pct(r1, _rho3d(roll, '2d')):+.0f} % against `2d` ({r1:.1f} against "
        f"{_rho3d(roll, '3d'):.1f} and {_rho3d(roll, '2d'):.1f}; {_measured('lps3d')})"
    )


#: Largest change between two and one sheets a shell that still counts as converged [%]:
#: the tolerance of the other 3D ladders (the refinement and the increments, 1-2 %), of
#: the order of the default's own lumping error on PET2 53.4 N.
LPS_TOL = 3.0


def lps_rolls3d() -> str:
    """Two (the default) against one sheet a shell on :data:`LPS_ROLLS` (table)."""
    lps = _rec("lps3d")
    cpu_l = records.load("layered_study.lps3d")["cpu_s"]
    lines = [
        f"| roll | {_lps_default()} sheets a shell (default) | 1 sheet a shell | default "
        "against 1 sheet | CPU, 1 sheet / default |",
        "|---|---|---|---|---|",
    ]
    for case, h in LPS_ROLLS:
        roll = _run_id(case, h, "")[:-1]
        two = _rho3d(roll, LAYERED_3D)
        one = float(lps[f"{roll}/layered-3d_lps1"]["rho_fd"])
        cm = 100 * float(lps[f"{roll}/layered-3d_lps1"]["pile_height_m"])
        ratio = cpu_l[f"{roll}/layered-3d_lps1"] / cpu_l[f"{roll}/layered-3d_lps{_lps_default()}"]
        lines.append(
            f"| {_label(case)}, H {cm:.3g} cm | {two:.1f} | {one:.1f} | {_pct(two, one):+.1f} % "
            f"| {ratio:.1f}x |"
        )
    return "\n".join(lines)


def _head(name: str) -> dict[str, Any]:
    return _rec("head3d")[f"pet2-53.4N/{name}@{1e3 * HEAD_DEPTH:g}mm"]


def lps_summary() -> str:
    """docs/studies.md's line on the default sheets a shell against one (inline)."""
    lps = _rec("lps3d")
    d = []
    for case, h in LPS_ROLLS:
        roll = _run_id(case, h, "")[:-1]
        d.append(_pct(_rho3d(roll, LAYERED_3D), float(lps[f"{roll}/layered-3d_lps1"]["rho_fd"])))
    df = _pct(_head("layered-3d")["force_N"], _head("layered-3d_lps1")["force_N"])
    ok = max(abs(v) for v in d) <= LPS_TOL
    return (
        f"reads {_span(d, '.1f')} % {'above' if min(d) > 0 else 'from'} one sheet a shell on "
        f"{len(d)} rolls ({'within' if ok else 'not within'} {LPS_TOL:g} %); pressed to one "
        f"depth it carries {abs(df):.1f} % {'more' if df > 0 else 'less'} force than one sheet "
        f"a shell, so its field under the head is "
        + ("converged" if abs(df) <= LPS_TOL else "not converged")
        + " to that tolerance"
    )


def _and(xs: list[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return xs[0] if len(xs) == 1 else ", ".join(xs[:-1]) + " and " + xs[-1]


def head3d_lps() -> str:
    """How far the default's field under the head is from one sheet a shell (inline)."""
    two, one, cont = _head("layered-3d"), _head("layered-3d_lps1"), _head("3d")
    n = len(PRESSURE_DEPTHS)
    top = [k for k, d in enumerate(PRESSURE_DEPTHS) if d <= 2e-3]
    dp = [abs(_pct(two[f"pressure_{k}_Pa"], one[f"pressure_{k}_Pa"])) for k in range(n)]
    dp_top = max(dp[k] for k in top)
    dw = [
        abs(1e3 * (two[f"spread_half_width_{k}_m"] - one[f"spread_half_width_{k}_m"]))
        for k in range(len(SPREAD_DEPTHS))
    ]
    df = _pct(two["force_N"], one["force_N"])
    # the column's shape: each model's pressure per newton of its force
    shape = [
        _pct(two[f"pressure_{k}_Pa"] / two["force_N"], one[f"pressure_{k}_Pa"] / one["force_N"])
        for k in range(n)
    ]
    lower = [k for k in range(n) if two[f"pressure_{k}_Pa"] < one[f"pressure_{k}_Pa"] and df > 0]
    worst = max(abs(df), dp_top)
    verdict = "converged" if worst <= LPS_TOL else "not converged"
    return (
        f"pressed to the same depth, the default carries {abs(df):.1f} % "
        f"{'more' if df > 0 else 'less'} force than one sheet a shell, its pressure under "
        f"the head's centre is within {dp_top:.1f} % of one "
        f"sheet's in the top 2 mm ({max(dp):.1f} % at any depth to 16 mm) and its CMD spread "
        f"within {max(dw):.1f} mm: two sheets a shell is {verdict} for the field under the "
        f"head at the {LPS_TOL:g} % the readings meet (the table above), and one sheet a "
        f"shell carries {-_pct(one['force_N'], cont['force_N']):.0f} % less force than the "
        f"continuum where the default carries {-_pct(two['force_N'], cont['force_N']):.0f} % "
        f"less. Nor is the default's field one sheet's scaled up: per newton of force its "
        f"column's pressure differs by "
        + " / ".join(f"{v:+.0f}" for v in shape)
        + f" % at {' / '.join(f'{1e3 * d:g}' for d in PRESSURE_DEPTHS)} mm"
        + (
            f", and at {_and([f'{1e3 * PRESSURE_DEPTHS[k]:g}' for k in lower])} mm it is "
            "lower outright though it carries more force: the lumped sheets keep the load "
            "nearer the surface"
            if lower
            else ""
        )
        + ". The reading moves about a third as much as the force at one depth: with F "
        f"close to alpha d^2, the striker's energy fixes alpha d^3, so its depth goes as "
        f"alpha^(-1/3) ({_measured('head3d')})"
    )


def cost_default3d() -> str:
    """CPU time of a whole `woundroll run` in layered-3d and 3d on the default 3D mesh
    (inline, from the roll3d record)."""
    rec = records.load("layered_study.roll3d")
    cpu = rec["cpu_s"]
    parts = [
        f"{_label(c)} {cpu[f'{c}/{LAYERED_3D}_default_mesh'] / 60:.1f} CPU min "
        f"(3d {cpu[f'{c}/3d_default_mesh']:.0f} CPU s)"
        for c in ("pet1-26.7N", "pet2-53.4N")
    ]
    return "; ".join(parts) + f" ({_measured('roll3d')}, at load {rec['load_1min']:g})"


BLOCKS: dict[str, Callable[[], str]] = {
    "heights": heights,
    "provenance": provenance,
    "study_cost": study_cost,
    "table": table,
    "pet3_cost": pet3_cost,
    "soft": soft,
    "pile": pile,
    "shear08": shear08,
    "pet3": pet3,
    "zone": zone,
    "zone_ladder": zone_ladder,
    "zone_converged": zone_converged,
    "zone_summary": zone_summary,
    "verdict": verdict,
    "zone_provenance": zone_provenance,
    "fit": fit,
    "provenance3d": provenance3d,
    "table3d": table3d,
    "mu3d": mu3d,
    "head3d_table": head3d_table,
    "cost_ratio3d": cost_ratio3d,
    "study3d_cost": study3d_cost,
    "mesh_offset3d": mesh_offset3d,
    "cost3d": cost3d,
    "text3d": text3d,
    "lps_ladder3d": lps_ladder3d,
    "lps_rolls3d": lps_rolls3d,
    "head3d_lps": head3d_lps,
    "lps_summary": lps_summary,
    "cost_default3d": cost_default3d,
    "text3d_all": text3d_all,
}

if __name__ == "__main__":
    import sys

    for name in sys.argv[1:] or list(BLOCKS):
        print(f"--- {name}\n{BLOCKS[name]()}", flush=True)
