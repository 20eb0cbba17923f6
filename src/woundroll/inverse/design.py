"""Setpoint design: the tension, taper and nip load that wind a roll to a target.

``woundroll design CASE --target "60 Rho"``: find winder setpoints -- web tension at the core
``T0``, a taper (linear or hyperbolic, its fraction) and a nip load -- within the winder's
ranges, such that

* the roll reads the target hardness (instrument units, within a tolerance);
* the interlayer pressure stays inside a window ``[p_min, p_max]`` from the core up to the
  near-surface depth (one head radius below the surface; above it P falls to 0 at the free
  surface whatever the setpoints);
* the layer-mean hoop stress is nowhere negative (the starring indicator, docs/diagnosis.md).

Method (a verified surrogate for the hardness, exact winding for the rest):

1. The reading is set by the stresses under the head. The case's forward curve
   (:func:`woundroll.inverse.diagnosis.forward_curve`, 6-8 full runs) maps the reading to the
   near-surface pressure ``P_s`` (at one head radius); the target reading gives a target
   ``P_s*``.
2. For every candidate taper fraction (0 ... ``taper_max``, 7 values) and nip load (4 values
   of the range when the case has nip friction), ``T0`` is solved so that the 1D winding
   gives ``P_s = P_s*`` (Brent in ``ln T0``, about 10 windings of 10-30 ms), and the pressure
   window and hoop stress are checked on that winding.
3. The feasible candidate with the largest smallest margin is chosen (ties: less taper,
   less nip); with none feasible, the least violating one is reported as infeasible, with
   the violated constraints named.
4. The chosen setpoints are verified by full forward runs; if the reading misses the target
   by more than the tolerance (the surrogate assumes the reading depends on the stresses
   only through ``P_s``), ``T0`` is corrected by a secant on full runs (at most 4).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from woundroll.errors import InputError

if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.winding.result import WindingResult
    from woundroll.winding.tension import Taper

__all__ = ["Candidate", "Design", "DesignTarget", "design_setpoints"]

PLI = 175.126835


@dataclass(frozen=True)
class DesignTarget:
    """What the roll must be, and what the winder can do (SI; tension as a web stress).

    Attributes
    ----------
    reading : float
        Target surface hardness in ``scale``.
    scale : str
        "Rho", "g" (Rho-meter), ... as the case's instrument reads.
    tolerance : float
        Accepted |reading - target|.
    pressure_min, pressure_max : float [Pa]
        Interlayer pressure window (core to the near-surface depth).
    tension_min, tension_max : float [Pa]
        Range of the web tension at the core, as a stress in the web.
    nip_min, nip_max : float [N/m]
        Nip load range (per width).
    taper_kind : "linear", "hyperbolic" or "table"
    taper_max : float
        Largest taper fraction the winder allows (0-1); for a table, the largest drop of
        the tension below its value at the core.
    allow_negative_hoop : bool
        Drop the hoop-stress constraint.
    hoop_min : float [Pa]
        Smallest layer-mean hoop stress accepted (0: none negative; -20e3 accepts 20 kPa
        of compression, the defects report's starring criterion still flags it as watch).
    knots : int
        Table taper: number of knots, evenly spaced in radius from the core to the final
        radius (the first is the core tension ``T0``).
    monotone : bool
        Table taper: the tension may only fall as the roll grows (winders that cannot
        raise the tension during a wind).
    """

    reading: float
    scale: str = "Rho"
    tolerance: float = 1.0
    pressure_min: float = 0.0
    pressure_max: float = math.inf
    tension_min: float = 0.0
    tension_max: float = math.inf
    nip_min: float = 0.0
    nip_max: float = 0.0
    taper_kind: str = "linear"
    taper_max: float = 0.6
    allow_negative_hoop: bool = False
    hoop_min: float = 0.0
    knots: int = 4
    monotone: bool = True

    def __post_init__(self) -> None:
        if not (math.isfinite(self.reading) and self.reading > 0):
            raise InputError(f"must be a positive reading, got {self.reading!r}", "--target")
        if self.taper_kind not in ("linear", "hyperbolic", "table"):
            raise InputError(
                f"must be linear, hyperbolic or table, got {self.taper_kind!r}", "--taper"
            )
        if not 2 <= self.knots <= 12:
            raise InputError(f"must lie in 2 ... 12, got {self.knots!r}", "--knots")
        if not (math.isfinite(self.hoop_min) and self.hoop_min <= 0):
            raise InputError(
                f"must be zero or negative (a compression accepted), got {self.hoop_min!r}",
                "--hoop-min",
            )
        if not 0.0 <= self.taper_max <= 1.0:
            raise InputError(f"must lie in [0, 1], got {self.taper_max!r}", "--max-taper")
        for lo, hi, name in (
            (self.pressure_min, self.pressure_max, "--pressure"),
            (self.tension_min, self.tension_max, "--tension"),
            (self.nip_min, self.nip_max, "--nip"),
        ):
            if not (lo >= 0 and hi >= lo):
                raise InputError(f"needs 0 <= low <= high, got {lo:g}..{hi:g}", name)
        if not self.tolerance > 0:
            raise InputError(f"must be positive, got {self.tolerance!r}", "--tolerance")


@dataclass(frozen=True)
class Candidate:
    """One (taper, nip) pair with its solved tension and the constraint margins."""

    taper: float
    nip_load: float
    web_tension: float | None
    surface_pressure: float | None
    min_pressure: float | None
    max_pressure: float | None
    min_hoop: float | None
    violations: tuple[str, ...]
    score: float
    kind: str = ""
    table: tuple[float, ...] | None = None
    slacks: dict[str, float] = field(default_factory=dict)

    @property
    def feasible(self) -> bool:
        return not self.violations

    @property
    def worst_slack(self) -> float:
        """The smallest normalised slack over the constraints (< 0: violated; -inf if the
        target could not be reached)."""
        if self.web_tension is None:
            return -math.inf
        return min(self.slacks.values(), default=math.inf)

    def to_dict(self) -> dict[str, Any]:
        return {
            "taper_fraction": self.taper,
            "nip_load_N_per_m": self.nip_load,
            "web_tension_Pa": self.web_tension,
            "surface_pressure_Pa": self.surface_pressure,
            "min_pressure_Pa": self.min_pressure,
            "max_pressure_Pa": self.max_pressure,
            "min_hoop_stress_Pa": self.min_hoop,
            "violations": list(self.violations),
            "score": self.score,
            "taper_kind": self.kind,
            "table_factor": list(self.table) if self.table is not None else None,
            "slacks": self.slacks,
        }


@dataclass(frozen=True)
class Design:
    """Chosen setpoints, the roll they wind, margins and the candidates tried."""

    target: DesignTarget
    feasible: bool
    web_tension: float
    taper_kind: str
    taper: float
    nip_load: float
    reading: float
    winding: WindingResult
    pressure_depth: float
    web_thickness: float
    web_width: float
    margins: dict[str, float | None]
    candidates: tuple[Candidate, ...]
    full_runs: int
    notes: tuple[str, ...] = ()
    violations: tuple[str, ...] = field(default_factory=tuple)
    table_radius: tuple[float, ...] = ()
    table_factor: tuple[float, ...] = ()
    slacks: dict[str, float] = field(default_factory=dict)
    binding: str | None = None
    relaxations: tuple[dict[str, Any], ...] = ()

    def setpoints(self) -> dict[str, Any]:
        per_width = self.web_tension * self.web_thickness
        out: dict[str, Any] = {
            "web_tension_Pa": self.web_tension,
            "web_tension_N_per_m": per_width,
            "web_tension_pli": per_width / PLI,
            "web_tension_N": per_width * self.web_width,
            "taper_kind": self.taper_kind,
            "taper_fraction": self.taper,
            "nip_load_N_per_m": self.nip_load,
            "nip_load_pli": self.nip_load / PLI,
        }
        if self.table_radius:
            out["table"] = [
                {
                    "radius_m": r,
                    "diameter_m": 2 * r,
                    "factor": f,
                    "web_tension_Pa": f * self.web_tension,
                    "web_tension_N_per_m": f * per_width,
                    "web_tension_pli": f * per_width / PLI,
                }
                for r, f in zip(self.table_radius, self.table_factor, strict=True)
            ]
        return out

    def case_snippet(self) -> str:
        """The setpoints as case-file lines (``[winding]``)."""
        s = self.setpoints()
        lines = [
            "[winding]",
            f'tension = "{s["web_tension_N_per_m"]:.5g} N/m"',
            f'nip_load = "{s["nip_load_N_per_m"]:.5g} N/m"',
        ]
        if self.table_radius:
            rs = ", ".join(f'"{r * 1e3:.5g} mm"' for r in self.table_radius)
            fs = ", ".join(f"{f:.4f}" for f in self.table_factor)
            lines += ["[winding.taper]", 'kind = "table"', f"radius = [{rs}]", f"factor = [{fs}]"]
        elif self.taper > 0:
            lines += [
                "[winding.taper]",
                f'kind = "{self.taper_kind}"',
                f"fraction = {self.taper:.4g}",
            ]
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        w = self.winding
        unit_keys = {  # the target's dimensional fields, with their SI unit in the key
            "pressure_min": "pressure_min_Pa",
            "pressure_max": "pressure_max_Pa",
            "tension_min": "tension_min_Pa",
            "tension_max": "tension_max_Pa",
            "nip_min": "nip_min_N_per_m",
            "nip_max": "nip_max_N_per_m",
            "hoop_min": "hoop_min_Pa",
        }
        return {
            "feasible": self.feasible,
            "violations": list(self.violations),
            "setpoints": self.setpoints(),
            "target": {
                unit_keys.get(k, k): (None if isinstance(v, float) and not math.isfinite(v) else v)
                for k, v in self.target.__dict__.items()
            },
            "reading": self.reading,
            "margins": self.margins,
            "profiles": {
                "radius_m": w.radius.tolist(),
                "sigma_r_Pa": w.sigma_r.tolist(),
                "wound_on_tension_Pa": w.wot.tolist(),
                "layer_radius_m": w.layer_mean_hoop_stress()[0].tolist(),
                "layer_mean_hoop_stress_Pa": w.layer_mean_hoop_stress()[1].tolist(),
            },
            "pressure_depth_m": self.pressure_depth,
            "candidates": [c.to_dict() for c in self.candidates],
            "full_forward_runs": self.full_runs,
            "notes": list(self.notes),
            "slacks": self.slacks,
            "binding_constraint": self.binding,
            "relaxations": list(self.relaxations),
            "case_snippet": self.case_snippet(),
        }

    def summary(self) -> list[tuple[str, str]]:
        s = self.setpoints()
        m = self.margins
        rows = [
            ("feasible", "yes" if self.feasible else "NO: " + "; ".join(self.violations)),
            (
                "web tension at the core",
                f"{s['web_tension_pli']:.3g} pli = {s['web_tension_N_per_m']:.4g} N/m "
                f"({s['web_tension_N']:.4g} N, {self.web_tension / 1e6:.3g} MPa)",
            ),
            ("taper", self._taper_text()),
            ("nip load", f"{s['nip_load_pli']:.3g} pli = {self.nip_load:.4g} N/m"),
            (
                f"reading [{self.target.scale}]",
                f"{self.reading:.1f} (target {self.target.reading:.1f} +- "
                f"{self.target.tolerance:.2g})",
            ),
            (
                "interlayer pressure, core to near-surface",
                f"{m['min_pressure_Pa'] / 1e3:.3g}-{m['max_pressure_Pa'] / 1e3:.3g} kPa "
                f"(window {self.target.pressure_min / 1e3:.3g}-"
                f"{self.target.pressure_max / 1e3:.3g} kPa)",
            ),
            ("smallest layer-mean hoop stress", f"{m['min_hoop_stress_Pa'] / 1e3:.3g} kPa"),
        ]
        if self.binding is not None:
            rows.append(
                (
                    "binding constraint",
                    f"{_LABELS.get(self.binding, self.binding)} "
                    f"(normalised slack {self.slacks[self.binding]:+.3g})",
                )
            )
        for rel in self.relaxations:
            rows.append(("to make it feasible", rel["sentence"]))
        return rows

    def _taper_text(self) -> str:
        if not self.table_radius:
            return f"{self.taper_kind} {100 * self.taper:.0f} %"
        per_width = self.web_tension * self.web_thickness / PLI
        return "table: " + ", ".join(
            f"{2 * r * 100:.3g} cm dia. -> {f * per_width:.3g} pli"
            for r, f in zip(self.table_radius, self.table_factor, strict=True)
        )

    def plot(self, path: str | Path | None = None) -> Any:
        """Pressure with its window, layer-mean hoop stress and wound-on tension vs radius."""
        import matplotlib.pyplot as plt

        w = self.winding
        fig, (a1, a2, a3) = plt.subplots(3, 1, sharex=True, figsize=(6.4, 7.2))
        r = w.radius * 100
        a1.plot(r, -w.sigma_r / 1e3, color="C0")
        t = self.target
        if t.pressure_min > 0:
            a1.axhline(t.pressure_min / 1e3, color="C3", ls="--", lw=0.9, label="window")
        if math.isfinite(t.pressure_max):
            a1.axhline(t.pressure_max / 1e3, color="C3", ls="--", lw=0.9)
        a1.axvline((w.radius[-1] - self.pressure_depth) * 100, color="k", ls=":", lw=0.8)
        a1.set_ylabel("interlayer pressure [kPa]", fontsize=9)
        rm, st = w.layer_mean_hoop_stress()
        a2.plot(rm * 100, st / 1e3, color="C1")
        a2.axhline(0.0, color="k", lw=0.8)
        a2.set_ylabel("layer-mean hoop stress [kPa]", fontsize=9)
        a3.plot(r, w.wot / 1e6, color="C2")
        a3.set_ylabel("wound-on tension [MPa]", fontsize=9)
        a3.set_xlabel("radius [cm]")
        for a in (a1, a2, a3):
            a.grid(alpha=0.3)
        s = self.setpoints()
        a3.plot(r, self.wound_on_web_tension() / 1e6, color="C2", ls="--", lw=0.8)
        if self.table_radius:
            rk = np.asarray(self.table_radius)
            a3.plot(
                rk * 100, np.asarray(self.table_factor) * self.web_tension / 1e6, "o", color="C2"
            )
        taper = (
            "table taper"
            if self.table_radius
            else f"{self.taper_kind} taper {100 * self.taper:.0f} %"
        )
        a1.set_title(
            f"{'design' if self.feasible else 'best compromise (infeasible)'}: "
            f"{s['web_tension_pli']:.3g} pli, {taper}, "
            f"nip {s['nip_load_pli']:.3g} pli -> {self.reading:.1f} {t.scale}",
            fontsize=9,
        )
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig

    def wound_on_web_tension(self) -> np.ndarray:
        """The web tension set by the winder (without the nip's share) at the nodes [Pa]."""
        w = self.winding
        if self.table_radius:
            return self.web_tension * np.interp(w.radius, self.table_radius, self.table_factor)
        r_c, r_o = float(w.radius[0]), float(w.radius[-1])
        if self.taper_kind == "hyperbolic":
            return self.web_tension * (1.0 - self.taper * (1.0 - r_c / w.radius))
        return self.web_tension * (1.0 - self.taper * (w.radius - r_c) / (r_o - r_c))


_LABELS = {
    "pressure_min": "interlayer pressure at the window's low end",
    "pressure_max": "interlayer pressure at the window's high end",
    "hoop": "layer-mean hoop stress (starring)",
    "tension_min": "winder's lowest tension",
    "tension_max": "winder's highest tension",
}


def _slacks(
    pmin: float, pmax: float, hoop: float, t_low: float, t_high: float, target: DesignTarget
) -> dict[str, float]:
    """Normalised slack of each active constraint (>= 0 met; -0.2: 20 % beyond the limit).

    Pressures relative to their limits, the hoop stress relative to the pressure scale (the
    window's high end, else the largest pressure), tensions (lowest and highest web tension
    of the schedule) relative to the winder's range.
    """
    out: dict[str, float] = {}
    if target.pressure_min > 0:
        out["pressure_min"] = pmin / target.pressure_min - 1.0
    if math.isfinite(target.pressure_max):
        out["pressure_max"] = 1.0 - pmax / target.pressure_max
    if not target.allow_negative_hoop:
        scale = target.pressure_max if math.isfinite(target.pressure_max) else max(pmax, 1.0)
        out["hoop"] = (hoop - target.hoop_min) / scale
    if target.tension_min > 0:
        out["tension_min"] = float(t_low / target.tension_min - 1.0)
    if math.isfinite(target.tension_max):
        out["tension_max"] = float(1.0 - t_high / target.tension_max)
    return out


def _constraints(
    w: WindingResult, depth: float, target: DesignTarget
) -> tuple[float, float, float, list[str], float]:
    """min P, max P (core to the near-surface depth), min layer-mean hoop stress, the
    violated constraints and a violation score (0 when feasible; else relative excess)."""
    r = w.radius
    inside = r <= r[-1] - depth
    if not np.any(inside):
        inside = np.ones_like(r, dtype=bool)
    P = -w.sigma_r[inside]
    pmin, pmax = float(P.min()), float(P.max())
    hoop = float(w.layer_mean_hoop_stress()[1].min())
    viol: list[str] = []
    score = 0.0
    if pmin < target.pressure_min:
        viol.append(f"pressure {pmin / 1e3:.3g} kPa below the window")
        score += (target.pressure_min - pmin) / target.pressure_min
    if pmax > target.pressure_max:
        viol.append(f"pressure {pmax / 1e3:.3g} kPa above the window")
        score += (pmax - target.pressure_max) / target.pressure_max
    if hoop < target.hoop_min and not target.allow_negative_hoop:
        viol.append(f"negative hoop stress {hoop / 1e3:.3g} kPa")
        score += (target.hoop_min - hoop) / max(pmax, 1.0)
    return pmin, pmax, hoop, viol, score


def design_setpoints(
    case: Case | str | Path,
    target: DesignTarget,
    *,
    progress: Any = None,
    max_evaluations: int = 40,
) -> Design:
    """Setpoints for ``target`` on the case's web, core and roll size (module docstring).

    ``max_evaluations``: table taper only, the shapes the optimiser may try (each one
    solves ``T0`` by 2-4 windings).

    Raises
    ------
    InputError
        A target scale the instrument does not read; a target reading outside what the
        winder's tension range can produce on this roll.
    """
    from scipy.optimize import minimize

    problem = _SetpointProblem.build(case, target)
    # search: the grid of tapers and nip loads, T0 solved for each
    cands = problem.search(progress)
    solved = [c for c in cands if c.web_tension is not None]
    if not solved:
        raise InputError(
            f"no setpoint in the tension range {problem.t_lo / 1e6:.3g}-"
            f"{problem.t_hi / 1e6:.3g} MPa reads {target.reading:g} {target.scale} on this roll",
            "--target",
        )
    # rank: the best margin, then (table taper) the best table shape from there
    best = max(solved, key=_rank)
    if target.taper_kind == "table":
        best = problem.best_table(best, solved, cands, minimize, max_evaluations)
    # verify: full forward runs at the chosen setpoints
    return problem.verify(best, cands)


def _rank(c: Candidate) -> tuple[bool, float, float, float]:
    """Feasible first; then the largest smallest slack (best margin, or the least violated
    worst constraint: the best available compromise); ties: less taper/nip."""
    return (c.feasible, round(c.worst_slack, 6), -c.taper, -c.nip_load)


@dataclass
class _SetpointProblem:
    """The search of :func:`design_setpoints`: the roll, the target, the winder's tension
    range, the target near-surface pressure ``P_s*`` and the candidate grid."""

    model: Any  # RollModel
    target: DesignTarget
    t_lo: float
    t_hi: float
    ps_star: float
    nips: np.ndarray
    tapers: np.ndarray
    knots: np.ndarray
    r_check: np.ndarray
    notes: list[str]
    runs: int

    @classmethod
    def build(cls, case: Case | str | Path, target: DesignTarget) -> _SetpointProblem:
        """The forward curve maps the target reading to ``P_s*``; the grid of tapers and
        nip loads the search tries."""
        from woundroll.case import Case, load_case
        from woundroll.inverse.diagnosis import RollModel, forward_curve

        if not isinstance(case, Case):
            case = load_case(case)
        model = RollModel.from_case(case, target.scale)
        notes: list[str] = []
        if case.winding.thickness_profile is not None:
            notes.append("designed with the 1D model at the nominal thickness")
        base = model.schedule
        t_lo = max(target.tension_min, 1e-6 * base.web_stress)
        t_hi = min(target.tension_max, 64.0 * base.web_stress)
        curve = forward_curve(model, [target.reading])
        if not curve.monotone:
            raise InputError("the reading is not monotone in the tension on this roll", "--target")
        if not curve.covers(target.reading):
            raise InputError(
                f"no tension within 1/64-64 x the case's reads {target.reading:g} "
                f"{target.scale} (range {curve.reading[0]:.1f}-{curve.reading[-1]:.1f})",
                "--target",
            )
        # reading -> near-surface pressure (both monotone in T0 along the curve)
        t_star = float(curve.tension_for([target.reading])[0])
        ps_star = float(curve.surface_pressure_at([t_star])[0])
        if base.friction > 0 and target.nip_max > target.nip_min:
            nips = np.linspace(target.nip_min, target.nip_max, 4)
        else:
            nips = np.array([min(max(base.nip_load, target.nip_min), target.nip_max)])
            if target.nip_max > target.nip_min:
                notes.append(
                    "winding.friction = 0: the nip adds no wound-on tension in the 1D model; "
                    "nip load not designed"
                )
        r_core, r_out = model.core.outer_radius, model.outer_radius
        return cls(
            model=model,
            target=target,
            t_lo=t_lo,
            t_hi=t_hi,
            ps_star=ps_star,
            nips=nips,
            tapers=np.linspace(0.0, target.taper_max, 7),
            knots=np.linspace(r_core, r_out, target.knots),
            r_check=np.linspace(r_core, r_out, 65),
            notes=notes,
            runs=len(curve.points),
        )

    @property
    def grid_kind(self) -> str:
        """The taper law of the grid (a table starts from the linear one)."""
        return "linear" if self.target.taper_kind == "table" else self.target.taper_kind

    def winding(self, t0: float, taper: Taper, nip: float) -> WindingResult:
        """The roll at these setpoints as the reading sees it (after the case's entrained air
        and storage, :meth:`RollModel.wound`)."""
        m = self.model
        sched = replace(m.schedule, web_stress=t0, taper=taper, nip_load=float(nip))
        return m.wound(sched)

    def ps(self, t0: float, taper: Taper, nip: float) -> float:
        from woundroll.inverse.diagnosis import near_surface_pressure

        w = self.winding(t0, taper, nip)
        return near_surface_pressure(w.radius, w.sigma_r, self.model.depth)

    def _secant_tension(self, taper: Taper, nip: float, guess: float) -> float | None:
        """``T0`` for ``P_s = P_s*`` by a secant in (ln T0, ln P_s) from ``guess`` (P_s grows
        about like T0: 2-4 windings); None when it does not converge in 6 steps."""
        ps_star, t_lo, t_hi = self.ps_star, self.t_lo, self.t_hi
        x0, y0 = math.log(guess), math.log(max(self.ps(guess, taper, nip), 1e-9))
        x1 = x0 + math.log(ps_star) - y0
        for _ in range(6):
            x1 = min(max(x1, math.log(t_lo)), math.log(t_hi))
            y1 = math.log(max(self.ps(math.exp(x1), taper, nip), 1e-9))
            if abs(y1 - math.log(ps_star)) < 1e-5:
                return math.exp(x1)
            if y1 == y0:
                return None
            x0, y0, x1 = x1, y1, x1 + (math.log(ps_star) - y1) * (x1 - x0) / (y1 - y0)
        return None

    def candidate(
        self, taper: Taper, nip: float, guess: float | None = None, kind: str | None = None
    ) -> Candidate:
        """Solve T0 for P_s = P_s* (a secant in ln T0 from ``guess``, else Brent over the
        tension range), then the constraints on that winding."""
        from scipy.optimize import brentq

        kind = self.grid_kind if kind is None else kind
        frac = float(taper.fraction)
        tab = tuple(float(f) for f in taper.factor) if taper.kind == "table" else None
        t0 = None if guess is None else self._secant_tension(taper, nip, guess)
        if t0 is None:
            f_lo = self.ps(self.t_lo, taper, nip) - self.ps_star
            f_hi = self.ps(self.t_hi, taper, nip) - self.ps_star
            if f_lo > 0 or f_hi < 0:
                side = "above" if f_lo > 0 else "below"
                return Candidate(
                    frac, float(nip), None, None, None, None, None,
                    (f"target hardness {side} what the tension range gives",), math.inf,
                    kind, tab,
                )  # fmt: skip
            x = brentq(
                lambda lx: self.ps(math.exp(lx), taper, nip) - self.ps_star,
                math.log(self.t_lo),
                math.log(self.t_hi),
                xtol=1e-6,
            )
            t0 = math.exp(x)
        return self._checked(taper, nip, t0, frac, kind, tab)

    def _checked(
        self,
        taper: Taper,
        nip: float,
        t0: float,
        frac: float,
        kind: str,
        tab: tuple[float, ...] | None,
    ) -> Candidate:
        """The candidate at ``T0``: the constraints on its winding and its tension range."""
        target = self.target
        w = self.winding(t0, taper, nip)
        pmin, pmax, hoop, viol, score = _constraints(w, self.model.depth, target)
        fac = taper.factor_at(self.r_check, self.model.core.outer_radius, self.model.outer_radius)
        t_low, t_high = t0 * float(fac.min()), t0 * float(fac.max())
        if target.tension_min > 0 and t_low < target.tension_min * (1 - 1e-9):
            viol.append(f"tension {t_low / 1e6:.3g} MPa below the winder's range")
            score += (target.tension_min - t_low) / target.tension_min
        if t_high > target.tension_max * (1 + 1e-9):
            viol.append(f"tension {t_high / 1e6:.3g} MPa above the winder's range")
            score += (t_high - target.tension_max) / target.tension_max
        slack = _slacks(pmin, pmax, hoop, t_low, t_high, target)
        return Candidate(
            frac, float(nip), t0, self.ps_star, pmin, pmax, hoop, tuple(viol), score, kind, tab,
            slack,
        )  # fmt: skip

    def search(self, progress: Any) -> list[Candidate]:
        """Every (taper law, nip load, taper fraction) of the grid, ``T0`` solved for each;
        a table starts from the best linear or hyperbolic taper (both laws tried)."""
        from woundroll.winding.tension import Taper

        cands: list[Candidate] = []
        table = self.target.taper_kind == "table"
        kinds = ("linear", "hyperbolic") if table else (self.grid_kind,)
        grid = [(kd, tp, nip) for kd in kinds for nip in self.nips for tp in self.tapers]
        for k, (kd, tp, nip) in enumerate(grid):
            if progress is not None:
                progress("candidates", k / len(grid))
            if kd != kinds[0] and tp == 0.0:
                continue  # no taper: the same roll under either law
            cands.append(self.candidate(Taper(kd, float(tp)), nip, kind=kd))
        if progress is not None:
            progress("candidates", 1.0)
        return cands

    def best_table(
        self,
        grid_best: Candidate,
        solved: list[Candidate],
        cands: list[Candidate],
        minimize: Any,
        max_evaluations: int,
    ) -> Candidate:
        """The best table shape from the best grid taper (:func:`_optimise_table`), added to
        ``cands``; a note when the grid's taper does better."""
        target = self.target
        evaluated = list(solved)
        best = _optimise_table(
            grid_best,
            self.knots,
            target,
            self.candidate,
            evaluated,
            minimize,
            max_evaluations,
            self.model.core.outer_radius,
            self.model.outer_radius,
        )
        cands.append(best)
        if _rank(grid_best) > _rank(best):
            self.notes.append(
                f"the {grid_best.kind} taper {100 * grid_best.taper:.0f} % does better than the "
                f"best {target.knots}-knot table found (smallest slack "
                f"{grid_best.worst_slack:+.3g} against {best.worst_slack:+.3g}): more knots, "
                f"or --taper {grid_best.kind}"
            )
        return best

    def taper_of(self, best: Candidate) -> Taper:
        from woundroll.winding.tension import Taper

        if best.table is not None:
            return Taper("table", 0.0, tuple(float(r) for r in self.knots), best.table)
        return Taper(self.target.taper_kind, best.taper)

    def full_runs_tension(self, best: Candidate, taper: Taper) -> tuple[float, float, float]:
        """The chosen setpoints by full forward runs; a secant on ``T0`` (at most 4 runs)
        if the reading misses. Returns T0, its reading and the surrogate's miss."""
        target = self.target
        base = self.model.schedule
        model_d = replace(self.model, schedule=replace(base, taper=taper, nip_load=best.nip_load))
        t_a = best.web_tension
        r_a = model_d.evaluate(t_a).reading
        surrogate_miss = r_a - target.reading
        self.runs += 1
        t_b, r_b = None, None
        for _ in range(4):
            if abs(r_a - target.reading) <= target.tolerance:
                break
            if t_b is None:
                t_new = t_a * (1.0 + 0.1 * np.sign(target.reading - r_a))
            else:
                slope = (r_a - r_b) / (math.log(t_a) - math.log(t_b))
                t_new = math.exp(math.log(t_a) + (target.reading - r_a) / slope)
            t_new = min(max(t_new, self.t_lo), self.t_hi)
            t_b, r_b = t_a, r_a
            t_a = t_new
            r_a = model_d.evaluate(t_a).reading
            self.runs += 1
        return t_a, r_a, surrogate_miss

    def verify(self, best: Candidate, cands: list[Candidate]) -> Design:
        """The design at the verified tension: constraints, slacks, what to relax."""
        target, model = self.target, self.model
        taper_best = self.taper_of(best)
        nip = best.nip_load
        t_a, r_a, surrogate_miss = self.full_runs_tension(best, taper_best)
        w = self.winding(t_a, taper_best, nip)
        pmin, pmax, hoop, viol, _ = _constraints(w, model.depth, target)
        fac = taper_best.factor_at(self.r_check, model.core.outer_radius, model.outer_radius)
        t_low, t_high = t_a * float(fac.min()), t_a * float(fac.max())
        slacks = _slacks(pmin, pmax, hoop, t_low, t_high, target)
        for name, word in (("tension_min", "below"), ("tension_max", "above")):
            if slacks.get(name, 0.0) < -1e-9:
                viol.append(
                    f"tension {(t_low if word == 'below' else t_high) / 1e6:.3g} MPa {word} the "
                    "winder's range"
                )
        if abs(r_a - target.reading) > target.tolerance:
            viol.append(f"reading {r_a:.1f} misses the target by more than {target.tolerance:g}")
        if t_a != best.web_tension:
            self.notes.append(
                f"tension corrected by full forward runs from {best.web_tension / 1e6:.4g} to "
                f"{t_a / 1e6:.4g} MPa (the near-surface-pressure surrogate missed the target by "
                f"{surrogate_miss:+.2f} {target.scale})"
            )
        if any("hoop" in v for v in viol):
            self.notes.append(_hoop_note(w, cands, target))
        margins = {
            "min_pressure_Pa": pmin,
            "max_pressure_Pa": pmax,
            "min_hoop_stress_Pa": hoop,
            "pressure_min_margin": pmin / target.pressure_min if target.pressure_min > 0 else None,
            "pressure_max_margin": (
                target.pressure_max / pmax if math.isfinite(target.pressure_max) else None
            ),
            "lowest_web_tension_Pa": t_low,
            "highest_web_tension_Pa": t_high,
            "reading_error": r_a - target.reading,
            "surrogate_reading_error": surrogate_miss,
        }
        return Design(
            target=target,
            feasible=not viol,
            web_tension=t_a,
            taper_kind=target.taper_kind,
            taper=best.taper if best.table is None else 1.0 - min(best.table),
            nip_load=nip,
            reading=r_a,
            winding=w,
            pressure_depth=model.depth,
            web_thickness=model.web.thickness,
            web_width=model.web.width,
            margins=margins,
            candidates=tuple(cands),
            full_runs=self.runs,
            notes=tuple(self.notes),
            violations=tuple(viol),
            table_radius=tuple(float(r) for r in self.knots) if best.table is not None else (),
            table_factor=best.table or (),
            slacks=slacks,
            binding=min(slacks, key=slacks.get) if slacks else None,
            relaxations=tuple(_relaxations(slacks, viol, pmin, pmax, hoop, t_low, t_high)),
        )


def _table_factors(x: np.ndarray, target: DesignTarget) -> tuple[float, ...]:
    """Knot factors (the first 1) from unconstrained parameters: monotone, each knot drops
    a share ``sigmoid(x_k)`` of the way from the previous knot to ``1 - taper_max``; else
    each knot lies in ``[1 - taper_max, 1 + taper_max]``."""
    lo = 1.0 - target.taper_max
    sig = 1.0 / (1.0 + np.exp(-np.asarray(x, float)))
    f = [1.0]
    for s in sig:
        if target.monotone:
            f.append(f[-1] - (f[-1] - lo) * float(s))
        else:
            f.append(lo + 2.0 * target.taper_max * float(s))
    return tuple(f)


def _table_params(f: np.ndarray, target: DesignTarget) -> np.ndarray:
    """Inverse of :func:`_table_factors` (clipped inside the open interval)."""
    lo = 1.0 - target.taper_max
    out = []
    prev = 1.0
    for fk in f[1:]:
        if target.monotone:
            s = (prev - fk) / (prev - lo) if prev > lo else 0.5
            prev = fk
        else:
            s = (fk - lo) / (2.0 * target.taper_max) if target.taper_max > 0 else 0.5
        s = min(max(s, 1e-3), 1 - 1e-3)
        out.append(math.log(s / (1 - s)))
    return np.asarray(out)


def _optimise_table(
    start: Candidate,
    knots: np.ndarray,
    target: DesignTarget,
    candidate: Any,
    evaluated: list[Candidate],
    minimize: Any,
    max_evaluations: int,
    r_core: float,
    r_out: float,
) -> Candidate:
    """Knot factors of a piecewise-linear taper table that maximise the smallest normalised
    slack (the best margin when feasible, the least violated worst constraint when not),
    Nelder-Mead from the best linear taper (exact on the knots), ``T0`` solved for every
    shape. The nip load stays the best linear candidate's."""
    from woundroll.winding.tension import Taper

    if target.taper_max <= 0:
        return replace(start, kind="table", table=(1.0,) * len(knots))
    f0 = Taper(start.kind, start.taper).factor_at(knots, r_core, r_out)
    x0 = _table_params(f0, target)
    radius = tuple(float(r) for r in knots)
    # the start projected on the knots (exact for a linear taper)
    first = candidate(
        Taper("table", 0.0, radius, _table_factors(x0, target)),
        start.nip_load,
        start.web_tension,
        "table",
    )
    evaluated.append(first)
    state = {"guess": start.web_tension, "best": first}

    def objective(x: np.ndarray) -> float:
        f = _table_factors(x, target)
        c = candidate(Taper("table", 0.0, radius, f), start.nip_load, state["guess"], "table")
        evaluated.append(c)
        if c.web_tension is None:
            return 1e3
        state["guess"] = c.web_tension
        if (c.feasible, c.worst_slack) > (state["best"].feasible, state["best"].worst_slack):
            state["best"] = c
        return -c.worst_slack

    simplex = np.vstack([x0] + [x0 + 1.5 * e for e in np.eye(x0.size)])
    minimize(
        objective,
        x0,
        method="Nelder-Mead",
        options={
            "maxfev": max_evaluations,
            "initial_simplex": simplex,
            "xatol": 1e-3,
            "fatol": 1e-4,
        },
    )
    return state["best"]


def _relaxations(
    slacks: dict[str, float],
    viol: list[str],
    pmin: float,
    pmax: float,
    hoop: float,
    t_low: float,
    t_high: float,
) -> list[dict[str, Any]]:
    """For an infeasible design: per violated constraint (worst first), the limit that would
    admit the chosen compromise (relaxing all of them makes it feasible)."""
    out: list[dict[str, Any]] = []
    needed = {
        "pressure_min": (pmin, "lower the pressure window's low end to {:.3g} kPa", 1e-3),
        "pressure_max": (pmax, "raise the pressure window's high end to {:.3g} kPa", 1e-3),
        "hoop": (hoop, "accept a hoop stress down to {:.3g} kPa (--hoop-min)", 1e-3),
        "tension_min": (t_low, "a winder that runs down to {:.3g} MPa", 1e-6),
        "tension_max": (t_high, "a winder that runs up to {:.3g} MPa", 1e-6),
    }
    for name, slack in sorted(slacks.items(), key=lambda kv: kv[1]):
        if slack >= -1e-9:
            continue
        value, text, unit = needed[name]
        out.append(
            {
                "constraint": name,
                "normalised_slack": slack,
                "limit_needed_Pa": value,
                "sentence": text.format(value * unit),
            }
        )
    if not out and viol:
        out.append({"constraint": "reading", "normalised_slack": None, "limit_needed_Pa": None,
                    "sentence": "widen --tolerance or the tension range"})  # fmt: skip
    return out


def _hoop_note(w: WindingResult, cands: list[Candidate], target: DesignTarget) -> str:
    """Why the hoop stress is negative and what taper would remove it."""
    rm, st = w.layer_mean_hoop_stress()
    i = int(np.argmin(st))
    neg = rm[st < target.hoop_min]
    wot = float(np.interp(rm[i], w.radius, w.wot))
    text = (
        f"the layer-mean hoop stress falls to {st[i] / 1e3:.3g} kPa at r = {rm[i] * 100:.3g} cm "
        f"({100 * st[i] / wot:.2g} % of that layer's wound-on tension; below the limit on "
        f"r = {neg.min() * 100:.3g}-{neg.max() * 100:.3g} cm): the 1D model's physics, not a "
        "numerical artefact -- each later layer compresses the pile radially (E_r far below "
        "E_theta), the layers beneath move inward and lose the tension they were wound with; "
        "taper reduces it (less pressure from the later layers)"
    )
    ok = [c for c in cands if c.web_tension is not None and c.slacks.get("hoop", 0) >= 0]
    if ok:
        c = min(ok, key=lambda c: c.taper)
        others = [v for v in c.violations if "hoop" not in v]
        text += f"; the least grid taper without it is {c.kind} {100 * c.taper:.0f} % " + (
            f"which violates: {'; '.join(others)}" if others else "(feasible)"
        )
    else:
        text += (
            f"; no taper up to {100 * target.taper_max:.0f} % removes it at this target: "
            "raise --max-taper, or accept it with --hoop-min (the defects report's buckling "
            "margin says whether it matters)"
        )
    return text
