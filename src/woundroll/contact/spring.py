"""Roll stiffness under the striker: the 2D contact model's F(d) -> the roll spring {3}.

The step between the stresses in the roll and the striker's motion. :func:`roll_stiffness`
presses the instrument's head into the roll (:func:`woundroll.contact.indent`) and fits
``F = alpha d^2 + beta d`` {3} over the depths the striker reaches
(:func:`fit_roll_spring`); the result, :class:`RollStiffness`, also gives the fields and the
slip factor {23} at the impact's maximum depth. The single-point pipeline and every CMD
sector of the hardness profile go through here; the nip foundation uses
:func:`fit_roll_spring` alone.

Choices the paper leaves open (docs/contact.md, "Coupling"):

* the fit range: the striker's reach, ``d <= 1.25 d_max`` of the energy model {21};
* alpha, beta >= 0 (non-negative least squares);
* the depth of the contact solution: ``min(1 mm, H / 5)`` first (H the wound thickness;
  for a model with a cheaper guide, ``RollModelEntry.first_depth_from``, the depth where
  the guide's curve would stop when that is deeper); the loading goes on past it by the
  same steps while the fit window 1.25 d_max reaches beyond the computed curve (models that
  cannot extend are solved again, to 1.1 x 1.25 d_max); the window is sampled on the
  interpolated curve, so that the spring (and the reading) is a continuous function of the
  roll's state.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.contact.result import ContactResult, ContactState
from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import INTERLAYER_FRICTION

if TYPE_CHECKING:
    from woundroll.instruments import Instrument
    from woundroll.materials.web import Core, Web

#: Depth of the first contact solution [m] (capped at a fifth of the wound thickness).
FIRST_DEPTH = 1e-3
#: Points sampled on the interpolated F(d) over the striker's reach for the fit (spaced
#: like the contact solver's depth steps, ``(k / n)^1.5``).
WINDOW_SAMPLES = 24
#: The fit window in units of the striker's depth d_max {21}: ``d <= FIT_REACH d_max``.
FIT_REACH = 1.25
#: A deepened solution goes this much beyond the window (d_max moves with the refit).
DEEPEN_MARGIN = 1.1


@dataclass(frozen=True)
class SpringFit:
    """The roll spring {3} fitted to a computed force-depth curve (:func:`fit_roll_spring`).

    Attributes
    ----------
    alpha : float [N/m^2]
    beta : float [N/m]
    r2 : float [-]
        Coefficient of determination over the points used.
    max_rel_residual : float [-]
        Largest |F_fit - F| over the points used, divided by the largest |F| among them.
    fit_depth : float [m]
        Deepest point used in the fit.
    max_depth : float or None [m]
        The energy model's maximum depth {21} with this spring (None without an instrument).
    n_points : int
        Points used.
    extrapolated : bool
        ``max_depth`` lies beyond the deepest computed point: the curve must be computed deeper.
    """

    alpha: float
    beta: float
    r2: float
    max_rel_residual: float
    fit_depth: float
    max_depth: float | None
    n_points: int
    extrapolated: bool

    def to_dict(self) -> dict[str, float | int | bool | None]:
        return {
            "alpha_N_per_m2": self.alpha,
            "beta_N_per_m": self.beta,
            "fit_r2": self.r2,
            "fit_max_rel_residual": self.max_rel_residual,
            "fit_depth_m": self.fit_depth,
            "fit_points": self.n_points,
            "impact_depth_m": self.max_depth,
        }


def _nnls_quadratic(d: NDArray[np.float64], f: NDArray[np.float64]) -> tuple[float, float]:
    """Least squares ``f ~ alpha d^2 + beta d`` with alpha, beta >= 0: the unconstrained
    fit if both are >= 0, else the better of the two one-term fits (the exact non-negative
    solution of a two-column problem)."""
    dm = max(float(d.max()), 1e-300)
    A = np.stack([(d / dm) ** 2, d / dm], axis=1)
    coef = np.linalg.lstsq(A, f, rcond=None)[0]
    if coef[0] < 0 or coef[1] < 0:
        best = None
        for j in (0, 1):
            c = np.zeros(2)
            c[j] = max(float(A[:, j] @ f) / float(A[:, j] @ A[:, j]), 0.0)
            res = float(np.sum((A @ c - f) ** 2))
            if best is None or res < best[0]:
                best = (res, c)
        assert best is not None
        coef = best[1]
    return float(coef[0] / dm**2), float(coef[1] / dm)


#: Relative change of the fit window at which its iteration has settled.
WINDOW_TOL = 1e-6


def _window_fixed_point(
    next_window: Callable[[float], float], window: float, d_end: float
) -> float:
    """The fit window ``W = min(reach d_max(fit over [0, W]), d_end)``, solved.

    A few plain passes settle it on most curves. On a curve that stiffens much faster than
    d^2 (a slack roll: floor-soft outer layers over a hard body, F rising tenfold in the last
    millimetre) the map is decreasing with a slope below -1: a wider window fits a stiffer
    spring and a shallower d_max, and the plain passes jump between two windows (readings
    13.8 and 21.2 Rho on a Table 3 slack sector, by the parity of the pass count, so that
    the reading also moved 3 % with the contact's step count). ``h(W) = next(W) - W`` is
    then decreasing, with ``h(0+) > 0 >= h(d_end)``; its root by bisection is the window.
    """
    for _ in range(20):
        new = next_window(window)
        if abs(new - window) <= WINDOW_TOL * window:
            return new
        window = new
    lo, hi = 0.0, d_end
    if next_window(hi) >= hi * (1 - WINDOW_TOL):
        return hi
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if next_window(mid) > mid:
            lo = mid
        else:
            hi = mid
        if hi - lo <= WINDOW_TOL * hi:
            break
    return 0.5 * (lo + hi)


def fit_roll_spring(
    delta: ArrayLike,
    force: ArrayLike,
    instrument: object | None = None,
    *,
    reach: float = 1.25,
    min_points: int = 4,
    passes: int = 3,
    solve_window: bool = True,
) -> SpringFit:
    """Fit the roll spring ``F = alpha d^2 + beta d`` {3} to a force-depth curve.

    The one place where a computed F(d) (the contact model's, for an instrument head or a
    nip roller) becomes the spring of the 1.5D impact models.

    * Least squares with ``alpha, beta >= 0`` (NNLS): the energy model {21} needs a spring
      that stiffens from zero, and an unconstrained fit of a curve that stiffens faster
      than quadratic returns ``beta < 0`` (seen on hard rolls and with spherical tips).
    * With an ``instrument``, the fit is narrowed to the depths the striker reaches (the
      paper does not say over which range its quadratic was fitted; F(d) is not exactly
      quadratic, so the range matters): the energy model's maximum depth ``d_max`` {21} is
      computed with the fit, and the fit is repeated ``passes`` times on the curve
      interpolated (PCHIP through the origin) at ``WINDOW_SAMPLES`` depths spread over
      ``[0, reach * d_max]`` (capped at the deepest computed point), so that the spring is a
      continuous function of the roll's state; ``min_points`` is kept for compatibility.

    Parameters
    ----------
    delta, force : array [m], [N]
        The computed curve (depths increasing, without the origin or with it).
    instrument : Instrument, optional
        Striker whose reach narrows the fit.
    solve_window : bool
        Solve the window's fixed point (default); False: ``passes`` plain passes only.
    """
    d, f = _loaded_curve(delta, force)
    alpha, beta = _nnls_quadratic(d, f)
    d_max = None
    if instrument is not None:
        alpha, beta, ds, fs, d_max = _fit_over_the_reach(
            d, f, (alpha, beta), instrument, reach, passes, solve_window
        )
    else:
        ds, fs = d, f
    fit = (alpha * ds + beta) * ds
    ss_tot = float(np.sum((fs - fs.mean()) ** 2))
    r2 = 1.0 - float(np.sum((fs - fit) ** 2)) / ss_tot if ss_tot > 0 else 1.0
    return SpringFit(
        alpha=alpha,
        beta=beta,
        r2=r2,
        max_rel_residual=float(np.max(np.abs(fit - fs)) / max(float(np.max(np.abs(fs))), 1e-300)),
        fit_depth=float(ds.max()),
        max_depth=d_max,
        n_points=int(ds.size),
        extrapolated=bool(d_max is not None and d_max > float(d.max()) * (1 + 1e-9)),
    )


def _loaded_curve(
    delta: ArrayLike, force: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The curve's points at positive depth, checked (matching, finite, carrying load)."""
    d = np.asarray(delta, dtype=float).ravel()
    f = np.asarray(force, dtype=float).ravel()
    if d.shape != f.shape or d.size < 2:
        raise InputError("need matching depth and force arrays of >= 2 points", "roll_spring")
    if not (np.all(np.isfinite(d)) and np.all(np.isfinite(f))):
        raise InputError("the force-depth curve has non-finite values", "roll_spring")
    keep = d > 0
    d, f = d[keep], f[keep]
    if d.size < 2 or not np.any(f > 0):
        raise InputError("the force-depth curve carries no load", "roll_spring")
    return d, f


def _fit_over_the_reach(
    d: NDArray[np.float64],
    f: NDArray[np.float64],
    start: tuple[float, float],
    instrument: Any,
    reach: float,
    passes: int,
    solve_window: bool,
) -> tuple[float, float, NDArray[np.float64], NDArray[np.float64], float]:
    """The fit narrowed to the depths the striker reaches (:func:`fit_roll_spring`):
    (alpha, beta, the window's sample depths and forces, the energy model's depth)."""
    from woundroll.instruments.impact import energy_max_depth  # the striker's reach

    def impact_depth(a: float, b: float) -> float:
        return float(
            energy_max_depth(
                a,
                b,
                instrument.spring_stiffness,
                instrument.release_position,
                instrument.contact_position,
            )
        )

    # the window [0, reach d_max] is sampled on the interpolated curve at fixed
    # fractions of its length, so that the fit -- and the reading -- is a continuous
    # function of d_max: selecting the computed points inside the window made the
    # fit jump whenever a point left it (0.3 Rho on PET1 40 N, docs/contact.md)
    from woundroll.util.pchip import pchip  # SciPy's PCHIP without importing scipy.interpolate

    curve = pchip(np.concatenate([[0.0], d]), np.concatenate([[0.0], f]))
    frac = (np.arange(1, WINDOW_SAMPLES + 1) / WINDOW_SAMPLES) ** 1.5
    d_end = float(d.max())

    def fit_over(window: float) -> tuple[float, float]:
        ds = window * frac
        return _nnls_quadratic(ds, curve(ds))

    def next_window(window: float) -> float:
        return min(reach * impact_depth(*fit_over(window)), d_end)

    window = min(reach * impact_depth(*start), d_end)
    for _ in range(passes - 1):
        window = next_window(window)
    if solve_window:
        window = _window_fixed_point(next_window, window, d_end)
    alpha, beta = fit_over(window)
    ds = window * frac
    return alpha, beta, ds, curve(ds), impact_depth(alpha, beta)


#: The loading stops once its depth is this many times the fit window of the curve so far
#: (the plane-strain curve, softer than the CMD-corrected one, so its window is the wider).
#: 1.5 until the loading could be extended; at 1.2 no Table 3 sector needed a second solve.
STOP_MARGIN = 1.25
#: ... and not before this many increments.
STOP_MIN_STEPS = 6
#: The stop is not checked while the depth is below this fraction of the stop depth of the
#: last check (the window moves by a few per cent per increment: a check skipped here can
#: only delay the stop by an increment, which changes no reading).
STOP_SKIP = 0.75


def _past_the_reach(instrument: Any) -> Callable[[NDArray[np.float64], NDArray[np.float64]], bool]:
    """``stop(delta, force)`` for :func:`indent`: True once the depth passes STOP_MARGIN
    times the fit window ``FIT_REACH d_max`` of the curve computed so far.

    A hard roll, where the striker reaches 0.2 mm, was solved to 1 mm, 13 of its 24
    increments beyond any depth the fit uses. The increments up to the stop are the same
    as without it; where the window of the whole curve then reaches past the stop,
    :func:`roll_stiffness` deepens as before.
    """

    last = [0.0]  # the window at the last check

    def stop(delta: NDArray[np.float64], force: NDArray[np.float64]) -> bool:
        if delta.size <= STOP_MIN_STEPS or not np.any(force[1:] > 0):
            return False
        if float(delta[-1]) < STOP_SKIP * STOP_MARGIN * last[0]:
            return False  # far from the stop: the two fits (2.5 ms) are not needed yet
        # two plain passes, the wider window: where the passes cycle the solved window
        # lies between the two (the bisection of every step cost 5 ms, a factorisation's)
        fits = [
            fit_roll_spring(delta, force, instrument, reach=FIT_REACH, passes=p, solve_window=False)
            for p in (1, 2)
        ]
        window = max(FIT_REACH * float(f.max_depth) for f in fits)  # type: ignore[arg-type]
        last[0] = window
        return float(delta[-1]) >= STOP_MARGIN * window

    return stop


@dataclass(eq=False)
class RollStiffness:
    """Roll stiffness under the striker: the contact solution and the spring {3} used.

    Attributes
    ----------
    contact : ContactResult
        The contact model's F(d), a(d) and fields (at its largest depth); on the corrected
        2D path F(d) includes the CMD spreading (the fields are the 2D ones).
    spring : SpringFit
        ``alpha``, ``beta`` fitted over the depths the striker reaches, with the impact's
        maximum depth by the energy model {21}.
    model : str
        The contact model used: ``"2d"`` (plane strain), ``"2d+cmd-spread"`` (plane strain
        corrected for the load carried past the head's ends, the default for cylindrical
        heads, :mod:`woundroll.contact.plane_strain.cmd_spread`) or ``"3d"``.
    cmd_spread : CmdSpread or None
        The correction on the ``"2d+cmd-spread"`` path (L_eff(d), the plane-strain force).
    """

    contact: ContactResult
    spring: SpringFit
    model: str = "2d"
    cmd_spread: Any = None

    @property
    def alpha(self) -> float:
        return self.spring.alpha

    @property
    def beta(self) -> float:
        return self.spring.beta

    @property
    def extrapolated(self) -> bool:
        """The striker goes deeper than the contact model could be solved (half the head
        radius, a quarter of the wound thickness): the spring is extrapolated there."""
        return self.spring.extrapolated

    @property
    def impact_depth(self) -> float:
        """Maximum depth of the impact by the energy model {21} [m]."""
        return float(self.spring.max_depth)  # type: ignore[arg-type]

    @cached_property
    def at_impact(self) -> ContactState:
        """Fields, slip factor {23} and a at the impact's maximum depth (interpolated)."""
        return self.contact.at_depth(min(self.impact_depth, float(self.contact.delta[-1])))

    @property
    def semi_contact_width(self) -> float:
        """Semi-contact width a at the impact's maximum depth [m]."""
        return self.at_impact.semi_contact_width

    def to_dict(self) -> dict[str, Any]:
        """The contact model's JSON (arrays over depth), with the spring actually used.

        ``alpha_N_per_m2`` / ``beta_N_per_m`` are the fit over the striker's reach;
        ``full_range_fit`` is the unconstrained fit over the whole computed curve.
        """
        out = self.contact.to_dict()
        out["full_range_fit"] = {
            "alpha_N_per_m2": out.pop("alpha_N_per_m2"),
            "beta_N_per_m": out.pop("beta_N_per_m"),
            "fit_r2": out.pop("fit_r2"),
            "fit_max_rel_residual": out.pop("fit_max_rel_residual"),
        }
        out.update(self.spring.to_dict())
        out["model"] = self.model
        out["cmd_spread"] = None if self.cmd_spread is None else self.cmd_spread.to_dict()
        at = self.at_impact
        out["semi_contact_width_m"] = at.semi_contact_width
        out["depth_max_m"] = float(self.contact.delta[-1])
        out["at_impact_depth"] = at.to_dict()
        return out

    def plot(self, path: str | Path | None = None) -> list[Any]:
        """F(d) with the fit and a(d), and the slip-factor map {23} at the impact's depth.

        With ``path`` (``contact.png``) the second figure goes to ``contact_slip.png``.
        """
        from woundroll.contact.result import plot_slip_factor

        slip_path = None if path is None else str(path).removesuffix(".png") + "_slip.png"
        return [self.contact.plot(path), plot_slip_factor(self.at_impact, slip_path)]


def roll_stiffness(
    web: Web,
    core: Core,
    radius: ArrayLike,
    sigma_r: ArrayLike,
    instrument: Instrument,
    *,
    depth_max: float | None = None,
    start_depth: float | None = None,
    friction: float = INTERLAYER_FRICTION,
    update_modulus: bool = True,
    options: Any = None,
    field: str = "contact",
    model: str | None = None,
    options3d: Any = None,
) -> RollStiffness:
    """The contact solve that gives the roll spring {3} under the instrument's head.

    Parameters
    ----------
    web, core : Web, Core
    radius, sigma_r : array [m], [Pa]
        The roll's pre-impact radial stress profile (core to surface).
    instrument : Instrument
        Cylindrical head (radius, length) and striker (its reach).
    depth_max : float, optional [m]
        Fixed depth of the contact solution; a striker going deeper is an error. Default:
        ``start_depth`` (or ``min(1 mm, H / 5)``, or the deeper stop of the model's guide,
        :func:`_guided_depth`), the loading extended (or, for a model that cannot extend,
        solved again) while the fit window 1.25 d_max reaches past the computed curve (at
        most four solutions), up to
        the model's reach (just below half the head radius and a quarter of the wound
        thickness H); a striker going deeper still gets the extrapolated fit, flagged by
        :attr:`RollStiffness.extrapolated`.
    start_depth : float, optional [m]
        First depth when ``depth_max`` is not given (a softer variant of a roll already
        solved starts where that one ended).
    friction, update_modulus, options
        As :func:`woundroll.contact.indent`.
    field : str
        Table named in error messages (``"contact"``, ``"profile"``).
    model : str, optional
        The roll model by its name in :data:`woundroll.contact.models.ROLL_MODELS`:
        ``"2d"`` (plane strain), ``"2d+cmd-spread"`` (plane strain corrected for the load
        carried past the head's ends, :mod:`woundroll.contact.plane_strain.cmd_spread`) or ``"3d"``
        (:func:`woundroll.contact.solid3d.solver.indent3d`, any head). None: the registry's
        default for the instrument's head (:data:`~woundroll.contact.models.DEFAULT_ROLL_MODEL`).
    options3d : Contact3DOptions, optional
        Settings of the 3D model.

    Raises
    ------
    InputError
        A non-cylindrical head; bad options or depths (fields under ``field``).
    ConvergenceError
        The striker's depth kept growing past four solutions.
    """
    from woundroll.contact.models import resolve_model

    entry = resolve_model(model, instrument.head_shape, f"{field}.model")
    r = np.asarray(radius, dtype=float)
    reach = _model_reach(instrument, r)
    guided = None
    if depth_max is None and start_depth is None:
        guided = _guided_depth(entry, web, core, r, sigma_r, instrument, friction, update_modulus)
    depth = _first_depth(depth_max, start_depth, reach, guided)
    stop = None
    if depth_max is None and entry.extends:
        stop = _past_the_reach(instrument)
    for _ in range(4):
        try:
            contact, correction = entry.solve(
                web,
                core,
                r,
                sigma_r,
                instrument,
                depth_max=depth,
                friction=friction,
                update_modulus=update_modulus,
                options=options,
                options3d=options3d,
                # past the first depth by the same steps while the striker goes deeper
                **({"stop": stop, "extend_to": reach} if stop is not None else {}),
            )
        except InputError as exc:
            raise exc.at(field) from None
        spring = fit_roll_spring(contact.delta, contact.force, instrument, reach=FIT_REACH)
        solved = float(contact.delta[-1]) if stop is not None else depth  # extended
        if _deep_enough(spring, solved, depth_max, reach, field):
            return RollStiffness(contact, spring, entry.name, correction)
        depth = min(DEEPEN_MARGIN * FIT_REACH * float(spring.max_depth), reach)  # type: ignore[arg-type]
    raise ConvergenceError(
        f"the striker's depth kept growing past the contact solution ({depth * 1e3:.3g} mm) "
        "after 4 solutions"
    )


def _model_reach(instrument: Instrument, r: NDArray[np.float64]) -> float:
    """The contact model's reach: below half the head radius and a quarter of the wound
    thickness."""
    return 0.98 * min(
        0.5 * instrument.head_radius if instrument.head_shape != "punch" else np.inf,
        0.25 * float(r[-1] - r[0]),
    )


def _first_depth(
    depth_max: float | None, start_depth: float | None, reach: float, guided: float | None = None
) -> float:
    """The depth of the first contact solution (:func:`roll_stiffness`): ``depth_max``, else
    ``start_depth``, else FIRST_DEPTH or the guide's deeper stop (:func:`_guided_depth`),
    below the model's reach."""
    if depth_max is not None:
        return depth_max
    if start_depth is not None:
        return min(start_depth, reach)
    return min(max(FIRST_DEPTH, guided or 0.0), 0.8 * reach)


def _guided_depth(
    entry: Any,
    web: Web,
    core: Core,
    r: NDArray[np.float64],
    sigma_r: ArrayLike,
    instrument: Instrument,
    friction: float,
    update_modulus: bool,
) -> float | None:
    """Where the curve of ``entry`` is expected to stop: STOP_MARGIN times the fit window of
    the cheaper model ``entry.first_depth_from`` (its own defaults), or None (no guide, a
    head it cannot take, or it fails: the first depth is then FIRST_DEPTH).

    The 3D model's increments cost 0.2-0.3 s each, its mesh and depth steps are sized
    for the first depth, and its loading goes on past it by the same steps: a first depth
    of 1 mm on a roll where the striker goes 1.1 mm deep cost 24 + 11 increments (the
    extension) or 24 + 24 (a second solve) with the 24 increments of 2026-11; sized by the
    guide (the plane-strain spring corrected for the CMD spreading, 0.2 s, its window within
    a few per cent of 3D's on the Table 2 rolls) the loading takes about n_steps
    increments, on a mesh sized for the depths the curve covers. Only
    deeper than FIRST_DEPTH: on a hard roll the loading stops early on the mesh sized for
    1 mm, as without the guide (docs/contact.md, "3D model").
    """
    if entry.first_depth_from is None:
        return None
    from woundroll.contact.models import ROLL_MODELS

    guide = ROLL_MODELS[entry.first_depth_from]
    if instrument.head_shape not in guide.heads:
        return None
    try:
        spring = roll_stiffness(
            web,
            core,
            r,
            sigma_r,
            instrument,
            friction=friction,
            update_modulus=update_modulus,
            model=guide.name,
        )
    except (InputError, ConvergenceError):
        return None
    return STOP_MARGIN * FIT_REACH * spring.impact_depth


def _deep_enough(
    spring: SpringFit, solved: float, depth_max: float | None, reach: float, field: str
) -> bool:
    """The contact solution, solved to ``solved``, is deep enough for the spring.

    Deepen while the fit window [0, FIT_REACH d_max] is cut off by the solution's depth
    (not only when d_max itself is beyond it): the window then always has its full length
    and the spring stays continuous in the roll's state. Beyond the model's reach (a slack,
    floor-soft roll) the fit is extrapolated (:attr:`RollStiffness.extrapolated` says so);
    at a fixed ``depth_max`` the window is cut there, and a striker going deeper is an
    input error.
    """
    window_inside = FIT_REACH * float(spring.max_depth) <= solved * (1 + 1e-9)  # type: ignore[arg-type]
    if window_inside or (depth_max is None and solved >= reach * (1 - 1e-12)):
        return True
    if depth_max is not None and not spring.extrapolated:
        return True
    if depth_max is not None:
        raise InputError(
            f"the striker reaches {spring.max_depth * 1e3:.3g} mm, deeper than the "
            f"contact solution ({depth_max * 1e3:.3g} mm): raise it or leave it unset",
            f"{field}.depth_max",
        )
    return False
