"""Figures 16/17: one roll wound to several pile heights H."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from woundroll.errors import InputError
from woundroll.studies._common import (
    Progress,
    SummaryTable,
    _map,
    _measure,
    _prefix,
    _report,
    _savefig,
    _write,
)

#: Default pile heights of the pile-height study [m]; 8.89 cm is the Table 2 roll.
DEFAULT_PILE_HEIGHTS: tuple[float, ...] = (0.02, 0.04, 0.06, 0.0889)


@dataclass(frozen=True)
class PileHeightStudy:
    """Figures 16/17: one roll wound to several pile heights H.

    Attributes
    ----------
    case : str
    rolls : list of dict
        Per H (increasing): the row of :func:`tension_study` plus two columns that take the
        plane-strain roll apart (the reference is the largest H):

        * ``rho_fd_ref_mass``: this roll's spring {3} with the reference roll's active mass
          m_r {14}-{18} (removes the dependence of m_r on H);
        * ``rho_fd_ref_prestress_mass``: a contact solve on this roll's geometry (core,
          outer radius) with the *reference* roll's pre-impact sigma_r as a function of
          depth below the surface, over the common depth range ``reference_depth_max_m``
          (full-range fit {3}, ``alpha_ref_prestress_N_per_m2``, ``beta_...``), read with
          the reference mass. Between rolls only the plane-strain geometry differs: the
          ring and the core under a line load. (At the reference H it differs from
          ``rho_fd`` only by the fit range.)
        * ``axis_approach_m``, ``approach_share_deeper_1cm``, ``..._2cm``: the approach
          of the surface toward the core along the contact axis, int eps_r dr, at the
          solve's largest depth ``axis_depth_m`` (it should equal it), and the share of
          it from layers deeper than 1 cm and 2 cm (:func:`_axis_locality`).
    profiles : list of dict
        Pre-impact radius [m] and radial pressure -sigma_r [Pa] per H (Figure 16), at most
        ~400 points each (denser near the surface).
    reference_pile_height_m, reference_depth_max_m : float
    """

    case: str
    rolls: list[dict[str, Any]]
    profiles: list[dict[str, Any]]
    reference_pile_height_m: float
    reference_depth_max_m: float
    name: str = "pile-height"

    def rows(self) -> list[dict[str, Any]]:
        return [dict(r) for r in self.rolls]

    def to_dict(self) -> dict[str, Any]:
        return {
            "study": self.name,
            "figures": "reference paper, Figures 16-17",
            "case": self.case,
            "reference_pile_height_m": self.reference_pile_height_m,
            "reference_depth_max_m": self.reference_depth_max_m,
            "rolls": self.rows(),
            "pressure_profiles": self.profiles,
        }

    def summary(self) -> list[SummaryTable]:
        header = (
            "H [cm]",
            "outer radius [cm]",
            "Rho FD",
            "Rho energy",
            "Rho FD ref. m_r",
            "Rho FD ref. m_r+prestress",
            "m_r [g]",
            "alpha [N/m^2]",
            "beta [N/m]",
            "a [mm]",
            "max depth [mm]",
            "approach >1 cm deep [%]",
        )
        rows = []
        for r in self.rolls:
            rows.append(
                (
                    f"{r['pile_height_m'] * 100:.2f}",
                    f"{r['outer_radius_m'] * 100:.2f}",
                    f"{r['rho_fd']:.1f}",
                    f"{r['rho_energy']:.1f}",
                    f"{r['rho_fd_ref_mass']:.1f}",
                    "-"
                    if r["rho_fd_ref_prestress_mass"] is None
                    else f"{r['rho_fd_ref_prestress_mass']:.1f}",
                    f"{r['effective_mass_kg'] * 1e3:.2f}",
                    f"{r['alpha_N_per_m2']:.3g}",
                    f"{r['beta_N_per_m']:.3g}",
                    f"{r['semi_contact_width_m'] * 1e3:.2f}",
                    f"{r['impact_depth_m'] * 1e3:.2f}",
                    f"{r['approach_share_deeper_1cm'] * 100:.0f}",
                )
            )
        return [SummaryTable(f"Rho against pile height, {self.case} (Figures 16-17)", header, rows)]

    def notes(self) -> list[str]:
        h = self.reference_pile_height_m * 100
        return [
            f"ref. m_r: the active roll mass {{18}} of the H = {h:.2f} cm roll; "
            f"ref. m_r+prestress: also that roll's pre-impact sigma_r by depth (spring fitted "
            f"over 0-{self.reference_depth_max_m * 1e3:.2f} mm), so that only the plane-strain "
            "geometry (ring, core) changes with H.",
            "approach >1 cm deep: share of the head's approach (int eps_r dr along the contact "
            "axis) that comes from layers more than 1 cm below the surface.",
        ]

    def plot(self, prefix: str | Path) -> list[Path]:
        """Write ``pile_height_pressure.png`` (Fig. 16) and ``pile_height_rho.png`` (Fig. 17)."""
        from matplotlib.figure import Figure

        base = _prefix(prefix, "pile_height")
        paths_head = self._plot_under_head(base)
        fig = Figure(figsize=(10, 4.0), layout="constrained")
        ax1, ax2 = fig.subplots(1, 2)
        for i, p in enumerate(self.profiles):
            r = np.asarray(p["radius_m"])
            pr = np.asarray(p["pressure_Pa"])
            lab = f"H = {p['pile_height_m'] * 100:.2f} cm"
            ax1.plot(r * 100, pr / 1e3, color=f"C{i}", label=lab)
            ax2.plot((r[-1] - r) * 1e3, pr / 1e3, color=f"C{i}", label=lab)
        ax1.set_xlabel("radius [cm]")
        ax1.set_ylabel("pre-impact radial pressure $-\\sigma_r$ [kPa]")
        ax1.set_title(f"{self.case}: pressure in the roll (cf. Figure 16)")
        ax2.set_xscale("log")
        ax2.set_xlim(left=0.05)
        ax2.set_xlabel("depth below the surface [mm]")
        ax2.set_title("same, against depth (the zone the head loads)")
        for ax in (ax1, ax2):
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        paths = [_savefig(fig, Path(f"{base}_pressure.png"))]

        fig = Figure(figsize=(6.4, 4.2), layout="constrained")
        ax = fig.subplots()
        H = [r["pile_height_m"] * 100 for r in self.rolls]
        ax.plot(H, [r["rho_fd"] for r in self.rolls], "o-", label="FD")
        ax.plot(H, [r["rho_energy"] for r in self.rolls], "s--", label="energy")
        ax.plot(
            H,
            [r["rho_fd_ref_mass"] for r in self.rolls],
            "v:",
            label="FD, active mass $m_r$ of the largest H",
        )
        ax.plot(
            H,
            [r["rho_fd_ref_prestress_mass"] for r in self.rolls],
            "^-.",
            label="FD, $m_r$ and pre-stress of the largest H",
        )
        ax.set_xlabel("pile height H [cm]")
        ax.set_ylabel("Rho [-]")
        ax.set_ylim(bottom=0)
        ax.set_title(f"{self.case}: Rho against pile height (cf. Figure 17)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        paths.append(_savefig(fig, Path(f"{base}_rho.png")))
        return paths + paths_head

    def _plot_under_head(self, base: str) -> list[Path]:
        """``pile_height_under_head.png``: pressure under the head against depth at the
        impact's maximum depth (cf. the paper's Figure 10)."""
        from matplotlib.figure import Figure

        fig = Figure(figsize=(6.4, 4.2), layout="constrained")
        ax = fig.subplots()
        for i, p in enumerate(self.profiles):
            a = p.get("under_head_at_impact")
            if not a:
                continue
            d = np.asarray(a["depth_m"]) * 1e3
            ax.plot(
                d,
                np.asarray(a["pressure_Pa"]) / 1e6,
                color=f"C{i}",
                label=f"H = {p['pile_height_m'] * 100:.2f} cm",
            )
            ax.plot(d, np.asarray(a["pre_impact_pressure_Pa"]) / 1e6, ":", color=f"C{i}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("depth below the surface [mm]")
        ax.set_ylabel("radial pressure under the head [MPa]")
        ax.set_title(f"{self.case}: at the impact's depth (dotted: before impact)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return [_savefig(fig, Path(f"{base}_under_head.png"))]

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write ``study.json`` and the PNGs into ``out_dir``; return the paths."""
        return _write(self, out_dir)


def _axis_locality(contact: Any, web: Any) -> dict[str, float]:
    """Where the head's approach comes from: radial compression along the contact axis.

    On the axis (theta = 0) the shear strain vanishes by symmetry, so the approach of the
    surface toward the core is the integral of the radial strain, u = int eps_r dr. With
    nu_theta_r = nu_z_r = 0 (Table 2) the hypoelastic radial strain of an element is
    eps_r = int dP / E_r(P) from its pre-impact to its final pressure (law {2}), so u follows
    from the stress fields alone (at the solve's largest depth). ``axis_approach_m`` checks
    it against that depth; the shares say how much of it comes from deeper than 1 and 2 cm.
    """
    theta = np.abs(np.asarray(contact.element_theta))  # half or whole-annulus mesh
    on_axis = np.isclose(theta, theta.min(), rtol=1e-9, atol=0.0)
    z = getattr(contact, "element_z", None)  # 3D model: the column under the head's centre
    if z is not None:
        on_axis &= np.isclose(np.asarray(z), np.min(z), rtol=1e-9, atol=0.0)
    r = np.asarray(contact.element_r)[on_axis]
    p_pre = np.maximum(-np.asarray(contact.sigma_r_pre)[on_axis], 0.0)
    p_end = np.maximum(-np.asarray(contact.sigma_r)[on_axis], 0.0)
    # geometric grid in (P + p0): accurate for 1 / E_r ~ 1 / (K1 + P)
    p0 = 1e3
    t = np.linspace(0.0, 1.0, 257)[:, None]
    grid = (p_pre + p0) * ((p_end + p0) / (p_pre + p0)) ** t - p0
    compliance = 1.0 / web.radial_modulus.modulus_at_pressure(grid)
    eps = np.sum(0.5 * (compliance[1:] + compliance[:-1]) * np.diff(grid, axis=0), axis=0)
    order = np.argsort(r)
    r, eps = r[order], eps[order]
    r_out = float(contact.outer_radius)
    edges = np.concatenate([[2.0 * r[0] - 0.5 * (r[0] + r[1])], 0.5 * (r[1:] + r[:-1]), [r_out]])
    u = eps * np.diff(edges)
    depth = r_out - r
    total = float(u.sum())
    return {
        "axis_approach_m": total,
        "axis_depth_m": float(contact.delta[-1]),
        "approach_share_deeper_1cm": float(u[depth > 0.01].sum() / total),
        "approach_share_deeper_2cm": float(u[depth > 0.02].sum() / total),
    }


def _axis_pressure(c: Any, depth: float) -> dict[str, list[float]]:
    """Radial pressure under the head's centre against depth below the surface with the
    head at ``depth`` (the impact's maximum depth, FD): total -sigma_r on the contact axis
    (the paper's Figure 10 view, quasi-static)."""
    st = c.at_depth(min(depth, float(c.delta[-1])))
    theta = np.abs(np.asarray(c.element_theta))
    on = np.isclose(theta, theta.min(), rtol=1e-9, atol=0.0)
    z = getattr(c, "element_z", None)
    if z is not None:
        on &= np.isclose(np.asarray(z), np.min(z), rtol=1e-9, atol=0.0)
    depth = float(c.outer_radius) - np.asarray(c.element_r)[on]
    order = np.argsort(depth)
    return {
        "depth_m": depth[order].tolist(),
        "pressure_Pa": (-np.asarray(st.sigma_r)[on][order]).tolist(),
        "pre_impact_pressure_Pa": (-np.asarray(c.sigma_r_pre)[on][order]).tolist(),
    }


def _pile_height_job(
    name: str,
    overrides: tuple[str, ...],
    ref: dict[str, Any] | None,
) -> dict[str, Any]:
    """One pile height: the full run, then Rho with the reference roll's mass and pre-stress.

    ``ref`` (None for the reference roll itself): ``effective_mass`` [kg], ``depth`` [m]
    (increasing from 0 at the surface) and ``sigma_r`` [Pa] of the reference roll, and
    ``depth_max`` [m], the common indentation range of the like-for-like solves.
    """
    from woundroll.case import load_case
    from woundroll.contact import roll_stiffness
    from woundroll.instruments import hardness_from_spring

    out = _measure(name, overrides, keep=("winding", "contact"))
    row = out["row"]
    radius, sigma_r = out["radius"], out["sigma_r"]
    case = load_case(name, list(overrides))
    web, core = case.web.build(), case.core.build()
    out["axis_pressure"] = _axis_pressure(out["contact"], row["impact_depth_m"])
    row.update(_axis_locality(out.pop("contact"), web))
    row["contact_model"] = case.contact.roll_model(case.tester_setup.instrument.head_shape).name
    setup = case.tester_setup
    ins = setup.instrument
    depth = radius[-1] - radius
    if ref is None:
        ref = {
            "effective_mass": row["effective_mass_kg"],
            "depth": depth[::-1].copy(),
            "sigma_r": sigma_r[::-1].copy(),
            "depth_max": 1.25 * row["impact_depth_m"],
        }
        out["ref"] = ref
    m_ref = ref["effective_mass"]
    row["rho_fd_ref_mass"] = hardness_from_spring(
        setup, row["alpha_N_per_m2"], row["beta_N_per_m"], m_ref
    ).fd.rho
    if row["contact_model"] == "3d":
        # the pre-stress decomposition is a plane-strain question (ring and core under a
        # line load); the 3D study reports the locality columns instead
        row["alpha_ref_prestress_N_per_m2"] = row["beta_ref_prestress_N_per_m"] = None
        row["rho_fd_ref_prestress_mass"] = None
        return out
    # the reference roll's pre-impact sigma_r, by depth below the surface
    sigma_ref = np.interp(depth, ref["depth"], ref["sigma_r"])
    stiff = roll_stiffness(
        web,
        core,
        radius,
        sigma_ref,
        ins,
        start_depth=ref["depth_max"],
        friction=case.contact.friction,
        options=case.contact.contact_options(),
        model=row["contact_model"],
    )
    row["alpha_ref_prestress_N_per_m2"] = stiff.alpha
    row["beta_ref_prestress_N_per_m"] = stiff.beta
    row["rho_fd_ref_prestress_mass"] = hardness_from_spring(
        setup, stiff.alpha, stiff.beta, m_ref
    ).fd.rho
    return out


def _thin(radius: np.ndarray, values: np.ndarray, n: int = 400) -> tuple[list[float], ...]:
    """Keep at most ~n points of a profile, denser near the surface (log spacing in depth)."""
    if radius.size <= n:
        return radius.tolist(), values.tolist()
    depth = radius[-1] - radius
    keep = np.unique(
        np.concatenate(
            [
                np.searchsorted(-depth, -np.geomspace(max(depth[-2], 1e-9), depth[0], n // 2)),
                np.linspace(0, radius.size - 1, n // 2).astype(int),
                [0, radius.size - 1],
            ]
        ).clip(0, radius.size - 1)
    )
    return radius[keep].tolist(), values[keep].tolist()


def _pressure_profiles(heights: list[float], outs: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Each roll's interlayer pressure over the radius (thinned) and under the head."""
    profiles = []
    for h, o in zip(heights, outs, strict=True):
        rr, pp = _thin(o["radius"], -o["sigma_r"])
        profiles.append(
            {
                "pile_height_m": h,
                "radius_m": rr,
                "pressure_Pa": pp,
                "under_head_at_impact": o["axis_pressure"],
            }
        )
    return profiles


def pile_height_study(
    case: str = "pet2-53.4N",
    pile_heights: Sequence[float | str] = DEFAULT_PILE_HEIGHTS,
    progress: Progress | None = None,
    *,
    workers: int = 1,
    model: str | None = None,
) -> PileHeightStudy:
    """Figures 16/17: wind ``case`` to outer radius = core radius + H for each pile height.

    Parameters
    ----------
    case : str
        Bundled case name or case file; its ``[winding] outer_radius`` is overridden.
    pile_heights : sequence of float [m] or str with a unit
        At least one; the largest is the reference of the decomposition columns.
    progress : callable(stage, fraction), optional
    workers : int
        1: serial; 2: a spawned 2-process pool (the reference roll always runs first).
    model : str, optional
        Roll model of the spring (``contact.model``, a name in
        :data:`woundroll.contact.models.ROLL_MODELS`; None: the case's, by default the
        registry's); with ``"3d"`` the pre-stress decomposition column is not computed.

    The no-update solve is switched off (``contact.no_update=false``): not needed here.
    """
    from woundroll.case import load_case
    from woundroll.units import to_si

    heights = sorted(to_si(h, "length", "study.pile_heights") for h in pile_heights)
    if not heights or heights[0] <= 0:
        raise InputError("give positive pile heights", "study.pile_heights")
    base = load_case(case)
    r_core = base.core.build().outer_radius
    jobs = [
        (
            case,
            (
                f"winding.outer_radius={r_core + h!r} m",
                "contact.no_update=false",
                *(() if model is None else (f"contact.model='{model}'",)),
            ),
        )
        for h in heights
    ]
    n = len(jobs)

    def sub(lo: float, span: float) -> Progress | None:
        if progress is None:
            return None
        return lambda stage, f: progress(stage, lo + span * f)

    _report(progress, f"pile height: H = {heights[-1] * 100:.2f} cm (reference)", 0.0)
    ref_out = _pile_height_job(*jobs[-1], None)
    ref = ref_out.pop("ref")
    rest = _map(
        _pile_height_job,
        [(*j, ref) for j in jobs[:-1]],
        workers=workers,
        progress=sub(1.0 / n, 1.0 - 1.0 / n),
        label=lambda i: f"pile height: H = {heights[i] * 100:.2f} cm",
    )
    outs = [*rest, ref_out]
    profiles = _pressure_profiles(heights, outs)
    _report(progress, "done", 1.0)
    return PileHeightStudy(
        case=case,
        rolls=[o["row"] for o in outs],
        profiles=profiles,
        reference_pile_height_m=heights[-1],
        reference_depth_max_m=ref["depth_max"],
    )


def run(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> PileHeightStudy:
    """The registry's entry: :func:`pile_height_study` with its defaults."""
    return pile_height_study(progress=progress, workers=workers, model=model)
