"""The reference paper's studies on the Table 2 PET rolls, as data, tables and plots.

Three studies, each a function that runs the whole pipeline (winding -> 2D contact ->
impact, :func:`woundroll.run`) on bundled cases and returns a result object:

* :func:`tension_study` -- Figures 14/15 (and the no-update comparison of Figures 8/9):
  per roll of Table 2 the Rho reading by the finite-difference (FD) model {4}-{13} and the
  energy model {19}-{22}, the same with E_r frozen at its pre-impact value ("no update"),
  the impulse (FD), the roll spring alpha, beta {3}, the semi-contact width a and the
  impact's maximum depth.
* :func:`pile_height_study` -- Figures 16/17: one roll wound to several outer radii
  (pile height H = outer radius - core radius); the pre-impact radial pressure against
  radius, and Rho against H, with columns that take the H dependence of the plane-strain
  model apart (active mass, pre-stress, geometry; where along the axis the head's
  approach comes from; see :class:`PileHeightStudy`).
* :func:`slip_factor_study` -- Figure 18: the slip factor {23} near the head, the region
  where SF >= 1 and the largest SF.

Interface for the command line (``woundroll study NAME [--out DIR] [--json]``)
-------------------------------------------------------------------------------
::

    from woundroll.studies import STUDIES, run_study

    result = run_study(name, progress=progress)   # name in STUDIES: "tension",
                                                  # "pile-height", "slip", "all"
    result.to_dict()       # JSON-ready dict (SI, unit in every key): for --json
    result.summary()       # list[SummaryTable]; each unpacks as (title, header, rows),
                           # header a tuple of column titles (units in brackets), rows a
                           # list of tuples of already formatted strings: print as tables
    result.notes()         # list[str]: one-line remarks to print under the tables
    result.write(out_dir)  # writes study.json and the PNGs, returns list[Path]

``progress(stage: str, fraction: float)`` is called as the runs advance (``fraction`` of
the whole study, 0..1). An unknown ``name`` raises :class:`~woundroll.errors.InputError`
with field ``"study"``. ``run_study(name, workers=2)`` runs independent rolls in a
2-process pool (spawn start method); the default is 1 (serial), see ``docs/studies.md``.

Units: every function takes and returns SI (lengths [m], tensions [N], Rho [-], impulse
[N s]); ``pile_heights`` also accepts strings with a unit (``"4 cm"``). Plots use cm/mm.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple, Protocol

import numpy as np

from woundroll.errors import InputError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

Progress = Callable[[str, float], None]

#: The bundled rolls of the paper's Table 2.
TABLE2: tuple[str, ...] = (
    "pet1-26.7N",
    "pet1-33.4N",
    "pet1-40N",
    "pet1-46.7N",
    "pet2-26.7N",
    "pet2-53.4N",
    "pet2-80N",
)

#: The device manual's average impulse of one Rho-meter impact [N s] (paper, Fig. 7/15).
MANUAL_IMPULSE_NS = 0.267

#: Default pile heights of the pile-height study [m]; 8.89 cm is the Table 2 roll.
DEFAULT_PILE_HEIGHTS: tuple[float, ...] = (0.02, 0.04, 0.06, 0.0889)


class SummaryTable(NamedTuple):
    """A table to print: ``title``, column ``header`` (units in brackets), formatted ``rows``."""

    title: str
    header: tuple[str, ...]
    rows: list[tuple[str, ...]]


class StudyResult(Protocol):
    """What :func:`run_study` returns (the CLI's interface)."""

    name: str

    def to_dict(self) -> dict[str, Any]: ...

    def summary(self) -> list[SummaryTable]: ...

    def notes(self) -> list[str]: ...

    def write(self, out_dir: str | Path) -> list[Path]: ...


# ---------------------------------------------------------------------------------------
# one roll


def _report(progress: Progress | None, stage: str, fraction: float) -> None:
    if progress is not None:
        progress(stage, min(max(float(fraction), 0.0), 1.0))


def _measure(name: str, overrides: Sequence[str], keep: Sequence[str] = ()) -> dict[str, Any]:
    """Run one case and return its row (plain floats) plus the arrays named in ``keep``.

    Module level and returning plain data, so that a spawned worker process can run it.
    ``keep`` may hold ``"winding"`` (radius and sigma_r) and ``"contact"`` (the
    :class:`~woundroll.contact.ContactResult` itself).
    """
    from woundroll.case import load_case
    from woundroll.pipeline import run

    case = load_case(name, list(overrides))
    res = run(case)
    if res.hardness is None or res.contact is None:
        raise InputError(
            f"case {name!r} has no [tester] section read through the contact model", "study"
        )
    web = case.web.build()
    h = res.hardness.to_dict()
    stiffness = res.contact  # the spring used (alpha, beta) ...
    c = stiffness.contact  # ... and the contact solution under it
    d_fd = h["delta_max_m"]
    row: dict[str, Any] = {
        "case": name,
        "title": case.title,
        "material": case.web.preset or "",
        "tension_N": case.winding.schedule(web).web_stress * web.width * web.thickness,
        "outer_radius_m": float(res.winding.radius[-1]),
        "pile_height_m": float(res.winding.radius[-1] - res.winding.radius[0]),
        "rho_fd": h["rho_fd"],
        "rho_energy": h["rho_energy"],
        "impulse_Ns": h["impulse_Ns"],
        "elastic_impulse_bound_Ns": 2.0 * res.hardness.instrument.mass * h["impact_speed_m_per_s"],
        "alpha_N_per_m2": float(stiffness.alpha),
        "beta_N_per_m": float(stiffness.beta),
        "semi_contact_width_m": float(np.interp(d_fd, c.delta, c.half_width)),
        "delta_max_m": d_fd,
        "delta_max_energy_m": h["delta_max_energy_m"],
        "peak_force_N": h["peak_force_N"],
        "peak_contact_pressure_Pa": float(np.interp(d_fd, c.delta, c.peak_pressure)),
        "contact_time_s": h["contact_time_s"],
        "effective_mass_kg": h["effective_mass_kg"],
        "contact_depth_max_m": float(c.delta[-1]),
    }
    if res.no_update is not None:
        nu = res.no_update.to_dict()
        row.update(
            {
                "rho_fd_no_update": nu["rho_fd"],
                "rho_energy_no_update": nu["rho_energy"],
                "impulse_no_update_Ns": nu["impulse_Ns"],
                "alpha_no_update_N_per_m2": nu["alpha_N_per_m2"],
                "beta_no_update_N_per_m": nu["beta_N_per_m"],
            }
        )
    out: dict[str, Any] = {"row": row}
    if "winding" in keep:
        out["radius"] = np.asarray(res.winding.radius, dtype=float)
        out["sigma_r"] = np.asarray(res.winding.sigma_r, dtype=float)
    if "contact" in keep:
        out["contact"] = c
    return out


def _map(
    fn: Callable[..., Any],
    jobs: Sequence[tuple[Any, ...]],
    *,
    workers: int,
    progress: Progress | None,
    label: Callable[[int], str],
) -> list[Any]:
    """``[fn(*job) for job in jobs]``, serially or in a spawned process pool, in order."""
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError(f"must be a whole number >= 1, got {workers!r}", "workers")
    n = len(jobs)
    results: list[Any] = [None] * n
    if workers == 1 or n < 2:
        for i, job in enumerate(jobs):
            _report(progress, label(i), i / n)
            results[i] = fn(*job)
        _report(progress, "done", 1.0)
        return results
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=min(workers, n), mp_context=ctx) as pool:
        futures = {pool.submit(fn, *job): i for i, job in enumerate(jobs)}
        done = 0
        _report(progress, label(0), 0.0)
        for fut in as_completed(futures):
            i = futures[fut]
            results[i] = fut.result()
            done += 1
            _report(progress, label(i), done / n)
    return results


def _fmt(x: float, digits: int = 3) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{x:.{digits}g}" if abs(x) >= 1e-3 or x == 0 else f"{x:.2e}"


def _savefig(fig: Figure, path: Path) -> Path:
    fig.savefig(path, dpi=120)
    return path


def _write(result: Any, out_dir: str | Path) -> list[Path]:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    p = out / "study.json"
    p.write_text(json.dumps(result.to_dict(), indent=1, allow_nan=False) + "\n", encoding="utf-8")
    return [p, *result.plot(out)]


# ---------------------------------------------------------------------------------------
# Figures 14/15: tension


_TENSION_COLUMNS: tuple[tuple[str, str, Callable[[float], str]], ...] = (
    ("material", "material", str),
    ("tension_N", "tension [N]", lambda v: f"{v:.1f}"),
    ("rho_fd", "Rho FD", lambda v: f"{v:.1f}"),
    ("rho_energy", "Rho energy", lambda v: f"{v:.1f}"),
    ("rho_fd_no_update", "Rho FD no-upd", lambda v: f"{v:.1f}"),
    ("rho_energy_no_update", "Rho en. no-upd", lambda v: f"{v:.1f}"),
    ("impulse_Ns", "impulse [N s]", lambda v: f"{v:.3f}"),
    ("alpha_N_per_m2", "alpha [N/m^2]", lambda v: f"{v:.3g}"),
    ("beta_N_per_m", "beta [N/m]", lambda v: f"{v:.3g}"),
    ("semi_contact_width_m", "a [mm]", lambda v: f"{v * 1e3:.2f}"),
    ("delta_max_m", "max depth [mm]", lambda v: f"{v * 1e3:.2f}"),
)


@dataclass(frozen=True)
class TensionStudy:
    """Figures 14/15: Rho (FD, energy, no-update) and impulse against winding tension.

    Attributes
    ----------
    rolls : list of dict
        One row per roll, SI with the unit in the key (see :meth:`rows`). ``a`` and the
        maximum depth are the FD model's: ``semi_contact_width_m`` is the contact model's
        a(d) at ``delta_max_m``. ``elastic_impulse_bound_Ns`` = 2 m_s v at first contact.
    """

    rolls: list[dict[str, Any]]
    name: str = "tension"

    def rows(self) -> list[dict[str, Any]]:
        """The table, one dict per roll (keys with units: ``tension_N``, ``impulse_Ns``...)."""
        return [dict(r) for r in self.rolls]

    def material(self, material: str) -> list[dict[str, Any]]:
        """The rows of one material (``"PET1"``), by increasing tension."""
        return sorted(
            (r for r in self.rolls if r["material"] == material), key=lambda r: r["tension_N"]
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "study": self.name,
            "figures": "reference paper, Figures 14-15 (and 8-9: no update)",
            "manual_impulse_Ns": MANUAL_IMPULSE_NS,
            "rolls": self.rows(),
        }

    def summary(self) -> list[SummaryTable]:
        header = tuple(t for _, t, _ in _TENSION_COLUMNS)
        rows = [
            tuple(f(r[k]) if k in r else "-" for k, _, f in _TENSION_COLUMNS) for r in self.rolls
        ]
        return [SummaryTable("Rho against winding tension (Figures 14-15)", header, rows)]

    def notes(self) -> list[str]:
        notes = [
            "FD: finite-difference impact {4}-{13}; energy: {19}-{22}; no-upd: E_r frozen at "
            "its pre-impact value (Figures 8-9)."
        ]
        if self.rolls:
            notes.append(
                f"Device manual impulse: {MANUAL_IMPULSE_NS} N s; elastic bound 2 m v = "
                f"{self.rolls[0]['elastic_impulse_bound_Ns']:.3f} N s."
            )
        return notes

    def plot(self, prefix: str | Path) -> list[Path]:
        """Write ``tension_rho.png`` and ``tension_impulse.png`` (in directory ``prefix``,
        or next to it with it as a name prefix) and return the paths."""
        from matplotlib.figure import Figure

        base = _prefix(prefix, "tension")
        materials = sorted({r["material"] for r in self.rolls})
        colors = {m: f"C{i}" for i, m in enumerate(materials)}

        fig = Figure(figsize=(7.0, 4.6), layout="constrained")
        ax = fig.subplots()
        styles = (
            ("rho_fd", "FD", "o", "-"),
            ("rho_energy", "energy", "s", "--"),
            ("rho_fd_no_update", "FD, no update", "v", ":"),
            ("rho_energy_no_update", "energy, no update", "^", "-."),
        )
        for m in materials:
            rows = self.material(m)
            t = [r["tension_N"] for r in rows]
            for key, lab, marker, ls in styles:
                if all(key in r for r in rows):
                    ax.plot(
                        t,
                        [r[key] for r in rows],
                        marker=marker,
                        ls=ls,
                        color=colors[m],
                        mfc="none" if "no_update" in key else colors[m],
                        label=f"{m} {lab}",
                    )
        ax.set_xlabel("winding tension [N]")
        ax.set_ylabel("Rho [-] (1 Rho = 3.76 g)")
        ax.set_title("Rho-meter reading against winding tension (cf. Figure 14)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, ncol=2)
        paths = [_savefig(fig, Path(f"{base}_rho.png"))]

        fig = Figure(figsize=(6.4, 4.2), layout="constrained")
        ax = fig.subplots()
        for m in materials:
            rows = self.material(m)
            ax.plot(
                [r["tension_N"] for r in rows],
                [r["impulse_Ns"] for r in rows],
                "o-",
                color=colors[m],
                label=f"{m} FD",
            )
        ax.axhline(MANUAL_IMPULSE_NS, color="k", ls="--", label="device manual 0.267 N s")
        if self.rolls:
            ax.axhline(
                self.rolls[0]["elastic_impulse_bound_Ns"],
                color="0.5",
                ls=":",
                label="elastic bound 2 m v",
            )
        ax.set_xlabel("winding tension [N]")
        ax.set_ylabel("impulse [N s]")
        ax.set_title("Impulse of one impact (cf. Figure 15)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        paths.append(_savefig(fig, Path(f"{base}_impulse.png")))
        return paths

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write ``study.json`` and the PNGs into ``out_dir``; return the paths."""
        return _write(self, out_dir)


def _prefix(prefix: str | Path, stem: str) -> str:
    p = Path(prefix)
    if p.is_dir():
        return str(p / stem)
    return str(p)


def tension_study(
    cases: Iterable[str] = TABLE2,
    progress: Progress | None = None,
    *,
    overrides: Sequence[str] = (),
    workers: int = 1,
) -> TensionStudy:
    """Figures 14/15: run every roll and tabulate Rho, no-update Rho and impulse.

    Parameters
    ----------
    cases : iterable of str
        Bundled case names or case files (default: the seven rolls of Table 2).
    progress : callable(stage, fraction), optional
    overrides : sequence of str
        ``dotted.key=value`` overrides applied to every case (e.g. ``"contact.friction=0.2"``).
    workers : int
        1: one run after the other; 2: a spawned 2-process pool.
    """
    names = list(cases)
    if not names:
        raise InputError("no cases given", "study.cases")
    out = _map(
        _measure,
        # Figures 14/15 compare with the no-update solve (off by default in a case)
        [(n, ("contact.no_update=true", *overrides)) for n in names],
        workers=workers,
        progress=progress,
        label=lambda i: f"tension: {names[i]}",
    )
    return TensionStudy([o["row"] for o in out])


# ---------------------------------------------------------------------------------------
# Figures 16/17: pile height


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
                    f"{r['rho_fd_ref_prestress_mass']:.1f}",
                    f"{r['effective_mass_kg'] * 1e3:.2f}",
                    f"{r['alpha_N_per_m2']:.3g}",
                    f"{r['beta_N_per_m']:.3g}",
                    f"{r['semi_contact_width_m'] * 1e3:.2f}",
                    f"{r['delta_max_m'] * 1e3:.2f}",
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
        return paths

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
    row.update(_axis_locality(out.pop("contact"), web))
    setup = case.tester_setup
    ins = setup.instrument
    depth = radius[-1] - radius
    if ref is None:
        ref = {
            "effective_mass": row["effective_mass_kg"],
            "depth": depth[::-1].copy(),
            "sigma_r": sigma_r[::-1].copy(),
            "depth_max": 1.25 * row["delta_max_m"],
        }
        out["ref"] = ref
    m_ref = ref["effective_mass"]
    row["rho_fd_ref_mass"] = hardness_from_spring(
        setup, row["alpha_N_per_m2"], row["beta_N_per_m"], m_ref
    ).fd.rho
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


def pile_height_study(
    case: str = "pet2-53.4N",
    pile_heights: Sequence[float | str] = DEFAULT_PILE_HEIGHTS,
    progress: Progress | None = None,
    *,
    workers: int = 1,
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
        (case, (f"winding.outer_radius={r_core + h!r} m", "contact.no_update=false"))
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
    profiles = []
    for h, o in zip(heights, outs, strict=True):
        rr, pp = _thin(o["radius"], -o["sigma_r"])
        profiles.append({"pile_height_m": h, "radius_m": rr, "pressure_Pa": pp})
    _report(progress, "done", 1.0)
    return PileHeightStudy(
        case=case,
        rolls=[o["row"] for o in outs],
        profiles=profiles,
        reference_pile_height_m=heights[-1],
        reference_depth_max_m=ref["depth_max"],
    )


# ---------------------------------------------------------------------------------------
# Figure 18: slip factor


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


# ---------------------------------------------------------------------------------------
# all, and the registry


@dataclass(frozen=True)
class AllStudies:
    """The three studies together (``woundroll study all``)."""

    parts: tuple[Any, ...]
    name: str = "all"

    def to_dict(self) -> dict[str, Any]:
        return {"study": self.name, **{p.name: p.to_dict() for p in self.parts}}

    def summary(self) -> list[SummaryTable]:
        return [t for p in self.parts for t in p.summary()]

    def notes(self) -> list[str]:
        return [n for p in self.parts for n in p.notes()]

    def plot(self, prefix: str | Path) -> list[Path]:
        return [q for p in self.parts for q in p.plot(prefix)]

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write one ``study.json`` (a key per study) and every study's PNGs."""
        return _write(self, out_dir)


def _all(progress: Progress | None = None, *, workers: int = 1) -> AllStudies:
    steps = (
        (0.0, 0.55, lambda p: tension_study(progress=p, workers=workers)),
        (0.55, 0.35, lambda p: pile_height_study(progress=p, workers=workers)),
        (0.90, 0.10, lambda p: slip_factor_study(progress=p)),
    )
    parts = []
    for lo, span, fn in steps:
        sub = (
            None
            if progress is None
            else (lambda stage, f, lo=lo, span=span: progress(stage, lo + span * f))
        )
        parts.append(fn(sub))
    return AllStudies(tuple(parts))


#: Study name -> function(progress, *, workers) returning a :class:`StudyResult`.
STUDIES: dict[str, Callable[..., Any]] = {
    "tension": lambda progress=None, *, workers=1: tension_study(
        progress=progress, workers=workers
    ),
    "pile-height": lambda progress=None, *, workers=1: pile_height_study(
        progress=progress, workers=workers
    ),
    "slip": lambda progress=None, *, workers=1: slip_factor_study(progress=progress),
    "all": _all,
}


def run_study(name: str, *, progress: Progress | None = None, workers: int = 1) -> StudyResult:
    """Run the study ``name`` (a key of :data:`STUDIES`) and return its result.

    Raises
    ------
    InputError
        Field ``"study"`` for an unknown name (the message lists the known ones).
    """
    fn = STUDIES.get(name) if isinstance(name, str) else None
    if fn is None:
        raise InputError(f"unknown study {name!r}; known: {', '.join(STUDIES)}", "study")
    return fn(progress, workers=workers)


__all__ = [
    "DEFAULT_PILE_HEIGHTS",
    "MANUAL_IMPULSE_NS",
    "STUDIES",
    "TABLE2",
    "AllStudies",
    "PileHeightStudy",
    "SlipStudy",
    "StudyResult",
    "SummaryTable",
    "TensionStudy",
    "pile_height_study",
    "run_study",
    "slip_factor_study",
    "tension_study",
]
