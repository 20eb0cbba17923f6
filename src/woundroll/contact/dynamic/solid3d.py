"""The impact in time on the 3D finite-element roll: the paper's own dynamic reference model.

The reference paper's dynamic model is 3D (ABAQUS/Explicit, a VUMAT updating E_r with the
dynamic pressure; Figures 6-10). :mod:`woundroll.contact.dynamic.plane_strain` solves the impact on
the 2D plane-strain roll; this module solves it on the 3D roll of the quasi-static 3D model
(:mod:`woundroll.contact.solid3d.solver`), with everything shared: the mesh and the element
(:func:`~woundroll.contact.solid3d.solver.build_roll3d`,
:class:`~woundroll.contact.solid3d.solver.Roll3D`, the same defaults for the same depth), the
cylindrically orthotropic material with the hypoelastic radial modulus at the element's current
total radial stress, the head of the instrument (:class:`~woundroll.contact.heads.Head`: the
Rho-meter's cylinder, a sphere), the frictionless small-displacement contact along each surface
node's radial line, and the linear solver (:mod:`woundroll.contact.solid3d.linsolve`: PARDISO with
the symbolic analysis done once). What is added is what the 2D dynamic model adds (docs/dynamic.md):

* **Inertia of the roll**: the lumped mass :func:`~woundroll.contact.solid3d.fem.lumped_mass`
  (each element's mass shared by its 8 nodes), density ``web.density``.
* **The striker {1}** on one degree of freedom (mass m_s, spring k_s, released at rest at
  ``-x_in`` {10}-{11}); free flight to ``x_gap`` exact, the integration starts at contact with
  ``v_c`` and the roll at rest in its wound state. Quarter model (head centred on the roll
  width, symmetry planes theta = 0 and z = 0): the striker's mass and spring are divided by 4
  and every force and energy reported is multiplied back.
* **Contact in time**: the gap of a surface node is measured along its radial line to the
  head at the striker's new position, as in the quasi-static 3D model:
  ``g_i = c_i - d / cos(theta_i) - u_r,i`` with ``c_i = (R + lift_i) / cos(theta_i) - R``
  and d the head's depth. It is linear in d and in u_r, so the contact force ``lam_i >= 0``
  (radial, inward on the node) acts on the striker as ``lam_i / cos(theta_i)`` (its work
  conjugate; the quasi-static model reports ``sum f cos``, 1e-4 apart for a Rho-meter
  footprint). The complementarity problem ``lam >= 0, g >= 0, lam g = 0`` of every step is
  solved exactly on a candidate set (as in 2D).
* **Time integration**: implicit Newmark, gamma = 0.6, beta = (gamma + 1/2)^2 / 4 (the 2D
  model's choice and reasons: average acceleration is unstable with this contact); the
  internal force integrated incrementally ``f_int,n+1 = f_int,n + K_t du`` with the moduli at
  the mid-step stress extrapolated from the last increment (the 2D default).
* **Modified Newton (the factorisation reused over steps)**: the step's system
  ``A du = b - S^T lam`` with ``A = K_t + c0 M`` (and the contact LCP) is solved by the
  iteration ``du += A0^-1 (b - S^T lam - A du)`` with a factorisation ``A0`` of an earlier
  step, the contact forces updated in every pass by the LCP of the cached flexibility
  columns ``Z = A0^-1 S^T`` (stale columns only slow the iteration: the residual is the
  exact one), starting from the last step's increment, until the error left (the last
  correction times q / (1 - q), q the passes' observed rate of convergence; the last
  correction itself while q >= 1/2) is below ``newton_rtol`` of the step's increment and the
  gaps are complementary to ``1e-6`` of the depth scale. The passes' displacements are
  Anderson-mixed (memory ``anderson``, :mod:`woundroll.util.anderson`; the history is
  dropped when the factorisation or the columns change). A new factorisation is made when a
  step needs more than ``refactor_after`` passes (the tangent has moved too far); the
  flexibility columns of an older factorisation are recomputed from a step's second pass on
  (``refresh_after`` = 1: stale columns, not the stale tangent, were what kept a step's passes
  going: docs/dynamic.md). With PARDISO the passes' factorisation and solves are in single
  precision (``single_precision``; the residual is the exact double-precision one, so this
  changes the passes' count, not their fixed point). With ``reuse=False`` every step
  factorises in double precision (the reference the test compares with).

Outputs: :class:`woundroll.contact.dynamic.plane_strain.DynamicImpactResult` (the 2D model's
result), with the pressure along the contact axis (elements at theta = 0, z = 0) and on the surface
line z = 0, and ``stats`` (factorisations, solves, passes, seconds).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from woundroll.contact.dynamic import timeloop
from woundroll.contact.dynamic.plane_strain import DynamicImpactResult, DynamicOptions
from woundroll.contact.dynamic.timeloop import ImpactState, Increment, Newmark, Striker
from woundroll.contact.heads import Head
from woundroll.contact.solid3d import linsolve
from woundroll.contact.solid3d.fem import lumped_mass, orthotropic_moduli, stresses
from woundroll.contact.solid3d.solver import Contact3DOptions, Roll3D, build_roll3d
from woundroll.errors import ConvergenceError, InputError
from woundroll.util.anderson import Anderson
from woundroll.util.blas import one_blas_thread

if TYPE_CHECKING:
    from woundroll.instruments import Instrument
    from woundroll.materials.web import Core, Web

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Dynamic3DOptions:
    """Numerical settings of :func:`impact_dynamic3d`.

    Attributes
    ----------
    time_step, steps_per_contact, newmark_gamma, rayleigh_mass, rayleigh_stiffness,
    update_modulus, max_contact_times
        As :class:`woundroll.contact.dynamic.plane_strain.DynamicOptions` (the mass is lumped).
    reuse : bool
        Modified Newton: keep a factorisation over steps (module docstring). False: one
        factorisation per step.
    newton_rtol : float
        Stop the passes of a step when the error left (estimated from the last correction
        and the passes' rate of convergence, module docstring) is below this fraction of
        the step's displacement increment (max norm).
    refactor_after, refresh_after : int
        Passes in a step after which the effective stiffness is factorised anew, and after
        which the cached flexibility columns of an older factorisation are recomputed.
    anderson : int
        Memory of the Anderson mixing of the passes' displacements (0: plain passes).
    single_precision : bool
        Factorise and solve the passes in single precision (PARDISO only; with ``reuse``
        and ``update_modulus``): the passes' residual is exact, so only their count and
        the converged answer within ``newton_rtol`` change (docs/dynamic.md).
    mesh : Contact3DOptions or None
        The quasi-static 3D model's mesh and material settings (its ``n_steps``,
        ``midpoint``, ``predictor`` and ``slip`` do not apply).
    """

    time_step: float | None = None
    steps_per_contact: int = 400
    newmark_gamma: float = 0.6
    rayleigh_mass: float = 0.0
    rayleigh_stiffness: float = 0.0
    update_modulus: bool = True
    max_contact_times: float = 8.0
    reuse: bool = True
    newton_rtol: float = 1e-4
    refactor_after: int = 6
    refresh_after: int = 1
    anderson: int = 6
    single_precision: bool = True
    mesh: Contact3DOptions | None = None

    def __post_init__(self) -> None:
        f = "contact.dynamic_options"
        # the shared settings are checked by the 2D options' rules
        DynamicOptions(
            time_step=self.time_step,
            steps_per_contact=self.steps_per_contact,
            newmark_gamma=self.newmark_gamma,
            rayleigh_mass=self.rayleigh_mass,
            rayleigh_stiffness=self.rayleigh_stiffness,
            max_contact_times=self.max_contact_times,
        )
        if not (math.isfinite(self.newton_rtol) and 0 < self.newton_rtol < 1e-2):
            raise InputError(f"must lie in (0, 0.01), got {self.newton_rtol!r}", f"{f}.newton_rtol")
        for name in ("refactor_after", "refresh_after"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | np.integer) or v < 1:
                raise InputError(f"must be a positive integer, got {v!r}", f"{f}.{name}")
        a = self.anderson
        if isinstance(a, bool) or not isinstance(a, int | np.integer) or a < 0:
            raise InputError(f"must be a whole number >= 0, got {a!r}", f"{f}.anderson")
        if not isinstance(self.single_precision, bool):
            raise InputError(
                f"must be true or false, got {self.single_precision!r}", f"{f}.single_precision"
            )
        if self.mesh is not None and not isinstance(self.mesh, Contact3DOptions):
            raise InputError("must be a Contact3DOptions", "contact.options3d")

    @property
    def newmark_beta(self) -> float:
        return 0.25 * (self.newmark_gamma + 0.5) ** 2

    def as_2d(self) -> DynamicOptions:
        """The shared settings as :class:`DynamicOptions` (what the result reports)."""
        return DynamicOptions(
            time_step=self.time_step,
            steps_per_contact=self.steps_per_contact,
            newmark_gamma=self.newmark_gamma,
            rayleigh_mass=self.rayleigh_mass,
            rayleigh_stiffness=self.rayleigh_stiffness,
            update_modulus=self.update_modulus,
        )

    @classmethod
    def from_2d(
        cls, opts: DynamicOptions, mesh: Contact3DOptions | None = None
    ) -> Dynamic3DOptions:
        """The 3D settings of a case's ``contact.dynamic_options`` (a :class:`DynamicOptions`);
        a consistent mass is an input error (the 3D model's mass is lumped)."""
        if opts.mass != "lumped":
            raise InputError(
                "the 3D dynamic model has a lumped mass only", "contact.dynamic_options.mass"
            )
        if opts.modulus_update != "extrapolated":
            raise InputError(
                "the 3D dynamic model takes E_r at the extrapolated mid-step stress only",
                "contact.dynamic_options.modulus_update",
            )
        return cls(
            time_step=opts.time_step,
            steps_per_contact=opts.steps_per_contact,
            newmark_gamma=opts.newmark_gamma,
            rayleigh_mass=opts.rayleigh_mass,
            rayleigh_stiffness=opts.rayleigh_stiffness,
            update_modulus=opts.update_modulus,
            max_contact_times=opts.max_contact_times,
            mesh=mesh,
        )


class _Effective:
    """The step matrix ``A = (1 + c1 a1) K_t + (c0 + c1 a0) M`` of the roll: its values, its
    products, its (possibly stale) factorisation and the flexibility columns of that
    factorisation for the surface nodes."""

    def __init__(
        self, roll: Roll3D, m: FloatArray, c_k: float, c_m: float, single: bool = False
    ) -> None:
        self.roll = roll
        # the passes' own solver, of an explicit precision when the roll's is PARDISO (of
        # whatever kind): single when asked, else double (exact solves, which the first
        # pass's acceptance relies on); another solver (SuperLU, AMG) is the roll's own
        pardiso = isinstance(roll.solver, linsolve._Pardiso)
        self.single = single and pardiso
        self.solver = (
            linsolve.make_solver("pardiso", roll.asm.pattern, single=self.single)
            if pardiso
            else roll.solver
        )
        self.asm = roll.asm
        self.m = m
        self.c_k, self.c_m = c_k, c_m
        self.K = roll.asm.pattern.copy()  # upper triangle, CSR
        self.A = roll.asm.pattern.copy()
        self.n = roll.asm.n_free
        self.col_of: dict[int, int] = {}  # surface node -> column of Z
        self.Zt = np.zeros((16, self.n))  # Z's columns as rows: contiguous for the products
        self.col_factor = np.zeros(16, dtype=np.int64)  # factorisation each column is of
        self.n_cols = 0
        self.n_factor = self.n_solves = self.n_refresh = 0
        self.t_factor = self.t_solve = self.t_assembly = 0.0
        self.factored_D: FloatArray | None = None

    def set_moduli(self, D: FloatArray) -> None:
        t0 = time.perf_counter()
        kv = self.asm.values(D)
        self.K.data = kv
        av = self.c_k * kv
        av[self.asm.diag_pos] += self.c_m * self.m
        self.A.data = av
        self.D = D
        self.t_assembly += time.perf_counter() - t0

    def _sym(self, U: Any, x: FloatArray) -> FloatArray:
        # symmetric product from the upper triangle (U.T is a CSC view, no copy)
        return U @ x + U.T @ x - U.data[self.asm.diag_pos] * x

    def k_times(self, x: FloatArray) -> FloatArray:
        return self._sym(self.K, x)

    def a_times(self, x: FloatArray) -> FloatArray:
        return self._sym(self.A, x)

    def factor(self) -> None:
        t0 = time.perf_counter()
        self.solver.factor(self.A.data)
        self.t_factor += time.perf_counter() - t0
        self.n_factor += 1
        self.factored_D = self.D

    @property
    def current(self) -> bool:
        """The factorisation is of the current A."""
        return self.factored_D is self.D

    @property
    def exact(self) -> bool:
        """The solves are A's to round-off (current and in double precision)."""
        return self.current and not self.single

    def solve(self, b: FloatArray) -> FloatArray:
        t0 = time.perf_counter()
        x = self.solver.solve(b)
        self.t_solve += time.perf_counter() - t0
        self.n_solves += 1 if b.ndim == 1 else b.shape[1]
        return x

    def columns(self, nodes: NDArray[np.int64], fresh: bool = False) -> NDArray[np.int64]:
        """Columns of Z (``A0^-1`` of a unit inward radial force) of the surface nodes
        ``nodes`` (indices into the surface): computed for those not cached, and with
        ``fresh`` for those cached from an earlier factorisation; returns the column numbers."""
        sr = self.roll.sr
        todo = [
            int(i)
            for i in nodes
            if int(i) not in self.col_of
            or (fresh and self.col_factor[self.col_of[int(i)]] != self.n_factor)
        ]
        if todo:
            rhs = np.zeros((self.n, len(todo)))
            rhs[sr[todo], np.arange(len(todo))] = -1.0
            X = self.solve(rhs).reshape(self.n, len(todo))
            for c, i in enumerate(todo):
                if i not in self.col_of:
                    if self.n_cols == self.Zt.shape[0]:
                        self.Zt = np.vstack([self.Zt, np.zeros_like(self.Zt)])
                        self.col_factor = np.concatenate(
                            [self.col_factor, np.zeros_like(self.col_factor)]
                        )
                    self.col_of[i] = self.n_cols
                    self.n_cols += 1
                self.Zt[self.col_of[i]] = X[:, c]
                self.col_factor[self.col_of[i]] = self.n_factor
            if fresh:
                self.n_refresh += 1
        return np.array([self.col_of[int(i)] for i in nodes], dtype=np.int64)

    def columns_exact(self, cols: NDArray[np.int64]) -> bool:
        return self.exact and bool(np.all(self.col_factor[cols] == self.n_factor))


def _remaining(sizes: list[float]) -> float:
    """The error left after the passes whose corrections were ``sizes`` (max norms). An
    iteration converging linearly at the rate q leaves ``c q / (1 - q)`` after a correction
    c; q is taken as the larger of the last two ratios of successive corrections. Where that
    estimate would exceed c (q >= 1/2: not yet a steady linear convergence) or q is not
    known yet (the first pass), the last correction itself, the test used before
    (docs/dynamic.md)."""
    c = sizes[-1]
    if len(sizes) < 2 or sizes[-2] <= 0:
        return c
    q = c / sizes[-2]
    if len(sizes) > 2 and sizes[-3] > 0:
        q = max(q, sizes[-2] / sizes[-3])
    return c * q / (1.0 - q) if q < 0.5 else c


class _ImpactRoll3D:
    """The 3D roll in the time loop (:class:`woundroll.contact.dynamic.timeloop.FeRoll`):
    the moduli of a step, its modified-Newton solve with the contact (module docstring), the
    roll's Newmark update and its stresses."""

    label = "3D dynamic impact"
    n_stress = 6

    def __init__(
        self,
        roll: Roll3D,
        web: Web,
        head: Head,
        m: FloatArray,
        opts: Dynamic3DOptions,
        nm: Newmark,
        striker: Striker,
        r_out: float,
        depth_scale: float,
    ) -> None:
        self.roll, self.web, self.m, self.opts, self.nm = roll, web, m, opts, nm
        self.striker = striker
        single = opts.single_precision and opts.reuse and opts.update_modulus
        self.eff = _Effective(roll, m, 1.0 + nm.c1 * nm.a1, nm.c0 + nm.c1 * nm.a0, single)
        self.n = roll.asm.n_free
        self.sigma_pre, self.r_centre = roll.sigma_pre, roll.r_centre
        self.elastic = web.radial_unloading is None
        mesh = roll.mesh
        self.r_out, self.head_radius = r_out, head.radius
        self.surface_s = r_out * mesh.theta
        # surface geometry: radial-line gaps g = c - d w - u_r, w = 1 / cos(theta)
        th = roll.surf_theta
        cos_t = np.cos(th)
        lift = head.lift(r_out * np.sin(th), roll.surf_z)
        ok = np.isfinite(lift) & (cos_t > 0)
        self.ok = ok
        self.w = np.where(ok, 1.0 / np.where(ok, cos_t, 1.0), 0.0)
        self.c_gap = np.full(th.size, np.inf)
        self.c_gap[ok] = (r_out + lift[ok]) / cos_t[ok] - r_out
        self.n_contact = th.size
        self.line = np.arange(mesh.theta.size)  # surface nodes on z = 0 (k = 0)
        axis_el = np.flatnonzero((mesh.element_index[1] == 0) & (mesh.element_index[2] == 0))
        self.axis_elements = axis_el[np.argsort(mesh.element_index[0][axis_el])]
        self.tol_gap = 1e-6 * max(float(depth_scale), 1e-9)
        self.u_all = np.zeros(3 * mesh.n_nodes)
        # largest pressure each element has seen at the start (the unloading law's memory)
        p0 = np.maximum(-roll.sigma_pre, 0.0) if web.radial_unloading is not None else None
        self.frozen = self.moduli(roll.sigma_pre, p0) if not opts.update_modulus else None
        self.passes_total = 0
        self.max_passes = 0
        self.du_last: FloatArray | None = None

    def mass_times(self, x: FloatArray) -> FloatArray:
        return self.m * x

    def contact_pressure(self, lam: FloatArray) -> FloatArray:
        return lam[self.line] / self.roll.surf_area[self.line]

    def moduli(self, sigma_r_total: FloatArray, p_hist: FloatArray | None) -> FloatArray:
        """Element moduli at the total radial stress (Roll3D.moduli); with the web's
        unloading law, elements below the largest pressure they have seen take the
        unloading modulus (:mod:`woundroll.materials.unloading`, as the 2D model)."""
        roll, web = self.roll, self.web
        if p_hist is None:
            return roll.moduli(sigma_r_total)
        E_r = web.E_r(sigma_r_total)
        P = -sigma_r_total
        un = web.radial_unloading
        E_r = np.where(P < p_hist * (1.0 - 1e-9), un.modulus_at_pressure(P), E_r)
        return orthotropic_moduli(web, np.clip(E_r, roll.E_floor, roll.E_cap))

    def _set_moduli(self, st: ImpactState, k_step: int) -> FloatArray:
        """The step's moduli (at the extrapolated mid-step stress) in the step matrix; a
        linear material keeps its matrix and factorisation."""
        eff, frozen = self.eff, self.frozen
        if frozen is not None:
            D = frozen
        else:
            D = self.moduli(self.sigma_pre + st.sig[:, 0] + 0.5 * st.dsig_prev_r, st.p_hist)
        if k_step == 1 or (frozen is None and not np.array_equal(D, eff.D)):
            eff.set_moduli(D)
        else:
            D = eff.D
        if k_step == 1:
            eff.factor()
        return D

    def _gaps(self, st: ImpactState, du: FloatArray, dx: float) -> FloatArray:
        sr = self.roll.sr
        return self.c_gap - (st.x + dx - self.striker.xg) * self.w - (st.u[sr] + du[sr])

    def _solve(self, st: ImpactState) -> tuple[FloatArray, float, FloatArray, int]:
        """du, dx, lam of the step with the current A (modified Newton, docstring)."""
        nm, opts, eff, m = self.nm, self.opts, self.eff, self.m
        sr, w, ok = self.roll.sr, self.w, self.ok
        a0, a1, tol_gap = nm.a0, nm.a1, self.tol_gap
        s_eff = self.striker.stiffness(nm)
        a_pred = nm.predicted_acceleration(st.v, st.acc)
        v_pred = nm.predicted_velocity(st.v, st.acc, a_pred)
        b = -st.f_int + m * a_pred
        if a0 > 0 or a1 > 0:
            b = b - a0 * m * v_pred - (a1 * eff.k_times(v_pred) if a1 > 0 else 0.0)
        dx_free = self.striker.free_step(st, nm)
        if not opts.reuse and not eff.current:
            eff.factor()
        # the passes start from the last step's increment (the motion is smooth over a
        # step: ~10 % fewer passes than from zero, docs/history.md 2026-11-27)
        du = np.zeros(self.n) if self.du_last is None else self.du_last.copy()
        lm = st.lam.copy()
        scale_du = 0.0
        sizes: list[float] = []  # the passes' corrections (max norm)
        mix = Anderson(opts.anderson)
        basis = (eff.n_factor, eff.n_refresh)  # what the passes' map depends on
        for it in range(1, 61):
            du_in = du
            if it > opts.refactor_after and not eff.current:
                eff.factor()
            fresh = not opts.reuse or it > opts.refresh_after
            force = np.zeros(self.n)
            force[sr] = -lm
            res = b + force - eff.a_times(du)
            delta = eff.solve(res)
            du = du + delta
            dx = dx_free - float(w @ lm) / s_eff
            g = self._gaps(st, du, dx)
            cand = self.roll._widen((g < tol_gap) | (lm > 0), 1) & ok
            idx = np.flatnonzero(cand)
            change = delta
            exact = eff.exact
            if idx.size:
                cols = eff.columns(idx, fresh=fresh)
                exact = eff.columns_exact(cols)
                W = -eff.Zt[np.ix_(cols, sr[idx])].T
                W = 0.5 * (W + W.T) + np.outer(w[idx], w[idx]) / s_eff
                lam_c = timeloop.lcp(W, g[idx] - W @ lm[idx])
                dl = np.zeros(eff.n_cols)
                dl[cols] = lam_c - lm[idx]
                corr = dl @ eff.Zt[: eff.n_cols]
                change = delta + corr
                du = du + corr
                lm = np.zeros(self.n_contact)
                lm[idx] = lam_c
                dx = dx_free - float(w @ lm) / s_eff
                g = self._gaps(st, du, dx)
            if (eff.n_factor, eff.n_refresh) != basis:
                mix.reset()  # a new map: the history no longer describes it
                basis = (eff.n_factor, eff.n_refresh)
            mixed = mix.step(du_in, du)
            if it > 1:  # the first pass is the step's predictor: nothing to mix yet
                change = mixed - du_in
                du = mixed
                g = self._gaps(st, du, dx)
            scale_du = max(scale_du, float(np.max(np.abs(du))))
            feasible = bool(np.all(g[ok] >= -tol_gap)) and bool(
                np.all(np.abs(g[lm > 0]) <= tol_gap)
            )
            sizes.append(float(np.max(np.abs(change))))
            small = _remaining(sizes) <= opts.newton_rtol * max(scale_du, 1e-300)
            if feasible and (small or (exact and it == 1)):
                return du, dx, lm, it
        raise ConvergenceError(
            "3D dynamic impact: the modified-Newton passes of a step did not converge in 60; "
            "use a smaller time step"
        )

    def _damping_force(self, x: FloatArray) -> FloatArray:
        nm = self.nm
        return nm.a0 * self.m * x + (nm.a1 * self.eff.k_times(x) if nm.a1 > 0 else 0.0)

    def advance(self, st: ImpactState, k_step: int) -> Increment:
        """The step's increment: moduli, solve, the roll's Newmark update, stresses."""
        nm, eff, roll = self.nm, self.eff, self.roll
        D = self._set_moduli(st, k_step)
        du, dx, lam_new, passes = self._solve(st)
        self.du_last = du
        self.passes_total += passes
        self.max_passes = max(self.max_passes, passes)
        acc_new = nm.c0 * du - nm.predicted_acceleration(st.v, st.acc)
        v_new = st.v + nm.dt * ((1.0 - nm.gamma) * st.acc + nm.gamma * acc_new)
        f_int_new = st.f_int + eff.k_times(du)
        damping = None
        if nm.damped:
            damping = (self._damping_force(st.v), self._damping_force(v_new))
        self.u_all[roll.free] = du
        dsig = stresses(D, roll.asm.centre_strains(self.u_all))
        force = self.striker.scale * float(self.w @ lam_new)  # on the striker [N]
        return Increment(du, dx, lam_new, acc_new, v_new, f_int_new, dsig, force, damping)

    def stats(self) -> dict[str, Any]:
        eff = self.eff
        return {
            "factorisations": eff.n_factor,
            "rhs_solved": eff.n_solves,
            "column_refreshes": eff.n_refresh,
            "passes": self.passes_total,
            "max_passes_per_step": self.max_passes,
            "assembly_s": eff.t_assembly,
            "factor_s": eff.t_factor,
            "solve_s": eff.t_solve,
            "mesh_elements": self.roll.mesh.n_elements,
            "reuse": self.opts.reuse,
            "single_precision": eff.single,
        }


def _indent3d_estimate(
    web: Web,
    core: Core,
    r: FloatArray,
    s: FloatArray,
    instrument: Instrument,
    hd: Head,
    opts: Dynamic3DOptions,
    depth_max: float,
) -> tuple[float, float, float]:
    """The energy model's depth on a coarse quasi-static 3D solve to ``depth_max``, the
    roll's secant stiffness F(d)/d there and the cap of the depth scale (``depth_max``)
    (:func:`woundroll.contact.dynamic.timeloop.estimates`)."""
    from woundroll.contact.solid3d.solver import indent3d
    from woundroll.instruments import TabulatedLaw, impact_energy

    mesh_opts = opts.mesh if opts.mesh is not None else Contact3DOptions()
    est = indent3d(
        web,
        core,
        r,
        s,
        head=hd,
        depth_max=depth_max,
        update_modulus=opts.update_modulus,
        options=replace(mesh_opts, n_steps=8),
    )
    law = TabulatedLaw(est.delta, est.force)
    d_est = min(impact_energy(instrument, law).max_depth, float(est.delta[-1]))
    return d_est, float(np.interp(d_est, est.delta, est.force)) / d_est, depth_max


def impact_dynamic3d(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    instrument: Instrument,
    *,
    head: Head | None = None,
    contact_time: float | None = None,
    depth_scale: float | None = None,
    density: float | None = None,
    options: Dynamic3DOptions | None = None,
) -> DynamicImpactResult:
    """The striker hits the 3D FE roll: the impact solved in time (module docstring).

    Parameters
    ----------
    web, core, radius, sigma_r, instrument, density
        As :func:`woundroll.contact.dynamic.plane_strain.impact_dynamic` (``web.width``: the roll's
        width, the head centred on it).
    head : Head, optional
        Default: the instrument's (:meth:`Head.from_instrument`).
    contact_time : float, optional [s]
        Estimated contact duration (sets the time step). Default: from a coarse
        quasi-static 3D solve, ``pi sqrt(m_s / (k_s + F(d)/d))`` at the energy model's depth.
    depth_scale : float, optional [m]
        Expected maximum depth: sizes the mesh as the quasi-static model's ``depth_max``.
        Default: 1.25 x the energy model's depth on the same coarse solve.
    options : Dynamic3DOptions, optional

    Raises
    ------
    InputError
        Bad geometry or options (as :func:`woundroll.contact.solid3d.solver.indent3d`).
    ConvergenceError
        The striker does not leave within ``max_contact_times`` estimated contact times,
        the contact set or the modified-Newton passes do not settle.
    """

    t_start = time.perf_counter()
    opts = options if options is not None else Dynamic3DOptions()
    if not isinstance(opts, Dynamic3DOptions):
        raise InputError("must be a Dynamic3DOptions", "contact.dynamic_options")
    mesh_opts = opts.mesh if opts.mesh is not None else Contact3DOptions()
    hd = head if head is not None else Head.from_instrument(instrument)
    r = np.asarray(radius, dtype=float)
    s = np.asarray(sigma_r, dtype=float)
    rho_roll = timeloop.roll_density(web, density)
    r_out = float(r[-1])
    reach = 0.98 * min(0.5 * hd.radius, 0.25 * (r_out - core.outer_radius))
    to = reach if depth_scale is None else min(float(depth_scale), reach)
    contact_time, depth_scale = timeloop.estimates(
        instrument,
        contact_time,
        depth_scale,
        lambda: _indent3d_estimate(web, core, r, s, instrument, hd, opts, to),
    )
    dt = timeloop.time_step(opts, contact_time)
    roll = build_roll3d(
        web, core, r, s, head=hd, depth_max=min(float(depth_scale), reach), options=mesh_opts
    )
    m = lumped_mass(roll.mesh, rho_roll)[roll.free]
    striker = Striker.of(instrument, 4.0)  # quarter model
    fe = _ImpactRoll3D(roll, web, hd, m, opts, Newmark.of(opts, dt), striker, r_out, depth_scale)
    with one_blas_thread():  # woundroll.util.blas
        run = timeloop.run_impact(fe, contact_time, opts.max_contact_times)
    fields = timeloop.result_fields(run, fe, instrument)
    wall = time.perf_counter() - t_start
    return DynamicImpactResult(
        **fields,
        n_dof=fe.n + 1,
        density=rho_roll,
        solve_time_s=wall,
        options=opts.as_2d(),
        model="3D FE roll (quarter), implicit Newmark, frictionless contact",
        stats=fe.stats(),
    )
