"""Structured (r, theta, z) hexahedral mesh of the roll under a head, graded toward the contact.

The head presses at theta = 0, z = 0 (the point ``(R_out, 0, 0)`` of the undeformed outer
surface, z along the CMD from the head's centre). The problem is symmetric about the planes
theta = 0 and z = 0, so by default only the quarter ``0 <= theta <= theta_max``,
``0 <= z <= z_max`` is meshed (``theta_max = pi``: the half roll, the plane theta = pi is a
symmetry plane too; ``theta_max = pi / 2``: the paper's "locality" cut, u_theta = 0 on the
x-z plane, its Figure 4 with 1/8 of the roll). ``z_max`` is the distance from the head's centre
to the free CMD edge of the roll (half the width for a centred head).

Radially the outermost element ring has size ``surface_size`` and sizes grow geometrically
toward the core; tangentially and axially the sizes are uniform over a fine zone that covers
the head's footprint and grow geometrically beyond it
(:func:`woundroll.contact.plane_strain.mesh.graded_sizes`).

Nodes are numbered ``(k * n_theta + j) * n_r + i`` (i radial from the core, j tangential from
theta = 0, k axial from z = 0); element ``(i, j, k)`` has the nodes ``(i + a1, j + a2, k + a3)``
with local index ``a1 + 2 a2 + 4 a3``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from woundroll.contact.plane_strain.mesh import graded_sizes

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def _axis(length: float, fine_extent: float, fine_size: float, growth: float, field: str):
    """Nodes on [0, length]: uniform ``fine_size`` over ``[0, fine_extent]``, then graded."""
    fine_extent = min(fine_extent, length)
    n_f = max(1, int(np.ceil(fine_extent / fine_size - 1e-9)))
    fine = np.linspace(0.0, fine_extent, n_f + 1)
    rest = length - fine_extent
    if rest <= 1e-12 * length:
        return fine
    h = fine_extent / n_f
    sizes = graded_sizes(rest, min(h * growth, rest), growth, field)
    return np.concatenate([fine, fine_extent + np.cumsum(sizes)])


@dataclass(frozen=True)
class RollMesh3D:
    """A graded structured hexahedral mesh of a quarter (or eighth) of the roll.

    Attributes
    ----------
    r : ndarray [m]
        Radial node coordinates, core (index 0) to outer surface.
    theta : ndarray [rad]
        Tangential node angles from 0 (contact axis) to ``theta_max``.
    z : ndarray [m]
        Axial node coordinates from 0 (the head's centre plane) to the free CMD edge.
    """

    r: FloatArray
    theta: FloatArray
    z: FloatArray

    @property
    def shape(self) -> tuple[int, int, int]:
        """Nodes per direction ``(n_r, n_theta, n_z)``."""
        return self.r.size, self.theta.size, self.z.size

    @property
    def n_nodes(self) -> int:
        return self.r.size * self.theta.size * self.z.size

    @property
    def n_elements(self) -> int:
        return (self.r.size - 1) * (self.theta.size - 1) * (self.z.size - 1)

    def node(self, i: IntArray, j: IntArray, k: IntArray) -> IntArray:
        """Node number of the index triples ``(i, j, k)``."""
        n_r, n_t, _ = self.shape
        return (np.asarray(k) * n_t + np.asarray(j)) * n_r + np.asarray(i)

    @cached_property
    def element_index(self) -> tuple[IntArray, IntArray, IntArray]:
        """Radial, tangential, axial index ``(i, j, k)`` of every element (element order)."""
        n_r, n_t, n_z = self.shape
        k, j, i = np.meshgrid(
            np.arange(n_z - 1), np.arange(n_t - 1), np.arange(n_r - 1), indexing="ij"
        )
        return i.ravel(), j.ravel(), k.ravel()

    @cached_property
    def connectivity(self) -> IntArray:
        """Nodes of every element (n_el, 8), local index ``a1 + 2 a2 + 4 a3``."""
        i, j, k = self.element_index
        cols = []
        for a in range(8):
            a1, a2, a3 = a & 1, (a >> 1) & 1, (a >> 2) & 1
            cols.append(self.node(i + a1, j + a2, k + a3))
        return np.stack(cols, axis=1)

    def nodes_where(self, i: int | None = None, j: int | None = None, k: int | None = None):
        """Nodes on the index planes given (e.g. ``i=-1``: the outer surface), as a
        (n_theta, n_z)-ordered flat array when ``i`` is fixed, etc."""
        n_r, n_t, n_z = self.shape
        ii = np.arange(n_r) if i is None else np.array([i % n_r])
        jj = np.arange(n_t) if j is None else np.array([j % n_t])
        kk = np.arange(n_z) if k is None else np.array([k % n_z])
        K, J, I = np.meshgrid(kk, jj, ii, indexing="ij")
        return self.node(I.ravel(), J.ravel(), K.ravel())

    @cached_property
    def surface_nodes(self) -> IntArray:
        """Outer-surface nodes ordered ``k * n_theta + j``."""
        return self.nodes_where(i=-1)

    def element_centres(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(r, theta, z)`` of the element centres [m, rad, m]."""
        i, j, k = self.element_index
        rc = 0.5 * (self.r[:-1] + self.r[1:])
        tc = 0.5 * (self.theta[:-1] + self.theta[1:])
        zc = 0.5 * (self.z[:-1] + self.z[1:])
        return rc[i], tc[j], zc[k]


def build_mesh3d(
    r_in: float,
    r_out: float,
    *,
    z_max: float,
    theta_max: float,
    surface_size: float,
    radial_growth: float,
    tangential_size: float,
    fine_halfwidth: float,
    tangential_growth: float,
    axial_size: float,
    fine_halflength: float,
    axial_growth: float,
) -> RollMesh3D:
    """Graded quarter-roll mesh (module docstring); lengths in m, angles in rad."""
    radial = graded_sizes(r_out - r_in, surface_size, radial_growth, "contact.options.surface_size")
    r = r_out - np.concatenate([[0.0], np.cumsum(radial)])[::-1]
    r[0] = r_in
    s = _axis(
        r_out * theta_max,
        fine_halfwidth,
        tangential_size,
        tangential_growth,
        "contact.options.tangential_size",
    )
    theta = s / r_out
    theta[-1] = theta_max
    z = _axis(z_max, fine_halflength, axial_size, axial_growth, "contact.options.axial_size")
    return RollMesh3D(r=r, theta=theta, z=z)
