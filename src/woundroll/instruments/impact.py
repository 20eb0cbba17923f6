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
#: Elements per chunk of the vectorised energy model: its ~8 work arrays (8192 doubles,
#: 64 kB each) stay in the L2 cache, where whole-array temporaries of 1e6 go to memory.
_CHUNK = 8192


def _check_spring_coefficients(a: NDArray[np.float64], b: NDArray[np.float64]) -> None:
    if not (np.isfinite(a.min(initial=0.0)) and np.isfinite(a.max(initial=0.0))) or (
        a.size and a.min() < 0
    ):
        raise InputError(
            "alpha must be finite and >= 0 (the roll spring stiffens)", "roll_spring.alpha"
        )
    if not (np.isfinite(b.min(initial=0.0)) and np.isfinite(b.max(initial=0.0))) or (
        b.size and b.min() < 0
    ):
        raise InputError("beta must be finite and >= 0", "roll_spring.beta")


def _depth_chunk(
    a: NDArray[np.float64],
    b: NDArray[np.float64],
    k: float,
    xi: float,
    xg: float,
    rtol: float,
    out: NDArray[np.float64],
) -> None:
    """The root of {21} for one chunk into ``out``, in place. NaN/inf-free input.

    Start: the quadratic-part bound d_q (module docstring) and, for x_gap >= 0, the cubic
    bound d_c = (-3C / alpha)^(1/3), both exact in their own limit, combined as
    ``(d_q^-2 + d_c^-2)^(-1/2)`` (within 7 % of the root over alpha = 1e6..1e11,
    beta = 1e3..1e7: 5 Newton steps to rounding instead of 6 from the smaller bound). Newton
    from there: f is convex and increasing for d >= 0, so from below the root the first
    step lands above it and the rest decrease monotonically to it. The convergence test
    starts at the third step (none can pass it earlier from a 7 % start)."""
    m = a.size
    A = np.multiply(0.5, b)
    A += 0.5 * k
    B = k * xg
    C = 0.5 * k * (xg * xg - xi * xi)
    # d = -2C / (B + sqrt(B^2 - 4AC))
    d = out
    np.multiply(A, -4.0 * C, out=d)
    d += B * B
    np.sqrt(d, out=d)
    d += B
    np.divide(-2.0 * C, d, out=d)
    f = np.empty(m)
    fp = np.empty(m)
    if xg >= 0.0:  # alpha d^3/3 + C <= f: a second upper bound, sharp for large alpha
        # 1/d^2 = 1/d_q^2 + 1/d_c^2 with 1/d_c^2 = (alpha / (-3C))^(2/3)
        np.multiply(a, -1.0 / (3.0 * C), out=f)
        np.cbrt(f, out=f)
        f *= f
        np.multiply(d, d, out=fp)
        np.reciprocal(fp, out=fp)
        f += fp
        np.sqrt(f, out=f)
        np.reciprocal(f, out=d)
    a3 = a / 3.0
    A2 = np.multiply(2.0, A)
    for it in range(_NEWTON_MAX_ITER):
        # f = ((a/3 d + A) d + B) d + C, f' = (a d + 2A) d + B
        np.multiply(a3, d, out=f)
        f += A
        f *= d
        f += B
        f *= d
        f += C
        np.multiply(a, d, out=fp)
        fp += A2
        fp *= d
        fp += B
        f /= fp
        d -= f
        if it < 2:
            continue
        np.abs(f, out=f)
        np.multiply(d, rtol, out=fp)
        fp += 1e-300
        if np.all(f <= fp):
            return
    raise ConvergenceError(
        f"energy model: Newton did not converge in {_NEWTON_MAX_ITER} iterations "
        f"(largest relative step {np.max(f / d):.2e})"
    )


def _chunked(
    alpha: ArrayLike,
    beta: ArrayLike,
    k: float,
    xi: float,
    xg: float,
    rtol: float,
    rho_scale: float | None,
) -> NDArray[np.float64]:
    a = np.asarray(alpha, dtype=float)
    b = np.asarray(beta, dtype=float)
    _check_spring_coefficients(a, b)
    a, b = np.broadcast_arrays(a, b)
    shape = a.shape
    a, b = a.ravel(), b.ravel()
    out = np.empty(a.size)
    for i in range(0, a.size, _CHUNK):
        j = min(i + _CHUNK, a.size)
        d = out[i:j]
        _depth_chunk(a[i:j], b[i:j], k, xi, xg, rtol, d)
        if rho_scale is not None:  # F(d) / (3.76 g m_s) {22}, in place over d
            f = a[i:j] * d
            f += b[i:j]
            f *= d
            np.multiply(f, rho_scale, out=d)
    return out.reshape(shape)


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

    Evaluated in chunks of :data:`_CHUNK` elements with in-place work arrays (cache-sized:
    benchmarks/bench_impact.py measures it against the whole-array form).

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
    k, xi, xg = float(spring_stiffness), float(release_position), float(contact_position)
    return _chunked(alpha, beta, k, xi, xg, rtol, None)


def rho_energy(alpha: ArrayLike, beta: ArrayLike, instrument: Instrument) -> NDArray[np.float64]:
    """Energy-model reading ``Rho_max = F(d_max)/(3.76 g m_s)`` {22}, vectorised over (alpha, beta).

    Parameters
    ----------
    alpha, beta : float or array [N/m^2], [N/m]
        Roll-spring coefficients {3}.
    instrument : Instrument
        The striker (k_s, m_s, x_in, x_gap, Rho unit).
    """
    return _chunked(
        alpha,
        beta,
        instrument.spring_stiffness,
        instrument.release_position,
        instrument.contact_position,
        4e-16,
        1.0 / (instrument.rho_unit * instrument.mass),
    )


def _energy_max_depth_whole_array(
    alpha: ArrayLike,
    beta: ArrayLike,
    spring_stiffness: float,
    release_position: float,
    contact_position: float,
    *,
    rtol: float = 4e-16,
) -> NDArray[np.float64]:
    """The straightforward whole-array form of :func:`energy_max_depth` (same iteration on
    the full arrays with fresh temporaries): kept as the benchmark's and the tests'
    reference."""
    a = np.asarray(alpha, dtype=float)
    b = np.asarray(beta, dtype=float)
    _check_spring_coefficients(a, b)
    k, xi, xg = float(spring_stiffness), float(release_position), float(contact_position)
    a, b = np.broadcast_arrays(a, b)
    A = 0.5 * (b + k)
    B = k * xg
    C = 0.5 * k * (xg * xg - xi * xi)
    d = (-2.0 * C) / (B + np.sqrt(B * B - 4.0 * A * C))
    if xg >= 0.0:
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


#: Most points kept of an FD history (time, position, velocity, force); a longer contact is
#: decimated by 2 as it goes (:class:`_History`), so memory stays bounded whatever the
#: time step. The default resolution (2000 steps per contact) is kept whole.
_HISTORY_POINTS = 4096


class _History:
    """Every ``stride``-th step of the FD contact; when ``capacity`` points are held, every
    second one is dropped and the stride doubles (bounded memory, streamed). The scalars
    of the impact (peaks, impulse, end point) are computed on every step, not from this."""

    def __init__(self, capacity: int) -> None:
        self.capacity = max(int(capacity), 4)
        self.stride = 1
        self.n = 0
        self.buf = np.empty((4, self.capacity))

    def add(self, step: int, x: float, v: float, f: float) -> None:
        if step % self.stride:
            return
        if self.n == self.capacity:
            kept = self.buf[:, 0 : self.n : 2]  # the steps that are multiples of 2 stride
            self.n = kept.shape[1]
            self.buf[:, : self.n] = kept
            self.stride *= 2
            if step % self.stride:
                return
        self.buf[:, self.n] = (step, x, v, f)
        self.n += 1

    def arrays(self) -> tuple[NDArray[np.float64], ...]:
        return tuple(self.buf[j, : self.n].copy() for j in range(4))


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
    m_s = instrument.mass
    M = m_s + spring.effective_mass
    # free flight (exact) up to the contact at t_c, then the collision
    t_c = math.acos(-instrument.contact_position / instrument.release_position) / instrument.omega
    v_c = instrument.impact_speed
    v0 = v_c if collision == "keep-velocity" else m_s * v_c / M
    dt, T_est = _fd_time_step(instrument, spring.law, M, time_step, steps_per_contact)
    c = _contact_phase(instrument, spring, M, v0, dt, int(50 * T_est / dt) + 100)
    return _impact_result(instrument, spring, M, c, t_c, dt, collision)


def _fd_time_step(
    instrument: Instrument,
    law: Any,
    M: float,
    time_step: float | None,
    steps_per_contact: int,
) -> tuple[float, float]:
    """The time step, and the contact duration estimated from the secant stiffness at the
    energy model's depth (``pi sqrt(M / k)``)."""
    k = instrument.spring_stiffness
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
    return dt, T_est


@dataclass
class _ContactPhase:
    """The FD contact phase: steps taken, the end-of-contact fraction ``s`` of the last
    step, the last two states, the running impulse and peaks, the turning point."""

    i: int
    s: float
    x: float
    x_last: float
    v_now: float
    v_last: float
    f_last: float
    impulse: float
    f_max: float
    a_max: float
    d_max: float
    x_max: float
    hist: _History


def _contact_phase(
    instrument: Instrument, spring: Any, M: float, v0: float, dt: float, max_steps: int
) -> _ContactPhase:
    """Central differences {9} from the contact to the separation (module docstring)."""
    law = spring.law
    m_s, k = instrument.mass, instrument.spring_stiffness
    xg = instrument.contact_position
    m_r = spring.effective_mass
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
    hist = _History(_HISTORY_POINTS)
    loading = True
    d_max = math.nan
    x_max = math.nan
    impulse = 0.0  # trapezoid over the full steps so far
    f_max = 0.0
    a_max = -math.inf
    f_last = x_last = v_last = 0.0
    arg_last = 0.0
    i = 0
    while True:
        d = x - xg
        # the law's depth: d while loading, the unloading curve's afterwards
        arg = d if loading else d_max + (d - d_max) * inv_e2
        Fr = Fs(arg)
        x_next = 2.0 * x - x_prev - dt2M * (k * x + Fr)  # {9} ({8} when m_r = 0)
        if loading and x_next < x:
            # turning point: vertex of the parabola through x_prev, x, x_next
            curv = x_next - 2.0 * x + x_prev
            x_max = x - (x_next - x_prev) ** 2 / (8.0 * curv) if curv < 0 else x
            d_max = x_max - xg
            loading = False
        f_now = (m_s * (Fr if i > 0 else 0.0) - m_r * k * x) / M
        v_now = (x_next - x_prev) / (2.0 * dt)  # central difference (the first: start value)
        if not loading and f_now < 0.0 and i > 0:
            # end of contact: f crosses zero between this step and the one before
            s = f_last / (f_last - f_now) if f_last != f_now else 0.0
            break
        if not loading and arg < 0.0 <= Fr and i > 0:
            # the striker is back above the roll's surface and the law does not turn
            # negative there (beta = 0: F = alpha d^2 >= 0 on both sides of d = 0), so f
            # would never cross zero: the contact ended where the law's depth did
            s = arg_last / (arg_last - arg) if arg_last != arg else 0.0
            break
        if i > 0:
            impulse += 0.5 * (f_now + f_last) * dt
        f_max = max(f_max, f_now)
        a_max = max(a_max, (k * x + f_now) / m_s)
        hist.add(i, x, v_now, f_now)
        f_last, x_last, v_last, arg_last = f_now, x, v_now, arg
        x_prev, x = x, x_next
        i += 1
        if i > max_steps:
            raise ConvergenceError(
                f"impact_fd: contact did not end within {max_steps} steps "
                f"({max_steps * dt:.3g} s); the roll spring may not push the striker back"
            )
    return _ContactPhase(
        i, s, x, x_last, v_now, v_last, f_last, impulse, f_max, a_max, d_max, x_max, hist
    )


def _impact_result(
    instrument: Instrument,
    spring: Any,
    M: float,
    c: _ContactPhase,
    t_c: float,
    dt: float,
    collision: str,
) -> ImpactResult:
    """The exact end point, the histories, the peaks at the refined maximum depth and the
    rebound (the striker alone on its spring after separation, exact)."""
    m_s, k = instrument.mass, instrument.spring_stiffness
    xi, xg = instrument.release_position, instrument.contact_position
    m_r = spring.effective_mass
    v_c = instrument.impact_speed
    # the exact end point, interpolated between the last two steps
    s = c.s
    t_end = t_c + dt * (c.i - 1 + s)
    x_sep = c.x_last + s * (c.x - c.x_last)
    v_sep = c.v_last + s * (c.v_now - c.v_last)
    impulse = c.impulse + 0.5 * c.f_last * s * dt
    step_h, x_h, v_h, f_h = c.hist.arrays()
    t_h = np.concatenate([t_c + dt * step_h, [t_end]])
    x_h = np.concatenate([x_h, [x_sep]])
    v_h = np.concatenate([v_h, [v_sep]])
    f_h = np.concatenate([f_h, [0.0]])
    a_h = (k * x_h + f_h) / m_s
    a_max = max(c.a_max, k * x_sep / m_s)

    # peaks at the refined maximum depth (both are functions of the depth while loading)
    if not math.isfinite(c.d_max):
        raise ConvergenceError("impact_fd: no turning point found")
    F_peak = float(spring.law.force(c.d_max))
    a_peak = (k * c.x_max + F_peak) / M
    f_peak = max((m_s * F_peak - m_r * k * c.x_max) / M, c.f_max)
    a_peak = max(a_peak, a_max)

    # rebound: striker alone on its spring after separation (exact)
    back = math.sqrt(x_sep * x_sep + (m_s / k) * v_sep * v_sep)
    v_reb = math.sqrt(max(v_sep * v_sep + (k / m_s) * (x_sep * x_sep - xg * xg), 0.0))
    return ImpactResult(
        rho=a_peak / instrument.rho_unit,
        peak_deceleration=a_peak,
        peak_g=a_peak / instrument.g,
        peak_force=f_peak,
        max_depth=c.d_max,
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
