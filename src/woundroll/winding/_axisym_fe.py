"""Axisymmetric (r, z) finite elements of the wound stack (used by ``axisymmetric.py``).

Mesh: node ``(k, i)`` at layer-group boundary ``k`` (0 on the core) and sector edge ``i``
(``n_sectors + 1`` edges, free CMD edges at both ends); element ``(k, j)`` is layer group
``k`` in sector ``j``, the rectangle ``[R[k, j], R[k+1, j]] x [e_j, e_(j+1)]`` of the sector's
own build (nodes are shared by layer index, i.e. a layer is continuous across the CMD; the
tilt of the layers where the build changes across the CMD, at most a few per cent, is not
rotated into the material axes). Two unknowns per node, ``u_r`` and ``u_z``.

Interpolation (tensor product): linear in z; in r the exact solution of the uniform-modulus
ring, ``u_r`` in span{x^g, x^-g} (``x = r / r_m``, ``g = sqrt(E_theta / E_r)``), written as
``N_1 = sinh(g (s_2 - s)) / sinh(g D)``, ``N_2 = sinh(g (s - s_1)) / sinh(g D)`` with
``s = ln r``, ``D = s_2 - s_1`` (stable for g D -> 0, where it tends to linear in ln r);
``u_z`` linear in r (it must contain the rigid axial translation; a power-law basis for u_z
does not, and produced spurious shear). With ``shape="linear"`` u_r is linear in r too
(kept for the comparison in docs/profile.md).

Constitutive law: full cylindrically orthotropic compliance in (r, theta, z) with the
project's convention ``nu_ij = -eps_j / eps_i`` under ``sigma_i`` (materials/web.py):

    eps_r     =  sigma_r/E_r - nu_theta_r sigma_theta/E_theta - nu_z_r sigma_z/E_z
    eps_theta = -nu_theta_r sigma_r/E_theta + sigma_theta/E_theta - nu_theta_z sigma_z/E_theta
    eps_z     = -nu_z_r sigma_r/E_z - nu_theta_z sigma_theta/E_theta + sigma_z/E_z
    tau_rz    =  G_rz (du_r/dz + du_z/dr)

Energy per radian ``1/2 int (eps . C eps + G_rz gamma^2) r dr dz``: the radial integrals by
Gauss-Legendre (``NQ`` points), the axial ones exactly. Stiffness matrices are symmetric
positive definite and assembled straight into banded storage in the mesh's order (layer by
layer, CMD within a layer: bandwidth ``2 n_sectors + 5``), factorised by banded Cholesky
(LAPACK ``pbtrf``, called directly on a Fortran-ordered band): measured 1.9x faster than
SuperLU with a fill-reducing order on the Table 3 window (docs/profile.md, section 7).
"""

from __future__ import annotations

import numpy as np
from numpy.linalg import LinAlgError
from numpy.typing import NDArray
from scipy.linalg.lapack import dpbtrf, dpbtrs

FloatArray = NDArray[np.float64]

NQ = 6
_XQ, _WQ = np.polynomial.legendre.leggauss(NQ)
_PATTERN_CACHE_MAX = 400_000  # entries of a cached assembly pattern (window-sized stacks)
_GD_MAX = 60.0  # cap of g ln(r2/r1): the shapes are then pure surface exponentials


def _cholesky_band(ab: FloatArray) -> FloatArray:
    """Lower banded Cholesky factor (LAPACK ``dpbtrf``) of ``ab``, overwritten in place
    (``ab`` is built Fortran-ordered by :meth:`Stack._system`, so nothing is copied); as
    ``scipy.linalg.cholesky_banded`` without its checks and copy. The lower form: 1.89
    against 2.18 ms for the upper one on a Table 3 window (3,224 unknowns, half-bandwidth
    125, one BLAS thread)."""
    c, info = dpbtrf(ab, lower=1, overwrite_ab=1)
    if info > 0:
        raise LinAlgError(f"{info}-th leading minor not positive definite")
    if info < 0:
        raise ValueError(f"illegal value in {-info}-th argument of internal pbtrf")
    return c


def _cho_solve_band(cb: FloatArray, rhs: FloatArray) -> FloatArray:
    """Solve with the factor of :func:`_cholesky_band` (LAPACK ``dpbtrs``, ``rhs`` is
    overwritten)."""
    x, info = dpbtrs(cb, rhs, lower=1, overwrite_b=1)
    if info != 0:
        raise ValueError(f"illegal value in {-info}-th argument of internal pbtrs")
    return x


def material_matrices(
    E_r: FloatArray,
    E_t: float,
    E_z: float,
    nu_tr: float,
    nu_zr: float,
    nu_tz: float,
) -> FloatArray:
    """Stiffness ``C`` (..., 3, 3) in (r, theta, z): inverse of the compliance above, by
    cofactors (only ``S_rr = 1 / E_r`` varies; equal to ``np.linalg.inv`` to round-off)."""
    a = 1.0 / np.asarray(E_r, dtype=float)
    b, c = 1.0 / E_t, 1.0 / E_z
    d, e, f = -nu_tr / E_t, -nu_zr / E_z, -nu_tz / E_t
    c00 = b * c - f * f  # cofactors of the symmetric compliance [[a d e] [d b f] [e f c]]
    c01 = e * f - d * c
    c02 = d * f - e * b
    det = a * c00 + d * c01 + e * c02
    C = np.empty(a.shape + (3, 3))
    C[..., 0, 0] = c00 / det
    C[..., 0, 1] = C[..., 1, 0] = c01 / det
    C[..., 0, 2] = C[..., 2, 0] = c02 / det
    C[..., 1, 1] = (a * c - e * e) / det
    C[..., 1, 2] = C[..., 2, 1] = (d * e - a * f) / det
    C[..., 2, 2] = (a * b - d * d) / det
    return C


def _shape_rows(r1, r2, g, r, shape: str = "power") -> tuple[FloatArray, ...]:
    """Radial shape functions (module docstring) at radii ``r`` (..., q) of elements
    [r1, r2] (..., 1), ``g`` (..., 1), as eight separate arrays (no stacking: hot path):
    N_1, N_2, dN_1/dr, dN_2/dr for u_r and L_1, L_2 (shape of ``r``), dL_1/dr, dL_2/dr
    (shape of ``r1``: constant over the element) for u_z."""
    Lr = r2 - r1
    L1, L2 = (r2 - r) / Lr, (r - r1) / Lr
    dL2 = 1.0 / Lr
    dL1 = -dL2
    if shape == "linear":
        dN1, dN2 = np.broadcast_to(dL1, r.shape), np.broadcast_to(dL2, r.shape)
        return L1, L2, dN1, dN2, L1, L2, dL1, dL2
    s1, s2, s = np.log(r1), np.log(r2), np.log(r)
    D = s2 - s1
    gg = np.minimum(g, _GD_MAX / D)
    small = gg * D < 1e-6
    gs = np.where(small, 1e-6 / D, gg)  # sinh ratio -> linear in ln r (to 1e-13)
    den = np.sinh(gs * D)
    a1, a2 = gs * (s2 - s), gs * (s - s1)
    t = gs / (r * den)
    return np.sinh(a1) / den, np.sinh(a2) / den, -t * np.cosh(a1), t * np.cosh(a2), L1, L2, dL1, dL2


class Stack:
    """Assembly and solution of the incremental problem of a stack of layer groups.

    Parameters
    ----------
    dz : (n_sectors,) sector widths [m].
    core_stiffness : E_c per unit area [Pa] (``inf``: rigid, u_r = 0 on the core).
    material : (E_t, E_z, nu_tr, nu_zr, nu_tz).
    shear : callable E_r -> G_rz.
    """

    def __init__(self, dz, core_stiffness, material, shear, shape="power"):
        self.dz = np.asarray(dz, dtype=float)
        self.ncol = self.dz.size
        self.nc1 = self.ncol + 1
        self.E_c = float(core_stiffness)
        self.rigid = not np.isfinite(self.E_c)
        self.mat = material
        self.shear = shear
        self.shape = shape
        # local dof (a, b, c): radial node a, CMD node b, component c (0: u_r, 1: u_z)
        a, b, c = np.meshgrid([0, 1], [0, 1], [0, 1], indexing="ij")
        self._loc = (a.ravel(), b.ravel(), c.ravel())
        dzz = self.dz[:, None, None]
        self.M0 = dzz / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])[None]
        self.M1 = 1.0 / dzz * np.array([[1.0, -1.0], [-1.0, 1.0]])[None]
        self.Zx = np.array([[-0.5, 0.5], [-0.5, 0.5]])  # int M_b dM_d/dz dz
        self.u_z_fixed_node = self.ncol // 2  # on the core: removes the rigid translation

    def dofs(self, ne: int) -> NDArray[np.int64]:
        """Global dofs (ne, ncol, 8) of the elements of a stack of ``ne`` groups."""
        k = np.arange(ne)[:, None, None]
        j = np.arange(self.ncol)[None, :, None]
        a, b, c = self._loc
        return 2 * ((k + a) * self.nc1 + j + b) + c

    def _element_matrices(self, rn: FloatArray, E_r: FloatArray) -> tuple:
        """Element stiffness matrices of the groups ``E_r.shape[0]`` x sectors, as
        ``K[e, c, c', a, a', b, b']`` (component c, radial node a, CMD node b of the row;
        primed: of the column; ``e`` the element, groups outer, sectors inner): the tensor
        product of a radial 2x2 integral and an axial 2x2 integral per component pair, laid
        out so that each pair is one contiguous product (the global dofs are indexed to
        match in :meth:`_system`). Also returns the material matrices and G_rz.

        The radial integrals ``int f_i f_j w dr`` (weights r, 1, 1/r) of the rows
        ``F = (N_1, N_2, dN_1, dN_2, L_1, L_2, 1)`` are one batched product
        ``(F w) F^T``; each component pair (c, c') is then ``R_0 x Z_0 + R_1 x Z_1`` with
        the axial factors ``Z`` of :meth:`_axial_factors` (per sector, built once), one
        batched product too."""
        E_t, E_z, nu_tr, nu_zr, nu_tz = self.mat
        shp = E_r.shape
        nel = E_r.size
        r1, r2 = rn[:-1].reshape(nel, 1), rn[1:].reshape(nel, 1)
        h = 0.5 * (r2 - r1)
        rq = 0.5 * (r1 + r2) + h * _XQ  # (nel, NQ)
        wq = h * _WQ
        g = np.sqrt(E_t / E_r).reshape(nel, 1)
        N1, N2, dN1, dN2, L1, L2, dL1, dL2 = _shape_rows(r1, r2, g, rq, self.shape)
        F = np.empty((nel, 7, NQ))
        F[:, 0], F[:, 1], F[:, 2], F[:, 3], F[:, 4], F[:, 5] = N1, N2, dN1, dN2, L1, L2
        F[:, 6] = 1.0
        Fw = np.empty((nel, 13, NQ))  # rows F w_r (7), (N, dN) w_1 (4), N w_(1/r) (2)
        wr = wq * rq
        np.multiply(F, wr[:, None], out=Fw[:, :7])
        np.multiply(F[:, :4], wq[:, None], out=Fw[:, 7:11])
        np.multiply(F[:, :2], (wq / rq)[:, None], out=Fw[:, 11:])
        P = Fw @ F.transpose(0, 2, 1)  # (nel, 13, 7)
        Rrr, Rnn, Arz, Bzz = P[:, 2:4, 2:4], P[:, 0:2, 0:2], P[:, 2:4, 4:6], P[:, 4:6, 4:6]
        Rrt, Atz, Rtt = P[:, 9:11, 0:2], P[:, 7:9, 4:6], P[:, 11:13, 0:2]
        dL = np.concatenate([dL1, dL2], axis=1)  # (nel, 2): constant over the element
        Ag = P[:, 0:2, 6:7] * dL[:, None, :]
        Bgg = P[:, 6:7, 6:7] * (dL[:, :, None] * dL[:, None, :])
        C = material_matrices(E_r, E_t, E_z, nu_tr, nu_zr, nu_tz)
        Gs = self.shear(E_r)
        Cf = C.reshape(nel, 9, 1, 1)
        Gq = Gs.reshape(nel, 1, 1)
        R = np.empty((nel, 4, 2, 2, 2))  # [e, pair 00 01 10 11, a, a', term]
        R[:, 0, :, :, 0] = Cf[:, 0] * Rrr + Cf[:, 1] * (Rrt + Rrt.transpose(0, 2, 1))
        R[:, 0, :, :, 0] += Cf[:, 4] * Rtt
        R[:, 1, :, :, 0] = Cf[:, 2] * Arz + Cf[:, 5] * Atz
        R[:, 2, :, :, 0] = R[:, 1, :, :, 0].transpose(0, 2, 1)
        R[:, 3, :, :, 0] = Cf[:, 8] * Bzz
        R[:, 0, :, :, 1] = Gq * Rnn
        R[:, 1, :, :, 1] = Gq * Ag
        R[:, 2, :, :, 1] = R[:, 1, :, :, 1].transpose(0, 2, 1)
        R[:, 3, :, :, 1] = Gq * Bgg
        # K[e, pair, aa', bb'] = sum over the two terms of R[..., aa', term] Z[term, bb']
        K = R.reshape(shp[0], shp[1], 4, 4, 2) @ self._axial_factors()
        return K.reshape(nel, 2, 2, 2, 2, 2, 2), C, Gs

    def _axial_factors(self) -> FloatArray:
        """The axial 2x2 integrals of the component pairs (00, 01, 10, 11) by sector, the
        factors of the two radial terms of each pair: 00 ``(M0, M1)``, 01 ``(Zx, Zx^T)``,
        10 ``(Zx^T, Zx)``, 11 ``(M1, M0)``; (ncol, 4, 2 terms, 4 = (b, b')), built once."""
        if "_Z" not in self.__dict__:
            zx = np.broadcast_to(self.Zx, self.M0.shape)
            zt = zx.transpose(0, 2, 1)
            Z0 = np.stack([self.M0, zx, zt, self.M1], axis=1).reshape(self.ncol, 4, 1, 4)
            Z1 = np.stack([self.M1, zt, zx, self.M0], axis=1).reshape(self.ncol, 4, 1, 4)
            self._Z = np.concatenate([Z0, Z1], axis=2)
        return self._Z

    def _element_dofs(self, ne: int) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
        """Global row and column dofs matching :meth:`_element_matrices`' layout."""
        d = self.dofs(ne).reshape(-1, 2, 2, 2).transpose(0, 3, 1, 2)  # (e, c, a, b)
        shape = (d.shape[0], 2, 2, 2, 2, 2, 2)
        rows = np.broadcast_to(d[:, :, None, :, None, :, None], shape).ravel()
        cols = np.broadcast_to(d[:, None, :, None, :, None, :], shape).ravel()
        return rows, cols

    def bandwidth(self) -> int:
        """Upper bandwidth of the stiffness in the mesh's (layer by layer, then CMD) order:
        an element couples nodes (k, i) and (k + 1, i + 1), ``2 (ncol + 2) + 1`` dofs apart;
        a condensed deep part couples the ``2 (ncol + 1)`` dofs of one layer."""
        return max(2 * (self.nc1 + 1) + 1, 2 * self.nc1 - 1)

    def _system(
        self, rn: FloatArray, E_r: FloatArray, S: FloatArray | None
    ) -> tuple[FloatArray, NDArray[np.bool_], FloatArray | None, FloatArray | None]:
        """Stiffness of a stack of ``ne = E_r.shape[0]`` groups (local layers 0..ne), as the
        lower band ``ab`` (``ab[i - j, j] = A[i, j]``, i >= j, ``u`` = :meth:`bandwidth`) in the
        mesh's order. The bottom layer lies on the core (``S`` None: Hakiel's core spring or
        a rigid core, u_z fixed at one node) or carries the condensed stiffness ``S`` of a
        deep part."""
        ne = E_r.shape[0]
        n = 2 * (ne + 1) * self.nc1
        u = self.bandwidth()
        pattern = self._pattern(ne, S is not None)
        take, pos, fixed = pattern
        vals = [np.zeros(0)]
        C = Gs = None
        if ne > 0:
            Ke, C, Gs = self._element_matrices(rn, E_r)
            vals.append(Ke.ravel())
        if S is not None:
            vals.append(S.ravel())
        elif not self.rigid:
            vals.append((self.E_c * self.M0).ravel())
        v_ = np.concatenate(vals)
        # Fortran order (column j of the band contiguous), as LAPACK takes it without a copy
        ab = np.bincount(pos, weights=v_[take], minlength=(u + 1) * n).reshape(n, u + 1).T
        ab[0, fixed] = 1.0
        return ab, fixed, C, Gs

    def _pattern(self, ne: int, condensed: bool) -> tuple:
        """Where each entry of the element matrices (then the condensed deep part, or the
        core's spring) goes in the lower band of :meth:`_system`: the indices of the entries
        kept (lower triangle, free dofs) and their flat positions in ``ab``; the fixed dofs.
        Cached by stack height and bottom condition (the same every increment)."""
        cache = self.__dict__.setdefault("_pattern_cache", {})
        key = (ne, condensed)
        if key in cache:
            return cache[key]
        nc1 = self.nc1
        n = 2 * (ne + 1) * nc1
        u = self.bandwidth()
        rows, cols = [np.zeros(0, np.int64)], [np.zeros(0, np.int64)]
        if ne > 0:
            r_e, c_e = self._element_dofs(ne)
            rows.append(r_e)
            cols.append(c_e)
        fixed = np.zeros(n, dtype=bool)
        if condensed:
            i = np.arange(2 * nc1)
            rows.append(np.repeat(i, i.size))
            cols.append(np.tile(i, i.size))
        else:
            if self.rigid:
                fixed[0 : 2 * nc1 : 2] = True
            else:  # Hakiel's core condition, consistent over each sector's width
                i0 = 2 * np.arange(self.ncol)
                ii = np.stack([i0, i0 + 2], axis=-1)
                shape = (self.ncol, 2, 2)
                rows.append(np.broadcast_to(ii[:, :, None], shape).ravel())
                cols.append(np.broadcast_to(ii[:, None, :], shape).ravel())
            if ne == 0:
                fixed[1::2] = True  # no stack: only the core's radial spring
            else:
                fixed[2 * self.u_z_fixed_node + 1] = True
        r_, c_ = np.concatenate(rows), np.concatenate(cols)
        take = np.flatnonzero((r_ >= c_) & ~(fixed[r_] | fixed[c_]))
        pos = c_[take] * (u + 1) + r_[take] - c_[take]  # ab[i - j, j], Fortran order
        if take.size > _PATTERN_CACHE_MAX:
            return take, pos, fixed  # a big deep part: not worth the memory
        if len(cache) >= 16:
            cache.clear()
        cache[key] = (take, pos, fixed)
        return cache[key]

    def solve(
        self, rn: FloatArray, E_r: FloatArray, f_top: FloatArray, S: FloatArray | None = None
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Displacement increments of a stack of ``ne = E_r.shape[0]`` groups.

        rn : (ne + 1, ncol) node radii of each sector's build; E_r : (ne, ncol) element
        moduli; f_top : (ncol + 1,) radial nodal forces per radian on the top nodes; S: the
        condensed deep part under the bottom layer (:meth:`condense`), else the core.
        Returns du_r, du_z (ne + 1, ncol + 1) and the stress increments (5, ne, ncol) of
        :meth:`centre_stress`. Banded Cholesky in the mesh's order (LAPACK ``pbtrf``).
        """
        ne = E_r.shape[0]
        nc1 = self.nc1
        ab, fixed, C, Gs = self._system(rn, E_r, S)
        rhs = np.zeros(ab.shape[1])
        rhs[2 * ne * nc1 : 2 * (ne + 1) * nc1 : 2] = f_top
        rhs[fixed] = 0.0
        x = _cho_solve_band(_cholesky_band(ab), rhs)
        x = x.reshape(ne + 1, nc1, 2)
        du_r, du_z = x[..., 0], x[..., 1]
        if ne == 0:
            return du_r, du_z, np.zeros((5, 0, self.ncol))
        return du_r, du_z, self.centre_stress(rn, E_r, du_r, du_z, C, Gs)

    def condense(self, rn: FloatArray, E_r: FloatArray) -> FloatArray:
        """Freeze the deep part (``E_r.shape[0]`` >= 1 groups on the core): returns its Schur
        complement on its top layer (:meth:`condense_band`); :meth:`recover` gives the deep
        response to a displacement of that layer."""
        S, self._deep = self.condense_band(rn, E_r, None)
        return S

    def recover(self, x_top: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Response of the deep part frozen by :meth:`condense` (:meth:`recover_band`)."""
        return self.recover_band(self._deep, x_top)

    def condense_band(
        self, rn: FloatArray, E_r: FloatArray, S_below: FloatArray | None
    ) -> tuple[FloatArray, tuple]:
        """Freeze a band of ``E_r.shape[0]`` >= 1 groups lying on the core (``S_below``
        None) or on a frozen band below it whose Schur complement on the band's bottom
        layer is ``S_below``. The band is factorised (``A = L L^T``, banded, in the mesh's
        layer-by-layer order, from its bottom up) so that its top layer is eliminated last:
        the trailing block ``L_t`` of the factor gives the Schur complement
        ``S = L_t L_t^T`` (2 (ncol+1))^2 that the band and everything below it present to
        the layer above. Returns S and the band (for :meth:`recover_band`)."""
        ab, fixed, C, Gs = self._system(rn, E_r, S_below)
        cb = _cholesky_band(ab)
        u, n = cb.shape[0] - 1, cb.shape[1]
        t = n - 2 * self.nc1
        i = np.arange(t, n)
        off = i[:, None] - i[None, :]  # row - column
        Lt = np.where((off >= 0) & (off <= u), cb[np.clip(off, 0, u), i[None, :]], 0.0)
        S = Lt @ Lt.T
        S = 0.5 * (S + S.T)
        return S, (cb, S, rn, E_r, C, Gs)

    def recover_band(
        self, band: tuple, x_top: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Response of a frozen band (:meth:`condense_band`) to the displacement ``x_top``
        (ncol+1, 2) of its top layer: du_r, du_z of its layers (k_s + 1, ncol + 1, the
        bottom one being the top layer of the band below, if any) and the stress
        increments (5, k_s, ncol) of its elements. With a band below, the bottom layer's
        motion is what that band responds to (its own :meth:`recover_band`): the solve
        with ``S x_top`` on the top layer returns exactly the displacements that minimise
        the energy of the band and everything below it with the top layer held at x_top."""
        cb, S, rn, E_r, C, Gs = band
        nc1 = self.nc1
        rhs = np.zeros(cb.shape[1])
        rhs[-2 * nc1 :] = S @ x_top.ravel()
        x = _cho_solve_band(cb, rhs).reshape(-1, nc1, 2)
        x[-1] = x_top
        du_r, du_z = x[..., 0], x[..., 1]
        return du_r, du_z, self.centre_stress(rn, E_r, du_r, du_z, C, Gs)

    def centre_stress(self, rn, E_r, du_r, du_z, C, Gs) -> FloatArray:
        """Stress increments (5, ne, ncol): sigma_r, sigma_theta, sigma_z, tau_rz at the
        element centres, then sigma_r on the inner face of each element (on the core for
        the first: the core pressure). Both radii at once (:func:`_shape_rows`)."""
        r1, r2 = rn[:-1, :, None], rn[1:, :, None]
        rm = r1 + np.array([0.5, 0.0]) * (r2 - r1)  # (ne, ncol, 2): centre, inner face
        g = np.sqrt(self.mat[0] / E_r)[..., None]
        N1, N2, dN1, dN2, L1, L2, dL1, dL2 = _shape_rows(r1, r2, g, rm, self.shape)
        ur1, ur2, uz1, uz2 = du_r[:-1], du_r[1:], du_z[:-1], du_z[1:]  # (ne, nc1), a = 1, 2
        U1, U2 = (0.5 * (u[:, 1:] + u[:, :-1])[..., None] for u in (ur1, ur2))  # CMD mean
        Ud1, Ud2 = (u[:, 1:] - u[:, :-1] for u in (ur1, ur2))  # CMD difference
        Z1, Z2 = (0.5 * (u[:, 1:] + u[:, :-1]) for u in (uz1, uz2))
        Zd1, Zd2 = (u[:, 1:] - u[:, :-1] for u in (uz1, uz2))
        dz = self.dz[None, :]
        e_r = dN1 * U1 + dN2 * U2  # (ne, ncol, 2)
        e_t = (N1 * U1 + N2 * U2) / rm
        e_z = (L1 * Zd1[..., None] + L2 * Zd2[..., None]) / dz[..., None]
        gam = (N1[..., 0] * Ud1 + N2[..., 0] * Ud2) / dz + dL1[..., 0] * Z1 + dL2[..., 0] * Z2
        out = np.empty((5,) + E_r.shape)
        for i in range(3):
            Ci = C[..., i, :, None]  # (ne, ncol, 3, 1)
            s_i = Ci[..., 0, :] * e_r + Ci[..., 1, :] * e_t + Ci[..., 2, :] * e_z
            out[i] = s_i[..., 0]
            if i == 0:
                out[4] = s_i[..., 1]
        out[3] = Gs * gam
        return out
