"""The layered roll beside the continuum (issue 25, item 3): does interlayer friction bring
the model toward the paper's measured facts?

Per roll of Table 2 and per pile height of the PET2 53.4 N roll (H = 2, 4, 6, 8.89 cm,
Figures 16/17) the Rho reading (FD {4}-{13}) with the plane-strain continuum (``"2d"``) and
the layered roll (``"layered"``) at mu = 0.1, 0.3, 0.5 (``contact.friction``), and beside
them the other explanations (item 4): G_r_theta frozen at its pre-impact value
(``contact.shear_frozen``) and a lower G/E_r (``contact.shear_ratio``). The facts to compare
with (docs/studies.md): the paper's tests read nearly the same at every pile height, and
soft PET2 reads below the continuum models.

The same study in 3D (``woundroll study layered-3d``, :func:`run_3d`): beside 2d and the
layered roll in plane strain, the 3D continuum (``"3d"``) and the layered roll in 3D
(``"layered-3d"``) at each mu, on the coarser 3D mesh :data:`COARSE_3D` (cost).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from woundroll.studies._common import (
    TABLE2,
    Progress,
    SummaryTable,
    _fmt,
    _map,
    _measure,
    _savefig,
    _write,
)
from woundroll.studies.pile_height import DEFAULT_PILE_HEIGHTS

#: Friction coefficients of the layered rows [-].
FRICTIONS: tuple[float, ...] = (0.1, 0.3, 0.5)
#: The roll of the pile-height series.
PILE_CASE = "pet2-53.4N"
#: Core outer radius of the bundled PET cases [m] (pile height = outer radius - this).
_PILE_OVERRIDE = "winding.outer_radius={r!r} m"
#: The other explanations (issue 25, item 4): column name -> (title, overrides, JSON fields)
EXPLANATIONS: dict[str, tuple[str, tuple[str, ...], dict[str, Any]]] = {
    "2d_shear_frozen": (
        "2d, G frozen",
        ("contact.model='2d'", "contact.shear_frozen=true"),
        {"model": "2d", "shear_frozen": True},
    ),
    "2d_shear_ratio1": (
        "2d, G = 1 E_r",
        ("contact.model='2d'", "contact.shear_ratio=1.0"),
        {"model": "2d", "shear_ratio": 1.0},
    ),
    "2d_shear_ratio0.5": (
        "2d, G = 0.5 E_r",
        ("contact.model='2d'", "contact.shear_ratio=0.5"),
        {"model": "2d", "shear_ratio": 0.5},
    ),
    "layered_mu0.3_shear_frozen": (
        "layered mu=0.3, G frozen",
        ("contact.model='layered'", "contact.friction=0.3", "contact.shear_frozen=true"),
        {"model": "layered", "friction": 0.3, "shear_frozen": True},
    ),
}
#: The 3D mesh of the study's 3D columns (both 3D models, :func:`run_3d`): the default
#: gradings, half the fine zone's elements and a third of the increments of
#: ``Contact3DOptions`` (a layered-3d roll costs about ten 3d solves on it, several times that on
#: the default mesh). **Assumption**: the two 3D models' difference, which is what the
#: columns compare, depends little on the mesh; the 3d column's own offset against the
#: default mesh is measured in docs/studies.md (layered section, a record).
COARSE_3D: tuple[str, ...] = (
    "contact.options3d.radial_growth=1.6",
    "contact.options3d.tangential_growth=1.6",
    "contact.options3d.axial_growth=1.6",
    "contact.options3d.n_fine=5",
    "contact.options3d.n_steps=8",
)


@dataclass(frozen=True)
class LayeredStudy:
    """Rho of each roll by the continuum and the layered model.

    Attributes
    ----------
    rows : tuple of dict
        ``case``, ``pile_height_m``, ``series`` ("table2" or "pile-height"), ``rho_2d`` and
        ``rho_layered_mu<mu>`` per friction [-], and ``delta_max_m`` of each; with
        ``three_d`` also ``rho_3d`` and ``rho_layered-3d_mu<mu>``.
    frictions : tuple of float
    three_d : bool
        The 3D columns (:func:`run_3d`, on the mesh :data:`COARSE_3D`).
    """

    rows: tuple[dict[str, Any], ...]
    frictions: tuple[float, ...] = FRICTIONS
    explanations: tuple[str, ...] = ()
    three_d: bool = False
    name: str = field(default="layered")

    def _columns(self) -> list[tuple[str, str, dict[str, Any]]]:
        """Every model column after 2d: (row key suffix, title, the JSON reading's fields)."""
        cols = [
            (f"layered_mu{m:g}", f"layered mu={m:g}", {"model": "layered", "friction": m})
            for m in self.frictions
        ]
        cols += [(e, EXPLANATIONS[e][0], dict(EXPLANATIONS[e][2])) for e in self.explanations]
        if self.three_d:
            cols.append(("3d", "3d", {"model": "3d"}))
            cols += [
                (
                    f"layered-3d_mu{m:g}",
                    f"layered-3d mu={m:g}",
                    {"model": "layered-3d", "friction": m},
                )
                for m in self.frictions
            ]
        return cols

    def to_dict(self) -> dict[str, Any]:
        rolls = []
        for r in self.rows:
            readings = [
                {"model": "2d", "rho_fd": r["rho_2d"], "impact_depth_m": r["delta_max_2d_m"]}
            ]
            readings += [
                {**fields, "rho_fd": r[f"rho_{key}"], "impact_depth_m": r[f"delta_max_{key}_m"]}
                for key, _, fields in self._columns()
            ]
            rolls.append(
                {
                    "case": r["case"],
                    "series": r["series"],
                    "pile_height_m": r["pile_height_m"],
                    "model_readings": readings,
                }
            )
        out: dict[str, Any] = {"study": self.name, "rolls": rolls}
        if self.three_d:
            out["overrides_3d"] = list(COARSE_3D)
        return out

    def summary(self) -> list[SummaryTable]:
        cols = self._columns()
        header = ("case", "H [cm]", "Rho 2d [-]", *(f"Rho {title} [-]" for _, title, _ in cols))
        tables = []
        kind = "continuum (2d, 3d) and layered" if self.three_d else "continuum (2d) and layered"
        for series, title in (
            ("table2", f"Table 2 rolls: {kind}"),
            ("pile-height", f"Pile heights of {PILE_CASE}: continuum and layered"),
        ):
            rows = [
                (
                    r["case"],
                    f"{r['pile_height_m'] * 100:.2f}",
                    _fmt(r["rho_2d"]),
                    *(_fmt(r[f"rho_{key}"]) for key, _, _ in cols),
                )
                for r in self.rows
                if r["series"] == series
            ]
            if rows:
                tables.append(SummaryTable(title, header, rows))
        return tables

    def notes(self) -> list[str]:
        pile = [r for r in self.rows if r["series"] == "pile-height"]
        out = []
        if len(pile) >= 2:
            lo, hi = pile[0], pile[-1]
            out.append(
                f"pile height {lo['pile_height_m'] * 100:.2f} -> {hi['pile_height_m'] * 100:.2f}"
                f" cm: 2d {lo['rho_2d'] / hi['rho_2d']:.2f}x; "
                + "; ".join(
                    f"{title} {lo[f'rho_{key}'] / hi[f'rho_{key}']:.2f}x"
                    for key, title, _ in self._columns()
                )
                + " (the paper's tests: nearly 1x)"
            )
        if self.three_d:
            out.append(
                "3d and layered-3d on a coarser 3D mesh than the default ("
                + ", ".join(o.removeprefix("contact.options3d.") for o in COARSE_3D)
                + "): compare the 3D columns with each other"
            )
        return out

    def write(self, out_dir: str | Path) -> list[Path]:
        return _write(self, out_dir)

    def plot(self, out_dir: str | Path) -> list[Path]:
        """``layered_pile_height.png``: Rho against pile height, 2d and layered (and the 3D
        models with ``three_d``)."""
        import matplotlib.pyplot as plt

        pile = [r for r in self.rows if r["series"] == "pile-height"]
        if not pile:
            return []
        h = [r["pile_height_m"] * 100 for r in pile]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(h, [r["rho_2d"] for r in pile], "ko-", label="2d continuum")
        for m in self.frictions:
            ax.plot(h, [r[f"rho_layered_mu{m:g}"] for r in pile], "s--", label=f"layered mu={m:g}")
        if self.three_d:
            ax.plot(h, [r["rho_3d"] for r in pile], "k^-", label="3d continuum (coarse)")
            for m in self.frictions:
                key = f"rho_layered-3d_mu{m:g}"
                ax.plot(h, [r[key] for r in pile], "d:", label=f"layered-3d mu={m:g} (coarse)")
        ax.set_xlabel("pile height H [cm]")
        ax.set_ylabel("Rho (FD) [-]")
        ax.set_title(f"{PILE_CASE}: continuum against layered")
        ax.legend()
        return [_savefig(fig, Path(out_dir) / "layered_pile_height.png")]


def _job(case: str, overrides: tuple[str, ...]) -> dict[str, Any]:
    row = _measure(case, overrides)["row"]
    return {
        "case": row["case"],
        "pile_height_m": row["pile_height_m"],
        "rho_fd": row["rho_fd"],
        "delta_max_m": row["impact_depth_m"],
    }


@dataclass(frozen=True)
class StudyJob:
    """One run of the study: ``case`` (bundled) with ``overrides``, its roll's ``series``
    ("table2" or "pile-height"), ``pile_height_m`` (the wound-to height of a pile-height run,
    None for a Table 2 roll) and the ``model`` column it fills (``"2d"``,
    ``"layered_mu<mu>"`` or a key of :data:`EXPLANATIONS`)."""

    case: str
    series: str
    pile_height_m: float | None
    model: str
    overrides: tuple[str, ...]


def study_models(
    frictions: Sequence[float] = FRICTIONS,
    explanations: Sequence[str] = tuple(EXPLANATIONS),
    three_d: bool = False,
) -> list[tuple[str, tuple[str, ...]]]:
    """The model columns: ``(name, overrides)`` of 2d, layered per mu, each explanation,
    and with ``three_d`` 3d and layered-3d per mu on the mesh :data:`COARSE_3D`."""
    models = [("2d", ("contact.model='2d'",))] + [
        (f"layered_mu{m:g}", ("contact.model='layered'", f"contact.friction={m!r}"))
        for m in frictions
    ]
    models += [(e, EXPLANATIONS[e][1]) for e in explanations]
    if three_d:
        models.append(("3d", ("contact.model='3d'", *COARSE_3D)))
        models += [
            (
                f"layered-3d_mu{m:g}",
                ("contact.model='layered-3d'", f"contact.friction={m!r}", *COARSE_3D),
            )
            for m in frictions
        ]
    return models


def study_rolls(
    cases: Sequence[str] = TABLE2, pile_heights: Sequence[float] = DEFAULT_PILE_HEIGHTS
) -> list[tuple[str, str, float | None, tuple[str, ...]]]:
    """The rolls: ``(case, series, pile height or None, overrides)``, the Table 2 rolls then
    :data:`PILE_CASE` wound to core radius + each of ``pile_heights`` [m]."""
    from woundroll.case import load_case

    r_core = load_case(PILE_CASE).core.build().outer_radius
    rolls: list[tuple[str, str, float | None, tuple[str, ...]]] = [
        (c, "table2", None, ()) for c in cases
    ]
    rolls += [
        (PILE_CASE, "pile-height", h, (_PILE_OVERRIDE.format(r=r_core + h),)) for h in pile_heights
    ]
    return rolls


def study_jobs(
    cases: Sequence[str] = TABLE2,
    pile_heights: Sequence[float] = DEFAULT_PILE_HEIGHTS,
    frictions: Sequence[float] = FRICTIONS,
    explanations: Sequence[str] = tuple(EXPLANATIONS),
    three_d: bool = False,
) -> list[StudyJob]:
    """Every run of :func:`layered_study` (roll-major: each roll's models in
    :func:`study_models` order); docs/scripts/layered_study.py measures the same list."""
    return [
        StudyJob(case, series, h, name, (*over, "contact.no_update=false", *m_over))
        for case, series, h, over in study_rolls(cases, pile_heights)
        for name, m_over in study_models(frictions, explanations, three_d)
    ]


def layered_study(
    cases: Sequence[str] = TABLE2,
    pile_heights: Sequence[float] = DEFAULT_PILE_HEIGHTS,
    frictions: Sequence[float] = FRICTIONS,
    progress: Progress | None = None,
    *,
    workers: int = 1,
    explanations: Sequence[str] = tuple(EXPLANATIONS),
    three_d: bool = False,
) -> LayeredStudy:
    """Rho by ``"2d"``, ``"layered"`` (each mu of ``frictions``) and the ``explanations``
    (keys of :data:`EXPLANATIONS`) for ``cases`` and for :data:`PILE_CASE` wound to core
    radius + each of ``pile_heights`` [m]; with ``three_d`` also ``"3d"`` and
    ``"layered-3d"`` (each mu) on the mesh :data:`COARSE_3D`."""
    jobs = study_jobs(cases, pile_heights, frictions, explanations, three_d)
    models = study_models(frictions, explanations, three_d)
    rolls = study_rolls(cases, pile_heights)
    out = _map(
        _job,
        [(j.case, j.overrides) for j in jobs],
        workers=workers,
        progress=progress,
        label=lambda i: f"{jobs[i].case} ({i + 1})",
    )
    rows = []
    for k, (case, series, _, _) in enumerate(rolls):
        got = out[k * len(models) : (k + 1) * len(models)]
        row: dict[str, Any] = {
            "case": case,
            "series": series,
            "pile_height_m": got[0]["pile_height_m"],
        }
        for (name, _), g in zip(models, got, strict=True):
            row[f"rho_{name}"] = g["rho_fd"]
            row[f"delta_max_{name}_m"] = g["delta_max_m"]
        rows.append(row)
    return LayeredStudy(
        rows=tuple(rows),
        frictions=tuple(frictions),
        explanations=tuple(explanations),
        three_d=three_d,
        name="layered-3d" if three_d else "layered",
    )


def run(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> LayeredStudy:
    """The registry's entry (``woundroll study layered``); ``model`` is not used (the
    study fixes its models: 2d and layered)."""
    return layered_study(progress=progress, workers=workers)


def run_3d(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> LayeredStudy:
    """The registry's entry ``woundroll study layered-3d``: the study's rolls in 2d, layered,
    3d and layered-3d (each mu of :data:`FRICTIONS`; the 2D explanations are the layered
    study's). Tens of CPU minutes (docs/studies.md gives the measured cost); ``model``
    is not used."""
    return layered_study(progress=progress, workers=workers, explanations=(), three_d=True)
