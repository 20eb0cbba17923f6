"""The time loop of the FE impacts: the striker on a finite-element roll, stepped in time.

The 2D (:mod:`woundroll.contact.dynamic.plane_strain`) and the 3D
(:mod:`woundroll.contact.dynamic.solid3d`) impacts differ in their roll (element, mass,
linear solver, how the contact set is found) and share everything else, which is here:

* the time step from the estimated contact duration (:func:`time_step`) and the Newmark
  constants (:class:`Newmark`: ``gamma``, ``beta = (gamma + 1/2)^2 / 4``, ``c0``, ``c1``);
* the striker {1} on one degree of freedom (:class:`Striker`): released at rest at
  ``-x_in``, its exact free flight to first contact, its mass and spring divided by the
  roll model's symmetry, its predicted step;
* the loop itself (:func:`run_impact`): each step asks the roll for its increment
  (:class:`FeRoll.advance`: moduli, the step's solve with the contact, the roll's Newmark
  update and stresses), then updates the striker, the stresses, the unloading law's memory,
  the energy budget and the histories, keeps the state at the peak deceleration, and stops
  once the striker has left the roll (contact force back to zero, moving away);
* closing the histories at separation (:func:`separation`) and the fields of
  :class:`~woundroll.contact.dynamic.plane_strain.DynamicImpactResult` they give.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import scipy.linalg as la
from numpy.typing import NDArray
from scipy.optimize import nnls

from woundroll.errors import ConvergenceError, InputError

if TYPE_CHECKING:
    from woundroll.instruments import Instrument

FloatArray = NDArray[np.float64]


def estimates(
    instrument: Instrument,
    contact_time: float | None,
    depth_scale: float | None,
    estimate: Callable[[], tuple[float, float, float]],
) -> tuple[float, float]:
    """The contact duration [s] and the depth scale [m] of the mesh where not given, from a
    quasi-static estimate: ``estimate()`` gives the energy model's depth d, the roll's
    secant stiffness F(d)/d there and the largest depth scale the model takes. The
    duration is the half period ``pi sqrt(m_s / (k_s + F(d)/d))``; the depth scale
    ``1.25 d``."""
    if contact_time is None or depth_scale is None:
        d_est, k_roll, cap = estimate()
        if depth_scale is None:
            depth_scale = min(1.25 * d_est, cap)
        if contact_time is None:
            k_sec = k_roll + instrument.spring_stiffness
            contact_time = math.pi * math.sqrt(instrument.mass / k_sec)
    return contact_time, depth_scale


def time_step(opts: Any, contact_time: float) -> float:
    """The step [s]: ``opts.time_step`` or the contact duration / ``steps_per_contact``; an
    input error when it would resolve the contact with fewer than 20 steps."""
    if not (math.isfinite(contact_time) and contact_time > 0):
        raise InputError(f"must be positive, got {contact_time!r}", "contact_time")
    dt = opts.time_step if opts.time_step is not None else contact_time / opts.steps_per_contact
    if dt > contact_time / 20:
        raise InputError(
            f"{dt:.3g} s is too coarse: the contact lasts about {contact_time:.3g} s; use at "
            f"most {contact_time / 20:.3g} s",
            "contact.dynamic_options.time_step",
        )
    return dt


@dataclass(frozen=True)
class Newmark:
    """Implicit Newmark constants of a step ``dt``, with Rayleigh damping ``a0 M + a1 K``."""

    dt: float
    gamma: float
    beta: float
    a0: float
    a1: float

    @classmethod
    def of(cls, opts: Any, dt: float) -> Newmark:
        return cls(dt, opts.newmark_gamma, opts.newmark_beta, opts.rayleigh_mass,
                   opts.rayleigh_stiffness)  # fmt: skip

    @property
    def c0(self) -> float:
        return 1.0 / (self.beta * self.dt * self.dt)

    @property
    def c1(self) -> float:
        return self.gamma / (self.beta * self.dt)

    @property
    def damped(self) -> bool:
        return self.a0 > 0 or self.a1 > 0

    def predicted_acceleration(self, v: Any, acc: Any) -> Any:
        """The part of the new acceleration known at the start: ``a_n+1 = c0 du - this``."""
        return v / (self.beta * self.dt) + (0.5 / self.beta - 1.0) * acc

    def predicted_velocity(self, v: Any, acc: Any, a_pred: Any) -> Any:
        """The part of the new velocity known at the start: ``v_n+1 = this + c1 du``."""
        return v + self.dt * (1.0 - self.gamma) * acc - self.dt * self.gamma * a_pred


@dataclass(frozen=True)
class Striker:
    """The striker {1} at first contact, its mass and spring per roll model (``scale``: the
    symmetry and, in 2D, the head length: a model force times ``scale`` is the head's)."""

    m_s: float
    k_s: float
    xg: float  # position at first contact (from the spring's equilibrium, + towards the roll)
    v_c: float  # speed at first contact
    t_c: float  # time of first contact, from release
    scale: float

    @classmethod
    def of(cls, instrument: Instrument, scale: float) -> Striker:
        xg = instrument.contact_position
        return cls(
            m_s=instrument.mass,
            k_s=instrument.spring_stiffness,
            xg=xg,
            v_c=instrument.impact_speed,
            t_c=math.acos(-xg / instrument.release_position) / instrument.omega,
            scale=scale,
        )

    @property
    def ms(self) -> float:
        return self.m_s / self.scale

    @property
    def ks(self) -> float:
        return self.k_s / self.scale

    def stiffness(self, nm: Newmark) -> float:
        """The striker's effective stiffness in a step, ``k_s + c0 m_s`` (per model)."""
        return self.ks + nm.c0 * self.ms

    def free_step(self, st: ImpactState, nm: Newmark) -> float:
        """The striker's step without contact force."""
        xa_pred = nm.predicted_acceleration(st.xv, st.xa)
        return (-self.ks * st.x + self.ms * xa_pred) / self.stiffness(nm)


@dataclass
class ImpactState:
    """The roll (free DOFs) and the striker at the end of a step."""

    u: FloatArray
    v: FloatArray
    acc: FloatArray
    f_int: FloatArray
    sig: FloatArray  # contact-induced element stresses, radial first
    dsig_prev_r: FloatArray  # the last step's radial stress increment
    p_hist: FloatArray | None  # largest pressure each element has seen (unloading law)
    lam: FloatArray  # contact forces on the surface nodes
    x: float
    xv: float
    xa: float


@dataclass
class Increment:
    """A step of the roll, solved with the contact (:meth:`FeRoll.advance`)."""

    du: FloatArray
    dx: float
    lam: FloatArray
    acc: FloatArray  # the roll's new acceleration, velocity and internal force
    v: FloatArray
    f_int: FloatArray
    dsig: FloatArray
    force: float  # the contact force on the striker [N], + pushing it back
    damping: tuple[FloatArray, FloatArray] | None  # damping forces at the start and the end


class FeRoll(Protocol):
    """What the time loop needs of a finite-element roll."""

    striker: Striker  # per model
    nm: Newmark
    n: int  # free DOFs
    sigma_pre: FloatArray  # pre-impact radial stress at the element centres
    r_centre: FloatArray  # radii of the element centres
    axis_elements: NDArray[np.int64]  # elements on the contact axis, in the order reported
    n_stress: int  # stress components of an element
    n_contact: int  # surface nodes that may touch the head
    surface_s: FloatArray  # arc length from the axis of the reported surface line's nodes
    r_out: float
    head_radius: float
    elastic: bool  # no unloading law
    label: str  # for messages

    def advance(self, st: ImpactState, k_step: int) -> Increment: ...

    def mass_times(self, x: FloatArray) -> FloatArray: ...

    def contact_pressure(self, lam: FloatArray) -> FloatArray: ...


def lcp(W: FloatArray, q: FloatArray) -> FloatArray:
    """``lam >= 0, q + W lam >= 0, lam (q + W lam) = 0`` for SPD ``W`` (NNLS on its Cholesky
    factor; the same method as the quasi-static model's)."""
    W = 0.5 * (W + W.T)
    scale = float(np.max(np.diag(W)))
    try:
        L = la.cholesky(W / scale, lower=True)
    except la.LinAlgError:
        raise ConvergenceError("contact flexibility matrix is not positive definite") from None
    b = -la.solve_triangular(L, q / scale, lower=True)
    try:
        lam, _ = nnls(L.T, b, maxiter=50 * max(q.size, 10))
    except RuntimeError as exc:
        raise ConvergenceError(f"contact active set did not settle ({exc})") from None
    return lam


@dataclass
class _Histories:
    """The striker's and the energies' histories from first contact, one entry a step."""

    times: list[float]
    x: list[float]
    v: list[float]
    decel: list[float]
    force: list[float]
    e_striker: list[float]
    e_kinetic: list[float]
    e_internal: list[float]

    @classmethod
    def at_contact(cls, s: Striker, st: ImpactState, e_in: float) -> _Histories:
        x, xv = st.x, st.xv
        return cls([s.t_c], [x], [xv], [s.k_s * x / s.m_s], [0.0],
                   [e_in + 0.5 * s.k_s * x * x], [0.0], [0.0])  # fmt: skip


def _initial_state(roll: FeRoll, s: Striker, unloading: bool) -> ImpactState:
    """The roll at rest in its wound state, the striker at first contact."""
    n = roll.n
    n_el = roll.sigma_pre.size
    return ImpactState(
        u=np.zeros(n),
        v=np.zeros(n),
        acc=np.zeros(n),
        f_int=np.zeros(n),
        sig=np.zeros((n_el, roll.n_stress)),
        dsig_prev_r=np.zeros(n_el),
        p_hist=np.maximum(-roll.sigma_pre, 0.0) if unloading else None,
        lam=np.zeros(roll.n_contact),
        x=s.xg,
        xv=s.v_c,
        xa=-s.k_s * s.xg / s.m_s,
    )


def _update_striker(st: ImpactState, dx: float, nm: Newmark) -> None:
    """The striker's Newmark update for its step ``dx``."""
    xa_pred = nm.predicted_acceleration(st.xv, st.xa)
    xa_new = nm.c0 * dx - xa_pred
    xv_new = st.xv + nm.dt * ((1.0 - nm.gamma) * st.xa + nm.gamma * xa_new)
    st.x, st.xv, st.xa = st.x + dx, xv_new, xa_new


def _update_roll(st: ImpactState, inc: Increment, sigma_pre: FloatArray) -> None:
    """The roll's state after the increment: stresses, the unloading law's memory, motion."""
    st.sig += inc.dsig
    st.dsig_prev_r = inc.dsig[:, 0]
    if st.p_hist is not None:
        st.p_hist = np.maximum(st.p_hist, -(sigma_pre + st.sig[:, 0]))
    st.u += inc.du
    st.v, st.acc, st.f_int = inc.v, inc.acc, inc.f_int
    st.lam = inc.lam


def run_impact(roll: FeRoll, contact_time: float, max_contact_times: float) -> dict[str, Any]:
    """Step the impact from first contact to separation (module docstring).

    Returns the histories closed at separation (``sep``, a :class:`Separation`), the energy
    histories, the energy input, the energy left in the roll and damped, the peak
    deceleration and the state then (step, pressure along the contact axis, contact
    pressure), and the number of steps.
    """
    s, nm = roll.striker, roll.nm
    dt = nm.dt
    st = _initial_state(roll, s, not roll.elastic)
    e_in = 0.5 * s.m_s * s.v_c * s.v_c
    e_int = 0.0  # work of the roll's internal forces (per model)
    e_damp = 0.0
    h = _Histories.at_contact(s, st, e_in)
    peak = -math.inf
    peak_state: tuple[Any, ...] | None = None
    max_steps = int(max_contact_times * contact_time / dt) + 10
    touched = False
    k_step = 0
    col = roll.axis_elements
    while True:
        k_step += 1
        if k_step > max_steps:
            raise ConvergenceError(
                f"{roll.label}: the striker did not leave the roll within {max_steps} steps "
                f"({max_steps * dt:.3g} s)"
            )
        inc = roll.advance(st, k_step)
        if inc.damping is not None:
            cv_old, cv_new = inc.damping
            e_damp += 0.5 * float((cv_old + cv_new) @ inc.du)
        e_int += 0.5 * float((st.f_int + inc.f_int) @ inc.du)
        _update_striker(st, inc.dx, nm)
        _update_roll(st, inc, roll.sigma_pre)
        force = inc.force
        decel = -st.xa  # accelerometer: (k_s x + f) / m_s
        h.times.append(s.t_c + k_step * dt)
        h.x.append(st.x)
        h.v.append(st.xv)
        h.decel.append(decel)
        h.force.append(force)
        h.e_striker.append(0.5 * s.m_s * st.xv * st.xv + 0.5 * s.k_s * st.x * st.x)
        h.e_kinetic.append(s.scale * 0.5 * float(st.v @ roll.mass_times(st.v)))
        h.e_internal.append(s.scale * e_int)
        if force > 0:
            touched = True
        if decel > peak:
            peak = decel
            p_axis = -(roll.sigma_pre[col] + st.sig[col, 0])
            peak_state = (k_step, p_axis, roll.contact_pressure(st.lam))
        if touched and force <= 0.0 and st.xv < 0.0:
            break
    assert peak_state is not None
    sep = separation(h.times, h.x, h.v, h.decel, h.force, dt, s.k_s, s.m_s, s.xg)
    energies = (np.asarray(h.e_striker), np.asarray(h.e_kinetic), np.asarray(h.e_internal))
    return {
        "sep": sep,
        "energies": energies,
        "energy_in": e_in,
        "energy_roll": float(energies[1][-1] + energies[2][-1]),
        "energy_damped": s.scale * e_damp,
        "peak": peak,
        "peak_state": peak_state,
        "n_steps": k_step,
    }


def result_fields(run: dict[str, Any], roll: FeRoll, instrument: Instrument) -> dict[str, Any]:
    """The :class:`~woundroll.contact.dynamic.plane_strain.DynamicImpactResult` fields of a
    run (all but the model's own: DOFs, density, timings, options, model, stats). The
    pressures along the contact axis are on the roll's ``axis_elements``; the contact
    pressure is reported on the surface within ten maximum depths plus five head radii of
    the axis."""
    s, dt, col = roll.striker, roll.nm.dt, roll.axis_elements
    sep = run["sep"]
    k_pk, p_axis, p_contact = run["peak_state"]
    contact_s = roll.surface_s
    half = contact_s <= 10 * max(float(np.max(sep.x) - s.xg), 1e-6) + 5 * roll.head_radius
    return {
        **sep.striker_fields(
            instrument,
            peak=run["peak"],
            peak_step=k_pk,
            dt=dt,
            t_contact=s.t_c,
            v_contact=s.v_c,
            contact_position=s.xg,
            energy_in=run["energy_in"],
            energy_roll=run["energy_roll"],
            energy_damped=run["energy_damped"],
            elastic=roll.elastic,
            energies=run["energies"],
        ),
        "axis_depth": roll.r_out - roll.r_centre[col],
        "axis_pressure": p_axis,
        "axis_pressure_pre": -roll.sigma_pre[col],
        "contact_s": contact_s[half],
        "contact_pressure": p_contact[half],
        "time_step": dt,
        "n_steps": run["n_steps"],
        "contact_position": s.xg,
    }


@dataclass(frozen=True)
class Separation:
    """The striker's history closed at separation (shared by the 2D and 3D FE impacts)."""

    t: FloatArray
    x: FloatArray
    v: FloatArray
    a: FloatArray
    f: FloatArray
    t_end: float
    x_sep: float
    v_sep: float
    impulse: float
    v_rebound: float
    back: float
    e_striker: float

    def striker_fields(
        self,
        instrument: Instrument,
        *,
        peak: float,
        peak_step: int,
        dt: float,
        t_contact: float,
        v_contact: float,
        contact_position: float,
        energy_in: float,
        energy_roll: float,
        energy_damped: float,
        elastic: bool,
        energies: tuple[FloatArray, FloatArray, FloatArray],
    ) -> dict[str, Any]:
        """The :class:`DynamicImpactResult` fields of the striker's side: the reading, the
        impulse and contact time, the rebound readouts (Schmidt R, Parotester L), the
        energy budget and the histories (2D and 3D FE impacts alike)."""
        from woundroll.instruments.readout import parotester_l, schmidt_r

        xg, v_c = contact_position, v_contact
        es, ek, ei = energies
        return {
            "rho": peak / instrument.rho_unit,
            "peak_deceleration": peak,
            "peak_time": peak_step * dt,
            "peak_force": float(np.max(self.f)),
            "max_depth": float(np.max(self.x) - xg),
            "impulse": self.impulse,
            "contact_time": self.t_end - t_contact,
            "contact_start": t_contact,
            "impact_speed": v_c,
            "rebound_speed": self.v_rebound,
            "restitution": self.v_rebound / v_c,
            "rebound_r": float(schmidt_r(self.back, instrument.release_position, xg)),
            "rebound_l": float(parotester_l(v_c, self.v_rebound)),
            "energy_in": energy_in,
            "energy_roll_left": energy_roll,
            "energy_damped": energy_damped,
            "energy_contact_loss": energy_in - self.e_striker - energy_roll - energy_damped,
            "elastic_rebound": elastic,
            "time": self.t,
            "position": self.x,
            "velocity": self.v,
            "deceleration": self.a,
            "contact_force": self.f,
            "energy_striker": es,
            "energy_roll_kinetic": ek,
            "energy_roll_internal": ei,
        }


def separation(
    times: list[float],
    xs: list[float],
    vs: list[float],
    acc: list[float],
    forces: list[float],
    dt: float,
    k_s: float,
    m_s: float,
    xg: float,
) -> Separation:
    """Close the striker's history where the contact force crosses zero between the last
    two steps (linear in the step), then the impulse (trapezoid), the striker's rebound
    speed at the contact position and how far back it swings, by its spring {1}, and its
    mechanical energy at separation (spring energy counted from the contact position)."""
    T, X, V, A, F = (np.asarray(h, dtype=float) for h in (times, xs, vs, acc, forces))
    f1, f2 = F[-2], F[-1]
    w = f1 / (f1 - f2) if f1 > 0 and f1 != f2 else 1.0
    t_end = float(T[-2] + w * dt)
    x_sep = float(X[-2] + w * (X[-1] - X[-2]))
    v_sep = float(V[-2] + w * (V[-1] - V[-2]))
    T[-1], X[-1], V[-1], F[-1] = t_end, x_sep, v_sep, 0.0
    A[-1] = k_s * x_sep / m_s
    return Separation(
        t=T,
        x=X,
        v=V,
        a=A,
        f=F,
        t_end=t_end,
        x_sep=x_sep,
        v_sep=v_sep,
        impulse=float(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(T))),
        v_rebound=math.sqrt(max(v_sep * v_sep + (k_s / m_s) * (x_sep * x_sep - xg * xg), 0.0)),
        back=math.sqrt(x_sep * x_sep + (m_s / k_s) * v_sep * v_sep),
        e_striker=0.5 * m_s * v_sep * v_sep + 0.5 * k_s * (x_sep * x_sep - xg * xg),
    )


def roll_density(web: Any, density: float | None) -> float:
    """The roll's density [kg/m^3]: ``density`` or the web's."""
    rho_roll = float(web.density if density is None else density)
    if not (math.isfinite(rho_roll) and rho_roll > 0):
        raise InputError(f"must be positive, got {density!r}", "contact.dynamic_density")
    return rho_roll
