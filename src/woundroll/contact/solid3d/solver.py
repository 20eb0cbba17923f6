"""The paper's 3D model of the roll under the head, quasi-static: hypoelastic, FE, any head.

The reference paper's ABAQUS model ("3D ABAQUS Modeling", its Figure 4): the wound roll as a
cylindrically orthotropic continuum between a rigid core and the outer surface, E_r from the
winding model's pre-impact sigma_r and updated with the pressure (its VUMAT, Pfeiffer {2}),
a graded mesh that resolves the contact; symmetry planes theta = 0 and z = 0. Here
quasi-static (the head pressed to increasing depths, as the 2D model of
:mod:`woundroll.contact.plane_strain.solver` does), with the same inputs and the same
:class:`~woundroll.contact.result.ContactResult` output, so the roll spring {3} is fitted the
same way. Choices (docs/contact.md, "3D model"):

* quarter model ``0 <= theta <= pi``, ``0 <= z <= W/2`` (head centred on the roll width,
  free CMD edge at z = W/2, u_theta = 0 on theta = 0 and pi, u_z = 0 on z = 0); the paper's
  locality cut (u_theta = 0 on theta = pi/2, 1/8 of the roll) with ``locality_cut=True``;
* hypoelastic E_r at the element-centre total radial stress, mid-step (two passes) as in 2D;
  G_r_theta, G_r_z from the web (2 E_r by default, Table 2); ``update_modulus=False`` freezes
  E_r (the paper's "no update");
* frictionless contact of a rigid head (:class:`woundroll.contact.heads.Head`) on the outer
  surface nodes, the gap measured along each node's radial line with the head moved by the
  depth (small-displacement contact: the nodes' tangential motion does not change the gap),
  solved exactly in every pass by a primal-dual active set (the active nodes' radial
  displacement prescribed, released where the contact force would pull);
* core: rigid, or radial Winkler springs E_c / r_c per area with u_theta = u_z = 0.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from woundroll.contact.heads import Head
from woundroll.contact.result import ContactResult
from woundroll.contact.solid3d.fem import Assembler3D, orthotropic_moduli, stresses
from woundroll.contact.solid3d.linsolve import make_solver, upper_times
from woundroll.contact.solid3d.mesh import RollMesh3D, build_mesh3d
from woundroll.contact.solid3d.options import Contact3DOptions
from woundroll.contact.stepping import LoadHistory, depth_schedule, result_fields
from woundroll.contact.stepping import check_profile as _check_profile
from woundroll.contact.stepping import check_scalar as _check_scalar
from woundroll.contact.stepping import half_width as _half_width
from woundroll.contact.stepping import solve_lcp as _solve_lcp
from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import INTERLAYER_FRICTION, Core, Web
from woundroll.units import to_si
from woundroll.util.blas import one_blas_thread

FloatArray = NDArray[np.float64]


# kw_only: the base class ends in defaulted fields (ContactResult.factorisations)
@dataclass(frozen=True, eq=False, kw_only=True)
class Contact3DResult(ContactResult):
    """:class:`ContactResult` of the 3D model, with what only 3D has.

    The inherited per-surface-node arrays (``contact_s``, ``contact_pressure``,
    ``contact_pressure_history``) are taken on the head's centre line z = 0; ``half_width``
    is the semi-contact width along the hoop there; ``force_per_length`` is the force divided
    by ``head_length`` (the cylinder's length, or the head's CMD extent for other shapes).
    Element fields cover the whole meshed quarter; ``tau_r_theta`` is the r-theta shear, so
    the inherited slip factor is the in-plane part of {23} as in 2D (``tau_r_z`` beside it).

    Attributes
    ----------
    half_length : ndarray [m]
        Semi-contact extent along the CMD on the line theta = 0, at every depth.
    element_z : ndarray [m]
        CMD coordinate of the element centres (0: the head's centre plane).
    sigma_z, tau_r_z : ndarray [Pa]
        Contact-induced CMD stress and r-z shear at ``depth_max``.
    surface_pressure : ndarray (n_theta, n_z) [Pa]
        Nodal contact pressure over the meshed quarter of the surface at ``depth_max``.
    surface_theta, surface_z : ndarray [rad], [m]
        Node coordinates of ``surface_pressure``.
    head : dict
        The head's shape and sizes (:meth:`Head.to_dict`).
    stats : dict
        Work counters and timings: factorisations, right-hand sides solved, seconds in
        assembly, factorisation and solves.
    """

    half_length: FloatArray
    element_z: FloatArray
    sigma_z: FloatArray
    tau_r_z: FloatArray
    surface_pressure: FloatArray
    surface_theta: FloatArray
    surface_z: FloatArray
    head: dict
    stats: dict


#: Passes of :meth:`Roll3D.solve_pass` after which the cached flexibility columns are
#: recomputed on the current factorisation (the fixed point then converges in a pass or
#: two). (5, 10, 14), not (8, 12): an increment whose stale columns need more than five
#: passes pays one multi-column solve instead, and the next increments start from fresh
#: columns: 0.87-0.89 of the CPU of a 3D reading of PET1 26.7 N / PET2 53.4 N, Rho moved by
#: -6e-7 / +4e-8 of itself (converged to the same gap tolerance along other passes;
#: docs/history.md, 2026-12-07).
REFRESH_PASSES = (5, 10, 14)


class Roll3D:
    """The roll under the head as a 3D FE model: mesh, assembler (stiffness for any
    per-element moduli, :class:`~woundroll.contact.solid3d.fem.Assembler3D`), held DOFs, the
    pre-impact radial stress at the element centres and the linear solver. Built by
    :func:`build_roll3d`; :func:`indent3d` presses the head into it, and a dynamic model can
    reuse it (``asm``, :func:`~woundroll.contact.solid3d.fem.lumped_mass` on ``mesh``)."""

    def __init__(
        self,
        web: Web,
        core: Core,
        r: FloatArray,
        s: FloatArray,
        mesh: RollMesh3D,
        opts: Contact3DOptions,
    ) -> None:
        self.web, self.mesh, self.opts = web, mesh, opts
        #: elements whose interlayer shear reached Coulomb's limit (slip emulation)
        self.slipped: NDArray[np.bool_] | None = None
        n_r, n_t, n_z = mesh.shape
        n_dof = 3 * mesh.n_nodes
        free = np.ones(n_dof, dtype=bool)
        core_nodes = mesh.nodes_where(i=0)
        free[3 * core_nodes + 1] = False
        free[3 * core_nodes + 2] = False
        free[3 * mesh.nodes_where(j=0) + 1] = False  # symmetry plane theta = 0
        free[3 * mesh.nodes_where(j=-1) + 1] = False  # theta = pi (symmetry) or the cut
        free[3 * mesh.nodes_where(k=0) + 2] = False  # symmetry plane z = 0
        if opts.cmd_edges == "fixed":
            free[3 * mesh.nodes_where(k=-1) + 2] = False  # plane-strain slab
        # tributary surface per node of a ring (theta, z), halved on the symmetry planes
        dth, dz = np.diff(mesh.theta), np.diff(mesh.z)
        self.trib_t = 0.5 * (np.concatenate([[0.0], dth]) + np.concatenate([dth, [0.0]]))
        self.trib_z = 0.5 * (np.concatenate([[0.0], dz]) + np.concatenate([dz, [0.0]]))
        area = np.outer(self.trib_z, self.trib_t).ravel()  # order k * n_t + j
        diagonal = None
        if core.rigid:
            free[3 * core_nodes] = False
        else:
            diagonal = np.zeros(n_dof)
            diagonal[3 * core_nodes] = core.stiffness * area  # E_c / r_c x r_c dtheta dz
        self.free = free
        self.asm = Assembler3D(mesh, free, diagonal)
        fi = self.asm.free_index
        self.surface = mesh.surface_nodes
        self.sr = fi[3 * self.surface]  # free index of the surface nodes' u_r
        if np.any(self.sr < 0):
            raise InputError("the outer surface must be free", "radius")
        self.R = float(mesh.r[-1])
        self.surf_area = self.R * area
        J, K = np.meshgrid(np.arange(n_t), np.arange(n_z))  # rows k, columns j
        self.surf_theta = mesh.theta[J.ravel()]
        self.surf_z = mesh.z[K.ravel()]
        rc, tc, zc = mesh.element_centres()
        self.r_centre, self.t_centre, self.z_centre = rc, tc, zc
        self.sigma_pre = np.interp(rc, r, s)
        self.E_floor = opts.min_modulus_ratio * web.E_theta
        self.E_cap = (
            math.inf if opts.max_modulus_ratio is None else opts.max_modulus_ratio * web.E_theta
        )
        self.solver = make_solver(opts.solver, self.asm.pattern)
        #: surface nodes whose flexibility comes from partial solves (:meth:`mark_surface`)
        self.marked: NDArray[np.bool_] | None = None
        self._W_key: tuple[int, bytes] | None = None
        self._W: FloatArray | None = None
        self.n_factor = 0
        self.n_solves = 0
        self._D: FloatArray | None = None
        self._cols: dict[int, FloatArray] = {}
        self._factored = self._exact = False
        self.pcg_iterations = self.n_pcg = self.n_pcg_failed = self.n_partial = 0
        self.t_assembly = self.t_factor = self.t_solve = 0.0
        # neighbours of each surface node in the (theta, z) grid, to widen the candidates
        g = np.arange(n_t * n_z).reshape(n_z, n_t)
        self.grid = g

    def moduli(self, sigma_r_total: FloatArray) -> FloatArray:
        E_r = np.clip(self.web.E_r(sigma_r_total), self.E_floor, self.E_cap)
        D = orthotropic_moduli(self.web, E_r)
        if self.slipped is not None and np.any(self.slipped):
            D[6:8, self.slipped] *= self.opts.slip_shear_fraction  # G_r_theta, G_r_z
        return D

    def factor(self, D: FloatArray) -> None:
        """Assemble K for the material constants ``D`` (kept if unchanged) and make it the
        matrix that :meth:`_solve` solves with.

        Modified Newton (``opts.reuse_factorisation``, off by default): the solves are
        conjugate gradients on the new K preconditioned by the factorisation of an earlier
        one, to the relative residual ``opts.pcg_tol`` (the same answer as a fresh
        factorisation to that tolerance: no accuracy is given up); K is factorised afresh
        when there is no factorisation yet, or as soon as a solve needs more than
        ``opts.pcg_max_iterations`` iterations (then for the rest of the increment)."""
        if self._D is not None and np.array_equal(D, self._D):
            return  # the factorisation and the cached flexibility columns still hold
        self._D = D.copy()
        t0 = time.perf_counter()
        self._U = self.asm.upper(D)
        self.t_assembly += time.perf_counter() - t0
        if self.opts.reuse_factorisation and self._factored:
            self._Ut = self._U.T.tocsr()  # for the products with K (only here)
            self._Ud = self._U.diagonal()
            self._exact = False
            return
        self._refactor()

    def _refactor(self) -> None:
        t1 = time.perf_counter()
        self.solver.factor(self._U.data)
        self.t_factor += time.perf_counter() - t1
        self.n_factor += 1
        self._factored = self._exact = True

    def _matvec(self, x: FloatArray) -> FloatArray:
        return upper_times(self._U, self._Ut, self._Ud, x)

    def _pcg(self, b: FloatArray) -> FloatArray | None:
        """Block conjugate gradients (independent columns) on the current K preconditioned
        by the factorised earlier K; None if it needs more than the allowed iterations."""
        B = b.reshape(b.shape[0], -1)
        tol = self.opts.pcg_tol * np.linalg.norm(B, axis=0)
        x = self.solver.solve(B)
        r = B - self._matvec(x)
        z = self.solver.solve(r)
        p = z.copy()
        rz = np.einsum("ij,ij->j", r, z)
        self.n_solves += 2 * B.shape[1]
        for it in range(self.opts.pcg_max_iterations + 1):
            live = np.linalg.norm(r, axis=0) > tol
            if not np.any(live):
                self.pcg_iterations = max(self.pcg_iterations, it)
                self.n_pcg += it * B.shape[1]
                return x.reshape(b.shape)
            if it == self.opts.pcg_max_iterations:
                break
            q = self._matvec(p)
            pq = np.einsum("ij,ij->j", p, q)
            alpha = np.where(live, rz / np.where(live, pq, 1.0), 0.0)
            x += alpha * p
            r -= alpha * q
            z = self.solver.solve(r)
            self.n_solves += B.shape[1]
            rz_new = np.einsum("ij,ij->j", r, z)
            beta = np.where(live, rz_new / np.where(live, rz, 1.0), 0.0)
            p = z + beta * p
            rz = rz_new
        return None

    def _solve(self, b: FloatArray) -> FloatArray:
        t0 = time.perf_counter()
        x = None if self._exact else self._pcg(b)
        if x is None:
            if not self._exact:
                self.n_pcg_failed += 1
                self.t_solve += time.perf_counter() - t0
                self._refactor()  # too far from the factorised K: factorise this one
                t0 = time.perf_counter()
            x = self.solver.solve(b)
            self.n_solves += 1 if b.ndim == 1 else b.shape[1]
        self.t_solve += time.perf_counter() - t0
        return x

    def _widen(self, mask: NDArray[np.bool_], width: int = 2) -> NDArray[np.bool_]:
        m = mask.reshape(self.grid.shape).copy()
        for _ in range(width):
            w = m.copy()
            w[1:] |= m[:-1]
            w[:-1] |= m[1:]
            w[:, 1:] |= m[:, :-1]
            w[:, :-1] |= m[:, 1:]
            m = w
        return m.ravel()

    def mark_surface(self, nodes: NDArray[np.bool_]) -> None:
        """The surface nodes the contact may reach (before the first factorisation): with
        PARDISO their radial unknowns are ordered last, and the flexibility among them is
        then a partial solve on every factorisation (:meth:`_columns`); the other solvers
        keep the cached whole-solve columns."""
        if self.solver.mark(self.sr[nodes]):
            self.marked = nodes.copy()

    def _columns(self, idx: NDArray[np.int64], refresh: bool = False) -> FloatArray:
        """Flexibility ``W`` (m, m) of the candidate surface nodes ``idx``: inward radial
        displacement per unit inward force. Where every candidate is marked
        (:meth:`mark_surface`), W of the factorised K by a partial solve (exact: one pass of
        :meth:`solve_pass` then solves the contact). Else by whole solves, columns cached; a
        cached column may come from an earlier stiffness (the moduli change a little per
        increment), which only slows the fixed-point iteration of :meth:`solve_pass`;
        ``refresh`` recomputes them all."""
        if self.marked is not None and self._exact and np.all(self.marked[idx]):
            # (not under modified Newton between factorisations: the factor is then an
            # earlier K's, and the cached columns below are solved with the current one)
            key = (self.n_factor, idx.tobytes())
            if self._W_key != key:
                t0 = time.perf_counter()
                W = self.solver.flexibility(self.sr[idx])
                self.t_solve += time.perf_counter() - t0
                self._W, self._W_key = 0.5 * (W + W.T), key
                self.n_partial += 1
            return self._W
        n = self.asm.n_free
        new = [i for i in idx if refresh or i not in self._cols]
        if new:
            rhs = np.zeros((n, len(new)))
            rhs[self.sr[new], np.arange(len(new))] = -1.0  # unit inward radial force
            X = self._solve(rhs)
            for c, i in enumerate(new):
                self._cols[i] = -X[self.sr, c]
        W = np.stack([self._cols[i][idx] for i in idx], axis=1)
        return 0.5 * (W + W.T)

    def solve_pass(
        self,
        bound: FloatArray,
        u_surf: FloatArray,
        f_old: FloatArray,
        guess: NDArray[np.bool_],
        tol: float,
    ) -> tuple[FloatArray, FloatArray]:
        """Displacement increment (free DOFs) and the new radial contact forces on the
        surface nodes (<= 0) for the bounds ``u_r <= bound`` with the factorised K.

        Frictionless contact as the linear complementarity problem on a candidate set (the
        predicted contact widened by one node): ``lam >= 0, g >= 0, lam . g = 0`` with g the
        gaps after the increment ``K du = f(lam) - f_old``. Solved by a fixed-point
        iteration on the candidates' flexibility W (cached, :meth:`_columns`): each pass
        solves the LCP ``g = q + W lam`` with ``q = g_exact - W lam_previous`` (exact
        :func:`_solve_lcp` as in 2D) and one system with the true K gives the exact gaps;
        it stops when the exact gaps satisfy the complementarity to ``tol``. With W from the
        current K one pass is exact; after :data:`REFRESH_PASSES` passes the columns are
        refreshed. A penetration outside the candidates enlarges the set.
        """
        n = self.asm.n_free
        reachable = np.isfinite(bound)
        cand = self._widen(guess | (f_old < 0), 1) & reachable
        lam_all = -f_old.copy()  # inward force magnitudes; du = 0 for the old forces
        du = np.zeros(n)
        for _ in range(12):
            idx = np.flatnonzero(cand)
            W = self._columns(idx)
            lam = lam_all[idx]
            scale, prev = 1.0, None
            for it in range(16):
                gap = bound - (u_surf + du[self.sr])
                g = gap[idx]
                on = lam > 0
                if np.all(g >= -tol) and np.all(np.abs(g[on]) <= tol):
                    break
                if prev is not None:
                    # secant scaling of the cached flexibility: the exact gaps' response to
                    # the last change of the forces (the moduli under the head change by a
                    # similar factor within a step)
                    dl, dg = lam - prev[0], g - prev[1]
                    den = float(dl @ (W @ dl))
                    if den > 0 and float(dg @ dl) > 0:
                        scale = float(np.clip(float(dg @ dl) / den, 0.1, 10.0))
                if it in REFRESH_PASSES and W is not self._W:
                    W, scale = self._columns(idx, refresh=True), 1.0
                prev = (lam.copy(), g.copy())
                Ws = scale * W
                lam = _solve_lcp(Ws, g - Ws @ lam)
                load = np.zeros(n)
                load[self.sr] = -f_old
                load[self.sr[idx]] -= lam
                du = self._solve(load)
            else:
                raise ConvergenceError("the 3D contact forces did not converge in 16 passes")
            lam_all = np.zeros(self.sr.size)
            lam_all[idx] = lam
            gap = bound - (u_surf + du[self.sr])
            bad = ~cand & (gap < -tol)
            if not np.any(bad):
                return du, -lam_all
            cand = (cand | self._widen(bad, 1)) & reachable
        raise ConvergenceError("the 3D contact set did not settle in 12 enlargements")


def _edge(coord: FloatArray, active: NDArray[np.bool_], gap: FloatArray) -> float:
    """Contact extent along one line of surface nodes from its first node, interpolated as
    in 2D (:func:`woundroll.contact.stepping.half_width`: beyond the edge the gap opens
    as (s - a)^(3/2)); the line's end if the contact reaches it."""
    if not active[0]:
        return 0.0
    j = 0
    while j + 1 < active.size and active[j + 1]:
        j += 1
    if j + 2 >= coord.size:
        return float(coord[min(j + 1, coord.size - 1)]) if j + 1 < coord.size else float(coord[j])
    return _half_width(coord, active.astype(float), np.maximum(gap, 0.0), 0, (1,))


def build_roll3d(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    *,
    head: Head,
    depth_max: float,
    options: Contact3DOptions | None = None,
) -> Roll3D:
    """Mesh and assemble the roll for a head pressed to ``depth_max`` (checks as
    :func:`indent3d`, which calls it)."""
    if not isinstance(web, Web):
        raise InputError("must be a woundroll.materials.Web", "web")
    if not isinstance(core, Core):
        raise InputError("must be a woundroll.materials.Core", "core")
    if not isinstance(head, Head):
        raise InputError("must be a woundroll.contact.heads.Head", "head")
    depth_max = _check_scalar(depth_max, "depth_max")
    r, s = _check_profile(web, core, radius, sigma_r)
    opts = options if options is not None else Contact3DOptions()
    if not isinstance(opts, Contact3DOptions):
        raise InputError("must be a Contact3DOptions", "options")
    _check_reach(web, core, float(r[-1]), head, depth_max, opts)
    mesh = _mesh_under_the_head(web, core, float(r[-1]), head, depth_max, opts)
    model = Roll3D(web, core, r, s, mesh, opts)
    return model


def _check_reach(
    web: Web,
    core: Core,
    r_out: float,
    head: Head,
    depth_max: float,
    opts: Contact3DOptions,
    field: str = "depth_max",
) -> None:
    """The head fits the roll's width, the depth (named ``field``: ``depth_max`` or
    ``extend_to``) the model's reach."""
    r_in = core.outer_radius
    z_max = 0.5 * web.width
    if head.cmd_halfwidth >= z_max and opts.cmd_edges == "free":
        raise InputError(
            f"the head ({2 * head.cmd_halfwidth * 1e3:.3g} mm along the CMD) is wider than "
            f"the roll ({web.width * 1e3:.3g} mm)",
            "head.length" if head.shape == "cylinder" else "head.radius",
        )
    if head.shape != "punch" and depth_max >= 0.5 * head.radius:
        raise InputError(
            f"must be below half the head radius ({0.5 * head.radius:g} m), got {depth_max:g} m",
            field,
        )
    if depth_max >= 0.25 * (r_out - r_in):
        raise InputError(
            f"must be below a quarter of the wound thickness "
            f"({0.25 * (r_out - r_in):g} m), got {depth_max:g} m",
            field,
        )


def _mesh_under_the_head(
    web: Web, core: Core, r_out: float, head: Head, depth_max: float, opts: Contact3DOptions
) -> RollMesh3D:
    """The graded mesh sized by the head's geometric footprint at ``depth_max`` (half
    extents a_y, a_z; :class:`Contact3DOptions` may set each size)."""
    r_in = core.outer_radius
    z_max = 0.5 * web.width
    a_y, a_z = head.footprint(depth_max, r_out)
    if a_y >= 0.25 * r_out:
        raise InputError("the head is too large for the roll's radius", "head.radius")
    nf = opts.n_fine
    t_size = opts.tangential_size if opts.tangential_size is not None else a_y / nf
    fine_t = opts.fine_halfwidth if opts.fine_halfwidth is not None else a_y
    surface = opts.surface_size if opts.surface_size is not None else max(web.thickness, a_y / nf)
    if head.shape == "cylinder":
        z_size = opts.axial_size if opts.axial_size is not None else min(a_z / 12.0, a_y / 2.0)
        fine_z = opts.fine_halflength if opts.fine_halflength is not None else a_z + a_y
        if opts.fine_halflength is None:
            z_size, fine_z = _on_the_head_end(a_z, z_size, fine_z, 0.9 * z_max)
    else:
        z_size = opts.axial_size if opts.axial_size is not None else a_z / nf
        fine_z = opts.fine_halflength if opts.fine_halflength is not None else a_z
    fine_z = min(fine_z, 0.9 * z_max)
    for name, size, extent in (
        ("options.tangential_size", t_size, a_y),
        ("options.axial_size", z_size, min(a_z, z_max)),
        ("options.surface_size", surface, a_y),
    ):
        if size > extent / 3.0:
            raise InputError(
                f"{size * 1e3:.3g} mm is too coarse for the contact "
                f"(half extent {extent * 1e3:.3g} mm; at most a third of it)",
                name,
            )
    if surface >= 0.5 * (r_out - r_in):
        raise InputError("is too large for the wound thickness", "options.surface_size")
    return build_mesh3d(
        r_in,
        r_out,
        z_max=z_max,
        theta_max=0.5 * math.pi if opts.locality_cut else math.pi,
        surface_size=surface,
        radial_growth=opts.radial_growth,
        tangential_size=t_size,
        fine_halfwidth=max(fine_t, t_size),
        tangential_growth=opts.tangential_growth,
        axial_size=z_size,
        fine_halflength=max(fine_z, z_size),
        axial_growth=opts.axial_growth,
    )


def _on_the_head_end(a_z: float, size: float, extent: float, limit: float) -> tuple[float, float]:
    """The CMD fine zone's element size and extent with a node on the cylinder's end z = a_z.

    The end is sharp (the Rho-meter's rounding is not published): the head reaches the
    surface nodes with z <= a_z only, so the load-carrying length is that of the last node
    under the head plus its tributary half element. With the nodes spaced from z = 0
    regardless of the end, that length moved by up to an element (1.06 mm of 12.7) with
    the fine zone's extent a_z + a_y, i.e. with ``depth_max``: F(d) of PET2 53.4 N at a 2 cm
    pile 2.4-3 % apart on meshes sized for 1.26 and 1.45 mm, while each mesh parameter
    refined alone moved it by < 0.3 % (docs/history.md). The size is rounded down to fit a
    whole number of elements on [0, a_z] (the node 1e-12 inside the end, so that rounding
    cannot put it outside) and the extent up to a whole number of them; unchanged where the
    zone would pass ``limit``."""
    n_head = max(1, math.ceil(a_z / size - 1e-9))
    h = a_z * (1.0 - 1e-12) / n_head
    fine = h * math.ceil(extent / h - 1e-9)
    if fine > limit:
        return size, extent
    return h, fine


class _Loading3D:
    """The head pressed into the 3D roll increment by increment: the surface nodes' bounds
    under the head, the state between the increments and the frozen stiffness of
    ``update_modulus=False``."""

    def __init__(
        self,
        model: Roll3D,
        head: Head,
        delta: FloatArray,
        friction: float,
        update_modulus: bool,
    ) -> None:
        self.model, self.delta, self.friction = model, delta, friction
        mesh, r_out = model.mesh, model.R
        th = model.surf_theta
        self.cos_t = np.cos(th)
        self.lift = head.lift(r_out * np.sin(th), model.surf_z)
        self.reach = np.isfinite(self.lift) & (self.cos_t > 0)
        n_el = mesh.n_elements
        self.u = np.zeros(model.asm.n_free)
        self.u_prev = np.zeros_like(self.u)
        self.sig = np.zeros((n_el, 6))
        self.f_surf = np.zeros(th.size)
        self.tol = 1e-3 * delta[1]  # gap tolerance, as in 2D
        if model.opts.slip == "reduced-shear":
            model.slipped = np.zeros(n_el, dtype=bool)
        if model.marked is None and model.n_factor == 0:
            # the fine zone holds the contact to about twice depth_max (docs/contact.md);
            # not the loading's last depth: an extended loading orders the unknowns as the
            # direct one does, so that their increments agree to the bit
            depth_max = float(delta[min(model.opts.n_steps, delta.size - 1)])
            model.mark_surface(self.reachable_at(2.0 * depth_max))
        self.D_frozen = model.moduli(model.sigma_pre) if not update_modulus else None
        if self.D_frozen is not None:
            model.factor(self.D_frozen)  # one factorisation for all increments
        self.dsig_last: FloatArray | None = None
        self.u_all = np.zeros(3 * mesh.n_nodes)

    def reachable_at(self, d: float) -> NDArray[np.bool_]:
        """The surface nodes that the head pressed to ``d`` reaches in the undeformed roll,
        and their neighbours (the contact of a compliant roll lies within the
        geometric one as a rule; a candidate outside costs whole solves, not accuracy)."""
        return self.model._widen(self.bound_at(d) < 0.0, 1) & self.reach

    def bound_at(self, d: float) -> FloatArray:
        """The radial displacement at which a surface node meets the head pressed to d."""
        r_out, reach = self.model.R, self.reach
        out = np.full(self.cos_t.size, np.inf)
        out[reach] = (r_out - d + self.lift[reach]) / self.cos_t[reach] - r_out
        return out

    def solve(
        self,
        D: FloatArray,
        bound: FloatArray,
        guess: NDArray[np.bool_],
        on_factor: bool = False,
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The increment with the factorised K: (du, new contact forces, stresses at the
        moduli ``D``). ``on_factor``: the factorisation in place is meant even where it is
        not D's (the lagged predictor's trial; a subclass that factorises in its solve must
        not factorise D then)."""
        model = self.model
        du, f_new = model.solve_pass(bound, self.u[model.sr], self.f_surf, guess, self.tol)
        self.u_all[model.free] = du
        return du, f_new, stresses(D, model.asm.centre_strains(self.u_all))

    def _moduli(self, bound: FloatArray, guess: NDArray[np.bool_], ratio: float) -> FloatArray:
        """The increment's moduli, factorised: mid-step modulus (midpoint rule), the
        mid-step stress from a trial solve on the factorisation of the last increment
        (``predictor="lagged"``, the default: second order, no extra factorisation), from
        the last increment's stress rate (``"rate"``), or from a trial solve at the
        start-of-step modulus (on the first increment, where no factorisation exists yet,
        and with ``"trial"``)."""
        model, sig = self.model, self.sig
        if self.D_frozen is not None:
            return self.D_frozen
        D = model.moduli(model.sigma_pre + sig[:, 0])
        if model.opts.midpoint:
            if self.dsig_last is not None and model.opts.predictor == "rate":
                d_half = 0.5 * ratio * self.dsig_last[:, 0]
            else:
                # a trial increment: at the start-of-step moduli (the first increment, and
                # "trial"), or on the K factorised for the last increment ("lagged": its
                # moduli half a step behind, an O(h^2) increment, enough for the midpoint
                # rule's order)
                lagged = self.dsig_last is not None and model.opts.predictor == "lagged"
                if not lagged:
                    model.factor(D)
                _, _, trial = self.solve(D, bound, guess, on_factor=lagged)
                d_half = 0.5 * trial[:, 0]
            D = model.moduli(model.sigma_pre + sig[:, 0] + d_half)
        model.factor(D)
        return D

    def _slip(self) -> None:
        """Slip emulation (Figure 19): where the interlayer shear reaches mu P, {23}, the
        transverse shear moduli drop for the rest of the loading."""
        model, sig = self.model, self.sig
        assert model.slipped is not None
        tau = np.hypot(sig[:, 3], sig[:, 4])
        grew = (tau >= self.friction * np.maximum(-(model.sigma_pre + sig[:, 0]), 0.0)) & (tau > 0)
        if np.any(grew & ~model.slipped):
            model.slipped |= grew
            if self.D_frozen is not None:
                self.D_frozen = model.moduli(model.sigma_pre)
                model.factor(self.D_frozen)

    def advance(self, k: int) -> FloatArray:
        """Press the head to ``delta[k]``: the increment solved, the state updated; returns
        the bounds of the surface nodes there."""
        model, delta, u = self.model, self.delta, self.u
        bound = self.bound_at(delta[k])
        u_surf = u[model.sr]
        # predicted contact: the last increment's motion extrapolated
        ratio = (delta[k] - delta[k - 1]) / max(delta[k - 1] - delta[max(k - 2, 0)], 1e-300)
        u_pred = u_surf + ratio * (u_surf - self.u_prev[model.sr]) if k > 1 else u_surf
        guess = (self.f_surf < 0) | (bound - u_pred < 0)
        D = self._moduli(bound, guess, ratio)
        du, f_new, dsig = self.solve(D, bound, guess)
        self.dsig_last = dsig
        self.u_prev = u.copy()
        self.u = u + du
        self.sig += dsig
        if model.slipped is not None:
            self._slip()
        self.f_surf = f_new
        return bound


Stop = Callable[[FloatArray, FloatArray], bool]


def loading_depths(
    web: Web,
    core: Core,
    r_out: float,
    head: Head,
    depth_max: float,
    opts: Contact3DOptions,
    stop: Stop | None,
    extend_to: float | str | None,
) -> FloatArray:
    """The depths of a 3D loading: ``d_k = depth_max (k / n_steps)^step_exponent`` to
    ``depth_max``; with ``stop`` and ``extend_to``, on by the same law to ``extend_to``
    (checked against the model's reach as ``depth_max`` is, under the field
    ``extend_to``; :func:`woundroll.contact.stepping.depth_schedule`)."""
    deepest = None
    if stop is not None and extend_to is not None:
        deepest = max(_check_scalar(extend_to, "extend_to"), depth_max)
        _check_reach(web, core, r_out, head, deepest, opts, "extend_to")
    return depth_schedule(depth_max, int(opts.n_steps), opts.step_exponent, deepest)


def _press3d(load: _Loading3D, stop: Stop | None = None) -> tuple[LoadHistory, FloatArray]:
    """Every depth of ``load.delta`` in turn, recorded on the line z = 0 (quarter model:
    forces times 4), until ``stop(delta, force)`` says so (the curve then ends at the last
    depth solved, and the loading's state is that depth's). Returns the history and the
    contact's half length along the CMD."""
    model, delta = load.model, load.delta
    mesh = model.mesh
    n_t, n_z = mesh.theta.size, mesh.z.size
    s_line = model.R * mesh.theta
    h = LoadHistory.start(delta, mesh.n_elements, n_t)
    half_len = np.zeros(delta.size)
    n = delta.size - 1
    for k in range(1, n + 1):
        bound = load.advance(k)
        f_new = load.f_surf
        p = -f_new / model.surf_area
        gap = (bound - load.u[model.sr]).reshape(n_z, n_t)
        act = (f_new < 0).reshape(n_z, n_t)
        h.record(
            k,
            -4.0 * float(np.sum(f_new * load.cos_t)),
            _edge(s_line, act[0], gap[0]),
            float(p.max()),
            load.sig[:, [0, 1, 3]],
            p.reshape(n_z, n_t)[0],
        )
        half_len[k] = _edge(mesh.z, act[:, 0], gap[:, 0])
        if stop is not None and k < n and stop(delta[: k + 1], h.force[: k + 1]):
            return h.up_to(k + 1), half_len[: k + 1]
    return h, half_len


def _result3d(
    load: _Loading3D,
    h: LoadHistory,
    half_len: FloatArray,
    head: Head,
    update_modulus: bool,
    times: tuple[float, float],
) -> Contact3DResult:
    """The result of :func:`indent3d` (``times``: its start and its setup's seconds)."""
    model, friction = load.model, load.friction
    mesh = model.mesh
    t0, t_setup = times
    sig, tc, n_t, n_z = load.sig, model.t_centre, mesh.theta.size, mesh.z.size
    length = float(head.length) if head.shape == "cylinder" else 2.0 * head.cmd_halfwidth
    elements = (model.r_centre * np.cos(tc), model.r_centre * np.sin(tc), model.r_centre, tc)
    return Contact3DResult(
        **result_fields(
            h,
            force=h.force,
            stress=(sig[:, 0], sig[:, 1], sig[:, 3]),
            sigma_pre=model.sigma_pre,
            friction=friction,
            elements=elements,
            contact_s=model.R * mesh.theta,
        ),
        force_per_length=h.force / length,
        head_radius=head.radius,
        head_length=length,
        outer_radius=model.R,
        update_modulus=update_modulus,
        n_elements=mesh.n_elements,
        n_dof=model.asm.n_free,
        mesh_shape=(mesh.r.size - 1, n_t - 1, n_z - 1),  # type: ignore[arg-type]
        solve_time_s=time.perf_counter() - t0,
        half_length=half_len,
        element_z=model.z_centre,
        sigma_z=sig[:, 2],
        tau_r_z=sig[:, 4],
        surface_pressure=(-load.f_surf / model.surf_area).reshape(n_z, n_t).T,
        surface_theta=mesh.theta,
        surface_z=mesh.z,
        head=head.to_dict(),
        stats={
            "factorisations": model.n_factor,
            "rhs_solved": model.n_solves,
            "assembly_s": model.t_assembly,
            "factor_s": model.t_factor,
            "solve_s": model.t_solve,
            "setup_s": t_setup,
            "pcg_iterations": model.n_pcg,
            "pcg_max_iterations_used": model.pcg_iterations,
            "pcg_refactorisations": model.n_pcg_failed,
            "partial_solves": model.n_partial,
            # "pardiso-mixed": refinement steps, solves redone in double, largest residual
            "refinement_steps": getattr(model.solver, "refinement_steps", 0),
            "double_fallbacks": getattr(model.solver, "double_fallbacks", 0),
            "double_factorisations": getattr(model.solver, "double_factorisations", 0),
            "largest_refined_residual": getattr(model.solver, "largest_residual", 0.0),
            "slipped_elements": 0 if model.slipped is None else int(model.slipped.sum()),
        },
    )


def indent3d(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    *,
    head: Head,
    depth_max: float | str = 1e-3,
    friction: float = INTERLAYER_FRICTION,
    update_modulus: bool = True,
    options: Contact3DOptions | None = None,
    stop: Stop | None = None,
    extend_to: float | str | None = None,
) -> Contact3DResult:
    """Press a rigid head into the wound roll (3D) and return F(d), a(d) and the fields.

    Parameters
    ----------
    web, core, radius, sigma_r, depth_max, friction, update_modulus
        As :func:`woundroll.contact.indent` (the roll's width is ``web.width``).
    head : Head
        Cylinder (axis along the CMD, rounded ends), sphere or flat punch.
    options : Contact3DOptions, optional
    stop, extend_to
        As :func:`woundroll.contact.indent`: ``stop(delta, force)`` [m], [N] after each
        increment ends the loading there; with ``extend_to`` [m] the loading goes on past
        ``depth_max`` by the same step law until ``stop`` says so or the depth reaches
        ``extend_to`` (the increments up to ``depth_max`` are the same as without it). The
        mesh is sized for ``depth_max`` (the head's footprint there) either way
        (docs/contact.md, "3D model": the fine zone still holds the contact at about twice
        that depth).

    Returns
    -------
    Contact3DResult

    Raises
    ------
    InputError
        Bad geometry, a head wider than the roll, a depth beyond the model's reach, a mesh
        too coarse for the contact, bad options.
    ConvergenceError
        The contact set does not settle.
    """
    t0 = time.perf_counter()
    depth_max = _check_scalar(depth_max, "depth_max")
    friction = to_si(friction, "dimensionless", "friction")
    if friction < 0:
        raise InputError(f"must be zero or positive, got {friction:g}", "friction")
    model = build_roll3d(
        web, core, radius, sigma_r, head=head, depth_max=depth_max, options=options
    )
    opts = model.opts
    delta = loading_depths(web, core, model.R, head, depth_max, opts, stop, extend_to)
    t_setup = time.perf_counter() - t0
    load = _Loading3D(model, head, delta, friction, update_modulus)
    with one_blas_thread():  # woundroll.util.blas (the assembly's small per-ring products)
        h, half_len = _press3d(load, stop)
    return _result3d(load, h, half_len, head, update_modulus, (t0, t_setup))
