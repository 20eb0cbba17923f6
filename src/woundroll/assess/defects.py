"""Defect risk from the stresses in a roll: starring/buckling, core crush, slip and
telescoping, blocking, slack lanes.

Each criterion compares a demand with a capacity and reports the margin
``capacity / demand`` (> 1 is safe) and a risk level: "high" below 1, "watch" below
:data:`WATCH_MARGIN` (or where a practical rule flags it), "low" above, "n/a" when the case
does not give the limit. Sources and assumptions: docs/diagnosis.md, "Defect risk".

* **starring / buckling** -- negative (compressive) hoop stress, from the layer-mean hoop
  stress of the 1D model (the smooth part of the node values). Practical rule (Good and
  Roisum, *Winding: Machines, Mechanics and Measurements*, 2008): any negative hoop stress
  near the core is a starring risk ("watch"). Buckling estimate: a layer held by the pile on
  both sides wrinkles like a sandwich face on a thick core, ``sigma_cr = 0.5 (E_theta E_r
  G_r_theta)^(1/3)`` (Hoff and Mautner 1945; design coefficient 0.5 as in Allen 1969), with
  E_r and G_r_theta (default 2 E_r, Table 2) at the most compressed layer; "high" when
  ``|sigma_theta| > sigma_cr``. The estimate assumes the layers do not slip on each other;
  a slipping layer buckles far earlier, hence the practical rule.
* **core crush** -- core pressure against ``[defects] core_strength``.
* **interlayer slip / telescoping** -- Coulomb friction ``mu P(r)`` at each interface
  against the shear it must carry: an axial acceleration ``a`` of the roll (handling,
  ``axial_acceleration_g``) needs ``tau = m_out(r) a / (2 pi r W)`` where ``m_out`` is the
  mass outside ``r``; a torque ``M`` through the roll (``torque``, start/stop of a
  center-driven roll) needs ``tau = M / (2 pi r^2 W)`` (statics of a cylinder). The margin is
  the smallest ``mu P / tau`` over the interfaces (the outer layer, where P = 0, excluded:
  the outermost 1 % of the wound thickness, assumption).
* **blocking** -- the largest interlayer pressure against ``[defects] blocking_pressure``
  (layers stick above a material-specific pressure; no general value exists).
* **slack** -- near-surface interlayer pressure below ``slack_pressure`` (default 1 kPa,
  assumption), and, across the CMD, lanes whose effective wound-on tension is below
  ``slack_fraction`` (default 0.7) of the lanes' median.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from woundroll.errors import InputError
from woundroll.materials.web import INTERLAYER_FRICTION

if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.inverse.diagnosis import Diagnosis
    from woundroll.materials.web import Core, Web
    from woundroll.winding.result import WindingResult

__all__ = [
    "Criterion",
    "DefectLimits",
    "DefectReport",
    "assess_lanes",
    "assess_roll",
    "buckling_stress",
    "defect_report",
]

#: Margin below which a criterion is flagged "watch".
WATCH_MARGIN = 1.5
G0 = 9.81
#: Outer part of the wound thickness left out of the slip check (P -> 0 at the surface).
SLIP_SKIN = 0.01


@dataclass(frozen=True)
class DefectLimits:
    """Limits of ``[defects]`` (SI; None when not given)."""

    core_strength: float | None = None
    blocking_pressure: float | None = None
    friction: float = INTERLAYER_FRICTION
    axial_acceleration: float | None = None
    torque: float | None = None
    slack_pressure: float = 1e3
    slack_fraction: float = 0.7

    @classmethod
    def from_case(cls, case: Case) -> DefectLimits:
        d = getattr(case, "defects", None)
        mu = case.contact.friction
        if d is None:
            return cls(friction=mu)
        return cls(
            core_strength=d.core_strength,
            blocking_pressure=d.blocking_pressure,
            friction=d.friction if d.friction is not None else mu,
            axial_acceleration=None
            if d.axial_acceleration_g is None
            else d.axial_acceleration_g * G0,
            torque=d.torque,
            slack_pressure=d.slack_pressure,
            slack_fraction=d.slack_fraction,
        )


@dataclass(frozen=True)
class Criterion:
    """One defect criterion: demand against capacity, margin and risk, with its source."""

    name: str
    risk: str
    margin: float | None
    demand: float | None
    capacity: float | None
    unit: str
    where_m: float | None
    sentence: str
    source: str
    #: Dotted case key the criterion needs and the case does not give ("n/a" criteria), e.g.
    #: ``defects.core_strength``; None when the criterion was checked.
    needs: str | None = None

    def to_dict(self) -> dict[str, Any]:
        def num(v: float | None) -> float | None:
            return None if v is None or not math.isfinite(v) else float(v)

        return {
            "name": self.name,
            "risk": self.risk,
            "margin": num(self.margin),
            "demand": num(self.demand),
            "capacity": num(self.capacity),
            "unit": self.unit,
            "where_radius_m": num(self.where_m),
            "sentence": self.sentence,
            "source": self.source,
            "needs": self.needs,
        }


def _risk(margin: float | None) -> str:
    if margin is None:
        return "n/a"
    if margin < 1.0:
        return "high"
    return "watch" if margin < WATCH_MARGIN else "low"


def buckling_stress(E_theta: float, E_r: float, G_r_theta: float) -> float:
    """Wrinkling estimate ``0.5 (E_theta E_r G_r_theta)^(1/3)`` [Pa] (Hoff and Mautner 1945,
    design coefficient of Allen 1969)."""
    return 0.5 * (E_theta * E_r * G_r_theta) ** (1.0 / 3.0)


def assess_roll(
    winding: WindingResult,
    web: Web,
    core: Core,
    limits: DefectLimits,
    *,
    pressure_depth: float = 0.0065,
) -> list[Criterion]:
    """Every roll-level criterion (module docstring) for one 1D winding result."""
    out = _starring(winding, web, core)
    out.append(_core_crush(winding, limits))
    out.extend(_slip(winding, web, limits))
    out.append(_blocking(winding, limits))
    out.append(_slack(winding, limits, pressure_depth))
    return out


def _starring(winding: WindingResult, web: Web, core: Core) -> list[Criterion]:
    """Starring (practical rule) and buckling (wrinkling estimate): the smooth (layer-mean)
    hoop stress. Two criteria, so that each risk agrees with its own margin: the rule has
    none (any compression is "watch"), the estimate's risk follows its margin."""
    r = winding.radius
    rm, st = winding.layer_mean_hoop_stress()
    i = int(np.argmin(st))
    smin = float(st[i])
    src_star = "docs/diagnosis.md#starring-and-buckling"
    if smin >= 0:
        return [
            Criterion(
                "starring", "low", None, 0.0, None, "Pa", None,
                "no negative hoop stress anywhere in the roll", src_star,
            )
        ]  # fmt: skip
    E_r = float(np.interp(rm[i], r, winding.E_r))
    G = web.G_r_theta if web.G_r_theta is not None else 2.0 * E_r
    s_cr = buckling_stress(web.E_theta, E_r, G)
    margin = s_cr / -smin
    depth = (rm[i] - core.outer_radius) / (r[-1] - core.outer_radius)
    return [
        Criterion(
            "starring", "watch", None, -smin, None, "Pa", float(rm[i]),
            f"negative hoop stress {smin / 1e3:.3g} kPa at r = {rm[i] * 100:.2f} cm "
            f"({100 * depth:.0f} % of the wound thickness from the core): a starring risk "
            "if layers slip (practical rule: any compression is watched; no margin)",
            src_star,
        ),
        Criterion(
            "buckling", _risk(margin), margin, -smin, s_cr, "Pa", float(rm[i]),
            f"hoop compression {-smin / 1e3:.3g} kPa against the wrinkling estimate "
            f"{s_cr / 1e6:.3g} MPa of layers that do not slip (margin {margin:.3g})",
            src_star,
        ),
    ]  # fmt: skip


def _core_crush(winding: WindingResult, limits: DefectLimits) -> Criterion:
    r0 = float(winding.radius[0])
    pc = float(winding.core_pressure)
    if limits.core_strength is None:
        return Criterion(
            "core crush", "n/a", None, pc, None, "Pa", r0,
            f"core pressure {pc / 1e3:.3g} kPa; not checked without defects.core_strength",
            "docs/diagnosis.md#core-crush", needs="defects.core_strength",
        )  # fmt: skip
    m = limits.core_strength / pc if pc > 0 else math.inf
    return Criterion(
        "core crush", _risk(m), m, pc, limits.core_strength, "Pa", r0,
        f"core pressure {pc / 1e3:.3g} kPa against a core strength of "
        f"{limits.core_strength / 1e3:.3g} kPa (margin {m:.3g})",
        "docs/diagnosis.md#core-crush",
    )  # fmt: skip


def _blocking(winding: WindingResult, limits: DefectLimits) -> Criterion:
    r = winding.radius
    P = -winding.sigma_r
    k = int(np.argmax(P))
    if limits.blocking_pressure is None:
        return Criterion(
            "blocking", "n/a", None, float(P[k]), None, "Pa", float(r[k]),
            f"largest interlayer pressure {P[k] / 1e3:.3g} kPa; not checked without "
            "defects.blocking_pressure",
            "docs/diagnosis.md#blocking", needs="defects.blocking_pressure",
        )  # fmt: skip
    m = limits.blocking_pressure / float(P[k]) if P[k] > 0 else math.inf
    return Criterion(
        "blocking", _risk(m), m, float(P[k]), limits.blocking_pressure, "Pa", float(r[k]),
        f"largest interlayer pressure {P[k] / 1e3:.3g} kPa at r = {r[k] * 100:.2f} cm "
        f"against the blocking limit {limits.blocking_pressure / 1e3:.3g} kPa",
        "docs/diagnosis.md#blocking",
    )  # fmt: skip


def _slack(winding: WindingResult, limits: DefectLimits, pressure_depth: float) -> Criterion:
    """The near-surface pressure against the slack limit."""
    from woundroll.inverse.diagnosis import near_surface_pressure

    r = winding.radius
    ps = near_surface_pressure(r, winding.sigma_r, pressure_depth)
    m = ps / limits.slack_pressure
    return Criterion(
        "slack", _risk(m), m, limits.slack_pressure, ps, "Pa", float(r[-1] - pressure_depth),
        f"interlayer pressure {ps / 1e3:.3g} kPa at {pressure_depth * 1e3:.1f} mm below "
        f"the surface (slack below {limits.slack_pressure / 1e3:.3g} kPa)",
        "docs/diagnosis.md#slack",
    )  # fmt: skip


def _slip(winding: WindingResult, web: Web, limits: DefectLimits) -> list[Criterion]:
    r = winding.radius
    P = -winding.sigma_r
    R, W = float(r[-1]), web.width
    keep = r < R - SLIP_SKIN * (R - r[0])
    out = []
    for name, key, given, tau, what in (
        (
            "telescoping",
            "axial_acceleration_g",
            limits.axial_acceleration,
            lambda a: web.density * math.pi * (R**2 - r**2) * W * a / (2 * math.pi * r * W),
            "axial acceleration",
        ),
        ("torque slip", "torque", limits.torque, lambda m: m / (2 * math.pi * r**2 * W), "torque"),
    ):
        src = "docs/diagnosis.md#interlayer-slip-and-telescoping"
        if given is None:
            out.append(
                Criterion(
                    name,
                    "n/a",
                    None,
                    None,
                    None,
                    "-",
                    None,
                    f"not checked without defects.{key}",
                    src,
                    needs=f"defects.{key}",
                )
            )
            continue
        need = tau(given)
        cap = limits.friction * P
        ratio = np.where(need[keep] > 0, cap[keep] / np.maximum(need[keep], 1e-300), np.inf)
        j = int(np.argmin(ratio))
        m = float(ratio[j])
        unit_txt = f"{given / G0:.3g} g" if name == "telescoping" else f"{given:.3g} N m"
        out.append(
            Criterion(
                name,
                _risk(m),
                m,
                float(need[keep][j]),
                float(cap[keep][j]),
                "Pa",
                float(r[keep][j]),
                f"{what} {unit_txt}: friction mu P = {cap[keep][j] / 1e3:.3g} kPa against "
                f"{need[keep][j] / 1e3:.3g} kPa of shear needed at r = {r[keep][j] * 100:.2f} cm "
                f"(margin {m:.3g})",
                src,
            )
        )
    return out


def assess_lanes(diagnosis: Diagnosis, case: Case, limits: DefectLimits) -> list[dict[str, Any]]:
    """Per CMD position of a diagnosis: the roll criteria of a 1D roll wound at the lane's
    effective tension, and the slack-lane check against the lanes' median."""
    from dataclasses import replace

    from woundroll.winding.hakiel import WindingOptions, wind

    web, core = case.web.build(), case.core.build()
    r_out = case.winding.final_radius(web, core)
    sched = case.winding.schedule(web)
    opts = WindingOptions.from_dict(case.winding.options, "winding.options")
    wot = diagnosis.wound_on_tension
    med = float(np.nanmedian(wot)) if np.any(np.isfinite(wot)) else math.nan
    lanes = []
    for i, x in enumerate(diagnosis.position):
        t = float(diagnosis.web_tension[i])
        entry: dict[str, Any] = {"position_m": float(x), "status": diagnosis.status[i]}
        if not math.isfinite(t):
            entry["criteria"] = []
            entry["slack_lane"] = diagnosis.status[i] == "below range"
            lanes.append(entry)
            continue
        w = wind(web, core, r_out, replace(sched, web_stress=t), options=opts)
        crit = assess_roll(w, web, core, limits, pressure_depth=diagnosis.pressure_depth)
        crit = [c for c in crit if c.needs is None]  # unchecked: said once, for the roll
        entry["criteria"] = [c.to_dict() for c in crit]
        ratio = float(wot[i] / med) if med > 0 else math.nan
        entry["wound_on_tension_over_median"] = ratio
        entry["slack_lane"] = bool(ratio < limits.slack_fraction) or any(
            c.name == "slack" and c.risk == "high" for c in crit
        )
        entry["risk"] = _worst([c.risk for c in crit] + (["high"] if entry["slack_lane"] else []))
        lanes.append(entry)
    return lanes


def _worst(risks: list[str]) -> str:
    for level in ("high", "watch", "low"):
        if level in risks:
            return level
    return "n/a"


@dataclass(frozen=True)
class DefectReport:
    """Roll-level criteria and, with readings, per-lane criteria."""

    roll: list[Criterion]
    lanes: list[dict[str, Any]] = field(default_factory=list)
    limits: DefectLimits = field(default_factory=DefectLimits)

    @property
    def risk(self) -> str:
        return _worst([c.risk for c in self.roll] + [ln.get("risk", "n/a") for ln in self.lanes])

    @property
    def unchecked(self) -> list[tuple[str, str]]:
        """(criterion, case key to set) of every criterion not checked for want of a limit."""
        return [(c.name, c.needs) for c in self.roll if c.needs is not None]

    def needs_note(self) -> str:
        """One sentence, said once under the criteria, on how to give the limits that the
        "n/a" rows name ("" when every criterion was checked)."""
        if not self.unchecked:
            return ""
        return (
            "n/a: not checked for want of a limit; set the key the finding names in the "
            "case's [defects] section or with --set KEY=VALUE (docs/diagnosis.md#defect-risk)."
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "risk": self.risk,
            "unchecked": [{"name": n, "needs": k} for n, k in self.unchecked],
            "roll": [c.to_dict() for c in self.roll],
            "lanes": self.lanes,
            "limits": {
                "core_strength_Pa": self.limits.core_strength,
                "blocking_pressure_Pa": self.limits.blocking_pressure,
                "friction": self.limits.friction,
                "axial_acceleration_m_per_s2": self.limits.axial_acceleration,
                "torque_N_m": self.limits.torque,
                "slack_pressure_Pa": self.limits.slack_pressure,
                "slack_fraction": self.limits.slack_fraction,
            },
            "watch_margin": WATCH_MARGIN,
        }

    def summary(self) -> list[tuple[str, str, str]]:
        """(criterion, risk, sentence) rows; lanes condensed to one row per criterion."""
        rows = [(c.name, c.risk, c.sentence) for c in self.roll]
        if self.lanes:
            slack = [ln for ln in self.lanes if ln.get("slack_lane")]
            rows.append(
                (
                    "slack lanes",
                    "high" if slack else "low",
                    (
                        "slack at "
                        + ", ".join(f"{ln['position_m'] / 0.0254:.1f} in" for ln in slack)
                        if slack
                        else "no lane below "
                        f"{100 * self.limits.slack_fraction:.0f} % of the median wound-on tension"
                    ),
                )
            )
            worst: dict[str, tuple[str, float]] = {}
            for ln in self.lanes:
                for c in ln.get("criteria", []):
                    lvl = {"high": 3, "watch": 2, "low": 1}.get(c["risk"], 0)
                    if lvl > worst.get(c["name"], ("", -1))[1]:
                        worst[c["name"]] = (f"{ln['position_m'] / 0.0254:.1f} in", lvl)
            for name, (where, lvl) in worst.items():
                if lvl >= 2:
                    risk = {3: "high", 2: "watch"}[lvl]
                    rows.append((f"{name} (lanes)", risk, f"worst lane at {where}"))
        return rows

    def _plot_lanes(self, ax: Any) -> None:
        """Per-lane margins against CMD position, one line per criterion; slack lanes shaded."""
        x = np.array([ln["position_m"] for ln in self.lanes]) / 0.0254
        names = sorted({c["name"] for ln in self.lanes for c in ln.get("criteria", [])})
        for name in names:
            m = [
                next(
                    (c["margin"] for c in ln.get("criteria", []) if c["name"] == name),
                    None,
                )
                for ln in self.lanes
            ]
            y = np.array([np.nan if v is None else v for v in m], dtype=float)
            if np.any(np.isfinite(y)):
                ax.plot(x, y, "o-", ms=3, label=name)
        for xi, ln in zip(x, self.lanes, strict=True):
            if ln.get("slack_lane"):
                ax.axvspan(xi - 0.3, xi + 0.3, color="C3", alpha=0.2, lw=0)
        ax.axhline(1.0, color="k", lw=1.0)
        ax.axhline(WATCH_MARGIN, color="k", ls="--", lw=0.8)
        ax.set_yscale("log")
        ax.set_xlabel("CMD position [in] (red: slack lane)")
        ax.set_ylabel("margin per lane")
        ax.grid(alpha=0.3, which="both")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, ncol=3)
        else:  # no lane was diagnosed (every reading outside the forward curve)
            ax.text(0.5, 0.5, "no lane with a diagnosed tension", transform=ax.transAxes,
                    ha="center", va="center", fontsize=8, color="0.35")  # fmt: skip

    def plot(self, path: str | Path | None = None) -> Any:
        """Margins of every roll criterion (log scale, 1 and the watch line marked); with
        lanes, the margins per lane across the CMD below."""
        import matplotlib.pyplot as plt

        crit = [c for c in self.roll if c.margin is not None and math.isfinite(c.margin)]
        if self.lanes:
            fig, (ax, ax2) = plt.subplots(2, 1, figsize=(6.4, 6.0))
            self._plot_lanes(ax2)
        else:
            fig, ax = plt.subplots(figsize=(6.4, 3.2))
        colors = {"high": "C3", "watch": "C1", "low": "C2"}
        names = [c.name for c in crit]
        ax.barh(names, [c.margin for c in crit], color=[colors.get(c.risk, "C7") for c in crit])
        ax.axvline(1.0, color="k", lw=1.0)
        ax.axvline(WATCH_MARGIN, color="k", ls="--", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel("margin = capacity / demand (1: limit, dashed: watch)")
        ax.set_title(f"defect risk: {self.risk}", fontsize=9)
        ax.grid(alpha=0.3, axis="x", which="both")
        # criteria without a margin are named, not drawn: a bar would put them anywhere
        rest = [f"{c.name} ({c.risk})" for c in self.roll if c not in crit]
        if rest:
            ax.text(
                0.0,
                -0.32 if not self.lanes else -0.3,
                "no margin: " + ", ".join(rest),
                transform=ax.transAxes,
                fontsize=7,
                color="0.35",
                va="top",
            )
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def defect_report(
    case: Case, diagnosis: Diagnosis | None = None, winding: WindingResult | None = None
) -> DefectReport:
    """Defect risk of ``case`` (its 1D winding, or ``winding``) and, given a diagnosis, of
    each diagnosed CMD lane."""
    from woundroll.winding.hakiel import WindingOptions, wind

    limits = DefectLimits.from_case(case)
    web, core = case.web.build(), case.core.build()
    if winding is None:
        winding = wind(
            web,
            core,
            case.winding.final_radius(web, core),
            case.winding.schedule(web),
            options=WindingOptions.from_dict(case.winding.options, "winding.options"),
        )
    setup = case.tester_setup
    depth = setup.instrument.head_radius if setup is not None else 0.0065
    if limits.friction <= 0:
        raise InputError(
            "interlayer friction must be positive for the slip check", "defects.friction"
        )
    roll = assess_roll(winding, web, core, limits, pressure_depth=depth)
    lanes = assess_lanes(diagnosis, case, limits) if diagnosis is not None else []
    return DefectReport(roll, lanes, limits)
