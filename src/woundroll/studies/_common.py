"""What every study shares: one roll through the pipeline as a row of plain floats, the
serial / process-pool map, the result protocol the CLI reads, and the small writers.

A study module (``tension.py``, ``pile_height.py``, ...) builds on these and defines
``run(progress=None, *, workers=1)``; ``woundroll/studies/__init__.py`` registers it.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple, Protocol

import numpy as np

from woundroll.errors import InputError
from woundroll.pipeline.vocabulary import versioned

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
    d_fd = h["impact_depth_m"]
    row: dict[str, Any] = {
        "case": name,
        "title": case.title,
        "material": case.web.preset or "",
        "tension_N": case.winding.schedule(web).web_stress * web.width * web.thickness,
        "outer_radius_m": float(res.winding.radius[-1]),
        "pile_height_m": float(res.winding.radius[-1] - res.winding.radius[0]),
        "rho_fd": h["rho_fd"],
        "rho_energy": h["rho_energy"],
        "impulse_N_s": h["impulse_N_s"],
        "elastic_impulse_bound_N_s": 2.0 * res.hardness.instrument.mass * h["impact_speed_m_per_s"],
        "alpha_N_per_m2": float(stiffness.alpha),
        "beta_N_per_m": float(stiffness.beta),
        "semi_contact_width_m": float(np.interp(d_fd, c.delta, c.half_width)),
        "impact_depth_m": d_fd,
        "impact_depth_energy_m": h["impact_depth_energy_m"],
        "peak_force_N": h["peak_force_N"],
        "peak_contact_pressure_Pa": float(np.interp(d_fd, c.delta, c.peak_pressure)),
        "contact_time_s": h["contact_time_s"],
        "effective_mass_kg": h["effective_mass_kg"],
        "depth_max_m": float(c.delta[-1]),
    }
    if res.no_update is not None:
        nu = res.no_update.to_dict()
        row.update(
            {
                "rho_fd_no_update": nu["rho_fd"],
                "rho_energy_no_update": nu["rho_energy"],
                "impulse_no_update_N_s": nu["impulse_N_s"],
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
    from concurrent.futures import as_completed

    from woundroll.util.pool import process_pool

    # the pool clean_stop() ends on SIGINT/SIGTERM (woundroll.util.pool)
    with process_pool(min(workers, n)) as pool:
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
    p.write_text(
        json.dumps(versioned(result.to_dict()), indent=1, allow_nan=False) + "\n", encoding="utf-8"
    )
    return [p, *result.plot(out)]


def _prefix(prefix: str | Path, stem: str) -> str:
    p = Path(prefix)
    if p.is_dir():
        return str(p / stem)
    return str(p)
