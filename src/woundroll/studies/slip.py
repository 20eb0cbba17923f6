"""Figure 18: the slip factor {23} near the head at the impact's maximum depth."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from woundroll.errors import InputError
from woundroll.studies._common import (
    Progress,
    SummaryTable,
    _fmt,
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

    def to_dict(self) -> dict[str, Any]:
        return {
            "study": self.name,
            "figures": "reference paper, Figure 18",
            "case": self.case,
            "friction": self.friction,
            "impact_depth_m": self.row["delta_max_m"],
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
                f"{self.row['delta_max_m'] * 1e3:.2f}",
                f"{self.fields_depth_m * 1e3:.2f}",
                f"{self.row['semi_contact_width_m'] * 1e3:.2f}",
                _fmt(self.max_slip_factor),
                f"{self.slip_depth_m * 1e3:.2f}",
                f"{self.slip_halfwidth_m * 1e3:.2f}",
                f"{self.n_slip} / {self.n_near}",
                f"{self.slip_depth_whole_m * 1e3:.1f}",
            )
        ]
        return [SummaryTable("Slip factor {23} near the head (Figure 18)", header, rows)]

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
        return [path]

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write ``study.json`` and the PNG into ``out_dir``; return the paths."""
        return _write(self, out_dir)


def slip_factor_study(
    case: str = "pet2-53.4N", friction: float = 0.3, progress: Progress | None = None
) -> SlipStudy:
    """Figure 18: run ``case`` with interlayer friction ``friction`` and map SF >= 1.

    The no-update solve is switched off. The fields are those at the impact's maximum
    depth (FD model), from ``ContactResult.at_depth``.
    """
    if (
        isinstance(friction, bool)
        or not isinstance(friction, int | float)
        or not (math.isfinite(friction) and friction >= 0)
    ):
        raise InputError(f"must be a number >= 0, got {friction!r}", "study.friction")
    _report(progress, f"slip: {case}", 0.0)
    out = _measure(
        case,
        (f"contact.friction={float(friction)!r}", "contact.no_update=false"),
        keep=("contact",),
    )
    row = out["row"]
    contact = out["contact"]
    depth_at = min(row["delta_max_m"], float(contact.delta[-1]))
    fields, source = contact.at_depth(depth_at), "at_depth"
    a = fields.semi_contact_width
    near = fields.outer_radius * np.abs(np.asarray(fields.element_theta)) <= 3.0 * a
    sf = np.asarray(fields.slip_factor)[near]
    d, w = fields.slip_extent(3.0 * a)
    _report(progress, "done", 1.0)
    return SlipStudy(
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


def run(progress: Progress | None = None, *, workers: int = 1) -> SlipStudy:
    """The registry's entry: :func:`slip_factor_study` with its defaults (serial: one roll)."""
    return slip_factor_study(progress=progress)
