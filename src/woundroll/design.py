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
   (:func:`woundroll.diagnosis.forward_curve`, 6-8 full runs) maps the reading to the
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
    taper_kind : "linear" or "hyperbolic"
    taper_max : float
        Largest taper fraction the winder allows (0-1).
    allow_negative_hoop : bool
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

    def __post_init__(self) -> None:
        if not (math.isfinite(self.reading) and self.reading > 0):
            raise InputError(f"must be a positive reading, got {self.reading!r}", "--target")
        if self.taper_kind not in ("linear", "hyperbolic"):
            raise InputError(f"must be linear or hyperbolic, got {self.taper_kind!r}", "--taper")
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

    @property
    def feasible(self) -> bool:
        return not self.violations

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

    def setpoints(self) -> dict[str, Any]:
        per_width = self.web_tension * self.web_thickness
        return {
            "web_tension_Pa": self.web_tension,
            "web_tension_N_per_m": per_width,
            "web_tension_pli": per_width / PLI,
            "web_tension_N": per_width * self.web_width,
            "taper_kind": self.taper_kind,
            "taper_fraction": self.taper,
            "nip_load_N_per_m": self.nip_load,
            "nip_load_pli": self.nip_load / PLI,
        }

    def to_dict(self) -> dict[str, Any]:
        w = self.winding
        return {
            "feasible": self.feasible,
            "violations": list(self.violations),
            "setpoints": self.setpoints(),
            "target": {
                k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                for k, v in self.target.__dict__.items()
            },
            "reading": self.reading,
            "margins": self.margins,
            "profiles": {
                "radius_m": w.radius.tolist(),
                "sigma_r_Pa": w.sigma_r.tolist(),
                "wot_Pa": w.wot.tolist(),
                "layer_radius_m": w.layer_mean_hoop_stress()[0].tolist(),
                "layer_mean_hoop_stress_Pa": w.layer_mean_hoop_stress()[1].tolist(),
            },
            "pressure_depth_m": self.pressure_depth,
            "candidates": [c.to_dict() for c in self.candidates],
            "full_forward_runs": self.full_runs,
            "notes": list(self.notes),
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
            ("taper", f"{self.taper_kind} {100 * self.taper:.0f} %"),
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
        return rows

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
        a1.set_title(
            f"{'design' if self.feasible else 'best compromise (infeasible)'}: "
            f"{s['web_tension_pli']:.3g} pli, {self.taper_kind} taper {100 * self.taper:.0f} %, "
            f"nip {s['nip_load_pli']:.3g} pli -> {self.reading:.1f} {t.scale}",
            fontsize=9,
        )
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


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
    if hoop < 0 and not target.allow_negative_hoop:
        viol.append(f"negative hoop stress {hoop / 1e3:.3g} kPa")
        score += -hoop / max(pmax, 1.0)
    return pmin, pmax, hoop, viol, score


def design_setpoints(
    case: Case | str | Path,
    target: DesignTarget,
    *,
    progress: Any = None,
) -> Design:
    """Setpoints for ``target`` on the case's web, core and roll size (module docstring).

    Raises
    ------
    InputError
        A target scale the instrument does not read; a target reading outside what the
        winder's tension range can produce on this roll.
    """
    from scipy.optimize import brentq

    from woundroll.case import Case, load_case
    from woundroll.diagnosis import RollModel, forward_curve, near_surface_pressure
    from woundroll.winding.tension import Taper

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
    runs = len(curve.points)
    if not curve.monotone:
        raise InputError("the reading is not monotone in the tension on this roll", "--target")
    if not curve.covers(target.reading):
        raise InputError(
            f"no tension within 1/64-64 x the case's reads {target.reading:g} {target.scale} "
            f"(range {curve.reading[0]:.1f}-{curve.reading[-1]:.1f})",
            "--target",
        )
    # reading -> near-surface pressure (both monotone in T0 along the curve)
    t_star = float(curve.tension_for([target.reading])[0])
    ps_star = float(curve.surface_pressure_at([t_star])[0])
    mu = base.friction
    if mu > 0 and target.nip_max > target.nip_min:
        nips = np.linspace(target.nip_min, target.nip_max, 4)
    else:
        nips = np.array([min(max(base.nip_load, target.nip_min), target.nip_max)])
        if target.nip_max > target.nip_min:
            notes.append(
                "winding.friction = 0: the nip adds no wound-on tension in the 1D model; "
                "nip load not designed"
            )
    tapers = np.linspace(0.0, target.taper_max, 7)
    web, core, r_out = model.web, model.core, model.outer_radius
    opts = model.winding_options
    from woundroll.winding.hakiel import wind

    def winding(t0: float, tp: float, nip: float) -> WindingResult:
        sched = replace(
            base, web_stress=t0, taper=Taper(target.taper_kind, float(tp)), nip_load=float(nip)
        )
        return wind(web, core, r_out, sched, options=opts)

    def ps(t0: float, tp: float, nip: float) -> float:
        w = winding(t0, tp, nip)
        return near_surface_pressure(w.radius, w.sigma_r, model.depth)

    cands: list[Candidate] = []
    for k, (tp, nip) in enumerate((tp, nip) for nip in nips for tp in tapers):
        if progress is not None:
            progress("candidates", k / (len(tapers) * len(nips)))
        f_lo = ps(t_lo, tp, nip) - ps_star
        f_hi = ps(t_hi, tp, nip) - ps_star
        if f_lo > 0 or f_hi < 0:
            side = "above" if f_lo > 0 else "below"
            cands.append(
                Candidate(
                    float(tp), float(nip), None, None, None, None, None,
                    (f"target hardness {side} what the tension range gives",), math.inf,
                )
            )  # fmt: skip
            continue
        x = brentq(
            lambda lx, tp=tp, nip=nip: ps(math.exp(lx), tp, nip) - ps_star,
            math.log(t_lo),
            math.log(t_hi),
            xtol=1e-6,
        )
        t0 = math.exp(x)
        w = winding(t0, tp, nip)
        pmin, pmax, hoop, viol, score = _constraints(w, model.depth, target)
        cands.append(
            Candidate(float(tp), float(nip), t0, ps_star, pmin, pmax, hoop, tuple(viol), score)
        )
    if progress is not None:
        progress("candidates", 1.0)
    solved = [c for c in cands if c.web_tension is not None]
    if not solved:
        raise InputError(
            f"no setpoint in the tension range {t_lo / 1e6:.3g}-{t_hi / 1e6:.3g} MPa reads "
            f"{target.reading:g} {target.scale} on this roll",
            "--target",
        )
    feasible = [c for c in solved if c.feasible]

    def margin(c: Candidate) -> float:
        m = []
        if target.pressure_min > 0:
            m.append(c.min_pressure / target.pressure_min)
        if math.isfinite(target.pressure_max):
            m.append(target.pressure_max / c.max_pressure)
        return min(m) if m else 1.0

    if feasible:
        best = max(feasible, key=lambda c: (round(margin(c), 6), -c.taper, -c.nip_load))
    else:
        best = min(solved, key=lambda c: (c.score, c.taper, c.nip_load))
    # verify with full forward runs; secant on T0 if the reading misses
    tp, nip = best.taper, best.nip_load
    model_d = replace(
        model,
        schedule=replace(base, taper=Taper(target.taper_kind, tp), nip_load=nip),
    )
    t_a = best.web_tension
    r_a = model_d.evaluate(t_a).reading
    surrogate_miss = r_a - target.reading
    runs += 1
    t_b, r_b = None, None
    for _ in range(4):
        if abs(r_a - target.reading) <= target.tolerance:
            break
        if t_b is None:
            t_new = t_a * (1.0 + 0.1 * np.sign(target.reading - r_a))
        else:
            slope = (r_a - r_b) / (math.log(t_a) - math.log(t_b))
            t_new = math.exp(math.log(t_a) + (target.reading - r_a) / slope)
        t_new = min(max(t_new, t_lo), t_hi)
        t_b, r_b = t_a, r_a
        t_a = t_new
        r_a = model_d.evaluate(t_a).reading
        runs += 1
    w = winding(t_a, tp, nip)
    pmin, pmax, hoop, viol, _ = _constraints(w, model.depth, target)
    if abs(r_a - target.reading) > target.tolerance:
        viol.append(f"reading {r_a:.1f} misses the target by more than {target.tolerance:g}")
    if t_a != best.web_tension:
        notes.append(
            f"tension corrected by full forward runs from {best.web_tension / 1e6:.4g} to "
            f"{t_a / 1e6:.4g} MPa (the near-surface-pressure surrogate missed the target by "
            f"{surrogate_miss:+.2f} {target.scale})"
        )
    margins = {
        "min_pressure_Pa": pmin,
        "max_pressure_Pa": pmax,
        "min_hoop_stress_Pa": hoop,
        "pressure_min_margin": pmin / target.pressure_min if target.pressure_min > 0 else None,
        "pressure_max_margin": (
            target.pressure_max / pmax if math.isfinite(target.pressure_max) else None
        ),
        "reading_error": r_a - target.reading,
        "surrogate_reading_error": surrogate_miss,
    }
    return Design(
        target=target,
        feasible=not viol,
        web_tension=t_a,
        taper_kind=target.taper_kind,
        taper=tp,
        nip_load=nip,
        reading=r_a,
        winding=w,
        pressure_depth=model.depth,
        web_thickness=web.thickness,
        web_width=web.width,
        margins=margins,
        candidates=tuple(cands),
        full_runs=runs,
        notes=tuple(notes),
        violations=tuple(viol),
    )
