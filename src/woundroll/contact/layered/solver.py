"""Indentation of a layered roll: separate web sheets with Coulomb friction near the head.

A continuum passes load between layers by shear; a wound roll is a stack of sheets held
together by friction. This model keeps the plane-strain continuum roll of
:mod:`woundroll.contact.plane_strain.solver` (its mesh law, curved elements, hypoelastic
radial modulus {2}, exact head-contact LCP and step control) and cuts it into sheets in a
*layered zone* of depth ``layered_depth`` under the outer surface:

* the zone is meshed with uniform shells of ``layers_per_shell`` web layers (one element
  ring per shell); below it the graded continuum mesh of the 2D model continues;
* on every ring boundary inside the zone, and on its bottom (the deepest sheet on the
  continuum), the nodes are duplicated for the tangential displacement: the sheet above
  and the material below each have their own ``u_theta`` there and share ``u_r``.
  Assumption (named): the interfaces stay closed (bilateral normal contact). The wound-in
  pressure keeps them closed before the impact and the head only adds compression under
  it; the interface pressure is reported so this can be checked (:class:`LayeredResult`);
* the tangential jump ``s = u_theta(above) - u_theta(below)`` obeys Coulomb's law with the
  friction coefficient mu = ``friction``: the interface shear force per node ``T`` (per unit
  CMD length [N/m]) stays within ``|T| <= mu P A``, with P the interface pressure (the
  wound-in radial stress plus the head's, ``-(sigma_pre + sigma_r)`` of the four elements
  at the node, at the start of the increment: explicit in the step, first order) and A the
  node's tributary interface arc; a node sticks (no jump increment) below the limit and
  slips opposite to T at it;
* the increment's friction problem is solved exactly (to a tolerance) by primal-dual
  active-set passes: the stick pairs carry an augmentation ``rho (s)^2`` in the factorised
  stiffness (LAPACK banded Cholesky) and their multipliers are found by Uzawa passes on it
  (each pass solves the head contact exactly, the 2D model's LCP); a stick pair whose force
  exceeds the bound slips, a slipping pair that moves against its force sticks; repeated
  until the sets hold. At the fixed point the continuum equations hold with exactly the
  interface forces T; ``rho`` only sets the rate. Where a pass changes the sets of at most
  :data:`WOODBURY_MAX` pairs against the factorised stiffness, the factor is corrected by a
  low-rank (Woodbury) update instead of factorised again (:class:`_Woodbury`; exact to
  rounding); each increment starts from the stick and slip sets the last one ended with.

With mu large every interface sticks and the model is the continuum roll on the same
mesh; with mu -> 0 the sheets slide freely and the stack bends as separate plates.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.contact.plane_strain.fem import Assembler, ring_major_order
from woundroll.contact.plane_strain.mesh import RollMesh, build_mesh, graded_sizes
from woundroll.contact.plane_strain.solver import (
    FINE_ZONE,
    ContactOptions,
    _Factor,
    _factorize,
    _indent_inputs,
    _Loading,
    _press,
    _result2d,
    _Roll,
    _Step,
    _step,
)
from woundroll.contact.result import ContactResult
from woundroll.contact.stepping import depth_schedule
from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import INTERLAYER_FRICTION, Core, Web

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Default depth of the layered zone as a multiple of ``a_geo`` (the half-chord of the
#: head's geometric intersection with the roll at ``depth_max``) -- the depth over which the
#: head's load is carried in the continuum (docs/contact.md, "The layered roll").
LAYERED_DEPTH = 1.0
#: A slipping pair returns to stick when its jump increment runs against its force by more
#: than this fraction of the largest displacement increment (hysteresis of the active set).
BACK_TOL = 1e-5
#: Pairs whose stick/slip state differs from the factorised stiffness's, up to which the
#: active-set passes correct the factor by a low-rank (Woodbury) update instead of
#: factorising again (:class:`_Woodbury`); measured on PET1 26.7 N (benchmarks/bench_layered.py).
WOODBURY_MAX = 16
#: Coulomb's bound of a pair that always sticks (outside ``_Diagnostics.slip_region``) [N/m].
_NO_LIMIT = 1e300


class _Woodbury:
    """The stiffness ``K = K_f + U C U^T`` solved through the factor of ``K_f`` (the
    Sherman-Morrison-Woodbury identity): ``U`` has one column ``e_b - e_a`` per interface
    pair whose augmentation differs from the factor's, ``C`` is ``+rho`` for a pair stuck
    since (augmented now, not in the factor) and ``-rho`` for one slipping since. With
    ``Z = K_f^-1 U`` and the capacitance ``S = C^-1 + U^T Z`` (m x m, m the changed pairs):
    ``K^-1 x = K_f^-1 x - Z S^-1 Z^T x``. The same interface as :class:`_Factor` for
    :func:`woundroll.contact.plane_strain.solver._step` (``forward`` / ``flexibility``),
    so the exact head-contact LCP runs on the updated stiffness unchanged; ``forward``
    returns the base factor's ``L^-1 e`` with ``e`` itself (for ``Z^T e``)."""

    def __init__(self, base: _Factor, Z: FloatArray, fa: IntArray, fb: IntArray, c: FloatArray):
        import scipy.linalg as la

        self.base, self.Z = base, Z
        UZ = Z[fb] - Z[fa]  # U^T Z (m x m), symmetric
        S = np.diag(1.0 / c) + 0.5 * (UZ + UZ.T)
        self._S = la.lu_factor(S, check_finite=False)
        self._la = la

    def _s_solve(self, x: FloatArray) -> FloatArray:
        return self._la.lu_solve(self._S, x, check_finite=False)

    def solve(self, b: FloatArray) -> FloatArray:
        return self.base.solve(b) - self.Z @ self._s_solve(self.Z.T @ b)

    def forward(self, b: FloatArray) -> tuple[FloatArray, FloatArray]:
        return self.base.forward(b), b

    def flexibility(
        self, rows: IntArray, B: FloatArray, n: int, pre: Any = None
    ) -> tuple[FloatArray, FloatArray | None, Callable[[FloatArray], FloatArray]]:
        pre_f, e = (None, None) if pre is None else pre
        G, gq, solve_f = self.base.flexibility(rows, B, n, pre_f)
        top = B.shape[0]
        ZB = self.Z[:top].T @ B  # Z^T B (m x columns)
        W = self._s_solve(ZB)
        G = G - ZB.T @ W
        we = None
        if e is not None:
            we = self._s_solve(self.Z.T @ e)
            gq = gq - ZB.T @ we
        Z = self.Z

        def solve_for(cc: FloatArray) -> FloatArray:
            y = W @ cc if we is None else W @ cc + we
            return solve_f(cc) - Z @ y

        return G, gq, solve_for


class _UpdatedFactor:
    """The factor of the stiffness at one stick set, and the low-rank updates to nearby
    sets (:class:`_Woodbury`), with the columns ``K_f^-1 (e_b - e_a)`` cached per pair."""

    def __init__(self, lu: _Factor, stick: NDArray[np.bool_], rho: FloatArray) -> None:
        self.lu, self.stick, self.rho = lu, stick.copy(), rho.copy()
        self.cols: dict[int, FloatArray] = {}

    def at(
        self, stick: NDArray[np.bool_], fa: IntArray, fb: IntArray, n: int
    ) -> _Factor | _Woodbury | None:
        """The factor at ``stick`` (``fa``, ``fb``: the pairs' free indices below and
        above, ``n`` the free DOFs); None where more than WOODBURY_MAX pairs differ."""
        diff = np.flatnonzero(stick != self.stick)
        if diff.size == 0:
            return self.lu
        if diff.size > WOODBURY_MAX:
            return None
        new = [int(i) for i in diff if int(i) not in self.cols]
        if new:
            U = np.zeros((n, len(new)))
            U[fb[new], np.arange(len(new))] = 1.0
            U[fa[new], np.arange(len(new))] = -1.0
            X = self.lu.solve(U)
            for q, i in enumerate(new):
                self.cols[i] = X[:, q]
        Z = np.stack([self.cols[int(i)] for i in diff], axis=1)
        c = np.where(stick[diff], self.rho[diff], -self.rho[diff])
        return _Woodbury(self.lu, Z, fa[diff], fb[diff], c)  # type: ignore[return-value]


@dataclass(frozen=True)
class LayeredOptions:
    """Settings of :func:`indent_layered` on top of the 2D model's :class:`ContactOptions`.

    Attributes
    ----------
    base : ContactOptions
        The continuum's mesh and step settings (``surface_size`` is replaced by the shell
        thickness; ``newton`` is not used: every increment is factorised at its moduli;
        ``slip`` must be ``"none"``: the sheets slip themselves).
    layered_depth : float or None
        Depth of the layered zone under the surface [m]; None -> :data:`LAYERED_DEPTH`
        a_geo. Rounded to whole shells.
    layers_per_shell : int
        Web layers per shell (one element ring) in the layered zone [-].
    penalty : float
        The stick pairs' augmentation ``rho`` as a multiple of the stiffness diagonal at the
        interface DOFs [-]; sets the rate of the passes only, not the answer.
    tol : float
        The Uzawa passes stop when the stick pairs' jump increments ``|s|`` are below
        ``tol`` times the largest displacement increment [-].
    max_passes : int
        Passes per increment before :class:`ConvergenceError`.
    interfaces : bool
        False: no cut (the continuum on the layered mesh, for verification).
    """

    base: ContactOptions = field(default_factory=lambda: ContactOptions(newton=False))
    layered_depth: float | None = None
    layers_per_shell: int = 1
    penalty: float = 100.0
    tol: float = 1e-5
    max_passes: int = 100
    interfaces: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.base, ContactOptions):
            raise InputError("must be a ContactOptions", "options.base")
        if self.base.slip != "none":
            raise InputError(
                "the layered model slips itself: leave options.slip at 'none'", "options.slip"
            )
        if not self.base.half_model:
            raise InputError("the layered model meshes the half roll", "options.half_model")
        d = self.layered_depth
        if d is not None and not (
            isinstance(d, int | float | np.number) and math.isfinite(d) and d > 0
        ):
            raise InputError(f"must be a positive length, got {d!r}", "layered_depth")
        n = self.layers_per_shell
        if not isinstance(n, int | np.integer) or isinstance(n, bool) or n < 1:
            raise InputError(f"must be a positive integer, got {n!r}", "layers_per_shell")
        for name in ("penalty", "tol"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"must be positive, got {v!r}", f"options.{name}")


@dataclass(frozen=True)
class _Diagnostics(LayeredOptions):
    """:class:`LayeredOptions` with two diagnostics of where the slip that softens the roll
    happens (docs/contact.md, "Zone depth"; tests/contact/test_layered_depth.py). Private:
    a subclass, so that LayeredOptions' fields and defaults (which the docs records hash)
    stay as they are.

    Attributes
    ----------
    slip_region : (float, float) or None
        ``(depth [m], half-angle [rad])``: only the interfaces no deeper than ``depth``
        and within ``half-angle`` of the head's centre line may slip; the others stick
        (mu infinite there, the continuum to the passes' tolerance) on the same mesh.
        None: every interface of the zone may slip. A diagnostic of where the slip that
        softens the roll happens (docs/contact.md, "Zone depth"), also a zone bounded in
        angle as well as depth.
    cohesion : float
        A shear strength the interfaces hold at no pressure [Pa]: the limit is
        ``(cohesion + mu P) A`` (the adhesion term of the Bowden-Tabor friction law,
        ``tau = tau_0 + mu p``). 0 (default): Coulomb's law. A diagnostic of how much
        strength at low pressure stops the deep slip (docs/contact.md, "Zone depth").
    """

    slip_region: tuple[float, float] | None = None
    cohesion: float = 0.0

    def __post_init__(self) -> None:
        super().__post_init__()
        reg = self.slip_region
        if reg is not None and not (
            isinstance(reg, tuple)
            and len(reg) == 2
            and all(isinstance(v, int | float | np.number) and v > 0 for v in reg)
        ):
            raise InputError(
                f"must be (depth [m], half-angle [rad]), both positive, got {reg!r}",
                "options.slip_region",
            )
        c = self.cohesion
        if not (isinstance(c, int | float | np.number) and math.isfinite(c) and c >= 0):
            raise InputError(f"must be a stress >= 0 [Pa], got {c!r}", "options.cohesion")

    @classmethod
    def of(cls, options: LayeredOptions, **kw: Any) -> _Diagnostics:
        """``options`` with the diagnostics ``kw``."""
        fields = {f.name: getattr(options, f.name) for f in dataclasses.fields(LayeredOptions)}
        return cls(**fields, **kw)


class LayeredMesh(RollMesh):
    """The 2D model's ring mesh with the interface rings doubled: ring ``lower[i]`` is
    original ring ``i`` seen from below, ``lower[i] + 1`` from above where ``i`` is an
    interface. Node numbering and geometry as :class:`RollMesh` (coincident rings)."""

    def __init__(self, r: FloatArray, theta: FloatArray, n_cut: int) -> None:
        super().__init__(r=r, theta=theta, j0=0, periodic=False)
        object.__setattr__(self, "n_cut", n_cut)

    @property
    def n_elements(self) -> int:
        return (self.n_r - 1 - self.n_cut) * (self.n_theta - 1)  # type: ignore[attr-defined]


def zone_shells(depth: float, shell: float, r_in: float, r_out: float) -> int:
    """Shells of thickness ``shell`` [m] in a layered zone ``depth`` [m] deep on a roll wound
    from ``r_in`` to ``r_out`` (2D and 3D layered models alike); the zone must be shallower
    than the wound thickness and leave a continuum below it (one-line errors naming
    ``layered_depth``)."""
    if depth >= r_out - r_in:
        raise InputError(
            f"the layered zone ({depth * 1e3:.4g} mm) must be shallower than the wound "
            f"thickness ({(r_out - r_in) * 1e3:.4g} mm)",
            "layered_depth",
        )
    n_shells = max(1, round(depth / shell))
    if n_shells * shell >= 0.9 * (r_out - r_in):
        raise InputError(
            f"the layered zone ({n_shells * shell * 1e3:.4g} mm) must leave a continuum below "
            f"it (wound thickness {(r_out - r_in) * 1e3:.4g} mm)",
            "layered_depth",
        )
    return n_shells


def layered_radii(
    r_in: float, r_out: float, shell: float, n_shells: int, growth: float
) -> FloatArray:
    """Ring radii [m], core to surface: ``n_shells`` uniform shells of thickness ``shell``
    under the surface, then sizes graded from ``shell`` by ``growth`` toward the core."""
    below = graded_sizes(r_out - r_in - n_shells * shell, shell, growth, "layered_depth")
    sizes = np.concatenate([np.full(n_shells, shell), below])
    r = r_out - np.concatenate([[0.0], np.cumsum(sizes)])[::-1]
    r[0] = r_in
    return r


class _CutAssembler(Assembler):
    """The 2D assembler plus the augmentation ``rho (u_a - u_b)^2`` on every interface
    pair (free indices ``fa`` below, ``fb`` above); ``rho`` per pair is ``penalty`` times
    the mean stiffness diagonal of the pair, set at each assembly (:attr:`rho`)."""

    def __init__(
        self,
        basis: Any,
        free: Any,
        diagonal: Any,
        fa: IntArray,
        fb: IntArray,
        penalty: float,
        order: IntArray | None = None,
    ) -> None:
        super().__init__(basis, free, diagonal, order)
        self.fa, self.fb, self.penalty = fa, fb, penalty
        self.rho = np.zeros(fa.size)
        #: the pairs augmented (the stick set of the active-set passes)
        self.stick = np.ones(fa.size, dtype=bool)
        self.band_stick = self.stick.copy()  # the stick set of the last assembly

    def band(self, *moduli: FloatArray, reverse: bool = False, springs: bool = True) -> FloatArray:
        ab = super().band(*moduli, reverse=reverse, springs=springs)
        if self.fa.size == 0:
            return ab
        n = self.n_free
        fa, fb = self.fa, self.fb

        def col(i: IntArray) -> IntArray:
            return n - 1 - i if reverse else i

        diag = 0.5 * (ab[0, col(fa)] + ab[0, col(fb)])
        self.rho = self.penalty * diag
        rho = np.where(self.stick, self.rho, 0.0)
        self.band_stick = self.stick.copy()
        ab[0, col(fa)] += rho
        ab[0, col(fb)] += rho
        hi, lo = np.maximum(fa, fb), np.minimum(fa, fb)
        ab[hi - lo, col(hi) if reverse else lo] -= rho
        return ab


def _pair_geometry(mesh: RollMesh, jj: IntArray, kk: IntArray) -> tuple[FloatArray, IntArray]:
    """The tributary interface arc [m] of each pair (tangential node ``jj`` on cut ring
    ``kk`` of the uncut ``mesh``) and the four elements around it (their mean stress is the
    pair's pressure)."""
    nr, nt = mesh.n_r, mesh.n_theta
    dth = np.diff(mesh.theta)
    trib_t = 0.5 * (np.concatenate([[0.0], dth]) + np.concatenate([dth, [0.0]]))

    def el(jq: IntArray, iq: IntArray) -> IntArray:
        return jq * (nr - 1) + iq

    elements = np.stack([el(jj - 1, kk - 1), el(jj, kk - 1), el(jj - 1, kk), el(jj, kk)], axis=1)
    assert np.all(elements < (nt - 1) * (nr - 1))
    return mesh.r[kk] * trib_t[jj], elements


class _LayeredRoll(_Roll):
    """The roll of the 2D model on the layered mesh (module docstring)."""

    def __init__(
        self,
        web: Web,
        core: Core,
        radius: FloatArray,
        sigma_r: FloatArray,
        mesh: RollMesh,
        cut: IntArray,
        opts: LayeredOptions,
    ) -> None:
        base = opts.base
        # the continuum roll on the uncut mesh: element data, pre-stress, moduli law
        super().__init__(web, core, radius, sigma_r, mesh, base)
        nr, nt = mesh.n_r, mesh.n_theta
        is_cut = np.zeros(nr, dtype=bool)
        is_cut[cut] = True
        lower = np.arange(nr) + np.concatenate([[0], np.cumsum(is_cut)[:-1]])
        upper = lower + is_cut
        nr2 = nr + int(is_cut.sum())
        r2 = np.empty(nr2)
        r2[lower] = mesh.r
        r2[upper] = mesh.r
        lmesh = LayeredMesh(r2, mesh.theta, int(is_cut.sum()))
        # element DOFs on the doubled rings
        conn = mesh.connectivity()
        j = conn // nr
        i = conn % nr
        ring = lower[i]
        node_r = j * nr2 + ring
        # inner nodes (0, 3) of an element sitting on a cut take the upper copy's u_theta
        ring_t = ring.copy()
        ring_t[:, [0, 3]] = upper[i[:, [0, 3]]]
        node_t = j * nr2 + ring_t
        dofs = np.empty((conn.shape[0], 8), dtype=np.int64)
        dofs[:, 0::2] = 2 * node_r
        dofs[:, 1::2] = 2 * node_t + 1
        self.basis = dataclasses.replace(self.basis, dofs=dofs)
        n_dof = 2 * lmesh.n_nodes
        free = np.zeros(n_dof, dtype=bool)
        free[np.unique(dofs)] = True
        core_nodes = lmesh.core_nodes()
        free[2 * core_nodes + 1] = False
        free[2 * lmesh.edge_nodes() + 1] = False
        diagonal = None
        if core.rigid:
            free[2 * core_nodes] = False
        else:
            th = mesh.theta
            dth = np.diff(th)
            trib = 0.5 * (np.concatenate([[0.0], dth]) + np.concatenate([dth, [0.0]]))
            diagonal = np.zeros(n_dof)
            diagonal[2 * core_nodes] = core.stiffness * trib
        # interface pairs: every cut ring, every tangential node off the symmetry lines
        jj, kk = np.meshgrid(np.arange(1, nt - 1), np.flatnonzero(is_cut), indexing="ij")
        jj, kk = jj.ravel(), kk.ravel()
        self.pair_a = 2 * (jj * nr2 + lower[kk]) + 1
        self.pair_b = 2 * (jj * nr2 + upper[kk]) + 1
        self.pair_ring, self.pair_j = kk, jj
        self.free = free
        # the unknowns ring by ring (surface first) where the mesh has more rings than
        # nodes on a ring, as a layered zone of many sheets does: the band narrows from
        # ~2 (n_r + cuts) to ~3 n_theta, the same equations (fem.ring_major_order)
        order = ring_major_order(nr2, nt, free, dofs)
        fi = np.full(n_dof, -1, dtype=np.int64)
        fi[np.flatnonzero(free) if order is None else order] = np.arange(int(free.sum()))
        self.assembler = _CutAssembler(
            self.basis, free, diagonal, fi[self.pair_a], fi[self.pair_b], opts.penalty, order
        )
        self.mesh = lmesh
        self.uncut_mesh = mesh
        self.xy = lmesh.node_xy()
        self.angle = lmesh.node_angle()
        self.surface = lmesh.surface_nodes()
        self.pair_arc, self.pair_elements = _pair_geometry(mesh, jj, kk)

    def jump(self, du: FloatArray) -> FloatArray:
        """Tangential jump ``u_theta(above) - u_theta(below)`` at the pairs [m]."""
        return du[self.pair_b] - du[self.pair_a]

    def pressure(self, sig_r: FloatArray) -> FloatArray:
        """Interface pressure [Pa] at the pairs: ``-(sigma_pre + sigma_r)`` of the four
        elements around each, averaged (compression positive)."""
        total = self.sigma_pre + sig_r
        return -np.mean(total[self.pair_elements], axis=1)


class _LayeredLoading(_Loading):
    """The 2D model's loading with the active-set passes in every solve (module docstring)."""

    def __init__(self, roll: _LayeredRoll, lopts: LayeredOptions, *args: Any) -> None:
        super().__init__(roll, lopts.base, *args)
        self.lopts = lopts
        self.T = np.zeros(roll.pair_a.size)  # interface shear force per pair [N/m]
        self.T_trial = self.T
        self.slip = np.zeros(roll.pair_a.size)  # accumulated |slip| [m]
        self.slip_trial = self.slip
        self.g_trial = np.zeros(roll.pair_a.size)
        self.stick_trial = np.ones(roll.pair_a.size, dtype=bool)
        self.passes = 0
        self.updates = 0  # active-set passes on a low-rank update of the factor
        # the pairs that may slip (_Diagnostics.slip_region); the others always stick
        self.may_slip = np.ones(roll.pair_a.size, dtype=bool)
        region = getattr(lopts, "slip_region", None)  # _Diagnostics
        self.cohesion = float(getattr(lopts, "cohesion", 0.0))
        if region is not None:
            depth, angle = region
            mesh = roll.uncut_mesh
            self.may_slip = (float(mesh.r[-1]) - mesh.r[roll.pair_ring] <= depth) & (
                mesh.theta[roll.pair_j] <= angle
            )

    def bound(self) -> FloatArray:
        """Coulomb's limit (cohesion + mu P) A per pair [N/m] at the start of the increment."""
        roll: _LayeredRoll = self.roll  # type: ignore[assignment]
        p = np.maximum(roll.pressure(self.sig[:, 0]), 0.0)
        # outside the slip region a bound no force reaches (finite: sign * bound stays a number)
        limit = (self.cohesion + self.friction * p) * roll.pair_arc
        return np.where(self.may_slip, limit, _NO_LIMIT)

    def solve(
        self, mod: tuple[FloatArray, ...], lu: _Factor, extra: FloatArray | None = None
    ) -> _Step:
        """The increment at fixed moduli with the interfaces' Coulomb law: the primal-dual
        active-set passes of the module docstring (``lu``: the stiffness factorised with
        the current stick set)."""
        roll: _LayeredRoll = self.roll  # type: ignore[assignment]
        asm: _CutAssembler = roll.assembler  # type: ignore[assignment]
        n_pairs = roll.pair_a.size

        def contact(load: FloatArray | None, lu: _Factor) -> _Step:
            return _step(
                roll,
                mod,
                lu,
                self.u,
                self.f_contact,
                self.lam,
                self.centre,
                self.head_radius,
                self.tol_gap,
                load,
            )

        if n_pairs == 0 or not self.lopts.interfaces:
            step = contact(extra, lu)
            if extra is not None:
                step.dsig = roll.stress_increment(mod, step.du)
            return step
        # a factor made by the 2D model's step control was assembled just before with the
        # stick set of that moment; one made at another set (the frozen stiffness of
        # update_modulus=False) is made again at the current one
        if getattr(lu, "stick", None) is None:
            lu.stick = asm.band_stick  # type: ignore[attr-defined]
        if not np.array_equal(lu.stick, asm.stick):  # type: ignore[attr-defined]
            lu = _factorize(roll, mod)
            lu.stick = asm.band_stick  # type: ignore[attr-defined]
            self.factorisations += 1
        g = self.bound()
        t_old = self.T
        stick = asm.stick.copy()
        updated = _UpdatedFactor(lu, stick, asm.rho)
        sign = np.sign(t_old)
        T = np.where(stick, t_old, sign * g)
        fa, fb = asm.fa, asm.fb
        for _ in range(self.lopts.max_passes):
            step, s, scale = self._stick_passes(contact, lu, T, t_old, stick, extra)
            # the active set: a stick pair over its limit slips along its force; a slipping
            # pair that moves against its force sticks
            over = stick & (np.abs(T) > g * (1.0 + 1e-9))
            back = ~stick & (s * sign < -BACK_TOL * scale)
            if not np.any(over) and not np.any(back):
                break
            sign = np.where(over, np.sign(T), sign)
            stick = (stick & ~over) | back
            T = np.where(stick, T, sign * g)
            asm.stick = stick
            near = updated.at(stick, fa, fb, asm.n_free) if WOODBURY_MAX > 0 else None
            if near is not None:
                lu = near  # type: ignore[assignment]
                self.updates += 1
                continue
            lu = _factorize(roll, mod)
            lu.stick = asm.band_stick  # type: ignore[attr-defined]
            updated = _UpdatedFactor(lu, stick, asm.rho)
            self.factorisations += 1
        else:
            raise self._unsettled("stick and slip zones")
        step.dsig = roll.stress_increment(mod, step.du)
        self.T_trial = T
        self.g_trial = g
        self.stick_trial = stick
        self.slip_trial = self.slip + np.where(stick, 0.0, np.abs(s))
        return step

    def _stick_passes(
        self,
        contact: Callable[[FloatArray | None, _Factor], _Step],
        lu: _Factor,
        T: FloatArray,
        t_old: FloatArray,
        stick: NDArray[np.bool_],
        extra: FloatArray | None,
    ) -> tuple[_Step, FloatArray, float]:
        """Uzawa passes at a fixed stick set on its augmented factor ``lu``: the interface
        forces ``T`` (updated in place) move the stick pairs until their tangential jumps
        vanish (to ``tol`` of the largest displacement increment); the last step, the jumps
        and that scale."""
        roll: _LayeredRoll = self.roll  # type: ignore[assignment]
        asm: _CutAssembler = roll.assembler  # type: ignore[assignment]
        rho = asm.rho
        for _ in range(self.lopts.max_passes):
            x = -(T - t_old)
            load = np.zeros(asm.n_free) if extra is None else extra.copy()
            np.add.at(load, asm.fb, x)
            np.add.at(load, asm.fa, -x)
            step = contact(load, lu)
            self.passes += 1
            s = roll.jump(step.du)
            scale = max(float(np.max(np.abs(step.du))), 1e-300)
            viol = float(np.max(np.abs(s[stick]), initial=0.0)) / scale
            T[stick] += rho[stick] * s[stick]
            if viol <= self.lopts.tol:
                return step, s, scale
        raise self._unsettled("stick multipliers")

    def _unsettled(self, what: str) -> ConvergenceError:
        k = min(self.history_k, self.delta.size - 1)
        return ConvergenceError(
            f"the interface {what} did not settle in {self.lopts.max_passes} passes at depth "
            f"{self.delta[k] * 1e3:.3g} mm; use more n_steps or raise options.max_passes"
        )

    history_k = 0

    def advance(self, k: int) -> _Step:
        self.history_k = k
        step = super().advance(k)
        self.T = self.T_trial
        # the next increment starts from this one's stick set (slipping pairs keep slipping
        # while the head goes on)
        asm: _CutAssembler = self.roll.assembler  # type: ignore[assignment]
        asm.stick = self.stick_trial.copy()
        self.slip = self.slip_trial
        return step


@dataclass(frozen=True)
class LayeredState:
    """The interfaces at the deepest depth solved (for studies and checks).

    Attributes
    ----------
    depth : ndarray [m]
        Depth of each interface pair under the undeformed surface.
    s : ndarray [m]
        Arc coordinate of each pair along the interface (r theta).
    pressure : ndarray [Pa]
        Interface pressure P (wound-in plus the head's).
    shear : ndarray [Pa]
        Interface shear traction T / A.
    slip : ndarray [m]
        Accumulated slip |q| summed over the increments.
    limit : ndarray [Pa]
        Coulomb's limit mu P (plus ``_Diagnostics.cohesion``) of the last increment (P at
        its start: explicit); 1e300 / A where the pair always sticks
        (``_Diagnostics.slip_region``).
    passes : int
        Head-contact solves (Uzawa passes) over the whole loading.
    n_shells : int
        Shells in the layered zone.
    """

    depth: FloatArray
    s: FloatArray
    pressure: FloatArray
    shear: FloatArray
    slip: FloatArray
    limit: FloatArray
    passes: int
    n_shells: int


def layered_mesh_inputs(
    web: Web,
    core: Core,
    r_out: float,
    head_radius: float,
    depth_max: float,
    lopts: LayeredOptions,
) -> tuple[RollMesh, IntArray, int]:
    """The uncut mesh, the interface ring indices (original numbering) and the shell count."""
    base = lopts.base
    r_in = core.outer_radius
    R_eff = 1.0 / (1.0 / head_radius + 1.0 / r_out)
    a_geo = math.sqrt(2.0 * R_eff * depth_max)
    shell = lopts.layers_per_shell * web.thickness
    depth = lopts.layered_depth if lopts.layered_depth is not None else LAYERED_DEPTH * a_geo
    n_shells = zone_shells(depth, shell, r_in, r_out)
    r = layered_radii(r_in, r_out, shell, n_shells, base.radial_growth)
    t_size = (
        base.tangential_size
        if base.tangential_size is not None
        else max(0.25 * web.thickness, a_geo / 40.0)
    )
    fine = base.fine_halfwidth if base.fine_halfwidth is not None else FINE_ZONE * a_geo
    theta_mesh = build_mesh(
        r_in,
        r_out,
        surface_size=min(shell, 0.4 * (r_out - r_in)),
        radial_growth=base.radial_growth,
        tangential_size=t_size,
        fine_halfwidth=max(fine, t_size),
        tangential_growth=base.tangential_growth,
        max_element_angle=base.max_element_angle,
    )
    mesh = RollMesh(r=r, theta=theta_mesh.theta, j0=0, periodic=False)
    cut = r.size - 1 - np.arange(1, n_shells + 1)
    return mesh, cut, n_shells


def indent_layered(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    *,
    head_radius: float | str,
    head_length: float | str,
    depth_max: float | str = 1e-3,
    friction: float = INTERLAYER_FRICTION,
    update_modulus: bool = True,
    options: LayeredOptions | None = None,
    stop: Callable[[FloatArray, FloatArray], bool] | None = None,
    extend_to: float | None = None,
    state: list[LayeredState] | None = None,
) -> ContactResult:
    """Press a rigid cylindrical head into the layered roll; F(d), a(d) and the fields as
    :func:`woundroll.contact.indent` (same parameters; ``options`` a
    :class:`LayeredOptions`; ``friction`` mu > 0 between the sheets). ``state``: a list
    the interfaces' :class:`LayeredState` at the last depth is appended to.

    Raises
    ------
    InputError
        As :func:`woundroll.contact.indent`; mu <= 0 (``contact.friction``); a layered zone
        as deep as the roll (``contact.layered_depth``).
    ConvergenceError
        The contact set or the interface friction does not settle.
    """
    t0 = time.perf_counter()
    lopts = options if options is not None else LayeredOptions()
    if not isinstance(lopts, LayeredOptions):
        raise InputError("must be a LayeredOptions", "options")
    sizes, mu, r, s, _ = _indent_inputs(
        web,
        core,
        radius,
        sigma_r,
        (head_radius, head_length, depth_max, extend_to if stop is not None else None),
        friction,
        lopts.base,
    )
    if not mu > 0:
        raise InputError(
            f"must be positive for the layered model (sheets with no friction carry no "
            f"shear between them), got {mu:g}",
            "friction",
        )
    head_radius, head_length, depth_max, deepest = sizes
    r_out = float(r[-1])
    mesh, cut, n_shells = layered_mesh_inputs(web, core, r_out, head_radius, deepest, lopts)
    if not lopts.interfaces:
        cut = cut[:0]
    roll = _LayeredRoll(web, core, r, s, mesh, cut, lopts)
    delta = depth_schedule(depth_max, int(lopts.base.n_steps), lopts.base.step_exponent, deepest)
    load = _LayeredLoading(roll, lopts, delta, head_radius, mu, update_modulus)
    # one BLAS thread (woundroll.util.blas): the many small banded factorisations of the
    # active-set passes ran 10-100x slower with OpenBLAS's threads on the loaded 2-core
    # machine (a 5-sheet test roll: 72 s against 2.3 s)
    from woundroll.util.blas import one_blas_thread

    with one_blas_thread():
        h, u_hist, s_surf = _press(load, 2.0, head_length, stop)
    res = _result2d(load, h, u_hist, s_surf, head_length, update_modulus, t0)
    res = dataclasses.replace(res, mesh_shape=(mesh.n_r - 1, mesh.n_theta))
    if state is not None:
        p = roll.pressure(load.sig[:, 0])
        state.append(
            LayeredState(
                depth=r_out - mesh.r[roll.pair_ring],
                s=r_out * mesh.theta[roll.pair_j],
                pressure=p,
                shear=load.T / roll.pair_arc,
                slip=load.slip,
                limit=load.g_trial / roll.pair_arc,
                passes=load.passes,
                n_shells=n_shells,
            )
        )
    return res


__all__ = ["LAYERED_DEPTH", "LayeredOptions", "LayeredState", "indent_layered"]
