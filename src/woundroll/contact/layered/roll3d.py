"""Indentation of a layered roll in 3D: web sheets with isotropic Coulomb friction near the head.

The 3D continuum roll of :mod:`woundroll.contact.solid3d.solver` (its hexahedra, hypoelastic
E_r {2}, symmetry planes theta = 0 and z = 0, exact frictionless head contact and step
control) cut into sheets in a *layered zone* of depth ``layered_depth`` under the outer
surface, as the plane-strain layered model (:mod:`woundroll.contact.layered.solver`) does in
2D:

* the zone is meshed with uniform shells of ``layers_per_shell`` web layers (one element
  ring per shell; :data:`LAYERS_PER_SHELL_3D` by default); below it the graded 3D mesh
  continues;
* on every ring boundary inside the zone, and on its bottom (the deepest sheet on the
  continuum), each node is duplicated for its two tangential displacements: the sheet above
  and the material below each have their own ``u_theta`` and ``u_z`` there and share
  ``u_r``. Assumption (named, as in 2D): the interfaces stay closed; the interface pressure
  is reported (:class:`Layered3DState`) so that it can be checked;
* the tangential jump ``s = u(above) - u(below)``, a 2-vector (theta, z), obeys isotropic
  Coulomb friction with mu = ``friction``: the interface force per node ``T`` (a 2-vector
  [N], the quarter model's node share) stays in the disc ``|T| <= mu P A``, with P the
  interface pressure (wound-in plus the head's, ``-(sigma_pre + sigma_r)`` averaged over
  the elements around the node, at the start of the increment: explicit, first order, as
  in 2D) and A the node's tributary interface area; a node sticks (no jump increment)
  inside the disc and slips along its force on the rim;
* per increment, primal-dual active-set passes as in 2D: the stick pairs carry an
  augmentation ``rho |s|^2`` in the factorised stiffness (the 3D model's sparse solver; the
  coupling entries are in the pattern from the start, so one symbolic analysis serves every
  stick set) and their forces are found by Uzawa passes on it (each pass solves the head
  contact exactly, the 3D model's LCP); the slipping pairs' forces are the return map of
  the trial force ``T + rho s`` onto the rim of the disc (its direction is iterated with
  the passes until the slip runs along the force); a stick pair whose force leaves the
  disc slips, a slipping pair that moves against its force sticks; repeated until the sets
  hold. At the fixed point the continuum equations hold with exactly the interface forces
  T; ``rho`` sets the rate only. Each increment starts from the last one's sets.

With mu large every interface sticks and the model is the 3D continuum on the same mesh;
with mu -> 0 the sheets slide freely in theta and z.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from woundroll.contact.heads import Head
from woundroll.contact.layered.solver import LAYERED_DEPTH, layered_radii, zone_shells
from woundroll.contact.solid3d.fem import Assembler3D, stresses
from woundroll.contact.solid3d.linsolve import make_solver
from woundroll.contact.solid3d.mesh import RollMesh3D
from woundroll.contact.solid3d.options import Contact3DOptions
from woundroll.contact.solid3d.solver import (
    Contact3DResult,
    Roll3D,
    Stop,
    _check_reach,
    _Loading3D,
    _mesh_under_the_head,
    _press3d,
    _result3d,
    loading_depths,
)
from woundroll.contact.stepping import check_profile, check_scalar
from woundroll.contact.stepping import solve_lcp as _solve_lcp
from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import INTERLAYER_FRICTION, Core, Web
from woundroll.units import to_si
from woundroll.util.anderson import Anderson
from woundroll.util.blas import one_blas_thread

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


#: Web layers per shell of the layered zone in 3D by default. Lumping sheets bonds layers
#: that would slip, so a shell of several sheets bends as one thick plate: PET2 53.4 N
#: (coarse mesh) reads 34.4 / 30.7 / 29.8 Rho at 9 / 2 / 1 sheets a shell (record
#: layered_study.lps3d, docs/contact.md "The layered roll in 3D"). Two sheets read within
#: 3.5 % of one at about half its cost; the 3D model's surface ring (3-9 sheets) does not.
LAYERS_PER_SHELL_3D = 2


@dataclass(frozen=True)
class Layered3DOptions:
    """Settings of :func:`indent_layered3d` on top of the 3D model's :class:`Contact3DOptions`.

    Attributes
    ----------
    base : Contact3DOptions
        The 3D mesh and step settings (``slip`` must be "none": the sheets slip themselves;
        ``reuse_factorisation`` must be False: every increment is factorised).
    layered_depth : float or None
        Depth of the layered zone [m]; None -> :data:`LAYERED_DEPTH` a_y (a_y the head's
        geometric half-extent along the hoop at ``depth_max``). Rounded to whole shells.
    layers_per_shell : int or None
        Web layers per shell (default :data:`LAYERS_PER_SHELL_3D`); None -> as many as
        make the 3D model's surface ring (``base.surface_size`` or its default): a mesh
        that costs what the continuum's does, and reads above the stack of sheets.
    penalty, tol, max_passes : float, float, int
        As :class:`woundroll.contact.layered.solver.LayeredOptions`.
    interfaces : bool
        False: no cut (the continuum on the layered mesh, for verification).
    relaxation : float
        ADMM over-relaxation (1: none).
    anderson : int
        Memory of the Anderson acceleration of the ADMM passes (0: none).
    gap_tol : float or None
        The head contact's gap tolerance as a fraction of the first depth increment; None:
        the 3D model's (1e-3). Tighter for verification against the continuum.
    """

    base: Contact3DOptions = field(default_factory=Contact3DOptions)
    layered_depth: float | None = None
    layers_per_shell: int | None = LAYERS_PER_SHELL_3D
    penalty: float = 0.1
    relaxation: float = 1.0
    anderson: int = 5
    gap_tol: float | None = None
    tol: float = 1e-5
    max_passes: int = 500
    interfaces: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.base, Contact3DOptions):
            raise InputError("must be a Contact3DOptions", "options.base")
        if self.base.slip != "none":
            raise InputError("the layered model slips itself: leave contact.slip at 'none'", "slip")
        if self.base.reuse_factorisation:
            raise InputError(
                "the layered 3D model factorises every stick set: leave it False",
                "options3d.reuse_factorisation",
            )
        d = self.layered_depth
        if d is not None and not (
            isinstance(d, int | float | np.number) and math.isfinite(d) and d > 0
        ):
            raise InputError(f"must be a positive length, got {d!r}", "layered_depth")
        n = self.layers_per_shell
        if n is not None and (not isinstance(n, int | np.integer) or isinstance(n, bool) or n < 1):
            raise InputError(f"must be a positive integer, got {n!r}", "layers_per_shell")
        if self.gap_tol is not None and not (math.isfinite(self.gap_tol) and self.gap_tol > 0):
            raise InputError(f"must be positive, got {self.gap_tol!r}", "options.gap_tol")
        for name in ("penalty", "tol"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"must be positive, got {v!r}", f"options.{name}")


class _CutAssembler3D(Assembler3D):
    """:class:`Assembler3D` on the doubled node numbering (``dofs`` given), with every
    interface pair augmented by ``rho |u_b - u_a|^2`` in the stiffness (free indices ``fa``
    below, ``fb`` above, (n_pairs, 2) for theta and z, -1 where held; the ADMM splitting
    of :meth:`_LayeredLoading3D._friction`). ``rho`` per pair is ``penalty`` times the mean
    stiffness diagonal of its DOFs, set at each assembly (:attr:`rho`)."""

    def __init__(
        self,
        base: Assembler3D,
        free: NDArray[np.bool_],
        dofs: IntArray,
        diagonal: FloatArray | None,
        fa: IntArray,
        fb: IntArray,
        penalty: float,
    ) -> None:
        # the element data of the uncut assembler (same rings, same elements)
        self.mesh, self.free, self.diagonal = base.mesh, free, diagonal
        self.M, self.B_centre = base.M, base.B_centre
        self.tri_a, self.tri_b = base.tri_a, base.tri_b
        self.ring, self.dtheta, self.dz = base.ring, base.dtheta, base.dz
        self._order, self._ring_start, self._fsft = base._order, base._ring_start, base._fsft
        self._Mf, self._fs = base._Mf, base._fs
        self.dofs = dofs
        self.free_index = np.full(free.size, -1, dtype=np.int64)
        self.free_index[free] = np.arange(int(free.sum()))
        n = self.n_free = int(free.sum())
        fe = self.free_index[dofs]
        a, b = fe[:, self.tri_a].ravel(), fe[:, self.tri_b].ravel()
        keep = (a >= 0) & (b >= 0)
        self._keep = np.flatnonzero(keep)
        # the doubled numbering need not keep an element's DOFs in increasing order
        rows, cols = np.minimum(a[keep], b[keep]), np.maximum(a[keep], b[keep])
        self.fa, self.fb, self.on = fa, fb, (fa >= 0) & (fb >= 0)
        pa, pb = fa[self.on], fb[self.on]
        keys = np.concatenate([rows * n + cols, np.minimum(pa, pb) * n + np.maximum(pa, pb)])
        uniq, inv = np.unique(keys, return_inverse=True)
        self._map, self._pair_pos = inv[: rows.size], inv[rows.size :]
        self.rows, self.cols, self.nnz = uniq // n, uniq % n, uniq.size
        self._diag = np.zeros(n) if diagonal is None else diagonal[free]
        self.diag_pos = np.flatnonzero(self.rows == self.cols)
        self.pattern = sp.csr_matrix((np.ones(self.nnz), (self.rows, self.cols)), shape=(n, n))
        self.pattern.sort_indices()
        self.penalty = penalty
        self.rho = np.zeros(fa.shape[0])

    def values(self, D: FloatArray) -> FloatArray:
        vals = super().values(D)
        if self.fa.shape[0] == 0:
            return vals
        X = np.concatenate([self.fa, self.fb], axis=1)
        dg = np.append(vals[self.diag_pos], np.nan)  # index -1 (held) reads nan
        self.rho = self.penalty * np.nanmean(np.where(X >= 0, dg[X], np.nan), axis=1)
        r = np.broadcast_to(self.rho[:, None], self.fa.shape)[self.on]
        vals[self.diag_pos[self.fa[self.on]]] += r
        vals[self.diag_pos[self.fb[self.on]]] += r
        vals[self._pair_pos] -= r
        return vals


class _NodeNumbering:
    """Node number of doubled ring ``i2``, hoop index ``j``, CMD index ``k`` (the doubled
    mesh numbers rings fastest, then the hoop, then the CMD)."""

    def __init__(self, n_t: int, nr2: int) -> None:
        self.n_t, self.nr2 = n_t, nr2

    def __call__(self, i2: Any, j: Any, k: Any) -> Any:
        return (np.asarray(k) * self.n_t + np.asarray(j)) * self.nr2 + np.asarray(i2)


def _doubled_dofs(
    mesh: RollMesh3D, lower: IntArray, upper: IntArray, node: _NodeNumbering
) -> IntArray:
    """Each element's 24 DOFs on the doubled mesh: an element's radial DOFs on its rings'
    ``lower`` nodes, its tangential ones on the inner ring's ``upper`` (outer-face) nodes
    and the outer ring's ``lower`` ones."""
    i, j, k = mesh.element_index
    dofs = np.empty((i.size, 24), dtype=np.int64)
    for a in range(8):
        a1, a2, a3 = a & 1, (a >> 1) & 1, (a >> 2) & 1
        ring = i + a1
        n_rad = node(lower[ring], j + a2, k + a3)
        n_tan = node(upper[ring] if a1 == 0 else lower[ring], j + a2, k + a3)
        dofs[:, 3 * a] = 3 * n_rad
        dofs[:, 3 * a + 1] = 3 * n_tan + 1
        dofs[:, 3 * a + 2] = 3 * n_tan + 2
    return dofs


class _LayeredRoll3D(Roll3D):
    """The 3D roll on the layered mesh (module docstring): :class:`Roll3D` with the doubled
    tangential DOFs of the interface rings ``cut`` (indices into ``mesh.r``)."""

    def __init__(
        self,
        web: Web,
        core: Core,
        r: FloatArray,
        s: FloatArray,
        mesh: RollMesh3D,
        opts: Contact3DOptions,
        cut: IntArray,
        penalty: float,
    ) -> None:
        super().__init__(web, core, r, s, mesh, opts)
        n_r, n_t, n_z = mesh.shape
        is_cut = np.zeros(n_r, dtype=bool)
        is_cut[cut] = True
        # ring i's radial (and inner tangential) nodes on doubled ring lower[i], the outer
        # face's tangential nodes of a cut ring on upper[i] = lower[i] + 1
        lower = np.arange(n_r) + np.concatenate([[0], np.cumsum(is_cut)[:-1]])
        upper = lower + is_cut
        nr2 = n_r + int(is_cut.sum())
        node = _NodeNumbering(n_t, nr2)
        dofs = _doubled_dofs(mesh, lower, upper, node)
        n_nodes = nr2 * n_t * n_z
        free, diagonal = self._constraints(dofs, node, nr2, n_nodes, core, opts)
        fi = np.full(3 * n_nodes, -1, dtype=np.int64)
        fi[free] = np.arange(int(free.sum()))
        fa, fb = self._pairs(np.flatnonzero(is_cut), lower, upper, node, fi)
        self.free = free
        self.asm = _CutAssembler3D(self.asm, free, dofs, diagonal, fa, fb, penalty)
        self.surface = node(nr2 - 1, *np.meshgrid(np.arange(n_t), np.arange(n_z), indexing="xy"))
        self.surface = self.surface.ravel()  # order k * n_t + j, as Roll3D's
        self.sr = fi[3 * self.surface]
        # "auto" in double precision: the friction iteration stops at a relative change
        # of 2e-5, near the mixed-precision solves' residual (3e-5), and with those its
        # verifications moved by up to 0.07 % of the force (docs/history.md, 2026-12-07)
        self.solver = make_solver(opts.solver, self.asm.pattern, mixed=False)
        self.n_dof_all = 3 * n_nodes
        self.extra: FloatArray | None = None
        self._fields: dict[int, FloatArray] = {}  # unit-load fields on the current factor
        self._stacked: tuple[bytes, FloatArray] | None = None  # the last candidates' fields
        # pair geometry: tributary area and the elements around each pair (their mean
        # radial stress is the pair's pressure)
        pr = mesh.r[self.pair_ring]
        self.pair_area = pr * self.trib_t[self.pair_j] * self.trib_z[self.pair_k]
        self.pair_elements = self._elements_around_pairs()

    def _constraints(
        self,
        dofs: IntArray,
        node: _NodeNumbering,
        nr2: int,
        n_nodes: int,
        core: Core,
        opts: Contact3DOptions,
    ) -> tuple[NDArray[np.bool_], FloatArray | None]:
        """The free DOFs of the doubled mesh (symmetry planes, the core's hold, the CMD
        edges as ``opts`` asks) and the core's radial springs (None on a rigid core)."""
        n_t, n_z = self.mesh.shape[1:]
        free = np.zeros(3 * n_nodes, dtype=bool)
        free[np.unique(dofs)] = True
        I2, J, K = np.meshgrid(np.arange(nr2), np.arange(n_t), np.arange(n_z), indexing="ij")
        every = node(I2, J, K)
        core_nodes = node(0, *np.meshgrid(np.arange(n_t), np.arange(n_z), indexing="ij")).ravel()
        free[3 * core_nodes + 1] = False
        free[3 * core_nodes + 2] = False
        free[3 * every[:, 0, :].ravel() + 1] = False  # theta = 0
        free[3 * every[:, -1, :].ravel() + 1] = False  # theta = pi (or the cut)
        free[3 * every[:, :, 0].ravel() + 2] = False  # z = 0
        if opts.cmd_edges == "fixed":
            free[3 * every[:, :, -1].ravel() + 2] = False
        if core.rigid:
            free[3 * core_nodes] = False
            return free, None
        area = np.outer(self.trib_t, self.trib_z).ravel()  # order j * n_z + k
        diagonal = np.zeros(3 * n_nodes)
        diagonal[3 * core_nodes] = core.stiffness * area
        return free, diagonal

    def _pairs(
        self,
        cut_rings: IntArray,
        lower: IntArray,
        upper: IntArray,
        node: _NodeNumbering,
        fi: IntArray,
    ) -> tuple[IntArray, IntArray]:
        """The interface pairs (every node of every cut ring, theta and z components) with
        a free DOF: their free indices on the inner (``fa``) and outer (``fb``) face; sets
        ``pair_ring``, ``pair_j``, ``pair_k``."""
        n_t, n_z = self.mesh.shape[1:]
        C, PJ, PK = np.meshgrid(cut_rings, np.arange(n_t), np.arange(n_z), indexing="ij")
        C, PJ, PK = C.ravel(), PJ.ravel(), PK.ravel()
        na, nb = node(lower[C], PJ, PK), node(upper[C], PJ, PK)
        fa = np.stack([fi[3 * na + 1], fi[3 * na + 2]], axis=1)
        fb = np.stack([fi[3 * nb + 1], fi[3 * nb + 2]], axis=1)
        live = np.any(fa >= 0, axis=1)
        self.pair_ring, self.pair_j, self.pair_k = C[live], PJ[live], PK[live]
        return fa[live], fb[live]

    def _elements_around_pairs(self) -> IntArray:
        """The (up to) eight elements around each interface pair (pairs, 8)."""
        n_r, n_t, n_z = self.mesh.shape
        ne_r, ne_t, ne_z = n_r - 1, n_t - 1, n_z - 1
        around = []
        for di in (-1, 0):
            for dj in (-1, 0):
                for dk in (-1, 0):
                    ei = self.pair_ring + di
                    ej = np.clip(self.pair_j + dj, 0, ne_t - 1)
                    ek = np.clip(self.pair_k + dk, 0, ne_z - 1)
                    around.append((ek * ne_t + ej) * ne_r + ei)
        return np.stack(around, axis=1)

    def factor(self, D: FloatArray) -> None:
        """Assemble K (with the interface pairs' augmentation at the current sets) and
        factorise it, unless neither the moduli nor the sets changed since."""
        if self._D is not None and np.array_equal(D, self._D):
            return
        self._D = D.copy()
        t0 = time.perf_counter()
        self._U = self.asm.upper(D)
        self.t_assembly += time.perf_counter() - t0
        self._refactor()
        self._fields = {}  # the unit-load fields belong to the factor
        self._stacked = None

    def _unit_fields(self, idx: IntArray) -> FloatArray:
        """Displacement fields (n_free, m) of a unit inward radial force on each surface node
        ``idx``, on the current factor (cached until the next factorisation; the new ones
        solved as one multi-column system; the matrix of the last ``idx`` kept, as the
        friction passes of an increment mostly share their candidates)."""
        key = idx.tobytes()
        if self._stacked is not None and self._stacked[0] == key:
            return self._stacked[1]
        new = [int(i) for i in idx if int(i) not in self._fields]
        if new:
            rhs = np.zeros((self.asm.n_free, len(new)))
            rhs[self.sr[new], np.arange(len(new))] = -1.0
            X = self._solve(rhs)
            for c, i in enumerate(new):
                self._fields[i] = X[:, c]
        X = np.stack([self._fields[int(i)] for i in idx], axis=1)
        self._stacked = (key, X)
        return X

    def solve_pass(
        self,
        bound: FloatArray,
        u_surf: FloatArray,
        f_old: FloatArray,
        guess: NDArray[np.bool_],
        tol: float,
    ) -> tuple[FloatArray, FloatArray]:
        """:meth:`Roll3D.solve_pass` by superposition: the layered model factorises every
        increment and solves its head contact at every friction pass, so the unit-load
        fields of the candidate nodes on the current factor are kept (:meth:`_unit_fields`)
        and each pass is one solve (the increment under the old contact forces and the
        interface load) plus the head contact's LCP on the exact flexibility; the
        displacement is that solve plus the fields times the contact forces (linear in
        them). Same fixed point as the iteration on cached columns: the exact LCP, a
        penetration outside the candidates enlarging the set."""
        n = self.asm.n_free
        reachable = np.isfinite(bound)
        cand = self._widen(guess | (f_old < 0), 1) & reachable
        load = np.zeros(n)
        load[self.sr] = -f_old
        du0 = self._solve(load)  # with the interface load of the pass (``extra``)
        gap0 = bound - (u_surf + du0[self.sr])
        for _ in range(12):
            idx = np.flatnonzero(cand)
            X = self._unit_fields(idx)
            lam = _solve_lcp(-X[self.sr[idx], :], gap0[idx])
            du = du0 + X @ lam
            lam_all = np.zeros(self.sr.size)
            lam_all[idx] = lam
            gap = bound - (u_surf + du[self.sr])
            bad = ~cand & (gap < -tol)
            if not np.any(bad):
                return du, -lam_all
            cand = (cand | self._widen(bad, 1)) & reachable
        raise ConvergenceError("the 3D contact set did not settle in 12 enlargements")

    def _solve(self, b: FloatArray) -> FloatArray:
        # the head-contact passes of Roll3D.solve_pass solve one load vector; the interface
        # forces of the current pass are added to it (the flexibility columns, unit loads
        # in a 2-D array, are solved without them)
        if b.ndim == 1 and self.extra is not None:
            b = b + self.extra
        return super()._solve(b)

    def jump(self, du: FloatArray) -> FloatArray:
        """Tangential jumps ``u(above) - u(below)`` (n_pairs, 2) [m] of free-DOF increments."""
        asm: _CutAssembler3D = self.asm  # type: ignore[assignment]
        x = np.append(du, 0.0)  # index -1 (a held component) reads 0
        return x[asm.fb] - x[asm.fa]

    def pair_load(self, dT: FloatArray) -> FloatArray:
        """The free-DOF load of interface force increments ``dT`` (n_pairs, 2): ``-dT`` on
        the sheet above, ``+dT`` on the material below."""
        asm: _CutAssembler3D = self.asm  # type: ignore[assignment]
        load = np.zeros(asm.n_free + 1)
        np.add.at(load, asm.fb.ravel(), -dT.ravel())
        np.add.at(load, asm.fa.ravel(), dT.ravel())
        return load[:-1]

    def pressure(self, sig_r: FloatArray) -> FloatArray:
        """Interface pressure [Pa] at the pairs (compression positive)."""
        total = self.sigma_pre + sig_r
        return -np.mean(total[self.pair_elements], axis=1)


def _norm(T: FloatArray) -> FloatArray:
    return np.sqrt(np.einsum("ij,ij->i", T, T))


def _project(y: FloatArray, g: FloatArray) -> FloatArray:
    """The return map: ``y`` (n, 2) onto the discs ``|T| <= g``."""
    ny = _norm(y)
    return y * np.minimum(1.0, g / np.where(ny > 0, ny, 1.0))[:, None]


class _LayeredLoading3D(_Loading3D):
    """The 3D loading with the interfaces' active-set passes in every solve."""

    def __init__(self, model: _LayeredRoll3D, lopts: Layered3DOptions, *args: Any) -> None:
        super().__init__(model, *args)
        self.lopts = lopts
        if lopts.gap_tol is not None:
            self.tol = lopts.gap_tol * self.delta[1]
        n_p = model.pair_ring.size
        self.u_all = np.zeros(model.n_dof_all)
        self.T = np.zeros((n_p, 2))  # interface force per pair [N] (quarter model's share)
        self.T_trial = self.T
        self.slip = np.zeros(n_p)  # accumulated |slip| [m]
        self.slip_trial = self.slip
        self.slip_vec = np.zeros((n_p, 2))  # accumulated slip vector [m]
        self.w_trial = np.zeros((n_p, 2))  # the last increment's slip [m]
        self.slip_vec_trial = self.slip_vec
        self.g_trial = np.zeros(n_p)
        self.stick_trial = np.ones(n_p, dtype=bool)
        self.passes = 0
        self.history_k = 0

    def bound(self) -> FloatArray:
        """Coulomb's limit mu P A per pair [N] at the start of the increment."""
        model: _LayeredRoll3D = self.model  # type: ignore[assignment]
        p = np.maximum(model.pressure(self.sig[:, 0]), 0.0)
        return self.friction * p * model.pair_area

    def _contact(
        self, bound: FloatArray, guess: NDArray[np.bool_], load: FloatArray
    ) -> tuple[FloatArray, FloatArray]:
        model: _LayeredRoll3D = self.model  # type: ignore[assignment]
        model.extra = load
        try:
            return model.solve_pass(bound, self.u[model.sr], self.f_surf, guess, self.tol)
        finally:
            model.extra = None

    def solve(
        self,
        D: FloatArray,
        bound: FloatArray,
        guess: NDArray[np.bool_],
        on_factor: bool = False,
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The increment at the factorised moduli ``D`` with the interfaces' Coulomb law
        (module docstring): (du, new contact forces, stresses); ``on_factor``: on the
        factorisation in place whatever ``D`` (the lagged predictor's trial, as in
        :meth:`_Loading3D.solve`)."""
        model: _LayeredRoll3D = self.model  # type: ignore[assignment]
        asm: _CutAssembler3D = model.asm  # type: ignore[assignment]
        n_p = model.pair_ring.size
        if n_p == 0 or not self.lopts.interfaces:
            du, f_new = self._contact(bound, guess, np.zeros(asm.n_free))
        else:
            du, f_new = self._friction(D, bound, guess, on_factor)
        self.u_all[model.free] = du
        return du, f_new, stresses(D, asm.centre_strains(self.u_all))

    def _friction(
        self, D: FloatArray, bound: FloatArray, guess: NDArray[np.bool_], on_factor: bool = False
    ) -> tuple[FloatArray, FloatArray]:
        """The increment's interface forces by ADMM (module docstring): the increment
        minimises ``1/2 du K du - f du - t_old . s + sum g |s|`` over the head's contact
        constraints; split ``s = w``: (1) the displacement with every pair augmented by
        ``rho |s - w + u|^2`` (the head contact solved exactly on that factor), (2) ``w``
        the shrinkage of ``s + u`` by ``g / rho`` (the return map onto the disc), (3) the
        scaled force ``u += s - w``; the interface force is ``T = rho u``."""
        model: _LayeredRoll3D = self.model  # type: ignore[assignment]
        asm: _CutAssembler3D = model.asm  # type: ignore[assignment]
        lopts = self.lopts
        g = self.bound()
        t_old = self.T
        if not on_factor:
            model.factor(D)  # every pair augmented by rho
        rho = asm.rho[:, None]
        u = _project(t_old, g) / rho
        w = np.zeros_like(u)
        alpha = lopts.relaxation
        n_p = u.shape[0]
        accel = Anderson(lopts.anderson)
        for _ in range(lopts.max_passes):
            du, f_new = self._contact(bound, guess, model.pair_load(rho * (u - w) - t_old))
            self.passes += 1
            s = model.jump(du)
            scale = max(float(np.max(np.abs(du))), 1e-300)
            s_hat = alpha * s + (1.0 - alpha) * w
            v = s_hat + u
            nv = _norm(v)
            shrink = np.maximum(0.0, 1.0 - g / (rho[:, 0] * np.where(nv > 0, nv, 1.0)))
            w_new = v * shrink[:, None]
            u_new = u + s_hat - w_new
            change = max(
                float(np.max(np.abs(s - w_new), initial=0.0)),
                float(np.max(np.abs(w_new - w), initial=0.0)),
            )
            if change / scale <= lopts.tol:
                u, w = u_new, w_new
                break
            z = accel.step(np.concatenate([u, w]).ravel(), np.concatenate([u_new, w_new]).ravel())
            u, w = z[: 2 * n_p].reshape(n_p, 2), z[2 * n_p :].reshape(n_p, 2)  # rows: u then w
        else:
            raise self._unsettled("stick and slip zones")
        T = _project(rho * u, g)
        stick = _norm(w) == 0
        self.T_trial = T
        self.g_trial = g
        self.stick_trial = stick
        self.slip_trial = self.slip + _norm(w)
        self.slip_vec_trial = self.slip_vec + w
        self.w_trial = w
        return du, f_new

    def _unsettled(self, what: str) -> ConvergenceError:
        k = min(self.history_k, self.delta.size - 1)
        return ConvergenceError(
            f"the interface {what} did not settle in {self.lopts.max_passes} passes at depth "
            f"{self.delta[k] * 1e3:.3g} mm; use more n_steps or raise options.max_passes"
        )

    def advance(self, k: int) -> FloatArray:
        self.history_k = k
        bound = super().advance(k)
        self.T = self.T_trial
        self.slip = self.slip_trial
        self.slip_vec = self.slip_vec_trial
        return bound


@dataclass(frozen=True)
class Layered3DState:
    """The interfaces at the deepest depth solved (for studies and checks).

    Attributes
    ----------
    depth, s, z : ndarray [m]
        Depth under the undeformed surface, arc coordinate (r theta at the surface) and CMD
        coordinate of each interface pair.
    pressure : ndarray [Pa]
        Interface pressure P (wound-in plus the head's).
    shear : ndarray (n, 2) [Pa]
        Interface shear traction T / A (theta, z).
    slip : ndarray (n, 2) [m]
        Accumulated slip vector (theta, z) over the increments.
    slip_increment : ndarray (n, 2) [m]
        The last increment's slip (theta, z).
    stick : ndarray of bool
        Pairs stuck in the last increment.
    limit : ndarray [Pa]
        Coulomb's limit mu P of the last increment.
    passes : int
        Head-contact solves (Uzawa passes) over the whole loading.
    n_shells, layers_per_shell : int
    """

    depth: FloatArray
    s: FloatArray
    z: FloatArray
    pressure: FloatArray
    shear: FloatArray
    slip: FloatArray
    slip_increment: FloatArray
    stick: NDArray[np.bool_]
    limit: FloatArray
    passes: int
    n_shells: int
    layers_per_shell: int


def layered_mesh3d(
    web: Web, core: Core, r_out: float, head: Head, depth_max: float, lopts: Layered3DOptions
) -> tuple[RollMesh3D, IntArray, int, int]:
    """The uncut layered mesh, its interface ring indices, the shell count and the layers
    per shell."""
    base = lopts.base
    r_in = core.outer_radius
    mesh = _mesh_under_the_head(web, core, r_out, head, depth_max, base)
    a_y, _ = head.footprint(depth_max, r_out)
    n_layers = lopts.layers_per_shell
    if n_layers is None:
        n_layers = max(1, round(float(mesh.r[-1] - mesh.r[-2]) / web.thickness))
    shell = n_layers * web.thickness
    depth = lopts.layered_depth if lopts.layered_depth is not None else LAYERED_DEPTH * a_y
    n_shells = zone_shells(depth, shell, r_in, r_out)
    r = layered_radii(r_in, r_out, shell, n_shells, base.radial_growth)
    cut = r.size - 1 - np.arange(1, n_shells + 1)
    return RollMesh3D(r=r, theta=mesh.theta, z=mesh.z), cut, n_shells, n_layers


def indent_layered3d(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    *,
    head: Head,
    depth_max: float | str = 1e-3,
    friction: float = INTERLAYER_FRICTION,
    update_modulus: bool = True,
    options: Layered3DOptions | None = None,
    state: list[Layered3DState] | None = None,
    stop: Stop | None = None,
    extend_to: float | str | None = None,
) -> Contact3DResult:
    """Press a rigid head into the layered 3D roll; F(d), a(d) and the fields as
    :func:`woundroll.contact.solid3d.solver.indent3d` (same parameters, ``stop`` and
    ``extend_to`` included: the mesh and the layered zone are sized for ``depth_max``;
    ``options`` a :class:`Layered3DOptions`; ``friction`` mu > 0 between the sheets).
    ``state``: a list the interfaces' :class:`Layered3DState` at the last depth solved is
    appended to. The result's ``stats`` add the passes, the shells and the layers per shell.

    Raises
    ------
    InputError
        As :func:`indent3d`; mu <= 0 (``friction``); a layered zone as deep as the roll
        (``layered_depth``); shells too thick for the contact (``layers_per_shell``).
    ConvergenceError
        The contact set or the interface friction does not settle.
    """
    t0 = time.perf_counter()
    lopts = options if options is not None else Layered3DOptions()
    if not isinstance(lopts, Layered3DOptions):
        raise InputError("must be a Layered3DOptions", "options")
    if not isinstance(web, Web):
        raise InputError("must be a woundroll.materials.Web", "web")
    if not isinstance(core, Core):
        raise InputError("must be a woundroll.materials.Core", "core")
    if not isinstance(head, Head):
        raise InputError("must be a woundroll.contact.heads.Head", "head")
    depth_max = check_scalar(depth_max, "depth_max")
    mu = to_si(friction, "dimensionless", "friction")
    if not mu > 0:
        raise InputError(
            f"must be positive for the layered model (sheets with no friction carry no "
            f"shear between them), got {mu:g}",
            "friction",
        )
    r, s = check_profile(web, core, radius, sigma_r)
    base = lopts.base
    r_out = float(r[-1])
    _check_reach(web, core, r_out, head, depth_max, base)
    mesh, cut, n_shells, n_layers = layered_mesh3d(web, core, r_out, head, depth_max, lopts)
    if not lopts.interfaces:
        cut = cut[:0]
    model = _LayeredRoll3D(web, core, r, s, mesh, base, cut, lopts.penalty)
    delta = loading_depths(web, core, r_out, head, depth_max, base, stop, extend_to)
    t_setup = time.perf_counter() - t0
    load = _LayeredLoading3D(model, lopts, head, delta, mu, update_modulus)
    with one_blas_thread():  # woundroll.util.blas
        h, half_len = _press3d(load, stop)
    res = _result3d(load, h, half_len, head, update_modulus, (t0, t_setup))
    stats = {
        **res.stats,
        "interface_passes": load.passes,
        "interface_pairs": int(model.pair_ring.size),
        "slipping_pairs": int(np.sum(~load.stick_trial)),
        "layered_shells": n_shells,
        "layers_per_shell": n_layers,
    }
    res = dataclasses.replace(res, stats=stats, solve_time_s=time.perf_counter() - t0)
    if state is not None:
        state.append(
            Layered3DState(
                depth=r_out - mesh.r[model.pair_ring],
                s=r_out * mesh.theta[model.pair_j],
                z=mesh.z[model.pair_k],
                pressure=model.pressure(load.sig[:, 0]),
                shear=load.T / model.pair_area[:, None],
                slip=load.slip_vec,
                slip_increment=load.w_trial,
                stick=load.stick_trial.copy(),
                limit=load.g_trial / model.pair_area,
                passes=load.passes,
                n_shells=n_shells,
                layers_per_shell=n_layers,
            )
        )
    return res


__all__ = [
    "LAYERS_PER_SHELL_3D",
    "Layered3DOptions",
    "Layered3DState",
    "indent_layered3d",
    "layered_mesh3d",
]
