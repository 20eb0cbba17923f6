"""Figure 18: the slip factor {23} near the head at the impact's maximum depth; Figure 19:
the Table 2 rolls read with and without the reduced-shear slip emulation."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from woundroll.errors import InputError
from woundroll.materials.web import INTERLAYER_FRICTION, SLIP_SHEAR_FRACTION
from woundroll.studies._common import (
    TABLE2,
    Progress,
    SummaryTable,
    _fmt,
    _map,
    _measure,
    _prefix,
    _report,
    _savefig,
    _write,
)


@dataclass(frozen=True)
class SlipStudy:
    """Figure 18: the slip factor {23} near the head at the impact's maximum depth.

    Attributes
    ----------
    row : dict
        The roll's row (as in :func:`tension_study`).
    friction : float
        Interlayer mu [-].
    fields_depth_m : float
        Head depth at which the fields are taken [m].
    fields_source : str
        ``"at_depth"`` (``ContactResult.at_depth`` at the FD maximum depth) or
        ``"depth_max"`` (the contact solve's largest depth, at or beyond the impact's).
    max_slip_factor : float
        Largest finite SF within 3 a of the contact axis.
    slip_depth_m, slip_halfwidth_m : float
        Depth below the surface and arc half-width of the SF >= 1 region within 3 a.
    slip_depth_whole_m : float
        Deepest element with SF >= 1 anywhere in the model [m] (the region is far larger
        than the contact, docs/studies.md).
    n_slip, n_near : int
        Elements with SF >= 1, and all elements, within 3 a of the axis.
    n_unbounded : int
        Elements within 3 a sheared with no interlayer pressure (SF = inf).
    emulation : tuple of dict
        Figure 19: per roll ``case``, ``rho_fd``/``rho_energy``/``impact_depth_m`` without slip
        and the same with ``_slip`` appended with the reduced-shear emulation, and
        ``slipped_elements`` (empty unless asked for).
    emulation_model : str
        Contact model of the emulation rows (``"2d"`` or ``"3d"``).
    slip_shear_fraction : float
        Share of the shear modulus a slipped element keeps in those rows.
    """

    case: str
    row: dict[str, Any]
    friction: float
    fields_depth_m: float
    fields_source: str
    max_slip_factor: float
    slip_depth_m: float
    slip_halfwidth_m: float
    n_slip: int
    n_near: int
    n_unbounded: int
    slip_depth_whole_m: float = math.nan
    contact: Any = field(default=None, repr=False, compare=False)
    name: str = "slip"
    emulation: tuple[dict[str, Any], ...] = ()
    emulation_model: str = "2d"
    slip_shear_fraction: float = SLIP_SHEAR_FRACTION

    def to_dict(self) -> dict[str, Any]:
        return {
            "study": self.name,
            "figures": "reference paper, Figure 18",
            "case": self.case,
            "friction": self.friction,
            "impact_depth_m": self.row["impact_depth_m"],
            "fields_depth_m": self.fields_depth_m,
            "fields_source": self.fields_source,
            "semi_contact_width_m": self.row["semi_contact_width_m"],
            "max_slip_factor_near_contact": self.max_slip_factor,
            "slip_region_depth_m": self.slip_depth_m,
            "slip_region_halfwidth_m": self.slip_halfwidth_m,
            "slip_elements_near_contact": self.n_slip,
            "elements_near_contact": self.n_near,
            "unbounded_slip_elements_near_contact": self.n_unbounded,
            "slip_region_depth_whole_model_m": self.slip_depth_whole_m,
            "roll": dict(self.row),
            **(
                {
                    "emulation": {
                        "figures": "reference paper, Figure 19",
                        "contact_model": self.emulation_model,
                        "slip_shear_fraction": self.slip_shear_fraction,
                        "friction": self.friction,
                        "rolls": [dict(r) for r in self.emulation],
                    }
                }
                if self.emulation
                else {}
            ),
        }

    def summary(self) -> list[SummaryTable]:
        header = (
            "case",
            "mu",
            "impact depth [mm]",
            "fields at [mm]",
            "a [mm]",
            "max SF",
            "SF>=1 depth [mm]",
            "SF>=1 half-width [mm]",
            "SF>=1 elements (within 3a)",
            "SF>=1 depth, whole model [mm]",
        )
        rows = [
            (
                self.case,
                f"{self.friction:g}",
                f"{self.row['impact_depth_m'] * 1e3:.2f}",
                f"{self.fields_depth_m * 1e3:.2f}",
                f"{self.row['semi_contact_width_m'] * 1e3:.2f}",
                _fmt(self.max_slip_factor),
                f"{self.slip_depth_m * 1e3:.2f}",
                f"{self.slip_halfwidth_m * 1e3:.2f}",
                f"{self.n_slip} / {self.n_near}",
                f"{self.slip_depth_whole_m * 1e3:.1f}",
            )
        ]
        tables = [SummaryTable("Slip factor {23} near the head (Figure 18)", header, rows)]
        if self.emulation:
            tables.append(
                SummaryTable(
                    f"Slip emulation, reduced shear (Figure 19): {self.emulation_model.upper()} "
                    f"model, mu {self.friction:g}, shear fraction {self.slip_shear_fraction:g}",
                    (
                        "case",
                        "Rho FD",
                        "Rho FD slip",
                        "change [%]",
                        "Rho energy",
                        "Rho energy slip",
                        "max depth [mm]",
                        "max depth slip [mm]",
                        "slipped elements",
                    ),
                    [
                        (
                            r["case"],
                            f"{r['rho_fd']:.1f}",
                            f"{r['rho_fd_slip']:.1f}",
                            f"{100 * (r['rho_fd_slip'] / r['rho_fd'] - 1):+.0f}",
                            f"{r['rho_energy']:.1f}",
                            f"{r['rho_energy_slip']:.1f}",
                            f"{r['impact_depth_m'] * 1e3:.2f}",
                            f"{r['impact_depth_slip_m'] * 1e3:.2f}",
                            f"{r['slipped_elements']}",
                        )
                        for r in self.emulation
                    ],
                )
            )
        return tables

    def notes(self) -> list[str]:
        return [
            "Fields from ContactResult.at_depth at the FD maximum depth; in-plane part of "
            "{23} (no tau_rz in plane strain)."
        ]

    def plot(self, prefix: str | Path) -> list[Path]:
        """Write ``slip_factor.png``: SF {23} within 4 a of the head, SF = 1 contour."""
        if self.contact is None:
            return []
        path = Path(f"{_prefix(prefix, 'slip')}_factor.png")
        from woundroll.contact import plot_slip_factor

        fig = plot_slip_factor(self.contact)
        fig.axes[0].set_title(
            f"{self.case}: slip factor at head depth {self.fields_depth_m * 1e3:.3g} mm "
            "(white: SF = 1; cf. Figure 18)",
            fontsize=9,
        )
        _savefig(fig, path)
        paths = [path]
        if self.emulation:
            paths.append(self._plot_emulation(Path(f"{_prefix(prefix, 'slip')}_emulation.png")))
        return paths

    def _plot_emulation(self, path: Path) -> Path:
        """``slip_emulation.png``: Rho (FD) of each roll with and without slip (Fig. 19)."""
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 3.6))
        x = np.arange(len(self.emulation))
        ax.bar(x - 0.2, [r["rho_fd"] for r in self.emulation], 0.4, label="no slip")
        ax.bar(x + 0.2, [r["rho_fd_slip"] for r in self.emulation], 0.4, label="reduced shear")
        ax.set_xticks(x, [r["case"] for r in self.emulation], fontsize=8)
        ax.set_ylabel("Rho (FD)")
        ax.set_title(
            f"Slip emulation ({self.emulation_model.upper()} contact, mu {self.friction:g}, "
            f"fraction {self.slip_shear_fraction:g}; cf. Figure 19)",
            fontsize=9,
        )
        ax.legend(fontsize=8)
        fig.tight_layout()
        _savefig(fig, path)
        plt.close(fig)
        return path

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write ``study.json`` and the PNG into ``out_dir``; return the paths."""
        return _write(self, out_dir)


def slip_factor_study(
    case: str = "pet2-53.4N",
    friction: float = INTERLAYER_FRICTION,
    progress: Progress | None = None,
    *,
    emulation_cases: Sequence[str] = (),
    slip_shear_fraction: float = SLIP_SHEAR_FRACTION,
    model: str | None = None,
    workers: int = 1,
) -> SlipStudy:
    """Figure 18: run ``case`` with interlayer friction ``friction`` and map SF >= 1;
    Figure 19: read ``emulation_cases`` with and without ``contact.slip = "reduced-shear"``.

    The no-update solve is switched off. The fields are those at the impact's maximum
    depth (FD model), from ``ContactResult.at_depth``. The emulation rows use the contact
    ``model`` ("2d" or "3d"; None: the registry's default,
    :data:`woundroll.contact.models.DEFAULT_ROLL_MODEL`), mu = ``friction`` and
    ``slip_shear_fraction``; ``workers`` runs them in a process pool.
    """
    if (
        isinstance(friction, bool)
        or not isinstance(friction, int | float)
        or not (math.isfinite(friction) and friction >= 0)
    ):
        raise InputError(f"must be a number >= 0, got {friction!r}", "study.friction")
    from woundroll.contact.models import resolve_model

    model = resolve_model(model, "cylinder", "study.model").name
    if model not in ("2d", "3d"):
        raise InputError(f"the slip emulation runs in '2d' or '3d', got {model!r}", "study.model")
    _report(progress, f"slip: {case}", 0.0)
    # the Figure 18 roll is read with the emulation rows' contact model, so that its row is
    # the emulation's no-slip row (the CMD-spreading correction of the default path is not
    # verified with reduced shear: the study names its model instead)
    out = _measure(
        case,
        (
            f"contact.friction={float(friction)!r}",
            "contact.no_update=false",
            f"contact.model='{model}'",
        ),
        keep=("contact",),
    )
    row = out["row"]
    contact = out["contact"]
    depth_at = min(row["impact_depth_m"], float(contact.delta[-1]))
    fields, source = contact.at_depth(depth_at), "at_depth"
    a = fields.semi_contact_width
    near = fields.outer_radius * np.abs(np.asarray(fields.element_theta)) <= 3.0 * a
    sf = np.asarray(fields.slip_factor)[near]
    d, w = fields.slip_extent(3.0 * a)
    emulation = _emulation_rows(
        emulation_cases, friction, model, slip_shear_fraction, workers, progress
    )
    _report(progress, "done", 1.0)
    return SlipStudy(
        emulation=tuple(emulation),
        emulation_model=model,
        slip_shear_fraction=float(slip_shear_fraction),
        case=case,
        row=row,
        friction=float(friction),
        fields_depth_m=depth_at,
        fields_source=source,
        max_slip_factor=float(np.max(sf[np.isfinite(sf)], initial=0.0)),
        slip_depth_m=d,
        slip_halfwidth_m=w,
        n_slip=int(np.sum(sf >= 1.0)),
        n_near=int(sf.size),
        n_unbounded=int(np.sum(np.isinf(sf))),
        slip_depth_whole_m=fields.slip_extent(math.pi * fields.outer_radius)[0],
        contact=fields,
    )


def _emulation_rows(
    emulation_cases: Sequence[str],
    friction: float,
    model: str,
    slip_shear_fraction: float,
    workers: int,
    progress: Progress | None,
) -> list[dict[str, Any]]:
    """Figure 19: each case read with and without ``contact.slip = "reduced-shear"``."""
    emulation: list[dict[str, Any]] = []
    if not emulation_cases:
        return emulation
    base = (
        f"contact.friction={float(friction)!r}",
        "contact.no_update=false",
        f"contact.model='{model}'",
        f"contact.slip_shear_fraction={float(slip_shear_fraction)!r}",
    )
    jobs = [
        (name, (*base, f"contact.slip='{mode}'"), ("contact",) if mode != "none" else ())
        for name in emulation_cases
        for mode in ("none", "reduced-shear")
    ]
    rows = _map(
        _measure,
        jobs,
        workers=workers,
        progress=None if progress is None else lambda s, f: progress(s, 0.1 + 0.9 * f),
        label=lambda i: f"slip emulation: {jobs[i][0]}",
    )
    for i, name in enumerate(emulation_cases):
        plain, slip = rows[2 * i]["row"], rows[2 * i + 1]
        c = slip["contact"]
        n = c.stats["slipped_elements"] if c.slipped is None else int(np.sum(c.slipped))
        emulation.append(
            {
                "case": name,
                "rho_fd": plain["rho_fd"],
                "rho_energy": plain["rho_energy"],
                "impact_depth_m": plain["impact_depth_m"],
                "rho_fd_slip": slip["row"]["rho_fd"],
                "rho_energy_slip": slip["row"]["rho_energy"],
                "impact_depth_slip_m": slip["row"]["impact_depth_m"],
                "slipped_elements": n,
            }
        )
    return emulation


def run(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> SlipStudy:
    """The registry's entry: :func:`slip_factor_study` on PET2 53.4 N (Figure 18) and the
    slip emulation on the seven Table 2 rolls (Figure 19) with the contact ``model``."""
    return slip_factor_study(
        progress=progress, emulation_cases=TABLE2, workers=workers, model=model
    )
