"""Structured (r, theta) quadrilateral mesh of the whole roll annulus, graded toward the contact.

The contact axis is theta = 0 (the point ``(R_out, 0)`` of the undeformed outer surface).
Radially the first element under the surface has size ``surface_size`` (default: the web
thickness, one layer) and sizes grow geometrically toward the core. Tangentially the
surface is divided uniformly (``tangential_size``) over the arc ``|s| <= fine_halfwidth``
around the contact axis (``s = R_out theta``), then sizes grow geometrically up to
``theta = +-pi``, where the mesh closes on itself (the annulus is periodic).

By default only the half ``0 <= theta <= pi`` is meshed: the problem (geometry, frictionless
contact, load) is symmetric about the contact axis, and the half model has no periodic
closure, so its stiffness matrix is banded (next paragraph). ``periodic=True`` meshes the
whole annulus (used to verify the symmetry).

Nodes are numbered ``j * n_r + i`` with ``i`` the radial index (0 at the core) and ``j`` the
tangential index (theta increasing): neighbouring nodes differ by at most ``n_r + 1``, so the
half model's stiffness has a half-bandwidth of ``2 n_r + 3`` DOFs. Elements are
counter-clockwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def graded_sizes(
    length: float, first: float, growth: float, field: str, largest: float | None = None
) -> FloatArray:
    """Element sizes [m] that start at ``first`` and grow geometrically to fill ``length``.

    The number of elements is the smallest that a ratio no larger than ``growth`` can fill;
    the ratio is then lowered so that the sizes sum to ``length`` exactly while the first
    size stays ``first``. With ``largest``, sizes grow (ratio ``growth``) only up to
    ``largest`` and the rest of the length is divided uniformly into sizes <= ``largest``.

    Parameters
    ----------
    length : float
        Total length to fill [m].
    first : float
        Size of the first element [m].
    growth : float
        Largest allowed ratio of neighbouring sizes [-], >= 1.
    field : str
        Dotted option name used in error messages.
    largest : float, optional
        Largest allowed size [m].
    """
    if first <= 0 or not math.isfinite(first):
        raise InputError(f"element size must be positive, got {first:g} m", field)
    if largest is not None:
        first = min(first, largest)
        sizes = graded_sizes(length, first, growth, field)
        if sizes.max() <= largest * (1.0 + 1e-12):
            return sizes
        n_g = (
            0
            if growth <= 1.0 + 1e-12
            else max(0, math.ceil(math.log(largest / first) / math.log(growth) - 1e-9))
        )
        grown = first * growth ** np.arange(n_g)
        while n_g and grown.sum() > length:  # cannot happen unless largest ~ length
            n_g -= 1
            grown = grown[:-1]
        rest = length - grown.sum()
        n_u = max(1, math.ceil(rest / largest - 1e-9))
        return np.concatenate([grown, np.full(n_u, rest / n_u)])
    if first >= length:
        return np.array([length])
    if growth <= 1.0 + 1e-12:
        n = math.ceil(length / first - 1e-9)
        return np.full(n, length / n)
    n = math.ceil(math.log1p(length * (growth - 1.0) / first) / math.log(growth) - 1e-9)
    n = max(n, 1)
    if abs(first * n - length) <= 1e-12 * length:
        return np.full(n, first)
    if first * n > length:  # uniform sizes already overfill: shrink them
        return np.full(n, length / n)

    def excess(q: float) -> float:
        return first * (q**n - 1.0) / (q - 1.0) - length

    # excess is increasing in q, negative at 1 and >= 0 at ``growth``: bisection (no
    # scipy.optimize at import; start-up time)
    lo, hi = 1.0 + 1e-12, growth * (1.0 + 1e-9)
    while hi - lo > 1e-14:
        mid = 0.5 * (lo + hi)
        if excess(mid) < 0:
            lo = mid
        else:
            hi = mid
    q = 0.5 * (lo + hi)
    sizes = first * q ** np.arange(n)
    return sizes * (length / sizes.sum())


@dataclass(frozen=True)
class RollMesh:
    """A graded structured mesh of the roll cross-section.

    Attributes
    ----------
    r : ndarray [m]
        Radial node coordinates, core (index 0) to outer surface.
    theta : ndarray [rad]
        Tangential node angles: [0, pi] (half model) or [-pi, pi) (periodic), increasing.
    periodic : bool
        True for the whole annulus (the last node ring connects to the first).
    j0 : int
        Tangential index of the contact axis.
    """

    r: FloatArray
    theta: FloatArray
    j0: int
    periodic: bool = False

    @property
    def n_r(self) -> int:
        """Number of radial node rings."""
        return self.r.size

    @property
    def n_theta(self) -> int:
        """Number of nodes on each ring."""
        return self.theta.size

    @property
    def n_nodes(self) -> int:
        return self.n_r * self.n_theta

    @property
    def n_elements(self) -> int:
        return (self.n_r - 1) * (self.n_theta if self.periodic else self.n_theta - 1)

    def node_xy(self) -> FloatArray:
        """Node coordinates ``(n_nodes, 2)`` [m]."""
        rr, tt = np.meshgrid(self.r, self.theta, indexing="xy")
        return np.stack([(rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel()], axis=1)

    def node_angle(self) -> FloatArray:
        """Polar angle of each node [rad]."""
        return np.repeat(self.theta, self.n_r)

    def connectivity(self) -> IntArray:
        """Element node indices ``(n_elements, 4)``, counter-clockwise."""
        nr, nt = self.n_r, self.n_theta
        n_el_t = nt if self.periodic else nt - 1
        j, i = np.meshgrid(np.arange(n_el_t), np.arange(nr - 1), indexing="ij")
        i, j = i.ravel(), j.ravel()
        jp = (j + 1) % nt
        return np.stack([j * nr + i, j * nr + i + 1, jp * nr + i + 1, jp * nr + i], axis=1)

    def surface_nodes(self) -> IntArray:
        """Indices of the outer-surface nodes, in the order of :attr:`theta`."""
        return np.arange(self.n_theta) * self.n_r + self.n_r - 1

    def core_nodes(self) -> IntArray:
        """Indices of the nodes on the core surface."""
        return np.arange(self.n_theta) * self.n_r

    def edge_nodes(self) -> IntArray:
        """Nodes on the symmetry lines theta = 0 and theta = pi (half model; empty if periodic)."""
        if self.periodic:
            return np.array([], dtype=np.int64)
        return np.concatenate(
            [np.arange(self.n_r), (self.n_theta - 1) * self.n_r + np.arange(self.n_r)]
        )


def build_mesh(
    r_in: float,
    r_out: float,
    *,
    surface_size: float,
    radial_growth: float,
    tangential_size: float,
    fine_halfwidth: float,
    tangential_growth: float,
    max_element_angle: float | None = None,
    periodic: bool = False,
) -> RollMesh:
    """Build the graded annulus mesh (module docstring).

    Parameters
    ----------
    r_in, r_out : float
        Core radius and outer radius of the roll [m].
    surface_size : float
        Radial size of the outermost element ring [m].
    radial_growth : float
        Ratio of neighbouring radial sizes toward the core [-].
    tangential_size : float
        Arc length of the surface elements in the fine zone [m].
    fine_halfwidth : float
        Arc half-width of the uniformly fine zone around the contact axis [m].
    tangential_growth : float
        Ratio of neighbouring tangential sizes away from the fine zone [-].
    periodic : bool
        Whole annulus instead of the half 0 <= theta <= pi.
    """
    dr = graded_sizes(r_out - r_in, surface_size, radial_growth, "options.surface_size")
    r = r_out - np.concatenate([[0.0], np.cumsum(dr)])[::-1]
    r[0] = r_in
    half_arc = math.pi * r_out
    n_fine = max(1, math.ceil(fine_halfwidth / tangential_size - 1e-9))
    w = min(n_fine * tangential_size, 0.5 * half_arc)
    s_fine = np.linspace(0.0, w, n_fine + 1)
    largest = None if max_element_angle is None else max_element_angle * r_out
    ds = graded_sizes(
        half_arc - w,
        min(tangential_size * tangential_growth, half_arc - w),
        tangential_growth,
        "options.tangential_size",
        largest,
    )
    s_half = np.concatenate([s_fine, w + np.cumsum(ds)])
    s_half[-1] = half_arc
    theta_half = s_half / r_out
    theta_half[-1] = math.pi
    if not periodic:
        return RollMesh(r=r, theta=theta_half, j0=0, periodic=False)
    # -pi (== +pi, shared) ... 0 ... last node before +pi
    theta = np.concatenate([-theta_half[::-1], theta_half[1:-1]])
    return RollMesh(r=r, theta=theta, j0=theta_half.size - 1, periodic=True)
