"""The 1.5D impact models: finite differences {4}-{13} and energy conservation {19}-{22}.

Striker: mass m_s on a spring k_s, released at rest at ``x = -x_in`` {10}-{12}, free until it
touches the roll at ``x = x_gap`` {4}. Roll: a spring ``F(d)``, ``d = x_s - x_gap`` {3}, {6},
with an active mass m_r {18} that moves with the striker while they are in contact {7}.

Finite-difference model (:func:`impact_fd`)
    * Free flight {4}, {8}: the central-difference recurrence {8} converges to the harmonic
      solution ``x = -x_in cos(omega t)``; woundroll uses that exact solution up to contact,
      so the contact starts exactly at ``t_c = arccos(-x_gap/x_in)/omega`` with speed
      ``v_c = omega sqrt(x_in^2 - x_gap^2)`` (Rho-meter preset, m_s = 0.12528 kg from {1}:
      1.1409 m/s; NOTES.md's 1.142 m/s uses the rounded 125 g of Table 1). The printed eqs. {12}
      and {13} carry two sign slips that cancel (``a^0`` should be ``+k_s x_in/m_s``, and the
      Taylor start ``x^{-1} = x^0 - dt v^0 + dt^2 a^0/2``); the start used here is the latter.
    * Contact {7}, {9}: ``(m_s + m_r) x'' + k_s x = -F(x - x_gap)``, central differences.
      The switch from m_s to m_s + m_r at contact is a modelling choice (``collision``):
      ``"plastic"`` (default) keeps the momentum, ``v -> m_s v_c/(m_s + m_r)``, and never creates
      energy; ``"keep-velocity"`` keeps the striker's speed as eq. {9} does, which adds
      ``m_r v_c^2/2`` of kinetic energy. With ``m_r = 0`` both are the same.
    * Rebound: after the turning point (maximum depth) the roll unloads along its unloading
      branch (:class:`~woundroll.instruments.roll_side.RollSpring`); the contact ends when the
      contact force on the striker, ``f = (m_s F - m_r k_s x_s)/(m_s + m_r)`` (from {5} with
      the common acceleration), falls to zero, i.e. at ``x_s = x_gap`` for an elastic roll
      without mass. Before the turning point the two bodies move together as in {7} (with
      ``m_r > 0`` f is slightly negative just after contact, which the paper's model ignores;
      it is kept in the impulse). The instant, position and speed of separation are
      interpolated linearly between steps. After separation the striker swings back alone on
      its spring (exact harmonic motion); re-contact with the roll is not modelled.
    * Reported deceleration: what an accelerometer on the striker feels, i.e. spring plus
      contact force, ``a = (k_s x_s + f)/m_s = (k_s x_s + F)/(m_s + m_r)``. Its peak, at maximum
      depth, gives ``rho_fd = a_max/(3.76 g)``.
    * Accuracy: the time step defaults to 1/``steps_per_contact`` of an estimated contact
      duration (``pi sqrt((m_s+m_r)/k)``, k the secant stiffness at the energy-model depth);
      the maximum depth is the vertex of the parabola through the three steps around it, and
      the peaks are evaluated there (they are functions of the depth alone).

Energy model (:func:`energy_max_depth`, :func:`rho_energy`, :func:`impact_energy`)
    ``k_s x_in^2/2 = k_s (x_gap + d)^2/2 + E_roll(d)`` {19}, {20}; for the quadratic spring
    the cubic {21}. ``Rho = F(d_max)/(3.76 g m_s)`` {22}: the roll-spring force only (the
    striker spring's ``k_s (x_gap + d_max)`` is left out, as printed) and no roll mass.
    The root: the left side minus the right side, ``f(d) = alpha d^3/3 + (beta + k_s) d^2/2 +
    k_s x_gap d + k_s (x_gap^2 - x_in^2)/2``, is convex for d >= 0 (alpha, beta >= 0) and
    negative at 0, so it has exactly one positive root. Dropping the cubic term gives a
    quadratic whose positive root (closed form, written without cancellation) bounds it from
    above and is exact for alpha = 0; Newton's method started there decreases monotonically to
    the root. No division by alpha anywhere.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import ConvergenceError, InputError
from woundroll.instruments.definitions import Instrument
from woundroll.instruments.readout import parotester_l, schmidt_r
from woundroll.instruments.roll_side import QuadraticLaw, TabulatedLaw, as_roll_spring

__all__ = [
    "COLLISIONS",
    "EnergyResult",
    "ImpactResult",
    "energy_max_depth",
    "impact_energy",
    "impact_fd",
    "rho_energy",
]

#: Collision models at first contact (see module docstring); the first is the default.
COLLISIONS = ("plastic", "keep-velocity")

_NEWTON_MAX_ITER = 60


# ----------------------------------------------------------------------------------------
# Energy model
# ----------------------------------------------------------------------------------------
def energy_max_depth(
    alpha: ArrayLike,
    beta: ArrayLike,
    spring_stiffness: float,
    release_position: float,
    contact_position: float,
    *,
    rtol: float = 4e-16,
) -> NDArray[np.float64]:
    """Maximum depth d_max [m] of the energy model, the positive root of {21}; vectorised.

    Parameters
    ----------
    alpha, beta : float or array [N/m^2], [N/m]
        Roll-spring coefficients {3}, >= 0, broadcast against each other.
    spring_stiffness : float [N/m]
        Striker spring k_s.
    release_position, contact_position : float [m]
        x_in and x_gap (``|x_gap| < x_in``).
    rtol : float
        Newton stops when every step is below ``rtol * d``.

    Raises
    ------
    InputError
        Negative or non-finite alpha or beta.
    ConvergenceError
        Newton did not reach ``rtol`` in 60 iterations (never seen for finite inputs).
    """
    a = np.asarray(alpha, dtype=float)
    b = np.asarray(beta, dtype=float)
    if not np.all(np.isfinite(a)) or np.any(a < 0):
        raise InputError(
            "alpha must be finite and >= 0 (the roll spring stiffens)", "roll_spring.alpha"
        )
    if not np.all(np.isfinite(b)) or np.any(b < 0):
        raise InputError("beta must be finite and >= 0", "roll_spring.beta")
    k, xi, xg = float(spring_stiffness), float(release_position), float(contact_position)
    a, b = np.broadcast_arrays(a, b)
    # quadratic part: A d^2 + B d + C (C < 0): its positive root bounds the cubic's from above
    A = 0.5 * (b + k)
    B = k * xg
    C = 0.5 * k * (xg * xg - xi * xi)
    d = (-2.0 * C) / (B + np.sqrt(B * B - 4.0 * A * C))
    if xg >= 0.0:  # alpha d^3/3 + C <= f as well: a second upper bound, sharp for large alpha
        with np.errstate(divide="ignore"):
            d_cub = np.where(a > 0, np.cbrt(-3.0 * C / np.where(a > 0, a, 1.0)), np.inf)
        d = np.minimum(d, d_cub)
    a3 = a / 3.0
    for _ in range(_NEWTON_MAX_ITER):
        f = ((a3 * d + A) * d + B) * d + C
        fp = (a * d + 2.0 * A) * d + B
        step = f / fp
        d = d - step
        if np.all(np.abs(step) <= rtol * d + 1e-300):
            return d
    raise ConvergenceError(
        f"energy model: Newton did not converge in {_NEWTON_MAX_ITER} iterations "
        f"(largest relative step {np.max(np.abs(step) / d):.2e})"
    )


def rho_energy(alpha: ArrayLike, beta: ArrayLike, instrument: Instrument) -> NDArray[np.float64]:
    """Energy-model reading ``Rho_max = F(d_max)/(3.76 g m_s)`` {22}, vectorised over (alpha, beta).

    Parameters
    ----------
    alpha, beta : float or array [N/m^2], [N/m]
        Roll-spring coefficients {3}.
    instrument : Instrument
        The striker (k_s, m_s, x_in, x_gap, Rho unit).
    """
    d = energy_max_depth(
        alpha,
        beta,
        instrument.spring_stiffness,
        instrument.release_position,
        instrument.contact_position,
    )
    a = np.asarray(alpha, dtype=float)
    b = np.asarray(beta, dtype=float)
    return (a * d + b) * d / (instrument.rho_unit * instrument.mass)


@dataclass(frozen=True)
class EnergyResult:
    """Energy-model result ({19}-{22}).

    Attributes
    ----------
    max_depth : float [m]
    peak_force : float [N]
        Roll-spring force at maximum depth, F(d_max).
    peak_deceleration : float [m/s^2]
        ``F(d_max)/m_s`` as in {22}.
    rho : float [Rho]
    """

    max_depth: float
    peak_force: float
    peak_deceleration: float
    rho: float


def _energy_depth_law(instrument: Instrument, law: Any) -> float:
    k, xi = instrument.spring_stiffness, instrument.release_position
    xg = instrument.contact_position
    if isinstance(law, QuadraticLaw):
        return float(energy_max_depth(law.alpha, law.beta, k, xi, xg))
    E0 = 0.5 * k * xi * xi

    if isinstance(law, TabulatedLaw):
        # exact on the piecewise-linear curve: find the segment, solve its quadratic
        D = law.depth
        G = 0.5 * k * (xg + D) ** 2 + law.energy(D) - E0
        if G[-1] >= 0:
            # G is negative at 0 and convex (G'' = k + F' > 0): negative up to the root,
            # positive beyond (not monotone when x_gap < 0); the first node with G >= 0
            i = max(int(np.argmax(G >= 0.0)) - 1, 0)
            s_lin = law.force_table[i] + k * (xg + D[i])
            s_quad = 0.5 * (law._slope[i] + k)
            c0 = G[i]
            disc = s_lin * s_lin - 4.0 * s_quad * c0
            return float(D[i] + (-2.0 * c0) / (s_lin + math.sqrt(max(disc, 0.0))))
        # beyond the table: the linear continuation of the last segment
        i = D.size - 2
        s_lin = law.force_table[-1] + k * (xg + D[-1])
        s_quad = 0.5 * (law._slope[i] + k)
        c0 = G[-1]
        return float(D[-1] + (-2.0 * c0) / (s_lin + math.sqrt(s_lin * s_lin - 4 * s_quad * c0)))

    def g(d: float) -> float:
        return float(0.5 * k * (xg + d) ** 2 + law.energy(d) - E0)

    hi = max(xi - xg, 1e-9)
    if g(hi) < 0:  # only if the roll pushes back with negative energy: a bad law
        raise InputError("the roll spring stores negative energy", "roll_spring")
    # g < 0 at 0 and >= 0 at hi: bisection to 1e-13 of the root (no scipy.optimize at import)
    lo = 0.0
    while hi - lo > max(1e-15, 1e-13 * hi):
        mid = 0.5 * (lo + hi)
        if g(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def impact_energy(instrument: Instrument, roll: object) -> EnergyResult:
    """The energy model for one impact ({19}-{22}).

    Parameters
    ----------
    instrument : Instrument
    roll : RollSpring, force law, (alpha, beta) or callable F(d)
        The roll's mass and restitution play no part in the energy model.
    """
    spring = as_roll_spring(roll)
    d = _energy_depth_law(instrument, spring.law)
    F = float(spring.law.force(d))
    a = F / instrument.mass
    return EnergyResult(max_depth=d, peak_force=F, peak_deceleration=a, rho=a / instrument.rho_unit)


# ----------------------------------------------------------------------------------------
# Finite-difference model
# ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ImpactResult:
    """Finite-difference impact ({4}-{13}) and the readings derived from it.

    Scalars are SI; time histories cover the contact phase on the FD grid (time from release),
    with the exact interpolated end point of the contact appended.

    Attributes
    ----------
    rho : float [Rho]
        Peak striker deceleration / 3.76 g (accelerometer reading: spring plus contact force).
    peak_deceleration : float [m/s^2]
    peak_g : float [-]
        Peak deceleration in g.
    peak_force : float [N]
        Peak contact force f.
    max_depth : float [m]
        Maximum of ``x_s - x_gap``.
    impulse : float [N s]
        ``int f dt`` over the contact.
    contact_time : float [s]
    contact_start, contact_end : float [s]
        From release.
    impact_speed : float [m/s]
        Striker speed just before contact.
    rebound_speed : float [m/s]
        Striker speed when it passes the contact position on the way back.
    back_position : float [m]
        How far behind equilibrium the rebound turns.
    rebound_r : float [-]
        Schmidt R for this striker (100 = full rebound).
    rebound_l : float [-]
        Parotester-style L = 1000 v_rebound/v_impact.
    time, position, velocity, deceleration, contact_force : ndarray
        [s], [m], [m/s], [m/s^2], [N].
    time_step : float [s]
    collision : str
    """

    rho: float
    peak_deceleration: float
    peak_g: float
    peak_force: float
    max_depth: float
    impulse: float
    contact_time: float
    contact_start: float
    contact_end: float
    impact_speed: float
    rebound_speed: float
    back_position: float
    rebound_r: float
    rebound_l: float
    time_step: float
    collision: str
    time: NDArray[np.float64] = field(repr=False)
    position: NDArray[np.float64] = field(repr=False)
    velocity: NDArray[np.float64] = field(repr=False)
    deceleration: NDArray[np.float64] = field(repr=False)
    contact_force: NDArray[np.float64] = field(repr=False)


def impact_fd(
    instrument: Instrument,
    roll: object,
    *,
    collision: str = "plastic",
    time_step: float | None = None,
    steps_per_contact: int = 2000,
) -> ImpactResult:
    """Finite-difference solution of one impact ({4}-{13}, module docstring).

    Parameters
    ----------
    instrument : Instrument
        The striker.
    roll : RollSpring, force law, (alpha, beta) or callable F(d)
        The roll side; a bare law means no roll mass and an elastic roll.
    collision : {"plastic", "keep-velocity"}
        Speed right after contact (module docstring). Default "plastic".
    time_step : float, optional [s]
        Fixed time step; default: estimated contact duration / ``steps_per_contact``.
    steps_per_contact : int
        Resolution of the automatic time step (default 2000, shown converged by the tests).

    Raises
    ------
    InputError
        Unknown collision model, a time step that resolves the contact with fewer than 20
        steps, or bad roll data.
    ConvergenceError
        The contact did not end within 50 estimated contact durations.
    """
    if collision not in COLLISIONS:
        raise InputError(
            f"must be one of {', '.join(COLLISIONS)}, got {collision!r}", "tester.collision"
        )
    spring = as_roll_spring(roll)
    law = spring.law
    m_s, k = instrument.mass, instrument.spring_stiffness
    xi, xg = instrument.release_position, instrument.contact_position
    m_r = spring.effective_mass
    M = m_s + m_r
    omega = instrument.omega
    v_c = instrument.impact_speed
    t_c = math.acos(-xg / xi) / omega
    v0 = v_c if collision == "keep-velocity" else m_s * v_c / M

    # time step from an estimated contact duration
    d_est = _energy_depth_law(instrument, law)
    k_sec = float(law.force(d_est)) / d_est + k
    T_est = math.pi * math.sqrt(M / k_sec)
    if time_step is None:
        if (
            isinstance(steps_per_contact, bool)
            or not isinstance(steps_per_contact, numbers.Integral)
            or steps_per_contact < 20
        ):
            raise InputError("must be an integer >= 20", "tester.steps_per_contact")
        dt = T_est / steps_per_contact
    else:
        dt = float(time_step)
        if not math.isfinite(dt) or dt <= 0:
            raise InputError(f"must be positive, got {time_step!r}", "tester.time_step")
        if dt > T_est / 20:
            raise InputError(
                f"{dt:.3g} s is too coarse: the contact lasts about {T_est:.3g} s; use at most "
                f"{T_est / 20:.3g} s (20 steps per contact)",
                "tester.time_step",
            )
    max_steps = int(50 * T_est / dt) + 100

    Fs = getattr(law, "force_scalar", None)
    if Fs is None:

        def Fs(d: float) -> float:
            return float(law.force(d))

    inv_e2 = 1.0 / spring.restitution**2
    dt2M = dt * dt / M
    # start (Taylor, cf. {13}): x^{-1} = x^0 - dt v^0 + dt^2 a^0 / 2, a^0 = -k x_gap / M
    x_start = xg - dt * v0 + 0.5 * dt * dt * (-k * xg / M)
    x_prev = x_start
    x = xg
    xs = [x]
    Fr_list = [0.0]
    loading = True
    d_max = math.nan
    x_max = math.nan
    end = None
    i = 0
    while True:
        d = x - xg
        if loading:
            Fr = Fs(d)
        else:
            Fr = Fs(d_max + (d - d_max) * inv_e2)
        if i > 0:
            Fr_list.append(Fr)
        x_next = 2.0 * x - x_prev - dt2M * (k * x + Fr)  # {9} ({8} when m_r = 0)
        if loading and x_next < x:
            # turning point: vertex of the parabola through x_prev, x, x_next
            curv = x_next - 2.0 * x + x_prev
            x_max = x - (x_next - x_prev) ** 2 / (8.0 * curv) if curv < 0 else x
            d_max = x_max - xg
            loading = False
        if not loading:
            f_now = (m_s * Fr - m_r * k * x) / M
            if f_now < 0.0 and i > 0:
                end = i
                x_after = x_next
                break
        x_prev, x = x, x_next
        xs.append(x)
        i += 1
        if i > max_steps:
            raise ConvergenceError(
                f"impact_fd: contact did not end within {max_steps} steps "
                f"({max_steps * dt:.3g} s); the roll spring may not push the striker back"
            )

    x_arr = np.asarray(xs[: end + 1])
    F_arr = np.asarray(Fr_list[: end + 1])
    n = x_arr.size
    t_arr = t_c + dt * np.arange(n)
    f_arr = (m_s * F_arr - m_r * k * x_arr) / M
    # velocity: central differences (the first from the start condition)
    x_ext = np.concatenate([[x_start], x_arr, [x_after]])
    v_arr = (x_ext[2:] - x_ext[:-2]) / (2.0 * dt)
    # end of contact: f crosses zero between steps end-1 and end
    f1, f2 = f_arr[-2], f_arr[-1]
    s = f1 / (f1 - f2) if f1 != f2 else 0.0
    t_end = t_arr[-2] + s * dt
    x_sep = x_arr[-2] + s * (x_arr[-1] - x_arr[-2])
    v_sep = v_arr[-2] + s * (v_arr[-1] - v_arr[-2])
    # histories: the contact steps, the last one replaced by the exact end point
    t_h = np.concatenate([t_arr[:-1], [t_end]])
    x_h = np.concatenate([x_arr[:-1], [x_sep]])
    v_h = np.concatenate([v_arr[:-1], [v_sep]])
    f_h = np.concatenate([f_arr[:-1], [0.0]])
    a_h = (k * x_h + f_h) / m_s
    # impulse: trapezoid over full steps plus the partial last one
    impulse = float(np.sum(0.5 * (f_arr[1:-1] + f_arr[:-2])) * dt + 0.5 * f1 * s * dt)

    # peaks at the refined maximum depth (both are functions of the depth while loading)
    if not math.isfinite(d_max):
        raise ConvergenceError("impact_fd: no turning point found")
    F_peak = float(law.force(d_max))
    a_peak = (k * x_max + F_peak) / M
    f_peak = max((m_s * F_peak - m_r * k * x_max) / M, float(np.max(f_h)))
    a_peak = max(a_peak, float(np.max(a_h)))

    # rebound: striker alone on its spring after separation (exact)
    back = math.sqrt(x_sep * x_sep + (m_s / k) * v_sep * v_sep)
    v_reb = math.sqrt(max(v_sep * v_sep + (k / m_s) * (x_sep * x_sep - xg * xg), 0.0))
    return ImpactResult(
        rho=a_peak / instrument.rho_unit,
        peak_deceleration=a_peak,
        peak_g=a_peak / instrument.g,
        peak_force=f_peak,
        max_depth=d_max,
        impulse=impulse,
        contact_time=t_end - t_c,
        contact_start=t_c,
        contact_end=t_end,
        impact_speed=v_c,
        rebound_speed=v_reb,
        back_position=back,
        rebound_r=float(schmidt_r(back, xi, xg)),
        rebound_l=float(parotester_l(v_c, v_reb)),
        time_step=dt,
        collision=collision,
        time=t_h,
        position=x_h,
        velocity=v_h,
        deceleration=a_h,
        contact_force=f_h,
    )
