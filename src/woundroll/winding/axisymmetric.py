"""Axisymmetric (r, z) center-winding model with a CMD thickness profile.

The roll is cut along the CMD (z) into ``n_sectors`` sectors, one finite element wide each.
Sector ``j`` has its own web thickness ``h_j`` (the sector average of the thickness profile)
and builds its own radius: after ``n`` layers its undeformed outer radius is
``r_c + n h_j``. The roll is grown layer group by layer group (``n_groups`` increments);
every increment solves the incremental elasticity problem of the wound stack under the
pressure the new group exerts, with the radial modulus taken at the mid-increment pressure.

Discretisation (``_axisym_fe``; docs/profile.md section 2)
----------------------------------------------------------
* Unknowns ``u_r`` and ``u_z`` at the nodes ``(k, i)``: group boundary ``k`` (0 on the core)
  and sector edge ``i``; element ``(k, j)`` is group ``k`` of sector ``j``. Nodes are shared
  by layer index (a layer is continuous across the CMD).
* Full cylindrically orthotropic law in (r, theta, z) (convention ``nu_ij = -eps_j/eps_i``
  under ``sigma_i``, ``nu_ij/E_i = nu_ji/E_j``; web.py) with ``E_r`` from the radial-modulus
  law, ``E_theta``, ``E_z``, ``nu_theta_r``, ``nu_z_r``, ``nu_theta_z`` and
  ``tau_rz = G_rz (du_r/dz + du_z/dr)``, ``G_rz = 2 E_r`` by default (Tables 2-3).
* Interpolation: linear in z; in r, ``u_r`` spans the exact uniform-modulus ring solution
  {x^g, x^-g} (``g = sqrt(E_theta/E_r)``), so a constant-modulus roll has no radial
  discretisation error and the surface boundary layer (``g`` up to ~1000) is represented
  within an element; ``u_z`` is linear in r.
* CMD edges free (``sigma_z = tau_rz = 0``, natural boundary condition). Core: Hakiel's
  ``u_r(r_c) = r_c sigma_r / E_c`` (consistent over each sector's width) or ``u_r = 0`` for a
  rigid core; **axially frictionless** (no shear traction between core and roll: the web is
  wound onto the core, not bonded to it, and this is the choice that keeps a uniform roll
  on a uniform core free of axial load from the core); ``u_z`` is fixed at one core node
  only to remove the rigid axial translation (the loads carry no net axial force, so the
  stresses do not depend on that node).
* ``shear_coupling=False``: the sectors are independent 1D plane-stress rolls (exact ring
  elements per sector, ``sigma_z = tau_rz = 0``): the previous column model, for comparison.
* Layer groups (midpoint rule): the ``m`` layers of a group are wound one after the other,
  each pressing on the stack below it. The increment applies the whole group's load
  ``sigma_j m h_j w_j`` (per radian) to a stack that includes ``(m - 1) / 2`` layers of the
  group itself; with ``m = 1`` the new layer is not in the stack (Hakiel's scheme). The
  group's own stresses are the averages over its layers: ``sigma_r = -p_j / 2`` and the hoop
  stress ``sigma_j`` plus ``(m - 1)/(2 m)`` of the hoop (and sigma_z, tau_rz) increment.
  Default **graded** grouping: single layers at the outer surface, a group holding about a
  quarter of the layers above it, equal groups below (``_split_layers``), at most
  ``MAX_GROUP_LAYERS`` = 2 layers per group (:func:`default_groups`) unless 200 or 400
  groups agree with that within 0.5 % on a column of the mean thickness
  (:func:`choose_groups`): the midpoint rule's error grows as ``m^2 - 1`` with the group
  size ``m``; the soft surface of a Table 2 roll (``E_theta / E_r`` ~ 1e4) needs ``m <= 2``
  for 1 %, PET3 does not (docs/profile.md, section 6).
* The group's pressure on the stack ``p_j = sigma_j m h_j / r_j`` and its own radial stress
  (the thin ring, ``-p_j / 2`` at its centre scaled by ``r_j / r_mid``) are taken on the
  undeformed geometry, as the nodal force ``-sigma_j w_j L`` of the small-strain increment
  (and as the 1D model does).
* ``core_pressure``: ``-sigma_r`` on the core, the inner face of the first group (its
  increments evaluated there from the element solution).
* Radial modulus per element at the mid-increment pressure, predicted from the previous
  increment's response scaled by the ratio of the loads (``corrections`` extra fixed-point
  solves optional). With ``K1 = 0`` (Table 3) ``E_r`` is floored at ``E_r_floor`` (default
  ``1e-6 E_theta``, 5 kPa) so that a slack sector stays solvable with zero stress.
* Lazy deep part, in levels of doubling depth (the 1D model's scheme): groups below the
  top ``window`` (16) are frozen and condensed onto the layer above them (Schur complement
  from a banded Cholesky in the mesh order). Level ``l`` spans ``window x 2^(l-1)`` to
  ``window x 2^l`` groups below the surface, is factorised on the Schur complement of the
  levels below it and frozen for ``flush x 2^(l-1)`` increments (``flush`` = 4), with E_r
  at the sigma_r predicted for the middle of that period (quadratic through the element's
  sigma_r now and at its last two refreshes). Refresh ``k`` re-solves levels 1 .. 1 +
  (trailing zero bits of k): O(log N) work per increment instead of a factorisation of
  the whole deep stack. A level's response is linear in the motion of its top layer and is
  recovered (passed down as the pending motion of the level below) when it is refreshed.
  ``levels=False``: the previous single frozen stack refreshed whole every ``flush``
  increments. ``window=None`` solves the whole stack every increment (banded Cholesky).
* Slack flag: ``slack[j]`` is True when, within ``SLACK_DEPTH`` (1 mm) of the surface, a
  group of sector ``j`` was wound without tension or its E_r sat at the floor.

Tension allocation (relaxation radius)
--------------------------------------
The incoming web of line tension ``F = T_w h_nom W`` (``T_w`` the web stress of the
:class:`~woundroll.winding.tension.TensionSchedule`, tapered at the mean radius of the
group, ``h_nom`` the web's nominal thickness, ``W`` the profile's CMD extent) is stress-free
at a radius ``R0``. At the deformed radius ``rho_j`` where the group lands on sector ``j``
(current deformed outer radius + half the group's thickness), the MD stress is
``sigma_j = E_theta max(rho_j - R0, 0) / R0``; ``R0`` is solved exactly (the total is
piecewise linear in ``1/R0``) so that ``sum_j sigma_j h_j w_j = F``. A nip adds
``mu N_j / h_j`` with ``N_j`` the local nip load per width (uniform ``tension.nip_load``
unless a ``nip`` callable gives the CMD distribution). The group's layers carry their
wound-on tension as initial hoop stress; their pressure on the stack below is
``p_j = sigma_j m h_j / r_j`` (``m`` layers in the group, ``r_j`` the undeformed radius
of the stack).

Outputs at the element (group, sector) centres: sigma_r, sigma_theta, sigma_z, tau_rz.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import LinAlgError, solveh_banded

from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.thickness_profile import ThicknessProfile
from woundroll.materials.web import Core, Web
from woundroll.winding import _axisym_fe as _fe
from woundroll.winding.tension import TensionSchedule

FloatArray = NDArray[np.float64]

#: Nip hook: ``nip(group_index, outer_radius[j], sigma_r_top[j]) -> N[j]`` [N/m per width].
NipHook = Callable[[int, FloatArray, FloatArray], FloatArray]

#: Fine grouping: graded toward the surface, at most ``MAX_GROUP_LAYERS`` layers per group
#: (:func:`default_groups`; the default unless :func:`choose_groups` finds a coarser one as
#: good). The grouping error grows as ``m^2 - 1`` with the group size ``m``
#: (midpoint rule); 2 layers keep every bundled PET roll within 0.5 % of the layer-by-layer
#: 1D model at every radius, 5 layers (the former 200 groups on Table 2's rolls) missed by
#: up to 4.9 % (docs/profile.md, section 6).
MAX_GROUP_LAYERS = 2
#: Lazy deep part of the FE model: groups below the top ``DEFAULT_WINDOW`` are frozen and
#: condensed in levels of doubling depth, level l refreshed every ``DEFAULT_FLUSH x 2^(l-1)``
#: increments (``window=None``: exact). 16 / 4 (frozen period a quarter of the depth) keep
#: Table 3 within 0.56 % pointwise of the exact solve, as 24 / 8 did with the single stack
#: (0.51 %); 16 / 8 with levels reached 2.3 % (docs/profile.md, section 7).
DEFAULT_WINDOW = 16
DEFAULT_FLUSH = 4
#: Depth below the surface [m] over which a slack group or a floored E_r flags the sector.
SLACK_DEPTH = 1e-3


@dataclass(frozen=True)
class AxisymmetricResult:
    """Stresses of an axisymmetric wound roll, SI; 2-D arrays are ``(n_groups, n_sectors)``,
    rows from the core outward, values at element (group, sector) centres.

    Attributes
    ----------
    z : ndarray [m]          sector centres (CMD).
    dz : ndarray [m]         sector widths.
    thickness : ndarray [m]  sector web thickness.
    radius : ndarray [m]     element-centre radii (undeformed build).
    sigma_r, sigma_theta, sigma_z, tau_rz : ndarray [Pa]
        Stresses of the (r, z) model (``sigma_z = tau_rz = 0`` with ``shear_coupling=False``).
    E_r : ndarray [Pa]       radial modulus at the final pressure.
    wot : ndarray [Pa]       wound-on tension of each group in each sector.
    nip_load : ndarray [N/m] nip load per width used for each group (zeros without nip).
    relaxation_radius : ndarray [m]  ``R0`` of each group (``inf`` when no web tension).
    outer_radius : ndarray [m]  final deformed outer radius of each sector.
    layers_per_group : ndarray  layers wound in each group.
    build_radius : ndarray [m]  undeformed outer radius of each sector (``r_c + n h_j``).
    core_radius : float [m]
    info : dict              counts, options, ``u_z_outer_m`` (axial displacement of the
                             outer surface per sector).
    slack : ndarray of bool  per sector: within ``SLACK_DEPTH`` (1 mm) of the surface a group
                             was wound without tension or its E_r sat at the floor, i.e. the
                             near-surface state (and a reading there) is set by the floor.
    core_pressure : ndarray [Pa]  ``-sigma_r`` on the core surface per sector (the inner face
                             of the first group; its centre lies half a group higher, where
                             sigma_r is lower by the steep gradient next to a stiff core).
    """

    z: FloatArray
    dz: FloatArray
    thickness: FloatArray
    radius: FloatArray
    sigma_r: FloatArray
    sigma_theta: FloatArray
    sigma_z: FloatArray
    tau_rz: FloatArray
    E_r: FloatArray
    wot: FloatArray
    nip_load: FloatArray
    relaxation_radius: FloatArray
    outer_radius: FloatArray
    layers_per_group: NDArray[np.int64]
    build_radius: FloatArray
    core_radius: float
    info: dict[str, Any] = field(default_factory=dict)
    slack: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))
    core_pressure: FloatArray = field(default_factory=lambda: np.zeros(0))

    @property
    def n_layers(self) -> int:
        return int(self.layers_per_group.sum())

    @property
    def sigma_r_outer(self) -> FloatArray:
        """Radial stress [Pa] of the outermost group, per sector."""
        return self.sigma_r[-1]

    @property
    def sigma_r_core(self) -> FloatArray:
        """Radial stress [Pa] on the core surface, per sector (``-core_pressure``)."""
        if self.core_pressure.size:
            return -self.core_pressure
        return self.sigma_r[0]

    @property
    def wot_mean(self) -> FloatArray:
        """Layer-weighted mean wound-on tension [Pa] per sector."""
        w = self.layers_per_group[:, None].astype(float)
        return (self.wot * w).sum(axis=0) / w.sum()

    def sector_profile(self, j: int) -> tuple[FloatArray, FloatArray]:
        """Radial stress profile of sector ``j`` for a contact model: radii [m] from the
        core surface (stress of the first group) through the group centres to the sector's
        undeformed outer radius (free surface, ``sigma_r = 0``), and sigma_r [Pa]."""
        r = np.concatenate([[self.core_radius], self.radius[:, j], [self.build_radius[j]]])
        s = np.concatenate([[self.sigma_r_core[j]], self.sigma_r[:, j], [0.0]])
        return r, s

    def column(self, j: int) -> dict[str, FloatArray]:
        """Radial profiles of sector ``j``: radius, sigma_r, sigma_theta, E_r."""
        return {
            "radius": self.radius[:, j],
            "sigma_r": self.sigma_r[:, j],
            "sigma_theta": self.sigma_theta[:, j],
            "E_r": self.E_r[:, j],
        }


def allocate_tension(
    rho: FloatArray, weight: FloatArray, line_force: float, E_theta: float
) -> tuple[FloatArray, float]:
    """Relaxation-radius allocation of a line tension across the CMD.

    Solves ``sum_j E_theta max(rho_j / R0 - 1, 0) weight_j = line_force`` for ``R0`` exactly
    (piecewise linear in ``s = 1/R0``; the active set is the ``k`` largest radii).

    Parameters
    ----------
    rho : ndarray [m]
        Radius where the web lands in each sector.
    weight : ndarray [m^2]
        ``h_j w_j`` (thickness times sector width).
    line_force : float [N]
        Total web tension force.
    E_theta : float [Pa]

    Returns
    -------
    sigma : ndarray [Pa]
        MD stress per sector (zero where slack).
    R0 : float [m]
        Relaxation radius (``inf`` when ``line_force`` is 0).
    """
    if line_force <= 0:
        return np.zeros_like(rho), math.inf
    order = np.argsort(-rho)
    r_sorted = rho[order]
    a = np.cumsum(weight[order] * r_sorted)  # sum of rho w over the k largest
    b = np.cumsum(weight[order])
    s = (line_force / E_theta + b) / a  # 1/R0 if the k largest are active
    # consistent k: the k-th radius taut (rho s > 1) and the next one slack (rho s <= 1)
    taut = r_sorted * s > 1.0
    nxt = np.append(r_sorted[1:], -np.inf) * s <= 1.0
    k = int(np.argmax(taut & nxt))
    s_k = s[k]
    sigma = E_theta * np.maximum(rho * s_k - 1.0, 0.0)
    return sigma, 1.0 / s_k


def _element_coefficients(
    r1: FloatArray, r2: FloatArray, E_r: FloatArray, E_t: float, nu: float
) -> tuple[FloatArray, ...]:
    """Exact ring element: with constant E_r, E_theta the radial stress is
    ``A x^(g-1) + B x^(-g-1)`` (``x = r / r_m``, ``r_m`` the element centre, ``g^2 = E_theta/E_r``)
    and ``u = r_m (A (g - nu) x^g - B (g + nu) x^(-g)) / E_theta``. Returns the inverse of the
    map (A, B) -> (u1, u2) and the powers needed for forces and stresses."""
    g = np.sqrt(E_t / E_r)
    rm = 0.5 * (r1 + r2)
    x1, x2 = r1 / rm, r2 / rm
    p1, p2 = x1**g, x2**g
    q1, q2 = 1.0 / p1, 1.0 / p2
    c = rm / E_t
    m11, m12 = c * (g - nu) * p1, -c * (g + nu) * q1
    m21, m22 = c * (g - nu) * p2, -c * (g + nu) * q2
    det = m11 * m22 - m12 * m21
    return g, x1, x2, p1, p2, q1, q2, m22 / det, -m12 / det, -m21 / det, m11 / det


def _element_stiffness(
    r1: FloatArray, r2: FloatArray, E_r: FloatArray, E_t: float, nu: float, w: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Exact stiffness (per radian, sector width ``w``) of ring elements [r1, r2]: entries
    k11, k12, k22 of the symmetric 2x2 matrix mapping (u1, u2) to the nodal forces
    ``(-r1 sigma_r(r1) w, r2 sigma_r(r2) w)``."""
    g, x1, x2, p1, p2, q1, q2, i11, i12, i21, i22 = _element_coefficients(r1, r2, E_r, E_t, nu)
    # sigma_r(x) = A x^(g-1) + B x^(-g-1); row vectors of the maps (A, B) -> forces
    s1a, s1b = -r1 * p1 / x1 * w, -r1 * q1 / x1 * w
    s2a, s2b = r2 * p2 / x2 * w, r2 * q2 / x2 * w
    k11 = s1a * i11 + s1b * i21
    k12 = s1a * i12 + s1b * i22
    k21 = s2a * i11 + s2b * i21
    k22 = s2a * i12 + s2b * i22
    return k11, 0.5 * (k12 + k21), k22


def _element_stress(
    r1: FloatArray,
    r2: FloatArray,
    E_r: FloatArray,
    E_t: float,
    nu: float,
    u1: FloatArray,
    u2: FloatArray,
    r_at: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    """sigma_r, sigma_theta [Pa] at ``r_at`` (the element centre) of the exact ring solution
    with end displacements u1, u2."""
    g, *_, i11, i12, i21, i22 = _element_coefficients(r1, r2, E_r, E_t, nu)
    A = i11 * u1 + i12 * u2
    B = i21 * u1 + i22 * u2
    x = r_at / (0.5 * (r1 + r2))
    xa, xb = x ** (g - 1.0), x ** (-g - 1.0)
    return A * xa + B * xb, g * (A * xa - B * xb)


def _column_solve(
    rn: FloatArray,
    E_r: FloatArray,
    F: FloatArray,
    E_t: float,
    nu: float,
    w: FloatArray,
    k_core: FloatArray | float,
    rigid: bool,
) -> FloatArray:
    """Independent plane-stress sectors (``shear_coupling=False``): radial displacement
    increments (ne + 1, ncol) of exact ring elements under the top forces ``F``; a
    tridiagonal Cholesky per sector."""
    ne, ncol = E_r.shape[0], w.size
    diag = np.zeros((ne + 1, ncol))
    k12 = np.zeros((ne, ncol))
    if not rigid:
        diag[0] += k_core
    if ne > 0:
        k11, k12, k22 = _element_stiffness(rn[:-1], rn[1:], E_r, E_t, nu, w)
        diag[:ne] += k11
        diag[1:] += k22
    rhs = np.zeros((ne + 1, ncol))
    rhs[ne] = F
    if rigid:  # node 0 fixed
        diag[0] = 1.0
        rhs[0] = 0.0
        if ne > 0:
            k12[0] = 0.0
    n = (ne + 1) * ncol
    if n == 1:  # one node (LAPACK's ptsv rejects n = 1)
        return rhs / diag
    ab = np.zeros((2, n))
    ab[1] = diag.T.ravel()
    up = np.zeros((ncol, ne + 1))
    up[:, 1:] = k12.T
    ab[0] = up.ravel()
    x = solveh_banded(ab, rhs.T.ravel(), check_finite=False)
    return x.reshape(ncol, ne + 1).T


#: Graded grouping: near the final outer surface a group holds about ``GRADE`` times the
#: number of layers above it (at least 1), so the outermost layers are wound one by one.
GRADE = 0.25


def _split_layers(n_layers: int, n_groups: int, grouping: str = "graded") -> NDArray[np.int64]:
    """Layers per group, from the core outward.

    ``"uniform"``: equal groups. ``"graded"``: a zone at the outer surface where a group
    holds ``max(1, floor(GRADE d))`` layers (``d`` layers above it when the roll is done:
    single layers at the surface, growing geometrically inward), and equal groups of about
    the zone's largest size below it; the total is exactly ``n_groups``.
    """
    base, extra = divmod(n_layers, n_groups)
    uniform = np.full(n_groups, base, dtype=np.int64)
    uniform[:extra] += 1
    if grouping == "uniform" or n_groups >= n_layers:
        return uniform
    best = None
    for cap in range(1, n_layers + 1):
        zone, d = [], 0
        while d < n_layers:
            s = min(cap, max(1, int(GRADE * d)))
            if s >= cap:
                break
            zone.append(s)
            d += s
        n_deep = n_groups - len(zone)
        if n_deep < 1 or d >= n_layers:
            break
        size = (n_layers - d) / n_deep
        if size < cap:  # the deep groups would be finer than the zone: stop growing
            break
        best = (zone, d, n_deep)
    if best is None:
        return uniform
    zone, d, n_deep = best
    b, e = divmod(n_layers - d, n_deep)
    deep = np.full(n_deep, b, dtype=np.int64)
    deep[:e] += 1
    return np.concatenate([deep, np.asarray(zone[::-1], dtype=np.int64)])


#: Coarser groupings tried by :func:`choose_groups`, coarsest first, and its tolerance.
COARSE_GROUPS = (200, 400)
GROUPING_TOL = 0.005


def choose_groups(
    web: Web,
    core: Core,
    outer_radius: float,
    tension: TensionSchedule,
    thickness: ThicknessProfile,
    E_r_floor: float,
) -> tuple[int, dict[str, Any]]:
    """The default grouping of a roll: the coarsest of :data:`COARSE_GROUPS` whose sigma_r
    stays within :data:`GROUPING_TOL` (0.5 %) of the fine grouping's (:func:`default_groups`,
    at most 2 layers per group), pointwise over the group centres (all but the outermost,
    wherever |sigma_r| exceeds 1 % of its peak) and at the core, else the fine grouping.

    The check winds the web at the profile's mean thickness as one plane-stress column (the
    1-sector path: milliseconds per increment, 1-3 % of the (r, z) model's cost). Why: the
    grouping error (the midpoint rule, growing as ``m^2 - 1`` with the group size ``m``) is a
    property of the material and the tension: 4.9 % with 200 groups on the soft pet2-80N
    roll, 0.4 % on pet3-2.3MPa (docs/profile.md, section 6); the fine grouping costs the
    (r, z) model 3-15x the time of 200 groups on Table 3. Returns the group count and a
    record of the check (in ``info["grouping_check"]``)."""
    edges = thickness.sector_edges(1)
    _, h = thickness.sector_average(1)
    column = ThicknessProfile.uniform(float(h[0]), float(edges[-1] - edges[0]))
    n_layers = int(round((outer_radius - core.outer_radius) / float(h[0])))
    fine = default_groups(max(n_layers, 1))
    kw: dict[str, Any] = {"n_sectors": 1, "E_r_floor": E_r_floor}
    ref = wind_axisymmetric(web, core, outer_radius, tension, column, n_groups=fine, **kw)
    record: dict[str, Any] = {"fine_groups": fine, "tolerance": GROUPING_TOL, "tried": {}}
    for G in sorted(g for g in COARSE_GROUPS if g < fine):
        a = wind_axisymmetric(web, core, outer_radius, tension, column, n_groups=G, **kw)
        s_ref = np.interp(a.radius[:-1, 0], ref.radius[:, 0], ref.sigma_r[:, 0])
        big = np.abs(s_ref) > 0.01 * np.max(np.abs(ref.sigma_r))
        dev = float(np.max(np.abs(a.sigma_r[:-1, 0][big] / s_ref[big] - 1), initial=0.0))
        if ref.core_pressure[0] > 0:
            dev = max(dev, abs(a.core_pressure[0] / ref.core_pressure[0] - 1))
        record["tried"][G] = dev
        if dev <= GROUPING_TOL:
            return G, record | {"groups": G}
    return fine, record | {"groups": fine}


def default_groups(n_layers: int, max_layers: int = MAX_GROUP_LAYERS) -> int:
    """Fewest graded groups (:func:`_split_layers`) with at most ``max_layers`` layers each."""
    G = min(n_layers, -(-n_layers // max_layers))
    while G < n_layers and int(_split_layers(n_layers, G).max()) > max_layers:
        G += 1
    return G


def _one_blas_thread() -> Any:
    """One BLAS thread while winding (:mod:`woundroll.util.blas`): the banded
    factorisations (bandwidth ~2 n_sectors) gain nothing from threads and lose 7x with them
    on a loaded 2-core machine (20.5 vs 3.0 ms a Table 3 window, docs/profile.md section 7)."""
    from woundroll.util.blas import one_blas_thread

    return one_blas_thread()


def _check_inputs(
    web: Any,
    core: Any,
    outer_radius: Any,
    tension: Any,
    thickness: Any,
    n_sectors: Any,
    grouping: Any,
    shape: Any,
    window: Any,
    flush: Any,
    corrections: Any,
    levels: Any = True,
) -> ThicknessProfile:
    """Validate the arguments of :func:`wind_axisymmetric`; returns the thickness profile."""
    if not isinstance(web, Web):
        raise InputError("must be a woundroll.materials.Web", "web")
    if not isinstance(core, Core):
        raise InputError("must be a woundroll.materials.Core", "core")
    if not isinstance(tension, TensionSchedule):
        raise InputError("must be a woundroll.winding.tension.TensionSchedule", "winding.tension")
    if isinstance(outer_radius, bool) or not isinstance(outer_radius, int | float | np.floating):
        raise InputError(f"must be a length in metres, got {outer_radius!r}", "roll.outer_radius")
    if thickness is None:
        thickness = ThicknessProfile.uniform(web.thickness, web.width)
    elif not isinstance(thickness, ThicknessProfile):
        raise InputError(
            "must be a ThicknessProfile (see woundroll.materials.thickness_profile)",
            "winding.thickness_profile",
        )
    if not (isinstance(n_sectors, int | np.integer) and n_sectors >= 1):
        raise InputError(f"must be a whole number >= 1, got {n_sectors!r}", "profile.n_sectors")
    if not (math.isfinite(outer_radius) and outer_radius > core.outer_radius):
        raise InputError(
            f"must exceed the core radius {core.outer_radius:g} m, got {outer_radius:g} m",
            "roll.outer_radius",
        )
    if grouping not in ("graded", "uniform"):
        raise InputError(f"choose graded or uniform, got {grouping!r}", "winding.grouping")
    if shape not in ("power", "linear"):
        raise InputError(f"choose power or linear, got {shape!r}", "winding.shape")
    if window is not None and (
        isinstance(window, bool) or not isinstance(window, int | np.integer) or window < 1
    ):
        raise InputError(f"must be a whole number >= 1 or None, got {window!r}", "winding.window")
    if isinstance(flush, bool) or not isinstance(flush, int | np.integer) or flush < 1:
        raise InputError(f"must be a whole number >= 1, got {flush!r}", "winding.flush")
    if isinstance(corrections, bool) or not isinstance(corrections, int) or corrections < 0:
        raise InputError(f"must be a whole number >= 0, got {corrections!r}", "winding.corrections")
    if not isinstance(levels, bool):
        raise InputError(f"must be true or false, got {levels!r}", "winding.levels")
    return thickness


@dataclass(frozen=True)
class _Build:
    """The roll's undeformed build: CMD sectors and layer groups, per sector ``j`` its
    thickness ``h_j`` and node radii ``r_c + n h_j`` (arrays (groups[+1], sectors))."""

    z: FloatArray  # sector centres [m]
    w: FloatArray  # sector widths [m]
    h: FloatArray  # sector thickness [m]
    r_c: float  # core radius [m]
    n_layers: int
    m: NDArray[np.int64]  # layers per group
    r_node: FloatArray  # group boundaries
    L: FloatArray  # group thickness
    r_mid: FloatArray  # group centres

    @property
    def top_frac(self) -> FloatArray:
        """Fraction ``(m - 1) / (2 m)`` of a group in the stack of its own increment."""
        return (self.m - 1) / (2.0 * self.m)


def _roll_build(
    thickness: ThicknessProfile,
    n_sectors: int,
    r_c: float,
    outer_radius: float,
    n_groups: int | None,
    grouping: str,
) -> _Build:
    """Sectors (sector averages of the profile), the layer count ``round((R - r_c) / mean
    h)``, the layer groups (:func:`default_groups` unless given) and the node radii."""
    edges = thickness.sector_edges(int(n_sectors))
    _, h = thickness.sector_average(int(n_sectors))
    w = np.diff(edges)
    h_mean = float(np.sum(h * w) / np.sum(w))
    n_layers = int(round((outer_radius - r_c) / h_mean))
    if n_layers < 1:
        raise InputError("the roll must hold at least one layer", "roll.outer_radius")
    if n_groups is None:
        n_groups = default_groups(n_layers)
    if not (isinstance(n_groups, int | np.integer) and 1 <= n_groups <= n_layers):
        raise InputError(
            f"must be a whole number in [1, {n_layers}] (the layer count), got {n_groups!r}",
            "winding.n_groups",
        )
    m = _split_layers(n_layers, int(n_groups), grouping)
    cum = np.concatenate([[0], np.cumsum(m)])
    r_node = r_c + cum[:, None] * h[None, :]
    return _Build(
        z=0.5 * (edges[1:] + edges[:-1]),
        w=w,
        h=h,
        r_c=r_c,
        n_layers=n_layers,
        m=m,
        r_node=r_node,
        L=np.diff(r_node, axis=0),
        r_mid=0.5 * (r_node[:-1] + r_node[1:]),
    )


class _Roll:
    """The roll being wound, one layer group per increment (:meth:`lay_group`).

    State: nodal displacements ``u``, ``uz`` and element stresses ``S`` (sigma_r,
    sigma_theta, sigma_z, tau_rz at the centres, sigma_r on the inner faces) of the groups
    wound so far; with the lazy deep part, the frozen groups ``< k_s`` condensed onto layer
    ``k_s`` (:meth:`freeze_deep_part`) and the motion of that layer since (``acc``).
    """

    def __init__(
        self,
        web: Web,
        core: Core,
        b: _Build,
        *,
        fe: bool,
        shape: str,
        floor: float,
        window: int | None,
        flush: int,
        corrections: int,
        levels: bool = True,
    ) -> None:
        G, ncol = b.m.size, b.h.size
        self.web, self.core, self.b = web, core, b
        self.fe, self.floor, self.corrections = fe, floor, corrections
        self.lazy = fe and window is not None
        self.window, self.flush = window, flush
        nnode = ncol + 1 if fe else ncol
        self.u = np.zeros((G + 1, nnode))  # radial displacement of the nodes
        self.uz = np.zeros((G + 1, nnode))
        self.S = np.zeros((5, G, ncol))
        self.wot = np.zeros((G, ncol))
        self.nip_used = np.zeros((G, ncol))
        self.floor_hit = np.zeros((G, ncol), dtype=bool)
        self.R0 = np.full(G, math.inf)
        # lagged predictor of the mid-increment stress: the last increment's response
        self.prev_dsr = np.zeros((G, ncol))
        self.prev_p: FloatArray | None = None
        self.prev_n = 0
        # lazy deep part
        self.k_s, self.S_deep, self.g_flush = 0, None, 0
        self.acc = np.zeros((ncol + 1, 2))
        self.s_flush = np.zeros((G, ncol))
        # levels of doubling depth (``levels=True``): the frozen bands from the window's
        # bottom down (level 1 first), each [bottom layer, top layer, band, pending motion
        # of its top layer]; the refresh count; each element's sigma_r at its last two
        # refreshes and the layer-time of those (the quadratic prediction of its modulus)
        self.use_levels = levels
        self.deep_factorised = 0  # groups factorised in deep-part refreshes (work measure)
        self.levels: list[list[Any]] = []
        self.n_refresh = 0
        self.t_layers = np.concatenate([[0.0], np.cumsum(b.m, dtype=float)])
        self.hist_t = np.full((2, G), np.nan)
        self.hist_s = np.zeros((2, G, ncol))
        if fe:
            self.stack = _fe.Stack(
                b.w,
                core.stiffness,
                (web.E_theta, float(web.E_z), web.nu_theta_r, web.nu_z_r, web.nu_theta_z),
                web.shear_r_z,
                shape,
            )
        self.k_core = 0.0 if core.rigid else core.stiffness * b.w  # column path: E_c w_j

    @property
    def s_r(self) -> FloatArray:
        return self.S[0]

    def at_sectors(self, v: FloatArray) -> FloatArray:
        """Nodal values (sector edges in the FE model) at the sector centres."""
        return 0.5 * (v[..., 1:] + v[..., :-1]) if self.fe else v

    def modulus(self, sig: FloatArray) -> FloatArray:
        """Radial modulus at radial stress ``sig``, floored at ``E_r_floor``."""
        return np.maximum(self.web.radial_modulus.modulus(sig), self.floor)

    # -- winder settings -> the tension each sector's layers are wound with ------------------
    def wound_on_tension(
        self, g: int, tension: TensionSchedule, nip: NipHook | None, outer_radius: float
    ) -> FloatArray:
        """Wound-on tension [Pa] of group ``g`` per sector: the line tension (tapered at the
        mean landing radius) allocated across the CMD by the relaxation-radius rule at the
        deformed radius where the group lands, plus the nip-induced ``mu N_j / h_j``."""
        b = self.b
        r_top = b.r_node[g] + self.at_sectors(self.u[g])
        rho = r_top + 0.5 * b.m[g] * b.h
        width = float(np.sum(b.w))
        r_bar = float(np.sum(rho * b.w) / width)
        line_force = (
            tension.web_stress
            * self.web.thickness
            * width
            * tension.taper.factor_at(r_bar, b.r_c, outer_radius)
        )
        sig_w, self.R0[g] = allocate_tension(rho, b.h * b.w, float(line_force), self.web.E_theta)
        if nip is not None:
            top = self.s_r[g - 1] if g > 0 else np.zeros(b.h.size)
            N = np.asarray(nip(g, r_top, top), dtype=float)
            if N.shape != (b.h.size,) or not np.all(np.isfinite(N)) or np.any(N < 0):
                raise InputError(
                    "the nip callable must return finite loads >= 0, one per sector", "winding.nip"
                )
        else:
            N = np.full(b.h.size, tension.nip_load)
        self.nip_used[g] = N
        sig = sig_w + tension.friction * N / b.h
        self.wot[g] = sig
        return sig

    # -- the increment: the group presses on the stack below it ------------------------------
    def lay_group(self, g: int, sig: FloatArray) -> None:
        """Wind group ``g`` with wound-on tension ``sig``: its layers are wound in sequence,
        each pressing on the stack below it; midpoint rule: the whole group load
        ``sig w L`` (per radian) acts on the stack extended by ``(m - 1) / 2`` layers of the
        group (:meth:`stack_radii`), with E_r at the mid-increment pressure."""
        b, S = self.b, self.S
        # pressure of the group on the stack below, on the undeformed geometry of the
        # (small-strain) increment, as the nodal force -sig w L applied below
        p = sig * b.m[g] * b.h / b.r_node[g]
        S[1, g] = sig  # initial hoop stress of the new group (sigma_r starts at 0)
        self.u[g + 1] = self.u[g]  # the group lands on the deformed stack
        self.uz[g + 1] = self.uz[g]
        if not np.any(sig > 0):
            return
        ne = g + 1 if b.m[g] > 1 else g
        if self.lazy and g - self.g_flush >= self.flush and ne - self.window > self.k_s:
            if self.use_levels:
                self.refresh_levels(g, ne)
            else:
                self.freeze_deep_part(g, ne)
        k0 = self.k_s
        F = -sig * b.w * b.L[g]
        s_old = self.s_r[k0:ne].copy()
        E2 = self.modulus(self.mid_increment_stress(g, ne, p, s_old))
        du, duz, dS = self.solve_stack(g, ne, E2, F)
        for _ in range(self.corrections if ne > k0 else 0):
            # corrector(s): E_r at the mid-increment pressure, fixed-point iteration
            E2 = self.modulus(s_old + 0.5 * dS[0])
            du, duz, dS_new = self.solve_stack(g, ne, E2, F)
            change = np.max(np.abs(dS_new[0] - dS[0])) / max(np.max(np.abs(dS_new[0])), 1e-300)
            dS = dS_new
            if change < 1e-6:
                break
        self.floor_hit[k0:ne] |= E2 <= self.floor
        self.prev_dsr[k0:ne] = dS[0]
        self.prev_p, self.prev_n = p, ne
        S[:, k0:g] += dS[:, : g - k0]
        # the group's own layers: sigma_r rises from 0 at the top to -p at the bottom (the
        # thin ring); a layer of the group felt on average (m - 1) / 2 of the m later
        # layers' loads, so that fraction of the hoop (and axial, shear) increment
        S[0, g] = -0.5 * p * b.r_node[g] / b.r_mid[g]
        S[4, g] = -p
        if ne > g:
            S[1:4, g] += b.top_frac[g] * dS[1:4, g - k0]
        self.u[k0 : ne + 1] += du
        self.uz[k0 : ne + 1] += duz
        if k0 > 0:
            self.acc += np.stack([du[0], duz[0]], axis=-1)
        if ne == g:
            self.u[g + 1] = self.u[g]
            self.uz[g + 1] = self.uz[g]

    def mid_increment_stress(self, g: int, ne: int, p: FloatArray, s_old: FloatArray) -> FloatArray:
        """Predicted sigma_r in the middle of increment ``g`` of the window's groups: the
        previous increment's response scaled by the ratio of the loads (lagged), else half
        the pressure the group exerts; the group's own part carries a quarter of it."""
        k0 = self.k_s
        pred = s_old - 0.5 * p[None, :]
        if ne > g:
            pred[g - k0] = -0.25 * p
        if self.prev_p is not None:
            k = max(min(self.prev_n, ne), k0)
            scale = np.divide(p, self.prev_p, out=np.ones_like(p), where=self.prev_p > 0)
            pred[: k - k0] = s_old[: k - k0] + 0.5 * self.prev_dsr[k0:k] * scale[None, :]
        return pred

    def stack_radii(self, g: int, ne: int) -> FloatArray:
        """Node radii of the stack of ``ne`` elements in increment ``g``. With ``m > 1``
        layers the stack includes the new group's element cut to ``(m - 1) / 2`` layers: on
        average a layer of the group lies on ``(m - 1) / 2`` layers of its own group
        (midpoint rule). With ``m = 1`` the new layer is not in the stack (Hakiel)."""
        b = self.b
        rn = b.r_node[: ne + 1].copy()
        if ne == g + 1:
            rn[ne] = b.r_node[ne - 1] + b.top_frac[ne - 1] * b.L[ne - 1]
        return rn

    def solve_stack(
        self, g: int, ne: int, E_r: FloatArray, F: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Displacement increments (radial, axial) of the nodes of layers ``k_s..ne`` and the
        stress increments (5, ne - k_s, ncol) of the stack of ``ne`` groups under the top
        forces ``F`` (per radian, per sector); ``E_r`` of the groups ``k_s..ne-1`` (the window
        above the frozen deep part, if any)."""
        web, k0, ncol = self.web, self.k_s, self.b.h.size
        rn = self.stack_radii(g, ne)[k0:]
        try:
            if self.fe:
                f_top = np.zeros(ncol + 1)
                f_top[:-1] += 0.5 * F
                f_top[1:] += 0.5 * F
                du, duz, dS = self.stack.solve(rn, E_r, f_top, self.S_deep)
            else:
                E_t, nu = web.E_theta, web.nu_theta_r
                du = _column_solve(rn, E_r, F, E_t, nu, self.b.w, self.k_core, self.core.rigid)
                duz = np.zeros_like(du)
                dS = np.zeros((5, ne - k0, ncol))
                if ne > k0:
                    r1, r2 = rn[:-1], rn[1:]
                    args = (r1, r2, E_r, E_t, nu, du[:-1], du[1:])
                    dS[0], dS[1] = _element_stress(*args, 0.5 * (r1 + r2))
                    dS[4] = _element_stress(*args, r1)[0]
        except (LinAlgError, RuntimeError) as exc:
            raise ConvergenceError(
                f"winding increment {g + 1}: singular stiffness ({exc})"
            ) from None
        if not (np.all(np.isfinite(du)) and np.all(np.isfinite(duz))):
            raise ConvergenceError(f"winding increment {g + 1}: non-finite displacements")
        return du, duz, dS

    # -- lazy deep part (FE model) -----------------------------------------------------------
    def recover_deep_part(self) -> None:
        """Add the frozen groups' response to the motion of the layer they are condensed
        onto since the last freeze (linear in it)."""
        k0 = self.k_s
        if k0 == 0:
            return
        dur, duzr, dSd = self.stack.recover(self.acc)
        self.u[:k0] += dur[:-1]
        self.uz[:k0] += duzr[:-1]
        self.S[:, :k0] += dSd
        self.acc = np.zeros_like(self.acc)

    def freeze_deep_part(self, g: int, ne: int) -> None:
        """Freeze the groups below the top ``window`` at the E_r predicted for the middle of
        the next ``flush`` increments and condense them onto the window's bottom layer."""
        self.recover_deep_part()
        b, s_r = self.b, self.s_r
        k_new = ne - int(self.window)
        done = float(np.sum(b.m[self.g_flush : g])) or 1.0
        ratio = float(np.sum(b.m[g : g + int(self.flush)])) / done
        d_prev = s_r[:k_new] - self.s_flush[:k_new]
        E_deep = self.modulus(s_r[:k_new] + 0.5 * ratio * d_prev)
        self.floor_hit[:k_new] |= E_deep <= self.floor
        self.S_deep = self.stack.condense(b.r_node[: k_new + 1], E_deep)
        self.deep_factorised += k_new
        self.k_s, self.g_flush = k_new, g
        self.acc = np.zeros_like(self.acc)
        self.s_flush[:] = s_r

    # -- lazy deep part in levels of doubling depth (FE model, the default) ------------------
    def recover_levels(self, n: int) -> None:
        """Apply the pending motion of the top ``n`` frozen levels, from the window's bottom
        down: each level's response to the motion of its top layer (linear in it, frozen
        moduli) updates its layers and stresses and becomes pending motion of the level
        below (the layer they share)."""
        for i in range(min(n, len(self.levels))):
            bot, top, band, acc = self.levels[i]
            if not np.any(acc):
                continue
            dur, duzr, dSd = self.stack.recover_band(band, acc)
            self.u[bot:top] += dur[:-1]
            self.uz[bot:top] += duzr[:-1]
            self.S[:, bot:top] += dSd
            if i + 1 < len(self.levels):
                self.levels[i + 1][3] += np.stack([dur[0], duzr[0]], axis=-1)
            acc[:] = 0.0
        if n > 0 and self.levels:
            self.acc = self.levels[0][3]

    def predicted_modulus(self, k0: int, k1: int, g: int, period: int) -> FloatArray:
        """E_r of groups ``k0..k1-1`` frozen for the ``period`` increments from ``g`` on: at
        the sigma_r predicted for the mean evaluation time of those increments (the middle
        of each, midpoint rule, in layers wound) by a quadratic through the element's
        sigma_r now and at its last two refreshes (linear with one, constant with none)."""
        T = self.t_layers
        G = self.b.m.size
        i = np.arange(g, min(g + period, G))
        t_star = float(np.mean(T[i] + 0.5 * self.b.m[i])) if i.size else T[g]
        t0 = T[g]
        s0 = self.s_r[k0:k1]
        t1, t2 = self.hist_t[0, k0:k1, None], self.hist_t[1, k0:k1, None]
        s1, s2 = self.hist_s[0, k0:k1], self.hist_s[1, k0:k1]
        with np.errstate(invalid="ignore", divide="ignore"):
            # Lagrange basis at t_star through (t0, s0), (t1, s1), (t2, s2)
            l0 = (t_star - t1) * (t_star - t2) / ((t0 - t1) * (t0 - t2))
            l1 = (t_star - t0) * (t_star - t2) / ((t1 - t0) * (t1 - t2))
            l2 = (t_star - t0) * (t_star - t1) / ((t2 - t0) * (t2 - t1))
            quad = l0 * s0 + l1 * s1 + l2 * s2
            lin = s0 + (t_star - t0) * (s0 - s1) / (t0 - t1)
        pred = np.where(np.isfinite(t2) & (t2 < t1), quad, np.where(np.isfinite(t1), lin, s0))
        return self.modulus(pred)

    def refresh_levels(self, g: int, ne: int) -> None:
        """Refresh number ``k`` of the deep part (one every ``flush`` increments): level
        ``l`` spans ``window x 2^(l-1)`` to ``window x 2^l`` groups below the surface and is
        frozen for ``flush x 2^(l-1)`` increments, so refresh ``k`` re-solves levels
        1 .. 1 + (trailing zero bits of k) and leaves the deeper ones (their Schur
        complement stands for them): O(window) work per level every ``2^(l-1)`` refreshes,
        O(log N) per increment instead of a factorisation of the whole deep stack
        (the 1D model's scheme, docs/winding.md, "Lazy deep part"). Pending motion of the
        re-solved levels is applied first; their groups are re-partitioned over the span
        from the top of the first level kept to the new window bottom ``ne - window`` and
        factorised from the bottom up with the moduli predicted for their frozen period."""
        self.n_refresh += 1
        k = self.n_refresh
        L = 1 + ((k & -k).bit_length() - 1)  # 1 + trailing zero bits of k
        W, F = int(self.window), int(self.flush)
        whole = L >= len(self.levels)
        self.recover_levels(len(self.levels) if whole else L)
        if whole:
            bottom, S = 0, None
            kept: list[list[Any]] = []
        else:
            bottom, S = self.levels[L][1], self.levels[L][2][1]
            kept = self.levels[L:]
        k_new = ne - W
        # the new levels from the window's bottom down (at most L unless all are re-solved)
        spans = []
        top, lvl = k_new, 1
        while top > bottom:
            bot = max(bottom, ne - W * 2**lvl)
            if not whole and lvl == L:
                bot = bottom
            spans.append((bot, top, lvl))
            top, lvl = bot, lvl + 1
        new: list[list[Any]] = []
        for bot, top, lvl in reversed(spans):
            E = self.predicted_modulus(bot, top, g, F * 2 ** (lvl - 1))
            self.floor_hit[bot:top] |= E <= self.floor
            S, band = self.stack.condense_band(self.b.r_node[bot : top + 1], E, S)
            self.deep_factorised += top - bot
            new.insert(0, [bot, top, band, np.zeros_like(self.acc)])
        self.levels = new + kept
        self.S_deep = S
        self.k_s, self.g_flush = k_new, g
        self.acc = self.levels[0][3]
        # sigma_r history of the elements whose state is current (re-solved and window)
        tg = self.t_layers[g]
        self.hist_t[1, bottom:ne] = self.hist_t[0, bottom:ne]
        self.hist_s[1, bottom:ne] = self.hist_s[0, bottom:ne]
        self.hist_t[0, bottom:ne] = tg
        self.hist_s[0, bottom:ne] = self.s_r[bottom:ne]

    # -- the wound roll ------------------------------------------------------------------------
    def slack(self, E_final: FloatArray) -> NDArray[np.bool_]:
        """Per sector: within ``SLACK_DEPTH`` of the surface a group was wound without
        tension or its radial modulus sat at the floor (final pressure or in an increment)."""
        b = self.b
        depth = b.r_node[-1][None, :] - b.r_mid
        near = depth <= max(SLACK_DEPTH, float(np.max(b.L[-1])))
        at_floor = (self.wot <= 0) | (E_final <= self.floor) | self.floor_hit
        return np.any(near & at_floor, axis=0)

    def result(self, info: dict[str, Any]) -> AxisymmetricResult:
        b, S = self.b, self.S
        if self.lazy:
            if self.use_levels:
                self.recover_levels(len(self.levels))
            else:
                self.recover_deep_part()
        if not np.all(np.isfinite(S)):
            raise ConvergenceError("non-finite stresses in the axisymmetric winding solution")
        E_final = np.asarray(self.web.radial_modulus.modulus(S[0]), dtype=float)
        return AxisymmetricResult(
            z=b.z,
            dz=b.w,
            thickness=b.h,
            radius=b.r_mid,
            sigma_r=S[0],
            sigma_theta=S[1],
            sigma_z=S[2],
            tau_rz=S[3],
            E_r=E_final,
            wot=self.wot,
            nip_load=self.nip_used,
            relaxation_radius=self.R0,
            outer_radius=b.r_node[-1] + self.at_sectors(self.u[-1]),
            layers_per_group=b.m,
            build_radius=b.r_node[-1].copy(),
            core_radius=b.r_c,
            info=info
            | {"u_z_outer_m": self.at_sectors(self.uz[-1]) if self.fe else np.zeros(b.h.size)},
            slack=self.slack(E_final),
            core_pressure=-S[4, 0].copy(),
        )


def wind_axisymmetric(
    web: Web,
    core: Core,
    outer_radius: float,
    tension: TensionSchedule,
    thickness: ThicknessProfile | None = None,
    *,
    n_sectors: int = 61,
    n_groups: int | None = None,
    shear_coupling: bool = True,
    nip: NipHook | None = None,
    E_r_floor: float | None = None,
    corrections: int = 0,
    progress: Callable[[int, int], None] | None = None,
    grouping: str = "graded",
    shape: str = "power",
    window: int | None = DEFAULT_WINDOW,
    flush: int = DEFAULT_FLUSH,
    levels: bool = True,
) -> AxisymmetricResult:
    """Wind a roll with a CMD thickness profile; stresses over (r, z).

    Parameters
    ----------
    web : Web
        Material (E_theta, E_z, radial-modulus law, nu_theta_r, nu_z_r, nu_theta_z, G_r_z)
        and nominal thickness [m].
    core : Core
        Core radius [m] and stiffness E_c [Pa] (``inf``: rigid).
    outer_radius : float [m]
        Target final radius; the layer count is ``round((R - r_c) / mean thickness)``.
    tension : TensionSchedule
        Web stress [Pa] (line tension = web stress x nominal thickness x width), taper,
        nip load [N/m] and friction.
    thickness : ThicknessProfile, optional
        CMD profile; default uniform ``web.thickness`` over ``web.width``.
    n_sectors : int
        CMD sectors (finite elements across the width).
    n_groups : int, optional
        Winding increments; default (graded grouping) :func:`choose_groups`: 200 or 400
        groups where they agree with groups of at most 2 layers (:func:`default_groups`)
        within 0.5 % on a column of the mean thickness, else the latter. Convergence:
        docs/profile.md, section 6.
    shear_coupling : bool
        True (default): the axisymmetric (r, z) finite-element model. False: independent
        sectors, each a 1D plane-stress roll (``sigma_z = tau_rz = 0``), for comparison.
    nip : callable, optional
        ``nip(g, outer_radius, sigma_r_top) -> N`` [N/m], the CMD nip-load distribution for
        group ``g``; default uniform ``tension.nip_load``.
    E_r_floor : float, optional [Pa]
        Lower bound of the radial modulus (default ``1e-6 E_theta``).
    corrections : int
        Extra fixed-point solves per increment for the mid-increment modulus (0: the
        lagged predictor alone, which matches 1 or 10 corrections within 0.1 %).
    progress : callable, optional
        ``progress(done, total)`` after each group.
    grouping : {"graded", "uniform"}
        Layer groups shrinking to single layers at the outer surface (default) or equal.
    shape : {"power", "linear"}
        Radial interpolation of u_r in the finite elements (module docstring).
    window, flush : int
        Lazy deep part: groups below the top ``window`` are frozen and condensed, refreshed
        every ``flush`` increments (``window=None``: the whole stack every increment, exact
        but ~8x slower on Table 3; the two differ by 0.2 % of max |sigma_r| there).
    levels : bool
        True (default): the frozen deep part in levels of doubling depth, O(log N) work per
        increment; False: one frozen stack refactorised whole at every refresh (the
        previous scheme, O(N) per refresh; kept for comparison, docs/profile.md section 7).

    Raises
    ------
    InputError
        Inconsistent geometry or counts. ConvergenceError: a singular or non-finite solve.
    """
    thickness = _check_inputs(
        web,
        core,
        outer_radius,
        tension,
        thickness,
        n_sectors,
        grouping,
        shape,
        window,
        flush,
        corrections,
        levels,
    )
    floor = 1e-6 * web.E_theta if E_r_floor is None else float(E_r_floor)
    if not (math.isfinite(floor) and floor > 0):
        raise InputError(f"must be positive, got {floor:g} Pa", "winding.E_r_floor")
    check = None
    if n_groups is None and grouping == "graded":
        n_groups, check = choose_groups(web, core, outer_radius, tension, thickness, floor)
    build = _roll_build(thickness, n_sectors, core.outer_radius, outer_radius, n_groups, grouping)
    fe = shear_coupling and build.h.size > 1
    roll = _Roll(
        web,
        core,
        build,
        fe=fe,
        shape=shape,
        floor=floor,
        window=window,
        flush=flush,
        corrections=corrections,
        levels=levels,
    )
    G = build.m.size
    with _one_blas_thread():
        for g in range(G):
            sig = roll.wound_on_tension(g, tension, nip, outer_radius)
            roll.lay_group(g, sig)
            if progress is not None:
                progress(g + 1, G)
        return roll.result(
            {
                "n_layers": build.n_layers,
                "n_groups": G,
                "grouping": grouping,
                "model": "axisymmetric FE (u_r, u_z)" if fe else "independent plane-stress sectors",
                "shape": shape,
                "shear_coupling": shear_coupling,
                "E_r_floor_Pa": floor,
                "line_force_N": tension.web_stress * web.thickness * float(np.sum(build.w)),
                "slack_depth_m": SLACK_DEPTH,
                "grouping_check": check,
                "deep_part": ("levels" if levels else "single") if roll.lazy else "none",
                "deep_groups_factorised": roll.deep_factorised,
            }
        )


def group_convergence(
    web: Web,
    core: Core,
    outer_radius: float,
    tension: TensionSchedule,
    thickness: ThicknessProfile | None = None,
    *,
    n_sectors: int = 61,
    n_groups: int | None = None,
    surface_depth: float = 5e-3,
    **kwargs: Any,
) -> dict[str, float]:
    """Convergence check of the layer grouping: wind with ``n_groups`` (default: the default
    grouping) and twice as many groups.

    Returns the largest change between the two of the radial stress at the core and of the
    mean wound-on tension, each relative to its largest magnitude [-]; of the radial stress
    in the outer ``surface_depth`` [m] (where a tester reads; the fine run interpolated to
    the coarse group centres of each sector), relative to the largest magnitude there
    (``surface_stress_change``) and pointwise relative to the local value wherever that is
    above 10 % of the largest (``surface_stress_change_pointwise``); and the two run times
    [s]. A change of a few 1e-3 means the coarser grouping is converged for practical
    purposes (docs/profile.md, section 6).
    """
    import time

    t0 = time.perf_counter()
    a = wind_axisymmetric(
        web,
        core,
        outer_radius,
        tension,
        thickness,
        n_sectors=n_sectors,
        n_groups=n_groups,
        **kwargs,
    )
    t1 = time.perf_counter()
    n_groups = int(a.layers_per_group.size)
    n2 = min(2 * n_groups, a.n_layers)
    b = wind_axisymmetric(
        web, core, outer_radius, tension, thickness, n_sectors=n_sectors, n_groups=n2, **kwargs
    )
    t2 = time.perf_counter()
    core_a, core_b = a.sigma_r_core, b.sigma_r_core
    d_abs, d_pt, s_max = 0.0, 0.0, 0.0
    for j in range(a.z.size):
        ra, rb = a.radius[:, j], b.radius[:, j]
        sel = ra >= a.build_radius[j] - surface_depth
        sa = a.sigma_r[sel, j]
        sb = np.interp(ra[sel], rb, b.sigma_r[:, j])
        s_max = max(s_max, float(np.max(np.abs(sb))))
        d_abs = max(d_abs, float(np.max(np.abs(sa - sb))))
    for j in range(a.z.size):
        ra, rb = a.radius[:, j], b.radius[:, j]
        sel = ra >= a.build_radius[j] - surface_depth
        sb = np.interp(ra[sel], rb, b.sigma_r[:, j])
        big = np.abs(sb) > 0.1 * s_max
        if np.any(big):
            d_pt = max(d_pt, float(np.max(np.abs(a.sigma_r[sel, j][big] / sb[big] - 1.0))))
    return {
        "n_groups": float(n_groups),
        "n_groups_fine": float(n2),
        "core_stress_change": float(np.max(np.abs(core_a - core_b)) / np.max(np.abs(core_b))),
        "wot_change": float(np.max(np.abs(a.wot_mean - b.wot_mean)) / np.max(np.abs(b.wot_mean))),
        "surface_stress_change": d_abs / s_max if s_max > 0 else 0.0,
        "surface_stress_change_pointwise": d_pt,
        "time_s": t1 - t0,
        "time_fine_s": t2 - t1,
    }
