"""Readings -> stresses: the wound-on tension and the interlayer pressure behind each reading.

The forward chain (:mod:`woundroll.pipeline`) maps winder settings to a reading:
winding (Hakiel, 1D) -> roll spring under the striker (2D contact, {3}) -> impact (FD
{4}-{13}) -> reading. With everything else fixed (web, core, roll size, taper shape, nip,
instrument), the reading is a monotone function of the tension level. This module inverts it:

1. **Tabulate** the reading over a tension grid once per case (:func:`forward_curve`): the
   web tension at the core ``T0`` on a geometric grid (factors 1/4 ... 4 of the case's,
   extended by factors of 2 until the readings are bracketed, at most 1/64 ... 64), one full
   forward run per point. Each point also keeps the wound-on tension of the outer layer and
   the near-surface interlayer pressure.
2. **Interpolate** monotone (PCHIP in ``log T0``) and **invert** by bracketing root-finding
   (Brent) on the interpolant: each position's mean reading gives its effective tension.
   The interpolant is checked against a full forward run at the median result
   (:attr:`Diagnosis.verification`); ``tests/test_diagnosis.py`` checks it at grid midpoints.
3. **Intervals** (confidence ``c``, default 95 %):

   * reading scatter: the mean reading's interval ``mean +- t(c, n-1) s / sqrt(n)`` (own SD
     where a position was read >= 2 times, else the sheet's pooled SD with its degrees of
     freedom, else the case's ``readings.repeatability`` with a normal quantile), mapped
     through the inverted curve (exact for a monotone curve);
   * material and thickness uncertainty (``[uncertainty]``: K1, K2 and their correlation,
     web thickness): one extra curve per parameter at +1 SD, the sensitivity
     ``d ln T0 / d p`` at each reading, combined linearly with the correlation
     (``var = J C J^T``) -- a first-order propagation; ``--uncertainty N`` (Monte Carlo) is
     the check;
   * both combined in quadrature in ``ln T0`` on each side.

"Effective wound-on tension" is the wound-on tension of the outer layer (web tension after
taper plus the nip-induced ``mu N / h``) of a roll wound at a uniform tension level that
reads like the lane; the tension at the core ``T0`` is reported too. "Near-surface interlayer
pressure" is ``P = -sigma_r`` at one head radius below the surface (assumption, the depth the
head's contact stresses reach; docs/diagnosis.md). Each CMD position is read as its own 1D
roll (lanes do not interact; the axisymmetric model is the subject of the profile fit).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import INTERLAYER_FRICTION

if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.instruments import HardnessResult, TesterSetup
    from woundroll.io.readings import Readings
    from woundroll.materials.web import Core, Web
    from woundroll.winding.tension import TensionSchedule

FloatArray = NDArray[np.float64]
Progress = Callable[[str, float], None]

__all__ = [
    "Diagnosis",
    "ForwardCurve",
    "ForwardPoint",
    "RollModel",
    "diagnose",
    "forward_curve",
    "reading_of",
    "set_point_units",
]

#: Initial grid of tension factors (times the case's tension) and the outermost factors.
GRID_FACTORS = (0.25, 0.5, 1.0, 2.0, 4.0)
MIN_FACTOR, MAX_FACTOR = 1.0 / 64.0, 64.0
#: Grid intervals holding a reading are subdivided to this tension ratio (docs/diagnosis.md).
REFINE_RATIO = 2.0**0.5


def reading_of(hardness: HardnessResult, scale: str) -> float:
    """The FD model's reading in ``scale`` ("Rho", "g", "R", "L")."""
    fd = hardness.fd
    return float({"Rho": fd.rho, "g": fd.peak_g, "R": fd.rebound_r, "L": fd.rebound_l}[scale])


@dataclass(frozen=True)
class ForwardPoint:
    """One full forward run at web tension ``web_stress`` (SI)."""

    web_stress: float
    wound_on_tension: float
    surface_pressure: float
    reading: float
    rho_fd: float
    extrapolated: bool


@dataclass(frozen=True)
class RollModel:
    """The forward chain of one case with the tension level (and web) as parameters.

    Build with :meth:`from_case`; :meth:`evaluate` runs winding -> contact -> impact.
    """

    web: Web
    core: Core
    outer_radius: float
    schedule: TensionSchedule
    setup: TesterSetup
    scale: str
    friction: float = INTERLAYER_FRICTION
    contact_options: Any = None
    depth: float = 0.0
    semi_contact_width_given: bool = False
    winding_options: Any = None
    contact_model: str | None = None  # a registry name; None: the default
    contact3d_options: Any = None  # the case's [contact.options3d] for the 3D model
    #: the case whose steps after winding (entrained air, storage) every forward run takes
    #: (:func:`woundroll.pipeline.runner.after_winding`); None: the roll as wound
    case: Any = field(default=None, repr=False, compare=False)

    @classmethod
    def from_case(cls, case: Case, scale: str | None = None) -> RollModel:
        """The forward model of ``case`` reading in ``scale`` (default: the instrument's)."""
        from woundroll.instruments import tester_from_spec
        from woundroll.io.readings import SCALES
        from woundroll.winding.hakiel import WindingOptions

        setup = case.tester_setup or tester_from_spec({"instrument": "rho-meter"})
        if setup.roll_spring is not None:
            raise InputError(
                "the diagnosis varies the tension through the contact model; an explicit "
                "[tester.roll_spring] does not depend on it: remove it",
                "tester.roll_spring",
            )
        inst = setup.instrument
        own = {v: k for k, v in SCALES.items()}[inst.readout]
        if scale is None:
            scale = own
        accel = {"Rho", "g"}
        if scale != own and not (scale in accel and own in accel):
            raise InputError(
                f"the readings are in {scale} but the case's instrument {inst.name!r} reads "
                f"{own}: set tester.instrument to the instrument that took them",
                "readings",
            )
        web = case.web.build()
        core = case.core.build()
        return cls(
            web=web,
            core=core,
            outer_radius=case.winding.final_radius(web, core),
            schedule=case.winding.schedule(web),
            setup=setup,
            scale=scale,
            friction=case.contact.friction,
            contact_options=case.contact.model_options(),
            depth=inst.head_radius,
            semi_contact_width_given="semi_contact_width" in (case.tester or {}),
            winding_options=WindingOptions.from_dict(case.winding.options, "winding.options"),
            contact_model=case.contact.model,
            contact3d_options=case.contact.contact3d_options(),
            case=case,
        )

    @property
    def roll_model(self) -> str:
        """The registry name of the roll model that reads this roll."""
        from woundroll.contact.models import resolve_model

        return resolve_model(self.contact_model, self.setup.instrument.head_shape).name

    @property
    def tension(self) -> float:
        """The case's web tension at the core T0 [Pa]."""
        return self.schedule.web_stress

    def with_web(self, web: Web) -> RollModel:
        return replace(self, web=web)

    def wound(self, schedule: TensionSchedule | None = None, web: Web | None = None) -> Any:
        """The roll wound on ``schedule`` (default the case's) from ``web`` (default the
        model's), as the contact model sees it: after the case's entrained air and storage
        (:func:`woundroll.pipeline.runner.after_winding`), as :func:`woundroll.run` does."""
        from woundroll.winding.hakiel import wind

        sched = self.schedule if schedule is None else schedule
        web = self.web if web is None else web
        w = wind(web, self.core, self.outer_radius, sched, options=self.winding_options)
        if self.case is None:
            return w
        from woundroll.pipeline.runner import after_winding

        return after_winding(
            self.case, w, web, self.core, self.outer_radius, sched, self.winding_options
        ).winding

    def evaluate(self, web_stress: float) -> ForwardPoint:
        """One full forward run at web tension ``web_stress`` [Pa] (taper and nip kept)."""
        from woundroll.contact import roll_stiffness
        from woundroll.pipeline import hardness_on_roll

        sched = replace(self.schedule, web_stress=float(web_stress))
        w = self.wound(sched)
        stiff = roll_stiffness(
            self.web,
            self.core,
            w.radius,
            w.sigma_r,
            self.setup.instrument,
            friction=self.friction,
            options=self.contact_options,
            model=self.contact_model,
            options3d=self.contact3d_options,
        )
        H = self.outer_radius - self.core.outer_radius
        h = hardness_on_roll(
            self.setup,
            stiff,
            H,
            self.web.density,
            semi_contact_width_given=self.semi_contact_width_given,
        )
        return ForwardPoint(
            web_stress=float(web_stress),
            wound_on_tension=float(w.wot[-1]),
            surface_pressure=near_surface_pressure(w.radius, w.sigma_r, self.depth),
            reading=reading_of(h, self.scale),
            rho_fd=float(h.fd.rho),
            extrapolated=bool(stiff.extrapolated),
        )


def near_surface_pressure(radius: ArrayLike, sigma_r: ArrayLike, depth: float) -> float:
    """Interlayer pressure ``P = -sigma_r`` [Pa] at ``depth`` below the outer surface
    (linear between nodes; the core's pressure if the roll is thinner than ``depth``)."""
    r = np.asarray(radius, dtype=float)
    s = np.asarray(sigma_r, dtype=float)
    return float(-np.interp(r[-1] - depth, r, s))


@dataclass(frozen=True)
class ForwardCurve:
    """Readings of full forward runs over a tension grid, and their monotone interpolant.

    Attributes
    ----------
    points : tuple of ForwardPoint
        Sorted by tension.
    scale : str
    """

    points: tuple[ForwardPoint, ...]
    scale: str
    #: the roll model that read every point (registry name, woundroll.contact.models)
    roll_model: str = ""

    @property
    def web_stress(self) -> FloatArray:
        return np.array([p.web_stress for p in self.points])

    @property
    def reading(self) -> FloatArray:
        return np.array([p.reading for p in self.points])

    @property
    def wound_on_tension(self) -> FloatArray:
        return np.array([p.wound_on_tension for p in self.points])

    @property
    def surface_pressure(self) -> FloatArray:
        return np.array([p.surface_pressure for p in self.points])

    @property
    def monotone(self) -> bool:
        """Readings strictly increase with tension over the grid."""
        return bool(np.all(np.diff(self.reading) > 0))

    def _interp(self, values: FloatArray, log: bool = False) -> Any:
        from scipy.interpolate import PchipInterpolator

        y = np.log(values) if log else values
        return PchipInterpolator(np.log(self.web_stress), y, extrapolate=False)

    def reading_at(self, web_stress: ArrayLike) -> FloatArray:
        """Interpolated reading at tension(s) [Pa] (NaN outside the grid)."""
        return self._interp(self.reading)(np.log(np.asarray(web_stress, dtype=float)))

    def wound_on_tension_at(self, web_stress: ArrayLike) -> FloatArray:
        # WOT = T0 f(R) + mu N / h is affine in T0: interpolate linearly, exact
        return np.interp(
            np.asarray(web_stress, dtype=float), self.web_stress, self.wound_on_tension
        )

    def surface_pressure_at(self, web_stress: ArrayLike) -> FloatArray:
        p = self.surface_pressure
        if np.all(p > 0):
            return np.exp(self._interp(p, log=True)(np.log(np.asarray(web_stress, dtype=float))))
        return self._interp(p)(np.log(np.asarray(web_stress, dtype=float)))

    def covers(self, reading: float) -> bool:
        r = self.reading
        return bool(r[0] <= reading <= r[-1])

    def tension_for(self, reading: ArrayLike) -> FloatArray:
        """Web tension T0 [Pa] whose interpolated reading is ``reading``; NaN outside the
        curve's range (bracketing Brent root-finding on the monotone interpolant)."""
        from scipy.optimize import brentq

        if not self.monotone:
            raise InputError(
                "the reading does not rise monotonically with the tension over "
                f"{self.web_stress[0]:.3g}-{self.web_stress[-1]:.3g} Pa: not invertible",
                "readings",
            )
        f = self._interp(self.reading)
        x = np.log(self.web_stress)
        r = self.reading
        out = []
        for v in np.atleast_1d(np.asarray(reading, dtype=float)):
            if not (r[0] <= v <= r[-1]):
                out.append(math.nan)
                continue
            k = int(np.clip(np.searchsorted(r, v), 1, r.size - 1))
            if v == r[k - 1]:
                out.append(float(self.web_stress[k - 1]))
                continue
            root = brentq(lambda t, v=v: float(f(t)) - v, x[k - 1], x[k], xtol=1e-12)
            out.append(math.exp(root))
        return np.asarray(out)

    def sensitivity(self) -> FloatArray:
        """d reading / d ln T0 at the grid points (finite differences)."""
        return np.gradient(self.reading, np.log(self.web_stress))

    def to_dict(self) -> dict[str, Any]:
        return {
            "scale": self.scale,
            "web_tension_Pa": self.web_stress.tolist(),
            "wound_on_tension_Pa": self.wound_on_tension.tolist(),
            "surface_pressure_Pa": self.surface_pressure.tolist(),
            "reading": self.reading.tolist(),
            "extrapolated_spring": [p.extrapolated for p in self.points],
        }


def forward_curve(
    model: RollModel,
    targets: ArrayLike = (),
    *,
    factors: tuple[float, ...] = GRID_FACTORS,
    progress: Callable[[float], None] | None = None,
    tensions: ArrayLike | None = None,
    refine: float = REFINE_RATIO,
) -> ForwardCurve:
    """Tabulate the reading over tension (module docstring, step 1).

    Parameters
    ----------
    model : RollModel
    targets : readings the curve must bracket (the grid is extended by factors of 2, within
        1/64 ... 64 times the case's tension, until it does).
    factors : initial grid, times the case's tension.
    tensions : explicit grid [Pa] instead (no extension, no refinement).
    refine : intervals of the grid that hold a target are subdivided at their geometric
        midpoint until the ratio of their end tensions is at most ``refine`` (1: never).
    """
    t_case = model.tension
    if not t_case > 0:
        raise InputError("the case's tension must be positive to diagnose", "winding.tension")
    grid = (
        sorted(float(t) for t in np.asarray(tensions, dtype=float))
        if tensions is not None
        else [t_case * f for f in factors]
    )
    pts: dict[float, ForwardPoint] = {}

    def step() -> None:
        # runs done over runs expected (the grid and two more, typically: extension and
        # refinement); it rises with every run and reaches 1 only at the end
        if progress is not None:
            progress(len(pts) / max(len(grid) + 2, len(pts) + 1))

    for t in grid:
        pts[t] = model.evaluate(t)
        step()
    targets = np.asarray(targets, dtype=float)
    targets = targets[np.isfinite(targets)]
    if tensions is None and targets.size:
        _extend_to_targets(model, pts, targets, step)
    if tensions is None and targets.size and refine > 1.0:
        _refine_at_targets(model, pts, targets, refine, step)
    if progress is not None:
        progress(1.0)
    return ForwardCurve(tuple(pts[t] for t in sorted(pts)), model.scale, model.roll_model)


def _extend_to_targets(
    model: RollModel,
    pts: dict[float, ForwardPoint],
    targets: FloatArray,
    step: Callable[[], None],
) -> None:
    """Extend the grid by factors of 2 (within MIN_FACTOR ... MAX_FACTOR of the case's
    tension) until it brackets the targets, or the chain has no answer there."""
    t_case = model.tension
    lo, hi = float(targets.min()), float(targets.max())
    stuck = {"low": False, "high": False}
    while True:
        ts = sorted(pts)
        r = [pts[t].reading for t in ts]
        if not stuck["low"] and lo < min(r) and ts[0] / 2 >= t_case * MIN_FACTOR * (1 - 1e-9):
            side, t_new = "low", ts[0] / 2
        elif not stuck["high"] and hi > max(r) and ts[-1] * 2 <= t_case * MAX_FACTOR * (1 + 1e-9):
            side, t_new = "high", ts[-1] * 2
        else:
            break
        try:
            pts[t_new] = model.evaluate(t_new)
            step()
        except (ConvergenceError, InputError):
            stuck[side] = True  # the chain has no answer there (e.g. too slack to solve)


def _refine_at_targets(
    model: RollModel,
    pts: dict[float, ForwardPoint],
    targets: FloatArray,
    refine: float,
    step: Callable[[], None],
) -> None:
    """Subdivide (geometric midpoints) the intervals that hold a target reading until
    their tension ratio is at most ``refine``: the interpolant is exact at grid points."""
    for _ in range(8):
        ts = sorted(pts)
        r = np.array([pts[t].reading for t in ts])
        split = set()
        for v in targets:
            k = int(np.searchsorted(r, v))
            if 0 < k < len(ts) and ts[k] / ts[k - 1] > refine * (1 + 1e-9):
                split.add(k)
        if not split:
            break
        for k in sorted(split):
            t_new = math.sqrt(ts[k] * ts[k - 1])
            pts[t_new] = model.evaluate(t_new)
            step()


@dataclass(frozen=True)
class Diagnosis:
    """Per CMD position: the effective tension and pressure that reproduce the readings.

    Arrays have one entry per reading position; NaN where the reading lies outside what the
    forward chain can produce (``status`` says which side) -- JSON null.

    Attributes
    ----------
    readings : Readings
    position : array [m]
    reading, reading_low, reading_high : arrays (scale of the readings)
        Mean reading and its confidence interval (scatter only).
    web_tension, web_tension_low, web_tension_high : arrays [Pa]
        Tension at the core T0 (winder setting, as a stress in the web).
    wound_on_tension(_low, _high) : arrays [Pa]
        Effective wound-on tension of the outer layer.
    surface_pressure(_low, _high) : arrays [Pa]
        Interlayer pressure at ``pressure_depth`` below the surface.
    status : tuple of str
        "ok", "below range" (softer than any tension the chain can wind), "above range".
    curve : ForwardCurve
    material_sensitivity : dict
        Parameter -> (SD, d ln T0 / d parameter at each position).
    verification : dict
        Full forward run at the median result: its reading vs the target.
    confidence : float
    pressure_depth : float [m]
    notes : tuple of str
    """

    readings: Readings
    position: FloatArray
    reading: FloatArray
    reading_low: FloatArray
    reading_high: FloatArray
    web_tension: FloatArray
    web_tension_low: FloatArray
    web_tension_high: FloatArray
    wound_on_tension: FloatArray
    wound_on_tension_low: FloatArray
    wound_on_tension_high: FloatArray
    surface_pressure: FloatArray
    surface_pressure_low: FloatArray
    surface_pressure_high: FloatArray
    status: tuple[str, ...]
    curve: ForwardCurve
    confidence: float
    pressure_depth: float
    case_tension: float
    material_sensitivity: dict[str, Any] = field(default_factory=dict)
    verification: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    #: the case's ``winding.tension`` as given: (kind, SI value); kind "force" [N],
    #: "force_per_length" [N/m] or "pressure" [Pa]
    set_point: tuple[str, float] | None = None
    web_width: float = math.nan
    web_thickness: float = math.nan

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (the CLI's ``diagnosis``); NaN -> null."""

        def lst(a: FloatArray) -> list[float | None]:
            return [None if not math.isfinite(float(v)) else float(v) for v in a]

        return {
            "position_m": lst(self.position),
            "scale": self.curve.scale,
            "reading": lst(self.reading),
            "reading_low": lst(self.reading_low),
            "reading_high": lst(self.reading_high),
            "web_tension_Pa": lst(self.web_tension),
            "web_tension_low_Pa": lst(self.web_tension_low),
            "web_tension_high_Pa": lst(self.web_tension_high),
            "wound_on_tension_Pa": lst(self.wound_on_tension),
            "wound_on_tension_low_Pa": lst(self.wound_on_tension_low),
            "wound_on_tension_high_Pa": lst(self.wound_on_tension_high),
            "surface_pressure_Pa": lst(self.surface_pressure),
            "surface_pressure_low_Pa": lst(self.surface_pressure_low),
            "surface_pressure_high_Pa": lst(self.surface_pressure_high),
            "status": list(self.status),
            "confidence": self.confidence,
            "pressure_depth_m": self.pressure_depth,
            "case_web_tension_Pa": self.case_tension,
            "material_sensitivity": {
                k: {"sd": sd, "dlnT_dp": lst(np.asarray(d))}
                for k, (sd, d) in self.material_sensitivity.items()
            },
            "curve": self.curve.to_dict(),
            "verification": self.verification,
            "notes": list(self.notes),
            "summary": self.sentence(),
            "roll_model": self.curve.roll_model,
        }

    def roll_level(self) -> tuple[float, float, float]:
        """Web tension at the core T0 [Pa] the whole roll reads like, and its interval.

        One position: that position's result (scatter and material). Several: T0 at the mean
        of the positions' mean readings; its interval maps the mean's confidence interval
        (Student t over the positions' means) through the forward curve and adds the median
        position's material half-width in quadrature in ``ln T0``. NaN where the reading
        lies beyond what the forward chain can produce (an open interval end likewise).
        """
        from scipy.stats import t as student

        k = self.position.size
        if k == 1:
            return (
                float(self.web_tension[0]),
                float(self.web_tension_low[0]),
                float(self.web_tension_high[0]),
            )
        c = self.curve
        r = self.reading
        rbar = float(np.mean(r))
        half = float(student.ppf(0.5 + 0.5 * self.confidence, k - 1) * np.std(r, ddof=1))
        half /= math.sqrt(k)
        T = float(c.tension_for(rbar)[0])
        lo = float(c.tension_for(max(rbar - half, c.reading[0]))[0])
        hi = float(c.tension_for(min(rbar + half, c.reading[-1]))[0])
        lo = math.nan if rbar - half < c.reading[0] else lo
        hi = math.nan if rbar + half > c.reading[-1] else hi
        # material half-width of each position: its interval minus its scatter part
        with np.errstate(invalid="ignore", divide="ignore"):
            lt = np.log(self.web_tension)
            scatter = lt - np.log(c.tension_for(np.clip(self.reading_low, c.reading[0], None)))
            m2 = (lt - np.log(self.web_tension_low)) ** 2 - scatter**2
        m2 = m2[np.isfinite(m2)]
        m = math.sqrt(max(float(np.median(m2)), 0.0)) if m2.size else 0.0
        if math.isfinite(T):
            if math.isfinite(lo):
                lo = math.exp(math.log(T) - math.hypot(math.log(T) - math.log(lo), m))
            if math.isfinite(hi):
                hi = math.exp(math.log(T) + math.hypot(math.log(hi) - math.log(T), m))
        return T, lo, hi

    def sentence(self, units: str | None = None) -> str:
        """The diagnosis in one sentence, against the case's set point (``winding.tension``).

        ``"this roll reads as if wound at 4.60 MPa (70.1 N, 2.62 pli), 31 % above the
        53.4 N set point (95 %: 55.2-84.0 N)"``: the roll-level web tension at the core
        (:meth:`roll_level`) as a stress, a force over the web width and a force per width;
        the deviation from the set point; the interval in the set point's unit. ``units``:
        ``"si"`` (MPa, N, N/m) or ``"us"`` (psi, lbf, pli); default: the set point's own
        family (:func:`set_point_units`).
        """
        kind, value = self.set_point or ("pressure", self.case_tension)
        system = units or set_point_units(kind, value)
        if system not in _UNIT_SYSTEMS:
            raise InputError(f"must be one of {', '.join(_UNIT_SYSTEMS)}, got {units!r}", "units")
        w, h = self.web_width, self.web_thickness
        if not (math.isfinite(w) and math.isfinite(h)):
            kind, value = "pressure", self.case_tension  # no geometry: stresses only
        per_stress = {"pressure": 1.0, "force": w * h, "force_per_length": h}
        unit, factor = _UNIT_SYSTEMS[system][kind]

        def setp(stress: float) -> str:
            return f"{stress * per_stress[kind] / factor:.3g}"

        set_text = f"the {value / factor:.3g} {unit} set point"
        T, lo, hi = self.roll_level()
        c = self.curve
        where = f"{self.position.size} positions, " if self.position.size > 1 else ""
        rbar = float(np.mean(self.reading))
        if not math.isfinite(T):
            softer = rbar < c.reading[0]
            edge = float(c.web_stress[0] if softer else c.web_stress[-1])
            ratio = edge / self.case_tension
            times = f"1/{1 / ratio:.3g} of" if ratio < 1 else f"{ratio:.3g} times"
            return (
                f"this roll reads {'softer' if softer else 'harder'} ({where}mean "
                f"{rbar:.1f} {c.scale}) than a roll wound at {setp(edge)} {unit}, "
                f"{'the slackest' if softer else 'the tightest'} tension the model reaches "
                f"({times} {set_text})"
            )
        parts = []
        for k in ("pressure", "force", "force_per_length"):
            if k == "pressure" or (math.isfinite(w) and math.isfinite(h)):
                u, f = _UNIT_SYSTEMS[system][k]
                parts.append(f"{T * per_stress[k] / f:.3g} {u}")
        dev = 100.0 * (T / self.case_tension - 1.0)
        if abs(dev) < 0.5:
            vs = f"on {set_text}"
        else:
            vs = f"{abs(dev):.0f} % {'above' if dev > 0 else 'below'} {set_text}"
        band = _interval_text(lo, hi, setp, unit)
        conf = f"{100 * self.confidence:.0f} %"
        sat = [st for st in self.status if st.startswith("saturated")]
        wound = "as if wound at"
        if self.position.size == 1 and sat:
            # a reading at the scale's end bounds the tension from one side only
            wound = "as if wound at least at" if "least" in sat[0] else "as if wound at most at"
        tail = self._positions_text(setp, unit)
        if sat:
            tail += (
                f"; {len(sat)} of {self.position.size} positions read at the scale's end "
                "(saturated): a bound there, not a value"
            )
        return (
            f"this roll reads {wound} {parts[0]} ({', '.join(parts[1:])}), {vs} "
            f"({conf}: {band}){tail}"
        ).replace(" ()", "")

    def _positions_text(self, setp: Callable[[float], str], unit: str) -> str:
        """ "; 5 positions, from 40.1 to 52.3 N": the positions' tension range."""
        tail = ""
        if self.position.size > 1:
            ok = np.isfinite(self.web_tension)
            tail = f"; {self.position.size} positions"
            if np.count_nonzero(ok) > 1:
                tail += (
                    f", from {setp(float(np.min(self.web_tension[ok])))} to "
                    f"{setp(float(np.max(self.web_tension[ok])))} {unit}"
                )
        return tail

    def summary(self) -> list[tuple[str, ...]]:
        """Rows for a table: position [in], reading, WOT [MPa] and P [kPa] with intervals
        (an interval end beyond what the chain can produce is open: ``<=`` / ``>=``)."""

        def fmt(v: float, lo: float, hi: float, scale: float, spec: str = ".3g") -> str:
            if not math.isfinite(v):
                return "-"
            mid = f"{v * scale:{spec}}"
            a, b = math.isfinite(lo), math.isfinite(hi)
            if a and b:
                return f"{mid} ({lo * scale:{spec}}-{hi * scale:{spec}})"
            if b:
                return f"{mid} (<= {hi * scale:{spec}})"
            if a:
                return f"{mid} (>= {lo * scale:{spec}})"
            return f"{mid} (unbounded)"

        rows = []
        for i in range(self.position.size):
            rows.append(
                (
                    f"{self.position[i] / 0.0254:.2f}",
                    fmt(self.reading[i], self.reading_low[i], self.reading_high[i], 1, ".1f"),
                    fmt(
                        self.wound_on_tension[i],
                        self.wound_on_tension_low[i],
                        self.wound_on_tension_high[i],
                        1e-6,
                    ),
                    fmt(
                        self.surface_pressure[i],
                        self.surface_pressure_low[i],
                        self.surface_pressure_high[i],
                        1e-3,
                    ),
                    self.status[i],
                )
            )
        return rows

    def plot(self, path_prefix: str | Path | None = None) -> list[Any]:
        """Two figures: the readings and the forward curve; the diagnosed WOT and pressure
        across the CMD with their intervals. Saved as ``<prefix>_curve.png`` and
        ``<prefix>_cmd.png`` when ``path_prefix`` is given."""
        import matplotlib.pyplot as plt

        c = self.curve
        fig1, ax = plt.subplots(figsize=(6.4, 4.2))
        ax.plot(c.web_stress / 1e6, c.reading, "o", color="k", label="full forward runs")
        tt = np.geomspace(c.web_stress[0], c.web_stress[-1], 200)
        ax.plot(tt / 1e6, c.reading_at(tt), "-", color="C0", label="monotone interpolant")
        ok = np.isfinite(self.web_tension)
        ax.errorbar(
            self.web_tension[ok] / 1e6,
            self.reading[ok],
            xerr=[
                (self.web_tension - self.web_tension_low)[ok] / 1e6,
                (self.web_tension_high - self.web_tension)[ok] / 1e6,
            ],
            fmt="s",
            color="C3",
            ms=4,
            capsize=3,
            label=f"readings -> tension ({100 * self.confidence:.0f} %)",
        )
        ax.set_xscale("log")
        ax.set_xlabel("web tension at the core T0 [MPa]")
        ax.set_ylabel(f"reading [{c.scale}]")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        fig1.tight_layout()
        fig2, (a1, a2) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
        x = self.position / 0.0254
        for a, mid, lo, hi, scale, label in (
            (
                a1,
                self.wound_on_tension,
                self.wound_on_tension_low,
                self.wound_on_tension_high,
                1e-6,
                "effective wound-on tension [MPa]",
            ),
            (
                a2,
                self.surface_pressure,
                self.surface_pressure_low,
                self.surface_pressure_high,
                1e-3,
                f"interlayer pressure at {self.pressure_depth * 1e3:.1f} mm [kPa]",
            ),
        ):
            a.fill_between(x, lo * scale, hi * scale, color="C0", alpha=0.25, lw=0)
            a.plot(x, mid * scale, "o-", color="C0")
            a.set_ylabel(label, fontsize=9)
            a.grid(alpha=0.3)
        a1.set_title(
            f"diagnosis from {self.readings.source or 'readings'} "
            f"({100 * self.confidence:.0f} % intervals)",
            fontsize=9,
        )
        a2.set_xlabel("CMD position [in]")
        fig2.tight_layout()
        if path_prefix is not None:
            fig1.savefig(f"{path_prefix}_curve.png", dpi=120)
            fig2.savefig(f"{path_prefix}_cmd.png", dpi=120)
        return [fig1, fig2]


#: Units of the diagnosis sentence: system -> tension kind -> (unit, SI value of one unit).
_UNIT_SYSTEMS: dict[str, dict[str, tuple[str, float]]] = {
    "si": {"pressure": ("MPa", 1e6), "force": ("N", 1.0), "force_per_length": ("N/m", 1.0)},
    "us": {
        "pressure": ("psi", 6894.757293168361),
        "force": ("lbf", 4.4482216152605),
        "force_per_length": ("pli", 4.4482216152605 / 0.0254),
    },
}


def _interval_text(lo: float, hi: float, setp: Callable[[float], str], unit: str) -> str:
    """An interval with open ends (NaN) written as a bound."""
    if math.isfinite(lo) and math.isfinite(hi):
        return f"{setp(lo)}-{setp(hi)} {unit}"
    if math.isfinite(hi):
        return f"<= {setp(hi)} {unit}"
    if math.isfinite(lo):
        return f">= {setp(lo)} {unit}"
    return "unbounded"


def set_point_units(kind: str, value: float) -> str:
    """The unit family of a tension set point given as ``(kind, SI value)``: ``"us"`` when
    it is a round number of pli, lbf or psi (2 pli, 6 lbf, 300 psi: to 1e-6, in steps of
    0.05), else ``"si"``. The case keeps the SI value only; a round US value is the trace
    its unit leaves."""
    _, f = _UNIT_SYSTEMS["us"][kind]
    x = value / f
    steps = x / 0.05
    return "us" if x > 0 and abs(steps - round(steps)) < 1e-6 * max(steps, 1.0) else "si"


def _quantiles(readings: Readings, confidence: float, repeatability: float | None) -> FloatArray:
    """Half-width of the confidence interval of each position's mean reading."""
    from scipy.stats import norm, t

    n = readings.count.astype(float)
    out = np.zeros(n.size)
    pooled = readings.pooled_sd
    dof_pooled = int(np.sum(readings.count - 1))
    q = 0.5 + 0.5 * confidence
    for i in range(n.size):
        if n[i] > 1:
            out[i] = t.ppf(q, n[i] - 1) * readings.sd[i] / math.sqrt(n[i])
        elif pooled is not None:
            out[i] = t.ppf(q, dof_pooled) * pooled / math.sqrt(n[i])
        elif repeatability is not None:
            out[i] = norm.ppf(q) * repeatability / math.sqrt(n[i])
    return out


def _perturbed_webs(model: RollModel, unc: Any) -> list[tuple[str, float, Web]]:
    """(name, SD, web at +1 SD) for every uncertain web parameter the case gives."""
    from woundroll.materials.radial_modulus import Pfeiffer

    out = []
    if unc is None:
        return out
    law = model.web.radial_modulus
    if isinstance(law, Pfeiffer):
        if unc.K1:
            out.append(
                ("K1", unc.K1, replace(model.web, radial_modulus=replace(law, K1=law.K1 + unc.K1)))
            )
        if unc.K2:
            out.append(
                ("K2", unc.K2, replace(model.web, radial_modulus=replace(law, K2=law.K2 + unc.K2)))
            )
    sd_h = unc.thickness_sd(model.web.thickness)
    if sd_h:
        out.append(("thickness", sd_h, replace(model.web, thickness=model.web.thickness + sd_h)))
    return out


def saturated_positions(readings: Any) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Positions with a reading at the top (``[0]``) or the bottom (``[1]``) end of the
    instrument's scale (:data:`woundroll.instruments.definitions.READING_RANGES`): saturated
    readings, which bound the roll's hardness from one side only."""
    from woundroll.instruments.definitions import READING_RANGES
    from woundroll.io.readings import SCALES

    n = np.size(readings.position)
    rng = READING_RANGES.get(SCALES.get(readings.scale, ""))
    if rng is None:
        return np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
    pos = np.asarray(readings.position, dtype=float)
    raw_p = np.asarray(readings.raw_position, dtype=float)
    raw_v = np.asarray(readings.raw_value, dtype=float)
    top, bottom = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool)
    for i, p in enumerate(pos):
        v = raw_v[np.isclose(raw_p, p, rtol=0.0, atol=1e-9)]
        top[i] = bool(np.any(v >= rng[1]))
        bottom[i] = bool(np.any(v <= rng[0])) and not top[i]
    return top, bottom


def diagnose(
    case: Case | str | Path,
    readings: Readings | str | Path | None = None,
    *,
    confidence: float = 0.95,
    progress: Progress | None = None,
    verify: bool = True,
) -> Diagnosis:
    """Readings -> effective wound-on tension and near-surface pressure per position.

    Parameters
    ----------
    case : Case or path / bundled name
        Web, core, roll size, taper, nip and instrument; its ``[readings]`` unless
        ``readings`` is given; its ``[uncertainty]`` for the material intervals.
    readings : Readings or a CSV path, optional
    confidence : float
        Two-sided confidence of the intervals (0.5 < c < 1).
    progress : callable, optional
        ``progress(stage, fraction)``; stages "forward curve", "material".
    verify : bool
        Run the full chain once more at the median result and report the interpolant's error.

    Raises
    ------
    InputError
        No readings; readings in a scale the case's instrument does not show; a forward
        curve that is not monotone (the instrument cannot tell the tensions apart).
    """
    case, readings = _diagnosis_inputs(case, readings, confidence)
    model = RollModel.from_case(case, readings.scale)
    repeat = case.readings.repeatability if case.readings is not None else None
    half = _quantiles(readings, confidence, repeat)
    r_mid = readings.mean
    r_lo, r_hi = r_mid - half, r_mid + half
    # forward: the reading over tension, bracketing every interval end
    stage = None if progress is None else (lambda f: progress("forward curve", f))
    curve = forward_curve(model, np.concatenate([r_lo, r_hi]), progress=stage)
    notes: list[str] = []
    _check_monotone(curve, readings.scale)
    # inverse: each position's tension and its scatter interval
    t_mid, t_lo, t_hi, status = _tensions_read(curve, readings, r_lo, r_mid, r_hi, notes)
    _input_notes(case, readings, repeat, notes)
    # material and thickness: first-order sensitivities of ln T0 (module docstring)
    unc = getattr(case, "uncertainty", None)
    sens = _material_sensitivity(model, unc, curve, r_mid, t_mid, progress, notes)
    m_half = _material_half_width(sens, unc, confidence, r_mid.size, notes)
    T, T_lo, T_hi = _combined_interval(t_mid, t_lo, t_hi, m_half)

    wot = lambda t: _affine(curve, t)  # noqa: E731
    P = lambda t: _power(curve, t)  # noqa: E731
    verification: dict[str, Any] = {}
    if verify and np.any(np.isfinite(T)):
        verification = _verify_median(model, curve, T, r_mid)
    if any(p.extrapolated for p in curve.points):
        notes.append(
            "some forward runs extrapolate the roll spring beyond the contact model's reach "
            "(very slack rolls): readings there are less certain"
        )
    return Diagnosis(
        readings=readings,
        position=readings.position,
        reading=r_mid,
        reading_low=r_lo,
        reading_high=r_hi,
        web_tension=T,
        web_tension_low=T_lo,
        web_tension_high=T_hi,
        wound_on_tension=wot(T),
        wound_on_tension_low=wot(T_lo),
        wound_on_tension_high=wot(T_hi),
        surface_pressure=P(T),
        surface_pressure_low=P(T_lo),
        surface_pressure_high=P(T_hi),
        status=status,
        curve=curve,
        confidence=confidence,
        pressure_depth=model.depth,
        case_tension=model.tension,
        material_sensitivity=sens,
        verification=verification,
        notes=tuple(notes),
        set_point=case.winding.tension,
        web_width=model.web.width,
        web_thickness=model.web.thickness,
    )


def _diagnosis_inputs(
    case: Case | str | Path, readings: Readings | str | Path | None, confidence: float
) -> tuple[Case, Readings]:
    """The case and its readings (the case's own [readings] file when none are given)."""
    from woundroll.case import Case, load_case
    from woundroll.io.readings import Readings, read_readings

    if not isinstance(case, Case):
        case = load_case(case)
    if not 0.5 < confidence < 1.0:
        raise InputError(f"must lie between 0.5 and 1, got {confidence!r}", "--confidence")
    if readings is None:
        readings = case.measured_readings
        if readings is None:
            raise InputError("no readings: give [readings] file = ... or --readings", "readings")
    elif not isinstance(readings, Readings):
        readings = read_readings(readings, width=case.web.width, field="--readings")
    return case, readings


def _check_monotone(curve: ForwardCurve, scale: str) -> None:
    """A curve that does not rise with the tension cannot be inverted."""
    if not curve.monotone:
        r = curve.reading
        raise InputError(
            f"the {scale} reading of this roll does not rise monotonically with the "
            f"tension ({', '.join(f'{v:.4g}' for v in r)} over "
            f"{curve.web_stress[0] / 1e6:.3g}-{curve.web_stress[-1] / 1e6:.3g} MPa): the "
            "instrument cannot tell the tensions apart on this roll, the tension is not "
            "identifiable from its readings",
            "readings",
        )


def _tensions_read(
    curve: ForwardCurve,
    readings: Readings,
    r_lo: FloatArray,
    r_mid: FloatArray,
    r_hi: FloatArray,
    notes: list[str],
) -> tuple[FloatArray, FloatArray, FloatArray, tuple[str, ...]]:
    """The tension of each position's mean reading and of its interval ends (NaN: open),
    and each position's status (ok, beyond the curve, saturated)."""
    t_mid = curve.tension_for(r_mid)
    t_lo = curve.tension_for(np.maximum(r_lo, curve.reading[0]))
    t_hi = curve.tension_for(np.minimum(r_hi, curve.reading[-1]))
    # an interval end beyond the curve is unbounded on that side
    t_lo = np.where(r_lo < curve.reading[0], math.nan, t_lo)
    t_hi = np.where(r_hi > curve.reading[-1], math.nan, t_hi)
    # a reading at the scale's end is saturated: the roll is at least that hard (or soft),
    # so it bounds the tension from one side only
    top, bottom = saturated_positions(readings)
    t_hi = np.where(top, math.nan, t_hi)
    t_lo = np.where(bottom, math.nan, t_lo)
    status = tuple(
        "saturated: at least"
        if tp
        else "saturated: at most"
        if bt
        else "below range"
        if m < curve.reading[0]
        else "above range"
        if m > curve.reading[-1]
        else "ok"
        for m, tp, bt in zip(r_mid, top, bottom, strict=True)
    )
    if np.any(top | bottom):
        notes.append(
            f"{int(np.sum(top | bottom))} position(s) read at the scale's end (saturated): "
            "their tension is a bound, the interval open on the saturated side"
        )
    return t_mid, t_lo, t_hi, status


def _input_notes(case: Case, readings: Readings, repeat: float | None, notes: list[str]) -> None:
    """What the diagnosis leaves out of the case and the readings."""
    if case.winding.thickness_profile is not None:
        notes.append(
            "each position is read as its own 1D roll at the nominal thickness; the case's "
            "thickness profile is not used here"
        )
    if not readings.has_scatter and repeat is None:
        notes.append(
            "no repeated readings and no readings.repeatability: the intervals hold the "
            "material uncertainty only"
        )


def _material_sensitivity(
    model: RollModel,
    unc: Any,
    curve: ForwardCurve,
    r_mid: FloatArray,
    t_mid: FloatArray,
    progress: Progress | None,
    notes: list[str],
) -> dict[str, Any]:
    """Per uncertain input: its SD and d ln T0 / d input at each position's reading (a
    forward curve on the web shifted by one SD, same reading)."""
    sens: dict[str, Any] = {}
    perturbed = _perturbed_webs(model, unc)
    for k, (name, sd, web) in enumerate(perturbed):
        if progress is not None:
            progress("material", k / len(perturbed))
        c2 = forward_curve(model.with_web(web), tensions=_bracket(curve, r_mid))
        if not c2.monotone:
            notes.append(f"{name} + 1 SD: forward curve not monotone, sensitivity skipped")
            continue
        # same reading, shifted material: how far does the tension move
        t2 = _tension_extrapolated(c2, r_mid)
        sens[name] = (sd, (np.log(t2) - np.log(t_mid)) / sd)
    if progress is not None and perturbed:
        progress("material", 1.0)
    return sens


def _material_half_width(
    sens: dict[str, Any], unc: Any, confidence: float, n: int, notes: list[str]
) -> FloatArray:
    """Half-width in ln T0 of the material interval: first-order propagation of the
    sensitivities (K1 and K2 with their correlation)."""
    from scipy.stats import norm

    z = norm.ppf(0.5 + 0.5 * confidence)
    var = np.zeros(n)
    if sens:
        names = list(sens)
        corr = {("K1", "K2"): getattr(unc, "K1_K2_correlation", 0.0)}
        for a in names:
            sa, da = sens[a]
            var += (da * sa) ** 2
        for (a, b), rho in corr.items():
            if a in sens and b in sens and rho:
                var += 2 * rho * sens[a][1] * sens[a][0] * sens[b][1] * sens[b][0]
        notes.append(
            "material intervals: first-order propagation of "
            + ", ".join(f"{n} (SD {sens[n][0]:.3g})" for n in names)
        )
    return z * np.sqrt(np.maximum(var, 0.0))


def _combined_interval(
    t_mid: FloatArray, t_lo: FloatArray, t_hi: FloatArray, m_half: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The scatter interval and the material half-width combined in quadrature in ln T0."""
    ln_mid = np.log(t_mid)
    ln_lo = ln_mid - np.sqrt((ln_mid - np.log(t_lo)) ** 2 + m_half**2)
    ln_hi = ln_mid + np.sqrt((np.log(t_hi) - ln_mid) ** 2 + m_half**2)
    return np.exp(ln_mid), np.exp(ln_lo), np.exp(ln_hi)


def _verify_median(
    model: RollModel, curve: ForwardCurve, T: FloatArray, r_mid: FloatArray
) -> dict[str, Any]:
    """The full chain once more at the median position's tension, against the curve; with an
    even number of positions the lower of the two middle ones (the position nearest the
    median was a tie there, decided by the last bit of the tensions)."""
    ok = np.flatnonzero(np.isfinite(T))
    if ok.size == 0:
        raise ConvergenceError("no position has a tension to verify")
    i = int(ok[np.argsort(T[ok], kind="stable")[(ok.size - 1) // 2]])
    full = model.evaluate(float(T[i]))
    return {
        "web_tension_Pa": float(T[i]),
        "target_reading": float(r_mid[i]),
        "full_forward_reading": full.reading,
        "error": full.reading - float(r_mid[i]),
        "surface_pressure_interpolated_Pa": float(_power(curve, np.array([T[i]]))[0]),
        "surface_pressure_full_Pa": full.surface_pressure,
    }


def _bracket(curve: ForwardCurve, readings: FloatArray) -> FloatArray:
    """The grid tensions around ``readings`` (one more point on each side, at least 3)."""
    r = curve.reading
    ok = readings[np.isfinite(readings)]
    if ok.size == 0:
        return curve.web_stress
    lo = max(int(np.searchsorted(r, ok.min())) - 2, 0)
    hi = min(int(np.searchsorted(r, ok.max())) + 2, r.size)
    lo, hi = (max(hi - 3, 0), hi) if hi - lo < 3 else (lo, hi)
    return curve.web_stress[lo:hi]


def _tension_extrapolated(curve: ForwardCurve, reading: FloatArray) -> FloatArray:
    """Inverse of the curve; beyond its ends, log-linear extrapolation of its end segments."""
    t = curve.tension_for(np.clip(reading, curve.reading[0], curve.reading[-1]))
    x, r = np.log(curve.web_stress), curve.reading
    lo = reading < r[0]
    hi = reading > r[-1]
    t[lo] = np.exp(x[0] + (reading[lo] - r[0]) * (x[1] - x[0]) / (r[1] - r[0]))
    t[hi] = np.exp(x[-1] + (reading[hi] - r[-1]) * (x[-1] - x[-2]) / (r[-1] - r[-2]))
    return t


def _affine(curve: ForwardCurve, t: FloatArray) -> FloatArray:
    """Wound-on tension at T0 = ``t``: affine in T0 (fit through the grid, exact)."""
    a, b = np.polyfit(curve.web_stress, curve.wound_on_tension, 1)
    return a * np.asarray(t, dtype=float) + b


def _power(curve: ForwardCurve, t: FloatArray) -> FloatArray:
    """Near-surface pressure at T0 = ``t``: monotone interpolant inside the grid, the end
    segments' power law outside."""
    t = np.asarray(t, dtype=float)
    out = np.full(t.size, math.nan)
    ok = np.isfinite(t)
    x, p = np.log(curve.web_stress), curve.surface_pressure
    inside = ok & (t >= curve.web_stress[0]) & (t <= curve.web_stress[-1])
    out[inside] = curve.surface_pressure_at(t[inside])
    if np.all(p > 0):
        lp = np.log(p)
        lo = ok & (t < curve.web_stress[0])
        hi = ok & (t > curve.web_stress[-1])
        out[lo] = np.exp(lp[0] + (np.log(t[lo]) - x[0]) * (lp[1] - lp[0]) / (x[1] - x[0]))
        out[hi] = np.exp(lp[-1] + (np.log(t[hi]) - x[-1]) * (lp[-1] - lp[-2]) / (x[-1] - x[-2]))
    return out
