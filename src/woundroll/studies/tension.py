"""Figures 14/15 (and 8-9): Rho (FD, energy, no-update) and impulse against winding tension."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from woundroll.errors import InputError
from woundroll.studies._common import (
    TABLE2,
    Progress,
    SummaryTable,
    _map,
    _measure,
    _prefix,
    _savefig,
    _write,
)

#: The device manual's average impulse of one Rho-meter impact [N s] (paper, Fig. 7/15).
MANUAL_IMPULSE_NS = 0.267


_TENSION_COLUMNS: tuple[tuple[str, str, Callable[[float], str]], ...] = (
    ("material", "material", str),
    ("tension_N", "tension [N]", lambda v: f"{v:.1f}"),
    ("rho_fd", "Rho FD", lambda v: f"{v:.1f}"),
    ("rho_energy", "Rho energy", lambda v: f"{v:.1f}"),
    ("rho_fd_no_update", "Rho FD no-upd", lambda v: f"{v:.1f}"),
    ("rho_energy_no_update", "Rho en. no-upd", lambda v: f"{v:.1f}"),
    ("impulse_N_s", "impulse [N s]", lambda v: f"{v:.3f}"),
    ("alpha_N_per_m2", "alpha [N/m^2]", lambda v: f"{v:.3g}"),
    ("beta_N_per_m", "beta [N/m]", lambda v: f"{v:.3g}"),
    ("semi_contact_width_m", "a [mm]", lambda v: f"{v * 1e3:.2f}"),
    ("impact_depth_m", "max depth [mm]", lambda v: f"{v * 1e3:.2f}"),
)


@dataclass(frozen=True)
class TensionStudy:
    """Figures 14/15: Rho (FD, energy, no-update) and impulse against winding tension.

    Attributes
    ----------
    rolls : list of dict
        One row per roll, SI with the unit in the key (see :meth:`rows`). ``a`` and the
        maximum depth are the FD model's: ``semi_contact_width_m`` is the contact model's
        a(d) at ``impact_depth_m``. ``elastic_impulse_bound_N_s`` = 2 m_s v at first contact.
    """

    rolls: list[dict[str, Any]]
    name: str = "tension"

    def rows(self) -> list[dict[str, Any]]:
        """The table, one dict per roll (keys with units: ``tension_N``, ``impulse_N_s``...)."""
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
            "manual_impulse_N_s": MANUAL_IMPULSE_NS,
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
                f"{self.rolls[0]['elastic_impulse_bound_N_s']:.3f} N s."
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
                [r["impulse_N_s"] for r in rows],
                "o-",
                color=colors[m],
                label=f"{m} FD",
            )
        ax.axhline(MANUAL_IMPULSE_NS, color="k", ls="--", label="device manual 0.267 N s")
        if self.rolls:
            ax.axhline(
                self.rolls[0]["elastic_impulse_bound_N_s"],
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


def run(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> TensionStudy:
    """The registry's entry: :func:`tension_study` on the seven rolls of Table 2, read with
    the roll ``model`` (None: each case's, by default the registry's)."""
    overrides = () if model is None else (f"contact.model='{model}'",)
    return tension_study(progress=progress, workers=workers, overrides=overrides)
