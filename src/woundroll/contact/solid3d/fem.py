"""Cylindrically orthotropic 8-node hexahedra in (r, theta, z): stiffness, mass, strains.

Reusable pieces of the 3D contact model (:mod:`woundroll.contact.solid3d.solver`) and of anything
else that needs the roll as a 3D body (a dynamic impact needs :func:`lumped_mass` too).

**Element.** The exact cylindrical brick ``r_i <= r <= r_i+1``, ``theta_j <= theta <=
theta_j+1``, ``z_k <= z <= z_k+1`` with the polar displacement components (u_r, u_theta, u_z)
trilinear in (r, theta, z), the cylindrical small strains

    eps_r = du_r/dr,  eps_t = (du_t/dtheta + u_r)/r,  eps_z = du_z/dz,
    g_rt = du_r/(r dtheta) + du_t/dr - u_t/r,  g_rz = du_r/dz + du_z/dr,
    g_tz = du_t/dz + du_z/(r dtheta),

integrated over r dr dtheta dz with 2 x 2 x 2 Gauss points. As in the 2D element
(:mod:`woundroll.contact.plane_strain.fem`, docs/contact.md "Why this element"): the hoop strain is
taken on the element's mid-angle (assumed hoop strain: no membrane locking of the hoop-stiff
layers), and each transverse shear strain is sampled on the mid-line of its own two directions
(g_rt at the mid r and mid theta, g_rz at mid r and mid z, g_tz at mid theta and mid z): no
parasitic shear when the long, thin surface elements bend. The element keeps exactly the
six zero-energy modes of a rigid body (tested).

**Fast assembly.** In polar components the element matrices do not depend on theta_j, and they
depend on the element's angle and length only through the factors 1/dtheta, 1/dz of the
derivatives and the volume dtheta dz. So for each radial ring i the matrices
``M[i, (p, q), s, t] = sum_g w_g r_g dr B_s[p]^T B_t[q]`` (p, q the strain components of a
non-zero material constant D_pq; s, t in {1, 1/dtheta, 1/dz}) are computed once, and the
stiffness of every element is one matrix product ``c(e) @ M[i(e)]`` with
``c = D_pq(e) dtheta dz f_s f_t``: a modulus update costs one GEMM per ring and a scatter.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from woundroll.contact.solid3d.mesh import RollMesh3D
from woundroll.materials.web import Web

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Non-zero entries (p, q) of the 6 x 6 material matrix, strains (r, t, z, rt, rz, tz).
D_PAIRS = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2), (3, 3), (4, 4), (5, 5))
_G = np.array([0.5 - 0.5 / np.sqrt(3.0), 0.5 + 0.5 / np.sqrt(3.0)])


def orthotropic_moduli(web: Web, E_r: FloatArray) -> FloatArray:
    """Material constants ``D_pq`` for :data:`D_PAIRS`, shape (9, n) [Pa].

    The normal block is the inverse of the web's compliance in (r, theta, z)
    (:func:`woundroll.contact.plane_strain.fem.plane_strain_moduli` for the convention
    nu_ij / E_i = nu_ji / E_j); shears G_r_theta, G_r_z (``web.shear_r_theta``,
    ``web.shear_r_z``: 2 E_r by default, Table 2) and G_theta_z.
    """
    E_r = np.asarray(E_r, dtype=float)
    Et, Ez = web.E_theta, float(web.E_z)
    a = 1.0 / E_r
    d = np.full_like(E_r, 1.0 / Et)
    f = np.full_like(E_r, 1.0 / Ez)
    b = np.full_like(E_r, -web.nu_theta_r / Et)  # S_rt
    c = np.full_like(E_r, -web.nu_z_r / Ez)  # S_rz
    e = np.full_like(E_r, -web.nu_theta_z / Et)  # S_tz
    # inverse of [[a, b, c], [b, d, e], [c, e, f]] by cofactors
    A11 = d * f - e * e
    A12 = c * e - b * f
    A13 = b * e - c * d
    A22 = a * f - c * c
    A23 = b * c - a * e
    A33 = a * d - b * b
    det = a * A11 + b * A12 + c * A13
    G_tz = np.full_like(E_r, float(web.G_theta_z))
    return np.stack(
        [
            A11 / det,
            A22 / det,
            A33 / det,
            A12 / det,
            A13 / det,
            A23 / det,
            web.shear_r_theta(E_r),
            web.shear_r_z(E_r),
            G_tz,
        ]
    )


def _phi(x: float) -> tuple[FloatArray, FloatArray]:
    return np.array([1.0 - x, x]), np.array([-1.0, 1.0])


def strain_rows(r0: float, dr: float, xi: float, eta: float, zeta: float) -> FloatArray:
    """Strain-displacement rows at the local point (xi, eta, zeta) in [0, 1]^3, split as
    ``B = B[0] + B[1] / dtheta + B[2] / dz``: shape (3, 6, 24) (DOFs ``3 a + c``)."""
    r = r0 + xi * dr
    (px, dx), (pe, de), (pz, dz) = _phi(xi), _phi(eta), _phi(zeta)
    B = np.zeros((3, 6, 24))
    for a in range(8):
        a1, a2, a3 = a & 1, (a >> 1) & 1, (a >> 2) & 1
        N = px[a1] * pe[a2] * pz[a3]
        Nr = dx[a1] * pe[a2] * pz[a3] / dr
        Nt = px[a1] * de[a2] * pz[a3]  # x 1/dtheta
        Nz = px[a1] * pe[a2] * dz[a3]  # x 1/dz
        ur, ut, uz = 3 * a, 3 * a + 1, 3 * a + 2
        B[0, 0, ur] = Nr
        B[0, 1, ur] = N / r
        B[1, 1, ut] = Nt / r
        B[2, 2, uz] = Nz
        B[1, 3, ur] = Nt / r
        B[0, 3, ut] = Nr - N / r
        B[2, 4, ur] = Nz
        B[0, 4, uz] = Nr
        B[2, 5, ut] = Nz
        B[1, 5, uz] = Nt / r
    return B


def _gauss_rows(r0: float, dr: float) -> list[tuple[float, FloatArray]]:
    """(weight x r, B rows) at the 8 Gauss points with the sampling rules of the module."""
    out = []
    for xi in _G:
        for eta in _G:
            for zeta in _G:
                B = strain_rows(r0, dr, xi, eta, zeta)
                B[:, 1] = strain_rows(r0, dr, xi, 0.5, zeta)[:, 1]  # assumed hoop strain
                B[:, 3] = strain_rows(r0, dr, 0.5, 0.5, zeta)[:, 3]
                B[:, 4] = strain_rows(r0, dr, 0.5, eta, 0.5)[:, 4]
                B[:, 5] = strain_rows(r0, dr, xi, 0.5, 0.5)[:, 5]
                out.append((0.125 * (r0 + xi * dr) * dr, B))
    return out


def ring_matrices(r: FloatArray) -> FloatArray:
    """``M`` of the module docstring, shape (n_rings, 9 * 3 * 3, 24 * 24)."""
    n = r.size - 1
    M = np.zeros((n, len(D_PAIRS), 3, 3, 24, 24))
    for i in range(n):
        for w, B in _gauss_rows(float(r[i]), float(r[i + 1] - r[i])):
            for ip, (p, q) in enumerate(D_PAIRS):
                for s in range(3):
                    for t in range(3):
                        m = np.outer(B[s, p], B[t, q])
                        if p != q:
                            m = m + np.outer(B[s, q], B[t, p])
                        M[i, ip, s, t] += w * m
    return M.reshape(n, len(D_PAIRS) * 9, 576)


def centre_rows(r: FloatArray) -> FloatArray:
    """Strain rows at the element centre per ring, shape (n_rings, 3, 6, 24)."""
    return np.stack(
        [strain_rows(float(r[i]), float(r[i + 1] - r[i]), 0.5, 0.5, 0.5) for i in range(r.size - 1)]
    )


def _folded(M: FloatArray, fsft: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The ring matrices ``M`` (n_rings, 9 x 3 x 3, 300) and the elements' size factors
    ``fsft`` (n_el, 3, 3), symmetric in their two size indices (s, t), folded onto the six
    pairs s <= t (``M[s, t] + M[t, s]`` off the diagonal): the element matrices are the
    same sums with 54 terms instead of 81."""
    pairs = [(a, b) for a in range(3) for b in range(a, 3)]
    n_rings, n_k = M.shape[0], M.shape[1] // 9
    Mr = M.reshape(n_rings, n_k, 3, 3, -1)
    Mf = np.stack(
        [Mr[:, :, a, b] + (Mr[:, :, b, a] if a != b else 0.0) for a, b in pairs], axis=2
    )  # (n_rings, n_k, 6, n_entries)
    fs = np.stack([fsft[:, a, b] for a, b in pairs], axis=1)  # (n_el, 6)
    return np.ascontiguousarray(Mf.reshape(n_rings, n_k * len(pairs), -1)), fs


@dataclass
class Assembler3D:
    """Sparse stiffness of the mesh on its free DOFs, rebuilt for any per-element moduli.

    Attributes
    ----------
    mesh : RollMesh3D
    free : ndarray of bool (3 n_nodes,)
        DOFs that are not held (core, symmetry planes).
    diagonal : ndarray (3 n_nodes,) or None
        Extra diagonal stiffness (a compliant core's Winkler springs) [N/m].
    """

    mesh: RollMesh3D
    free: NDArray[np.bool_]
    diagonal: FloatArray | None = None

    def __post_init__(self) -> None:
        mesh = self.mesh
        # local upper triangle: the local DOF order is increasing in the global DOF order
        # (module numbering), so it maps onto the global upper triangle
        self.tri_a, self.tri_b = np.triu_indices(24)
        tri = self.tri_a * 24 + self.tri_b
        self.M = np.ascontiguousarray(ring_matrices(mesh.r)[:, :, tri])
        self.B_centre = centre_rows(mesh.r)
        i, j, k = mesh.element_index
        self.ring = i
        self.dtheta = np.diff(mesh.theta)[j]
        self.dz = np.diff(mesh.z)[k]
        self.dofs = (3 * mesh.connectivity[:, :, None] + np.arange(3)).reshape(-1, 24)
        n_dof = 3 * mesh.n_nodes
        self.free_index = np.full(n_dof, -1, dtype=np.int64)
        self.free_index[self.free] = np.arange(int(self.free.sum()))
        self.n_free = int(self.free.sum())
        fe = self.free_index[self.dofs]  # (n_el, 24)
        rows = fe[:, self.tri_a].ravel()
        cols = fe[:, self.tri_b].ravel()
        keep = (rows >= 0) & (cols >= 0)
        self._keep = np.flatnonzero(keep)
        key = rows[keep] * self.n_free + cols[keep]
        uniq, self._map = np.unique(key, return_inverse=True)
        self.rows = uniq // self.n_free
        self.cols = uniq % self.n_free
        self.nnz = uniq.size
        self._order = np.argsort(self.ring, kind="stable")
        self._ring_start = np.searchsorted(self.ring[self._order], np.arange(mesh.r.size))
        scale = np.ones((3, self.ring.size))
        scale[1] = 1.0 / self.dtheta
        scale[2] = 1.0 / self.dz
        self._fsft = np.einsum("se,te->est", scale, scale) * (self.dtheta * self.dz)[:, None, None]
        self._Mf, self._fs = _folded(self.M, self._fsft)
        diag = np.zeros(self.n_free)
        if self.diagonal is not None:
            diag = self.diagonal[self.free]
        self._diag = diag
        #: positions of the diagonal entries (one per row, in row order)
        self.diag_pos = np.flatnonzero(self.rows == self.cols)
        # uniq is sorted by row then column: CSR order
        self.pattern = sp.csr_matrix(
            (np.ones(self.nnz), (self.rows, self.cols)), shape=(self.n_free, self.n_free)
        )
        self.pattern.sort_indices()

    def element_matrices(self, D: FloatArray) -> FloatArray:
        """Upper triangles (``tri_a <= tri_b``, 300 entries) of the element stiffness
        matrices (n_el, 300) for the material constants ``D`` (9, n_el)."""
        c = (D.T[:, :, None] * self._fs[:, None, :]).reshape(D.shape[1], -1)
        out = np.empty((D.shape[1], self._Mf.shape[2]))
        for i in range(self._Mf.shape[0]):
            sel = self._order[self._ring_start[i] : self._ring_start[i + 1]]
            if sel.size:
                out[sel] = c[sel] @ self._Mf[i]
        return out

    def values(self, D: FloatArray) -> FloatArray:
        """Upper-triangle values of the free-DOF stiffness in CSR order (``rows``/``cols``):
        the element entries summed into the pattern by a scatter matrix made once (a
        sparse product, faster than ``bincount`` over the kept entries)."""
        Ke = self.element_matrices(D).ravel()
        scatter = getattr(self, "_scatter", None)
        if scatter is None:
            scatter = self._scatter = sp.csr_matrix(
                (np.ones(self._keep.size), (self._map, self._keep)), shape=(self.nnz, Ke.size)
            )
        vals = scatter @ Ke
        vals[self.diag_pos] += self._diag
        return vals

    def upper(self, D: FloatArray) -> sp.csr_matrix:
        """The upper triangle of the free-DOF stiffness as a CSR matrix."""
        K = self.pattern.copy()
        K.data = self.values(D)
        return K

    def matrix(self, D: FloatArray) -> sp.csr_matrix:
        """The free-DOF stiffness (full, symmetric) as a CSR matrix."""
        U = self.upper(D)
        return (U + U.T - sp.diags(U.diagonal())).tocsr()

    def centre_strains(self, u: FloatArray) -> FloatArray:
        """Strains (r, t, z, rt, rz, tz) at the element centres (n_el, 6) for DOFs ``u``
        (all DOFs, held ones included)."""
        ue = u[self.dofs]  # (n_el, 24)
        out = np.empty((ue.shape[0], 6))
        for i in range(self.B_centre.shape[0]):
            sel = self._order[self._ring_start[i] : self._ring_start[i + 1]]
            if sel.size:
                p = (ue[sel] @ self.B_centre[i].reshape(18, 24).T).reshape(-1, 3, 6)
                out[sel] = p[:, 0] + p[:, 1] / self.dtheta[sel, None] + p[:, 2] / self.dz[sel, None]
        return out


def stresses(D: FloatArray, eps: FloatArray) -> FloatArray:
    """Stresses (r, t, z, rt, rz, tz) (n_el, 6) from strains (n_el, 6) and ``D`` (9, n_el)."""
    s = np.empty_like(eps)
    s[:, 0] = D[0] * eps[:, 0] + D[3] * eps[:, 1] + D[4] * eps[:, 2]
    s[:, 1] = D[3] * eps[:, 0] + D[1] * eps[:, 1] + D[5] * eps[:, 2]
    s[:, 2] = D[4] * eps[:, 0] + D[5] * eps[:, 1] + D[2] * eps[:, 2]
    s[:, 3] = D[6] * eps[:, 3]
    s[:, 4] = D[7] * eps[:, 4]
    s[:, 5] = D[8] * eps[:, 5]
    return s


def lumped_mass(mesh: RollMesh3D, density: float) -> FloatArray:
    """Row-sum lumped mass per DOF (3 n_nodes,) [kg]: each element's mass
    rho (r_i+1^2 - r_i^2)/2 dtheta dz shared equally by its 8 nodes (for a dynamic model)."""
    i, j, k = mesh.element_index
    vol = 0.5 * (mesh.r[i + 1] ** 2 - mesh.r[i] ** 2) * np.diff(mesh.theta)[j] * np.diff(mesh.z)[k]
    m_node = np.bincount(
        mesh.connectivity.ravel(), weights=np.repeat(density * vol / 8.0, 8), minlength=mesh.n_nodes
    )
    return np.repeat(m_node, 3)
