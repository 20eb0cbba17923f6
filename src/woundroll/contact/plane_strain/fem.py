"""Plane-strain bilinear quadrilaterals for a cylindrically orthotropic roll, vectorised.

Degrees of freedom are the polar components ``(u_r, u_theta)`` of each node's displacement
(in the node's own polar frame), so the core condition and the contact normal are simple.
The material law is diagonal-by-blocks in the local cylindrical axes ``(r, theta)``:

    [sigma_r, sigma_theta]^T = C [eps_r, eps_theta]^T,   tau_r_theta = G_r_theta gamma_r_theta.

``C`` is the inverse of the reduced plane-strain compliance (see :func:`plane_strain_moduli`).
Because ``C`` and ``G`` are constant in each element, every element stiffness is
``C11 A_rr + C12 A_rt + C22 A_tt + G A_s`` with four geometric matrices computed once; a load
increment only recombines them (no quadrature in the loop).

Two elements (``element=``):

* ``"curved"`` (default): the element is the exact annular sector
  ``r_i <= r <= r_i+1, theta_j <= theta <= theta_j+1``; ``u_r`` and ``u_theta`` are bilinear
  in ``(r, theta)`` and the strains are the polar ones,
  ``eps_r = du_r/dr``, ``eps_theta = (du_theta/dtheta + u_r) / r``,
  ``gamma = du_r/(r dtheta) + du_theta/dr - u_theta / r``, integrated over ``r dr dtheta``.
* ``"flat"``: the straight-edged (chord) isoparametric quadrilateral through the same nodes;
  strains are evaluated in Cartesian form and rotated to the local polar axes at each
  integration point (the element of earlier versions, kept for comparison).

**Assumed hoop strain (``assumed_hoop=True``, default).** With linear interpolation along
the hoop direction, a curved layer that bends inextensionally (``du_theta/dtheta + u_r = 0``,
the way a hoop-stiff roll deforms away from the head) cannot keep its hoop strain zero
across the element: ``u_r`` varies linearly along the element, ``du_theta/dtheta`` does
not, and the parasitic hoop strain costs E_theta, 1e3-1e4 times E_r here. This is the
membrane locking of linear curved elements (both the curved element and, through the axes
rotating between its Gauss points, the flat one). The remedy used is the classic one: the
hoop strain of each radial Gauss line is taken at the element's tangential mid-line (a
B-bar of eps_theta along theta), so only its mean along the element is constrained. It keeps
the element's rank (3 zero-energy modes: the rigid motions, exact for "flat", to first order
in the element angle for "curved"). docs/contact.md has the measured effect.

**Reduced shear.** The shear matrix ``A_s`` is integrated with one point at the element
centre by default (selective reduced integration), which removes the parasitic shear that
makes long thin bilinear elements too stiff in bending; the normal terms keep 2x2 Gauss
points (hoop: 2 radial points on the mid-line), so no hourglass mode appears.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.contact.plane_strain.mesh import RollMesh
from woundroll.materials.web import Web

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

_G = 1.0 / np.sqrt(3.0)
_GAUSS = np.array([[-_G, -_G], [_G, -_G], [_G, _G], [-_G, _G]])
_XI = np.array([-1.0, 1.0, 1.0, -1.0])
_ETA = np.array([-1.0, -1.0, 1.0, 1.0])


#: Largest normalised radial Poisson coupling sqrt(Q / (1 - c_tz^2)) of a stiff stack
#: (:func:`plane_strain_moduli`): 0.9 keeps the compliance's determinant at >= 19 % of its
#: coupling-free value.
MAX_RADIAL_COUPLING = 0.9


def radial_poisson_compliance(web: Web, E_r: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The compliances ``S_rt = -nu_tr / E_t`` and ``S_rz = -nu_zr / E_z`` [1/Pa] per element,
    with the radial Poisson ratios scaled down where E_r would make S indefinite
    (:func:`plane_strain_moduli`)."""
    E_r = np.asarray(E_r, dtype=float)
    Et, Ez = web.E_theta, float(web.E_z)
    c_rt = web.nu_theta_r * np.sqrt(E_r / Et)
    c_rz = web.nu_z_r * np.sqrt(E_r / Ez)
    c_tz = web.nu_theta_z * math.sqrt(Ez / Et)
    Q = c_rt * c_rt + c_rz * c_rz + 2.0 * c_rt * c_rz * c_tz
    bound = MAX_RADIAL_COUPLING**2 * (1.0 - c_tz * c_tz)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = np.where(Q > bound, np.sqrt(bound / np.where(Q > 0, Q, 1.0)), 1.0)
    return -f * web.nu_theta_r / Et, -f * web.nu_z_r / Ez


def plane_strain_moduli(
    web: Web, E_r: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """In-plane stiffness ``C11, C12, C22`` [Pa] and shear modulus ``G_r_theta`` [Pa].

    The 3D compliance of the cylindrically orthotropic web in axes (r, theta, z) is

        S = [[1/E_r, -nu_tr/E_t, -nu_zr/E_z],
             [-nu_tr/E_t, 1/E_t, -nu_tz/E_t],
             [-nu_zr/E_z, -nu_tz/E_t, 1/E_z]]

    with the web's convention nu_ij / E_i = nu_ji / E_j (``nu_theta_r`` the radial contraction
    under hoop stress, etc.). Plane strain (eps_z = 0, the roll is long in the CMD) gives
    sigma_z = -(S_zr sigma_r + S_zt sigma_t) / S_zz and the reduced compliance
    S'_ij = S_ij - S_iz S_jz / S_zz (i, j in r, theta), whose inverse is ``C``. So E_z,
    nu_z_r and nu_theta_z enter only through that reduction; for Table 2's data
    (nu_tr = nu_zr = 0) it is C11 = E_r, C12 = 0, C22 = E_t / (1 - nu_tz^2).

    Stiff stacks (assumption, docs/contact.md): S is positive definite only while the
    normalised couplings ``c_rt = nu_tr sqrt(E_r / E_t)``, ``c_rz = nu_zr sqrt(E_r / E_z)``
    (``c_ij^2 = nu_ij nu_ji``) satisfy ``Q = c_rt^2 + c_rz^2 + 2 c_rt c_rz c_tz <
    1 - c_tz^2``: with nu_tr fixed, the reciprocal nu_rt = nu_tr E_r / E_t grows with the
    radial modulus and, past E_r ~ E_t / nu_tr^2 (11 E_t at nu_tr = 0.3), the strain energy
    of the stack would turn negative. Under the head E_r = K2 (K1 - sigma_r) does reach that
    on a hard roll. Where it does, the two radial Poisson ratios are scaled down together so
    that Q stays at :data:`MAX_RADIAL_COUPLING` ^2 (1 - c_tz^2): the products nu_tr nu_rt and
    nu_zr nu_rz are held at that bound instead of growing with E_r (nu_rt then grows as
    sqrt(E_r), not E_r). Below the bound nothing changes.

    Parameters
    ----------
    web : Web
        Elastic constants.
    E_r : ndarray
        Radial modulus per element [Pa].
    """
    E_r = np.asarray(E_r, dtype=float)
    Et, Ez = web.E_theta, float(web.E_z)
    s_tt = 1.0 / Et
    s_zz = 1.0 / Ez
    s_rt, s_rz = radial_poisson_compliance(web, E_r)
    s_tz = -web.nu_theta_z / Et
    s_rr = 1.0 / E_r
    a = s_rr - s_rz * s_rz / s_zz
    b = s_rt - s_rz * s_tz / s_zz
    c = s_tt - s_tz * s_tz / s_zz
    det = a * c - b * b
    return c / det, -b / det, a / det, web.shear_r_theta(E_r)


@dataclass(frozen=True)
class ElementBasis:
    """Geometric element data, computed once per mesh.

    Attributes
    ----------
    A : ndarray (4, n_el, 8, 8)
        The matrices ``A_rr, A_rt, A_tt, A_s`` per element (module docstring), per unit
        CMD length [m^2 / m^2 = -].
    B_centre : ndarray (n_el, 3, 8)
        Local strains ``(eps_r, eps_t, gamma_rt)`` at the element centre from the element's
        polar nodal displacements [1/m] (the strains the stresses are recovered from).
    dofs : ndarray (n_el, 8)
        Global DOF numbers of each element (``2 node + 0`` radial, ``+1`` tangential).
    centre_xy : ndarray (n_el, 2)
        Element centre coordinates [m] (curved: the sector's centre ``(r_mid, theta_mid)``;
        flat: the image of the parent centre).
    area : ndarray (n_el,)
        Element areas [m^2].
    """

    A: FloatArray
    B_centre: FloatArray
    dofs: IntArray
    centre_xy: FloatArray
    area: FloatArray
    points: StrainPoints | None = None


@dataclass(frozen=True)
class StrainPoints:
    """The integration points the matrices ``A`` are summed from, kept in factored form:
    ``A_rr = sum_g w_g b_r b_r^T``, ``A_rt = sum_g w_g (b_r b_t^T + b_t b_r^T)``,
    ``A_tt = sum_g w_g b_t b_t^T`` over the normal points, ``A_s = sum_s w_s b_s b_s^T`` over
    the shear points. ``K x`` is then ``B^T D B x`` point by point (:meth:`Assembler.matvec`),
    about 150 multiply-adds per element instead of the 4 x 64 of the matrices.

    Attributes
    ----------
    w, b_r, b_t : ndarray (n_el, g), (n_el, g, 8), (n_el, g, 8)
        Normal points: weights [m^2] and the radial and hoop strain rows (hoop: the
        assumed one where ``assumed_hoop``).
    w_s, b_s : ndarray (n_el, s), (n_el, s, 8)
        Shear points (one, the centre, with reduced shear).
    """

    w: FloatArray
    b_r: FloatArray
    b_t: FloatArray
    w_s: FloatArray
    b_s: FloatArray

    @staticmethod
    def of(
        rows: list[tuple[FloatArray, FloatArray, FloatArray]],
        shear: tuple[FloatArray, FloatArray] | None,
    ) -> StrainPoints:
        """From the normal points' ``(w, B, hoop row)`` and, for reduced shear, the one
        shear point ``(w, b_s)`` (None: the shear at the normal points)."""
        w = np.stack([r[0] for r in rows], axis=1)
        b_r = np.stack([r[1][:, 0, :] for r in rows], axis=1)
        b_t = np.stack([r[2] for r in rows], axis=1)
        if shear is None:
            w_s, b_s = w, np.stack([r[1][:, 2, :] for r in rows], axis=1)
        else:
            w_s, b_s = shear[0][:, None], shear[1][:, None, :]
        return StrainPoints(w, b_r, b_t, w_s, b_s)


def _local_b(dN_dx: FloatArray, phi: FloatArray, node_angle: FloatArray) -> FloatArray:
    """Local strain-displacement matrices ``(..., 3, 8)`` in polar nodal DOFs.

    ``dN_dx`` (..., 4, 2) Cartesian shape-function gradients, ``phi`` (...,) the polar angle
    of the point, ``node_angle`` (n_el, 4) broadcast to match.
    """
    nx, ny = dN_dx[..., 0], dN_dx[..., 1]
    c, s = np.cos(phi)[..., None], np.sin(phi)[..., None]
    # local gradient components: d/dr along e_r = (c, s), d/(r dtheta) along e_t = (-s, c)
    dr = c * nx + s * ny
    dt = -s * nx + c * ny
    # nodal polar -> Cartesian: ux = cn ur - sn ut, uy = sn ur + cn ut
    cn, sn = np.cos(node_angle), np.sin(node_angle)
    # projections of each nodal basis vector on the local axes at the point
    er_r = c * cn + s * sn  # e_r(node) . e_r(point)
    er_t = -s * cn + c * sn  # e_r(node) . e_t(point)
    et_r = -c * sn + s * cn  # e_t(node) . e_r(point)
    et_t = s * sn + c * cn  # e_t(node) . e_t(point)
    shape = dN_dx.shape[:-1]
    B = np.zeros((*shape[:-1], 3, 8))
    # eps_r = d(u.e_r)/dr, eps_t = d(u.e_t)/(r dt) + u.e_r / r in the fixed local frame:
    # with u expressed in the fixed point frame, strains are plain Cartesian-like gradients.
    B[..., 0, 0::2] = dr * er_r
    B[..., 0, 1::2] = dr * et_r
    B[..., 1, 0::2] = dt * er_t
    B[..., 1, 1::2] = dt * et_t
    B[..., 2, 0::2] = dt * er_r + dr * er_t
    B[..., 2, 1::2] = dt * et_r + dr * et_t
    return B


ELEMENTS = ("curved", "flat")


def element_basis(
    mesh: RollMesh,
    *,
    element: str = "curved",
    reduced_shear: bool = True,
    assumed_hoop: bool = True,
) -> ElementBasis:
    """Compute :class:`ElementBasis` for ``mesh`` (vectorised over all elements).

    Parameters
    ----------
    mesh : RollMesh
    element : {"curved", "flat"}
        Exact annular-sector element with polar strains, or the straight-edged chord
        quadrilateral (module docstring).
    reduced_shear : bool
        One-point shear integration.
    assumed_hoop : bool
        Hoop strain taken on the element's tangential mid-line (removes membrane locking).
    """
    if element == "curved":
        return _curved_basis(mesh, reduced_shear, assumed_hoop)
    if element == "flat":
        return _flat_basis(mesh, reduced_shear, assumed_hoop)
    raise ValueError(f"unknown element {element!r}; known: {', '.join(ELEMENTS)}")


def _accumulate(
    A: FloatArray, w: FloatArray, B: FloatArray, bt: FloatArray, full_shear: bool
) -> None:
    """Add one integration point's contribution (weight ``w`` (ne,)) to the four matrices;
    ``bt`` the hoop-strain row to use (point's own or assumed)."""
    w = w[:, None]
    br, bs = B[:, 0, :], B[:, 2, :]
    wr = w * br  # the weight taken into one factor: one (ne, 8, 8) product per term
    A[0] += wr[:, :, None] * br[:, None, :]
    rt = wr[:, :, None] * bt[:, None, :]
    A[1] += rt
    A[1] += rt.transpose(0, 2, 1)
    A[2] += (w * bt)[:, :, None] * bt[:, None, :]
    if full_shear:
        A[3] += (w * bs)[:, :, None] * bs[:, None, :]


def _accumulate_points(A: FloatArray, pts: StrainPoints, full_shear: bool) -> None:
    """:func:`_accumulate` over all integration points at once, from the basis's own
    :class:`StrainPoints`: each matrix is one batched product ``sum_g (w_g b_g) b_g^T``
    instead of a pass over the (ne, 8, 8) arrays per point (``full_shear``: A_s from the
    shear points too; with reduced shear the caller sets it)."""
    w = pts.w[:, :, None]  # (ne, g, 1)
    br, bt = pts.b_r, pts.b_t  # (ne, g, 8)
    wr = (w * br).transpose(0, 2, 1)  # (ne, 8, g)
    A[0] += wr @ br
    rt = wr @ bt
    A[1] += rt
    A[1] += rt.transpose(0, 2, 1)
    A[2] += (w * bt).transpose(0, 2, 1) @ bt
    if full_shear:
        A[3] += (pts.w_s[:, :, None] * pts.b_s).transpose(0, 2, 1) @ pts.b_s


def _dofs(conn: IntArray) -> IntArray:
    dofs = np.empty((conn.shape[0], 8), dtype=np.int64)
    dofs[:, 0::2] = 2 * conn
    dofs[:, 1::2] = 2 * conn + 1
    return dofs


def _curved_basis(mesh: RollMesh, reduced_shear: bool, assumed_hoop: bool) -> ElementBasis:
    """The exact-sector element. Local coordinates ``a`` (radial, node 0 -> 1) and ``b``
    (tangential, node 0 -> 3) in [0, 1]; connectivity order (i, j), (i+1, j), (i+1, j+1),
    (i, j+1)."""
    conn = mesh.connectivity()
    r_node = np.tile(mesh.r, mesh.n_theta)
    th = mesh.node_angle()[conn]  # (ne, 4)
    r0, r1 = r_node[conn[:, 0]], r_node[conn[:, 1]]
    t0, t1 = th[:, 0], th[:, 3]
    if mesh.periodic:  # the element closing the annulus
        t1 = np.where(t1 < t0, t1 + 2.0 * np.pi, t1)
    dr, dt = r1 - r0, t1 - t0
    ne = conn.shape[0]

    def b_matrix(a: float, b: float) -> tuple[FloatArray, FloatArray]:
        N = np.array([(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b])
        N_a = np.array([-(1 - b), 1 - b, b, -b])
        N_b = np.array([-(1 - a), -a, a, 1 - a])
        r = r0 + a * dr
        d_r = N_a[None, :] / dr[:, None]  # d/dr
        d_t = N_b[None, :] / (dt * r)[:, None]  # d/(r dtheta)
        n_r = N[None, :] / r[:, None]  # N / r
        B = np.zeros((ne, 3, 8))
        B[:, 0, 0::2] = d_r
        B[:, 1, 0::2] = n_r
        B[:, 1, 1::2] = d_t
        B[:, 2, 0::2] = d_t
        B[:, 2, 1::2] = d_r - n_r
        return B, r

    A = np.zeros((4, ne, 8, 8))
    area = np.zeros(ne)
    pts = (0.5 - 0.5 * _G, 0.5 + 0.5 * _G)
    rows: list[tuple[FloatArray, FloatArray, FloatArray]] = []  # per point: w, B, hoop row
    for a in pts:
        B_mid, _ = b_matrix(a, 0.5)
        for b in pts:
            B, r = b_matrix(a, b)
            w = 0.25 * r * dr * dt  # r dr dtheta, Gauss weights 1/4
            rows.append((w, B, B_mid[:, 1, :] if assumed_hoop else B[:, 1, :]))
            area += w
    Bc, rc = b_matrix(0.5, 0.5)
    shear = (rc * dr * dt, Bc[:, 2, :]) if reduced_shear else None
    points = StrainPoints.of(rows, shear)
    _accumulate_points(A, points, not reduced_shear)
    if shear is not None:
        bs = shear[1]
        A[3] = shear[0][:, None, None] * bs[:, :, None] * bs[:, None, :]
    tc = t0 + 0.5 * dt
    centre = np.stack([rc * np.cos(tc), rc * np.sin(tc)], axis=1)
    return ElementBasis(
        A=A, B_centre=Bc, dofs=_dofs(conn), centre_xy=centre, area=area, points=points
    )


def _flat_basis(mesh: RollMesh, reduced_shear: bool, assumed_hoop: bool) -> ElementBasis:
    """The straight-edged element. Parent coordinates: xi radial (node 0 -> 1), eta
    tangential (node 0 -> 3)."""
    xy = mesh.node_xy()
    conn = mesh.connectivity()
    ang = mesh.node_angle()[conn]  # (ne, 4)
    X = xy[conn]  # (ne, 4, 2)

    def gradients(xi: FloatArray, eta: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        dN = np.stack([0.25 * _XI * (1 + eta * _ETA), 0.25 * _ETA * (1 + xi * _XI)], axis=-1)
        N = 0.25 * (1 + xi * _XI) * (1 + eta * _ETA)
        J = np.einsum("na,enb->eab", dN, X)  # (ne, 2, 2): J[a, b] = dx_b/dxi_a
        det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
        inv = (
            np.stack(
                [np.stack([J[:, 1, 1], -J[:, 0, 1]], -1), np.stack([-J[:, 1, 0], J[:, 0, 0]], -1)],
                -2,
            )
            / det[:, None, None]
        )
        dN_dx = np.einsum("eba,na->enb", inv, dN)  # dN/dx_b = sum_a invJ[b,a] dN/dxi_a
        pt = np.einsum("n,enb->eb", N, X)
        return dN_dx, det, pt

    def local_b(xi: float, eta: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        dN_dx, det, pt = gradients(np.float64(xi), np.float64(eta))
        return _local_b(dN_dx, np.arctan2(pt[:, 1], pt[:, 0]), ang), det, pt

    ne = conn.shape[0]
    A = np.zeros((4, ne, 8, 8))
    area = np.zeros(ne)
    rows = []
    for xi, eta in _GAUSS:
        B, det, _ = local_b(xi, eta)
        bt = local_b(xi, 0.0)[0][:, 1, :] if assumed_hoop else B[:, 1, :]
        _accumulate(A, det, B, bt, not reduced_shear)
        rows.append((det, B, bt))
        area += det
    Bc, det, pt = local_b(0.0, 0.0)
    shear = None
    if reduced_shear:
        bs = Bc[:, 2, :]
        shear = (4.0 * det, bs)
        A[3] = shear[0][:, None, None] * bs[:, :, None] * bs[:, None, :]
    points = StrainPoints.of(rows, shear)
    return ElementBasis(A=A, B_centre=Bc, dofs=_dofs(conn), centre_xy=pt, area=area, points=points)


def half_bandwidth(dofs: IntArray, free: NDArray[np.bool_], order: IntArray | None = None) -> int:
    """Half-bandwidth of K for element DOFs ``dofs`` (n_el, k) with the unknowns in
    ``order`` (default: the free DOFs in increasing number)."""
    index = np.full(free.size, -1, dtype=np.int64)
    index[np.flatnonzero(free) if order is None else order] = np.arange(int(free.sum()))
    return _band_of(index[dofs])


def _band_of(d: IntArray) -> int:
    """Half-bandwidth of K from the unknowns' indices per element ``d`` (n_el, k; -1 for
    a constrained DOF): the widest spread of one element's unknowns."""
    valid = d >= 0
    hi = np.where(valid, d, -1).max(axis=1)
    lo = np.where(valid, d, np.iinfo(np.int64).max).min(axis=1)
    ok = valid.any(axis=1)
    return int(np.max(hi[ok] - lo[ok])) if np.any(ok) else 0


def ring_major_order(
    n_r: int, n_theta: int, free: NDArray[np.bool_], dofs: IntArray
) -> IntArray | None:
    """The free DOFs ring by ring from the surface inward (along the hoop within a ring,
    from the contact axis), for a half-model mesh numbered column by column (node
    ``j n_r + i``, ring ``i`` from the core), where that makes the band of K narrower for
    the element DOFs ``dofs``; else None (the column order, e.g. the continuum roll's
    mesh, whose rings are fewer than the nodes on a ring). A ring costs about
    ``2 n_theta`` of half-bandwidth (``3 n_theta`` on the layered model's doubled rings),
    a column ``2 n_r``: a banded factorisation costs the square of the ratio less. The
    contact axis's surface nodes stay the first unknowns, as the solvers' leading-rows
    right-hand sides require."""
    if n_r <= n_theta:
        return None
    ring, j = np.meshgrid(np.arange(n_r)[::-1], np.arange(n_theta), indexing="ij")
    nodes = (j * n_r + ring).ravel()
    order = np.stack([2 * nodes, 2 * nodes + 1], axis=1).ravel()
    order = order[free[order]]
    if half_bandwidth(dofs, free, order) >= half_bandwidth(dofs, free):
        return None
    return order


#: Band positions of the element entries by DOF numbering (:meth:`Assembler._pad_pattern`).
_PAD_INDEX: dict[tuple[Any, ...], tuple[IntArray, IntArray]] = {}


class Assembler:
    """Assembly of ``K = sum_e (C11 A_rr + C12 A_rt + C22 A_tt + G A_s)`` on the free DOFs.

    The scatter map is built once; :meth:`values` forms the element values (one fused
    multiply-add over all elements) and :meth:`banded` / :meth:`csc` sum them with
    :func:`numpy.bincount` into LAPACK lower banded storage (half model: the node numbering
    makes K banded, solved by banded Cholesky) or a CSC matrix (whole annulus, sparse LU).

    Parameters
    ----------
    basis : ElementBasis
    free : ndarray of bool (n_dof,)
        True for unconstrained DOFs.
    diagonal : ndarray (n_dof,), optional
        Extra diagonal stiffness (elastic-core springs) [N/m per m].
    order : ndarray of int, optional
        The free DOFs in the order of the unknowns (default: increasing DOF number). The
        solvers place the contact axis's surface DOFs first (:func:`ring_major_order`).
    """

    def __init__(
        self,
        basis: ElementBasis,
        free: NDArray[np.bool_],
        diagonal: FloatArray | None = None,
        order: IntArray | None = None,
    ) -> None:
        self.basis = basis
        n_dof = free.size
        #: the DOF of each unknown (``x_full[free_dofs] = x``)
        self.free_dofs = np.flatnonzero(free) if order is None else np.asarray(order)
        if order is not None and not np.array_equal(np.sort(self.free_dofs), np.flatnonzero(free)):
            raise ValueError("order must list every free DOF once")
        self.free_index = np.full(n_dof, -1, dtype=np.int64)
        self.free_index[self.free_dofs] = np.arange(self.free_dofs.size)
        self.n_free = int(free.sum())
        d = self.free_index[basis.dofs]  # (ne, 8)
        self._diag_vals = np.array([])
        self._diag_idx = np.array([], dtype=np.int64)
        if diagonal is not None:
            fd = np.flatnonzero((np.asarray(diagonal) != 0) & free)
            self._diag_idx = self.free_index[fd]
            self._diag_vals = np.asarray(diagonal)[fd]
        self._diag_low = self._diag_vals  # spring entries are diagonal: all lower
        #: half-bandwidth of K in the free numbering
        self.bandwidth = _band_of(d)
        self._scatter_ready = False  # the general scatter map (:meth:`_scatter`), on first use
        self._slots: IntArray | None = None  # free index per element DOF (:meth:`matvec`)
        self._band_index_reversed: NDArray[np.int64] | None = None
        self._csc = None
        self._pad: Any = None

    def _scatter(self) -> None:
        """The scatter map of :meth:`values` / :meth:`banded` / :meth:`csc`, built once
        (the band of the static solve needs only :meth:`band`'s)."""
        if self._scatter_ready:
            return
        basis = self.basis
        d = self.free_index[basis.dofs]  # (ne, 8)
        rows = np.broadcast_to(d[:, :, None], (d.shape[0], 8, 8)).ravel()
        cols = np.broadcast_to(d[:, None, :], (d.shape[0], 8, 8)).ravel()
        keep = (rows >= 0) & (cols >= 0)
        self._keep = np.flatnonzero(keep)
        rows = np.concatenate([rows[keep], self._diag_idx])
        cols = np.concatenate([cols[keep], self._diag_idx])
        self._rows, self._cols = rows, cols
        n = self.n_free
        lower = rows >= cols
        self._lower = np.flatnonzero(lower)
        self._band_index = (rows[lower] - cols[lower]) * n + cols[lower]
        # geometric matrices gathered per kept entry (all, and the lower triangle only)
        n_el_entries = self._keep.size
        self._elem = self._keep // 64
        self._A = basis.A.reshape(4, -1)[:, self._keep]
        low_el = self._lower[self._lower < n_el_entries]
        self._elem_low = self._elem[low_el]
        self._A_low = self._A[:, low_el]
        self._scatter_ready = True

    def values(
        self, C11: FloatArray, C12: FloatArray, C22: FloatArray, G: FloatArray
    ) -> FloatArray:
        """All element (and spring) contributions, in the order of the scatter map."""
        self._scatter()
        e, A = self._elem, self._A
        ke = C11[e] * A[0] + C12[e] * A[1] + C22[e] * A[2] + G[e] * A[3]
        return np.concatenate([ke, self._diag_vals])

    def values_lower(
        self, C11: FloatArray, C12: FloatArray, C22: FloatArray, G: FloatArray
    ) -> FloatArray:
        """The lower-triangle part of :meth:`values` (what :meth:`banded` needs), half the work."""
        self._scatter()
        e, A = self._elem_low, self._A_low
        ke = C11[e] * A[0] + C12[e] * A[1] + C22[e] * A[2] + G[e] * A[3]
        return np.concatenate([ke, self._diag_low])

    def band(
        self,
        C11: FloatArray,
        C12: FloatArray,
        C22: FloatArray,
        G: FloatArray,
        *,
        reverse: bool = False,
        springs: bool = True,
    ) -> FloatArray:
        """Lower banded storage of K (as :meth:`banded` of :meth:`values_lower`, the same
        numbers) formed element by element: each element's 36 lower-triangle entries are
        one broadcast multiply-add of the moduli over the element rows (no gather of the
        moduli per entry), then summed into the band by one ``bincount``. ``springs``:
        include the core's springs."""
        if self._pad is None:
            self._pad = self._pad_pattern()
        A, index, spring_index = self._pad
        vals = C11[:, None] * A[0]
        vals += C12[:, None] * A[1]
        vals += C22[:, None] * A[2]
        vals += G[:, None] * A[3]
        n, bw = self.n_free, self.bandwidth
        size = (bw + 1) * n
        idx = index[1] if reverse else index[0]
        ab = np.bincount(idx, weights=vals.ravel(), minlength=size + 1)
        if springs and self._diag_low.size:
            # the core's springs after the elements, as a bincount of the two lists joined
            # would add them (one spring a node: distinct slots), without copying the lists
            ab[spring_index[1] if reverse else spring_index[0]] += self._diag_low
        # column-major slots (j (bw + 1) + d): the band is built Fortran-ordered, as LAPACK
        # takes it, so ``dpbtrf`` does not copy it first (the same numbers)
        return ab[:size].reshape(n, bw + 1).T

    def _pad_pattern(self) -> tuple[FloatArray, tuple[Any, Any], tuple[Any, Any]]:
        """The element matrices' lower triangles (4, n_el, 36) and their positions in the
        band (forward and reversed order; constrained entries go to a dummy slot)."""
        a, b = np.tril_indices(8)
        flat = a * 8 + b
        ne = self.basis.A.shape[1]
        A = self.basis.A.reshape(4, ne, 64)[:, :, flat]  # (4, ne, 36); symmetric
        d = self.free_index[self.basis.dofs]  # (ne, 8)
        n, bw = self.n_free, self.bandwidth
        # the positions depend on the numbering only, the same for the sectors of a
        # profile (meshes of equal shape): kept for the next assembler
        key = (n, bw, d.shape, d.tobytes())
        index = _PAD_INDEX.get(key)
        if index is None:
            ga, gb = d[:, a], d[:, b]
            hi, lo = np.maximum(ga, gb), np.minimum(ga, gb)
            ok = (ga >= 0) & (gb >= 0)
            dummy = (bw + 1) * n
            # band entry (hi - lo, column) at the column-major slot column (bw + 1) + hi - lo
            fwd = np.where(ok, lo * (bw + 1) + (hi - lo), dummy).ravel()
            rev = np.where(ok, (n - 1 - hi) * (bw + 1) + (hi - lo), dummy).ravel()
            index = (fwd, rev)
            _PAD_INDEX.clear()  # one numbering at a time (a profile's sectors share it)
            _PAD_INDEX[key] = index
        r = self._diag_idx
        springs = (r * (bw + 1), (n - 1 - r) * (bw + 1))  # diagonal: band row 0
        return A, index, springs

    def matvec(
        self, C11: FloatArray, C12: FloatArray, C22: FloatArray, G: FloatArray, x: FloatArray
    ) -> FloatArray:
        """``K x`` on the free DOFs for per-element moduli (any sign: used with moduli
        differences), without the core's springs.

        With the basis's :class:`StrainPoints` (the curved element): ``B^T D B x`` at the
        integration points, the strains of ``x`` at each point, the stresses at the
        element's moduli, their nodal forces summed by one ``bincount`` (0.48 against
        0.94 ms for the band and ``dsbmv`` on Table 3's sectors, the same numbers to
        round-off). Otherwise the lower band (:meth:`band`) multiplied by BLAS ``dsbmv``."""
        pts = self.basis.points
        if pts is None:
            from scipy.linalg.blas import dsbmv

            ab = self.band(C11, C12, C22, G, springs=False)
            return dsbmv(self.bandwidth, 1.0, ab, x, lower=1)
        n = self.n_free
        if self._slots is None:  # constrained DOFs gather a zero and scatter to a dummy
            d = self.free_index[self.basis.dofs]
            self._slots = np.where(d >= 0, d, n)
        slots = self._slots
        X = np.append(x, 0.0)[slots]  # (ne, 8)
        e_r = np.einsum("egi,ei->eg", pts.b_r, X)
        e_t = np.einsum("egi,ei->eg", pts.b_t, X)
        g = np.einsum("egi,ei->eg", pts.b_s, X)
        s_r = pts.w * (C11[:, None] * e_r + C12[:, None] * e_t)
        s_t = pts.w * (C12[:, None] * e_r + C22[:, None] * e_t)
        s_s = pts.w_s * (G[:, None] * g)
        y = np.einsum("egi,eg->ei", pts.b_r, s_r)
        y += np.einsum("egi,eg->ei", pts.b_t, s_t)
        y += np.einsum("egi,eg->ei", pts.b_s, s_s)
        return np.bincount(slots.ravel(), y.ravel(), minlength=n + 1)[:n]

    def banded(
        self, vals: FloatArray, *, lower_only: bool = False, reverse: bool = False
    ) -> FloatArray:
        """Lower banded storage ``ab[i - j, j] = K[i, j]``, i >= j (LAPACK ``dpbtrf``, 'L').

        ``vals`` from :meth:`values`, or from :meth:`values_lower` with ``lower_only=True``.
        ``reverse``: the same for ``P K P`` with P the reversal of the free DOF order
        (``ab[d, j] = K[n - 1 - j, n - 1 - j - d]``), assembled directly.

        (The lower form: OpenBLAS's threaded upper-form factorisation was found 10-100x
        slower on a loaded 2-core machine.)
        """
        self._scatter()
        n, bw = self.n_free, self.bandwidth
        w = vals if lower_only else vals[self._lower]
        index = self._band_index
        if reverse:
            if self._band_index_reversed is None:
                r, c = self._rows[self._lower], self._cols[self._lower]
                self._band_index_reversed = (r - c) * n + (n - 1 - r)
            index = self._band_index_reversed
        ab = np.bincount(index, weights=w, minlength=(bw + 1) * n)
        return ab.reshape(bw + 1, n)

    def csc(self, vals: FloatArray) -> Any:
        """Global stiffness on the free DOFs as a CSC matrix."""
        self._scatter()
        if self._csc is None:
            keys, inv = np.unique(self._cols * self.n_free + self._rows, return_inverse=True)
            indices = (keys % self.n_free).astype(np.int32)
            indptr = np.searchsorted(keys // self.n_free, np.arange(self.n_free + 1)).astype(
                np.int32
            )
            self._csc = (inv, keys.size, indices, indptr)
        inv, nnz, indices, indptr = self._csc
        data = np.bincount(inv, weights=vals, minlength=nnz)
        import scipy.sparse as sp  # the whole-annulus check only

        return sp.csc_matrix((data, indices, indptr), shape=(self.n_free, self.n_free))
