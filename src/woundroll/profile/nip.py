"""The nip roller as a beam on the roll: CMD distribution of the nip load.

A nip roller of bending stiffness ``EI`` [N m^2] spans the web; it is pressed onto the roll
by two equal bearing forces at its ends (``P = N_mean W / 2`` each, ``N_mean`` the set nip
load per width [N/m], ``W`` the web width). The roll is an elastic foundation that is
**nonlinear** (the contact law of each CMD sector, ``q = alpha_j d^2 + beta_j d`` [N/m per
unit CMD length] at the local indentation ``d`` [m], from the contact model, or any
callable) and **non-uniform** (each sector has its own law and its own outer radius: a
sector whose radius is ``g_j`` below the largest one is touched only after the roller has
closed that gap).

Formulation (assumptions named)
-------------------------------
* Euler-Bernoulli beam, cubic Hermite elements, nodes at the sector edges, each sector cut
  into ``refine`` elements; bearing nodes at ``overhang`` [m] beyond each web edge
  (default 0: loads at the web edges).
* Roll surface: rigid except for the local foundation law (Winkler: no CMD coupling in the
  roll's response to the nip); the roll's deflection as a whole is neglected.
* Local indentation ``d(z) = w(z) - gap(z)``, foundation force 0 where ``d <= 0`` (the
  roller lifts off; no adhesion). Foundation integrated by 3-point Gauss per element.
* Newton iterations with backtracking from the rigid-roller solution (a uniform approach
  solved by bisection); :class:`~woundroll.errors.ConvergenceError` if the residual does not
  fall below ``1e-10`` of the total load in 60 iterations.

The nip-induced tension ``mu N(z) / h(z)`` (Good, Wu and Fikes 1994) is then allocated by
the local nip load: :func:`nip_hook` returns the callable that
:func:`woundroll.winding.axisymmetric.wind_axisymmetric` calls for each winding increment.

Table 3 of the reference paper gives "P_nip 2.3 MPa", a pressure, whereas a winder sets a
nip load per width. woundroll reads the nip as a load per width ``N`` [N/m] (see
docs/profile.md for the interpretation used in the bundled case).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import solve_banded

from woundroll.errors import ConvergenceError, InputError

FloatArray = NDArray[np.float64]

#: Foundation: ``(radius, sigma_r) -> (alpha [N/m^3], beta [N/m^2])`` per unit CMD length.
FoundationFn = Callable[[FloatArray, FloatArray], tuple[float, float]]

_GP = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
_GW = np.array([5.0, 8.0, 5.0]) / 9.0


@dataclass(frozen=True)
class NipRoller:
    """The nip roller, SI.

    Attributes
    ----------
    EI : float [N m^2]
        Bending stiffness of the roller (``E I``).
    line_load : float [N/m]
        Mean nip load per web width; the bearing forces are ``line_load W / 2`` each.
    overhang : float [m]
        Distance of each bearing beyond the web edge (0: loads at the web edges).
    radius : float [m]
        Roller radius (for a contact-model foundation).
    friction : float [-]
        Nip-to-roll friction mu for the nip-induced tension mu N / h.
    """

    EI: float
    line_load: float
    overhang: float = 0.0
    radius: float = 0.05
    friction: float = 0.0

    def __post_init__(self) -> None:
        for name in ("EI", "radius"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InputError(f"must be positive, got {v!r}", f"winding.nip.{name}")
        for name in ("line_load", "overhang"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InputError(f"must be zero or positive, got {v!r}", f"winding.nip.{name}")
        if not (math.isfinite(self.friction) and 0 <= self.friction <= 2):
            raise InputError(f"must lie in [0, 2], got {self.friction!r}", "winding.nip.friction")

    @classmethod
    def tube(
        cls, E: float, outer_radius: float, inner_radius: float, line_load: float, **kw: float
    ) -> NipRoller:
        """A tubular roller: ``I = pi (R^4 - r^4) / 4``."""
        if not (0 <= inner_radius < outer_radius):
            raise InputError("need 0 <= inner_radius < outer_radius", "winding.nip.inner_radius")
        I = math.pi * (outer_radius**4 - inner_radius**4) / 4.0
        return cls(EI=E * I, line_load=line_load, radius=outer_radius, **kw)


def roller_from_induced_tension(
    induced_stress: float,
    thickness: float,
    friction: float,
    *,
    EI: float,
    radius: float = 0.05,
    overhang: float = 0.0,
) -> NipRoller:
    """A roller whose mean nip load gives the nip-induced tension ``mu N / h = induced_stress``.

    The interpretation of Table 3's "P_nip 2.3 MPa" used for the bundled case (docs/profile.md):
    a stress in the same units and row as T_w, i.e. the nip's share of the wound-on tension,
    so ``N = induced_stress h / mu``.

    Parameters
    ----------
    induced_stress : float [Pa]
    thickness : float [m]
        Web thickness h.
    friction : float [-]
        mu > 0.
    EI : float [N m^2]
    radius, overhang : float [m]
    """
    for name, v in (
        ("induced_stress", induced_stress),
        ("thickness", thickness),
        ("friction", friction),
    ):
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"must be positive, got {v!r}", f"winding.nip.{name}")
    return NipRoller(
        EI=EI,
        line_load=induced_stress * thickness / friction,
        overhang=overhang,
        radius=radius,
        friction=friction,
    )


@dataclass(frozen=True)
class NipSolution:
    """Nip-load distribution.

    Attributes
    ----------
    z : ndarray [m]            sector centres.
    load : ndarray [N/m]       nip load per unit CMD length at the sector centres
                               (mean over each sector).
    indentation : ndarray [m]  local indentation at the sector centres (<= 0: no contact).
    node_z, deflection : ndarray [m]  beam nodes and their deflection toward the roll.
    total : float [N]          total load carried (equals the bearing forces).
    iterations : int
    """

    z: FloatArray
    load: FloatArray
    indentation: FloatArray
    node_z: FloatArray
    deflection: FloatArray
    total: float
    iterations: int


def _hermite(xi: FloatArray, L: FloatArray) -> FloatArray:
    """Hermite shape functions at xi in [-1, 1] for elements of lengths L: (n_el, 4)."""
    N1 = 0.25 * (1 - xi) ** 2 * (2 + xi)
    N2 = 0.125 * (1 - xi) ** 2 * (1 + xi)
    N3 = 0.25 * (1 + xi) ** 2 * (2 - xi)
    N4 = -0.125 * (1 + xi) ** 2 * (1 - xi)
    return np.stack([N1 * np.ones_like(L), N2 * L, N3 * np.ones_like(L), N4 * L], axis=1)


def solve_nip(
    edges: ArrayLike,
    alpha: ArrayLike,
    beta: ArrayLike,
    roller: NipRoller,
    *,
    gap: ArrayLike | None = None,
    refine: int = 4,
    bilateral: bool = False,
) -> NipSolution:
    """Nip-load distribution of a beam on a nonlinear, non-uniform foundation.

    Parameters
    ----------
    edges : array_like [m]
        Sector edges along the CMD (``n + 1`` increasing values).
    alpha, beta : array_like [N/m^3], [N/m^2]
        Foundation law of each sector per unit CMD length, ``q = alpha d^2 + beta d``; >= 0,
        ``alpha + beta > 0`` somewhere. Scalars are broadcast.
    roller : NipRoller
    gap : array_like, optional [m]
        Initial clearance of each sector (``max(r) - r_j`` for outer radii ``r_j``); default 0.
    refine : int
        Beam elements per sector.
    bilateral : bool
        False (default): the foundation pushes only (lift-off where ``d <= 0``). True: a
        linear foundation that also pulls (Hetenyi's classical beam on elastic foundation;
        used to verify the beam solver); needs ``alpha = 0``.

    Raises
    ------
    InputError
        Bad arrays. ConvergenceError: Newton did not converge.
    """
    e, a, b, g = _nip_inputs(edges, alpha, beta, gap, refine, bilateral)
    n = e.size - 1
    total = roller.line_load * (e[-1] - e[0])
    z_mid = 0.5 * (e[1:] + e[:-1])
    if total == 0:
        zero = np.zeros(n)
        return NipSolution(z_mid, zero, zero - g, e.copy(), np.zeros(e.size), 0.0, 0)
    beam = _NipBeam(e, a, b, g, roller, refine, bilateral)
    u = np.zeros(beam.ndof)
    u[0::2] = _rigid_approach(e, a, b, g, total)
    u, q, it = beam.newton(u, total)
    return beam.solution(u, q, z_mid, it)


def _nip_inputs(
    edges: ArrayLike,
    alpha: ArrayLike,
    beta: ArrayLike,
    gap: ArrayLike | None,
    refine: int,
    bilateral: bool,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Sector edges, and alpha, beta, gap broadcast to one value per sector (checked)."""
    e = np.asarray(edges, dtype=float)
    if e.ndim != 1 or e.size < 2 or np.any(np.diff(e) <= 0) or not np.all(np.isfinite(e)):
        raise InputError("sector edges must be >= 2 increasing finite values", "winding.nip.edges")
    n = e.size - 1
    a = np.broadcast_to(np.asarray(alpha, dtype=float), (n,)).copy()
    b = np.broadcast_to(np.asarray(beta, dtype=float), (n,)).copy()
    g = np.zeros(n) if gap is None else np.broadcast_to(np.asarray(gap, dtype=float), (n,)).copy()
    for name, v in (("alpha", a), ("beta", b), ("gap", g)):
        if not np.all(np.isfinite(v)) or np.any(v < 0):
            raise InputError("must be finite and >= 0 in every sector", f"winding.nip.{name}")
    if not np.any(a + b > 0):
        raise InputError(
            "the foundation has no stiffness (alpha = beta = 0 everywhere)",
            "winding.nip.foundation",
        )
    if bilateral and np.any(a != 0):
        raise InputError("a bilateral foundation must be linear (alpha = 0)", "winding.nip.alpha")
    if not (isinstance(refine, int) and refine >= 1):
        raise InputError(f"must be a whole number >= 1, got {refine!r}", "winding.nip.refine")
    return e, a, b, g


def _rigid_approach(
    e: FloatArray, a: FloatArray, b: FloatArray, g: FloatArray, total: float
) -> float:
    """Rigid-roller start: the uniform approach d0 at which the sector loads sum to
    ``total`` (bisection; the upper end of the last bracket)."""
    width = np.diff(e)

    def carried(d0: float) -> float:
        dd = np.maximum(d0 - g, 0.0)
        return float(np.sum((a * dd * dd + b * dd) * width))

    lo, hi = 0.0, float(np.max(g)) + 1e-9
    while carried(hi) < total:
        hi *= 2.0
        if hi > 1.0:
            raise ConvergenceError("nip: the foundation cannot carry the load within 1 m approach")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if carried(mid) < total else (lo, mid)
    return hi


class _NipBeam:
    """The roller as Hermite beam elements (sector edges subdivided, plus the bearing
    overhang) on the sectors' foundation, its stiffness in LAPACK band storage."""

    def __init__(
        self,
        e: FloatArray,
        a: FloatArray,
        b: FloatArray,
        g: FloatArray,
        roller: NipRoller,
        refine: int,
        bilateral: bool,
    ) -> None:
        n = e.size - 1
        self.e, self.bilateral, self.n = e, bilateral, n
        # mesh: sector edges subdivided, plus bearing nodes
        sub = np.linspace(0.0, 1.0, refine + 1)[:-1]
        nodes = np.concatenate(
            [(e[:-1, None] + np.diff(e)[:, None] * sub[None, :]).ravel(), e[-1:]]
        )
        sector_of_el = np.repeat(np.arange(n), refine)
        if roller.overhang > 0:
            nodes = np.concatenate([[e[0] - roller.overhang], nodes, [e[-1] + roller.overhang]])
            sector_of_el = np.concatenate([[-1], sector_of_el, [-1]])
        L = np.diff(nodes)
        ne = L.size
        self.nodes, self.L, self.ne = nodes, L, ne
        self.ndof = 2 * nodes.size
        self.dof = np.stack(
            [
                2 * np.arange(ne),
                2 * np.arange(ne) + 1,
                2 * np.arange(ne) + 2,
                2 * np.arange(ne) + 3,
            ],
            axis=1,
        )
        # beam stiffness in LAPACK band storage (Hermite dofs: 3 bands each side)
        c = roller.EI / L**3
        ke = np.empty((ne, 4, 4))
        ke[:, 0] = np.stack([12 * c, 6 * c * L, -12 * c, 6 * c * L], 1)
        ke[:, 1] = np.stack([6 * c * L, 4 * c * L**2, -6 * c * L, 2 * c * L**2], 1)
        ke[:, 2] = -ke[:, 0]
        ke[:, 3] = np.stack([6 * c * L, 2 * c * L**2, -6 * c * L, 4 * c * L**2], 1)
        self.K = self.banded(ke)
        self.K_abs = np.abs(self.K)
        self.zc = nodes - nodes.mean()
        # foundation at Gauss points of the elements that lie on the web
        self.on = sector_of_el >= 0
        self.Nq = np.stack([_hermite(np.full(ne, x), L) for x in _GP], axis=1)  # (ne, 3, 4)
        self.wq = 0.5 * L[:, None] * _GW[None, :] * self.on[:, None]  # (ne, 3)
        s = np.where(self.on, sector_of_el, 0)
        self.s = s
        self.aq, self.bq, self.gq = a[s][:, None], b[s][:, None], g[s][:, None]
        self.g = g

    def banded(self, blocks: FloatArray) -> FloatArray:
        ab = np.zeros((7, self.ndof))
        for i in range(4):
            for j in range(4):
                np.add.at(ab, (3 + i - j, self.dof[:, j]), blocks[:, i, j])
        return ab

    @staticmethod
    def matvec(ab: FloatArray, x: FloatArray) -> FloatArray:
        y = ab[3] * x
        for k in range(1, 4):
            y[:-k] += ab[3 - k, k:] * x[k:]
            y[k:] += ab[3 + k, :-k] * x[:-k]
        return y

    def bending(self, u: FloatArray) -> FloatArray:
        """u minus its rigid-body part (w = a + b z, theta = b), which K maps to zero exactly:
        K u is then computed without the round-off of the large rigid displacements."""
        zc = self.zc
        w = u[0::2]
        b = float(np.dot(zc, w - w.mean()) / np.dot(zc, zc))
        out = u.copy()
        out[0::2] -= w.mean() + b * zc
        out[1::2] -= b
        return out

    def beam_force(self, u: FloatArray) -> FloatArray:
        return self.matvec(self.K, self.bending(u))

    def foundation(self, u: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Nodal foundation forces, tangent stiffness and load at the Gauss points."""
        Nq, aq, bq, gq = self.Nq, self.aq, self.bq, self.gq
        w = np.einsum("eqk,ek->eq", Nq, u[self.dof])
        if self.bilateral:
            d = w - gq
            kq = np.broadcast_to(bq, d.shape)
            q = bq * d
        else:
            d = np.maximum(w - gq, 0.0)
            q = aq * d * d + bq * d
            kq = np.where(w > gq, 2 * aq * d + bq, 0.0)
        fint = np.zeros(self.ndof)
        np.add.at(fint, self.dof, np.einsum("eq,eqk->ek", self.wq * q, Nq))
        return fint, kq, q

    def newton(self, u: FloatArray, total: float) -> tuple[FloatArray, FloatArray, int]:
        """Newton with a backtracking line search on the residual, from ``u``: half the load
        at each bearing. Returns u, the Gauss-point loads and the iterations."""
        K, wq, Nq = self.K, self.wq, self.Nq
        F = np.zeros(self.ndof)
        F[0] = F[-2] = 0.5 * total
        fint, kq, q = self.foundation(u)
        R = self.beam_force(u) + fint - F
        tol = 1e-10 * total
        it = 0
        hist: list[float] = []
        for it in range(1, 61):  # noqa: B007
            Kt = K + self.banded(np.einsum("eq,eqk,eql->ekl", wq * kq, Nq, Nq))
            # tiny spring on every dof, relative to the foundation, against lift-off modes
            Kt[3] += 1e-9 * max(float(np.max(wq * kq)), 1e-300)
            du = solve_banded((3, 3), Kt, -R, check_finite=False)
            r0 = np.linalg.norm(R)
            # round-off floor of the residual: the beam terms K u cancel to ~eps |K| |u|
            floor = 1e-13 * float(np.linalg.norm(self.matvec(self.K_abs, np.abs(self.bending(u)))))
            # the foundation must carry the bearing forces (to the beam's round-off floor)
            balanced = abs(float(np.sum(fint[0::2])) - total) <= max(1e-8 * total, floor)
            hist.append(r0)
            # stagnation at a small residual: a very stiff roller (EI / L^3 >> foundation)
            # makes the Newton system ill-conditioned; accept once the foundation carries
            # the load
            stalled = it > 5 and r0 < 1e-4 * total and r0 > 0.5 * hist[-6]
            if balanced and (
                r0 < max(tol, floor) or np.linalg.norm(du) <= 1e-12 * np.linalg.norm(u) or stalled
            ):
                break
            step = 1.0
            for _ in range(30):
                u_try = u + step * du
                f_try, kq_try, q_try = self.foundation(u_try)
                R_try = self.beam_force(u_try) + f_try - F
                if np.linalg.norm(R_try) < r0 or step < 1e-6:
                    break
                step *= 0.5
            u, R, kq, q, fint = u_try, R_try, kq_try, q_try, f_try
        else:
            raise ConvergenceError(
                f"nip beam: Newton did not converge (residual "
                f"{np.linalg.norm(R) / total:.2e} of the load after 60 iterations)"
            )
        return u, q, it

    def solution(self, u: FloatArray, q: FloatArray, z_mid: FloatArray, it: int) -> NipSolution:
        """Per-sector mean load and centre indentation."""
        n, s, on, ne, L = self.n, self.s, self.on, self.ne, self.L
        width = np.diff(self.e)
        load = np.zeros(n)
        np.add.at(load, s[on], (self.wq * q)[on].sum(axis=1))
        load /= width
        w_mid = np.einsum("ek,ek->e", _hermite(np.zeros(ne), L)[:, :], u[self.dof])
        ind = np.zeros(n)
        cnt = np.zeros(n)
        np.add.at(ind, s[on], w_mid[on])
        np.add.at(cnt, s[on], 1.0)
        return NipSolution(
            z=z_mid,
            load=load,
            indentation=ind / cnt - self.g,
            node_z=self.nodes,
            deflection=u[0::2].copy(),
            total=float(np.sum(load * width)),
            iterations=it,
        )


def nip_hook(
    edges: ArrayLike, alpha: ArrayLike, beta: ArrayLike, roller: NipRoller
) -> Callable[[int, FloatArray, FloatArray], FloatArray]:
    """The winding model's nip callable: for each increment, the nip-load distribution of
    :func:`solve_nip` with the gap from the current outer-radius profile.

    The foundation laws (``alpha``, ``beta`` per sector) are fixed during winding (see
    docs/profile.md: they are evaluated once, on a preliminary roll).
    """
    e = np.asarray(edges, dtype=float)

    def hook(g: int, outer_radius: FloatArray, sigma_r_top: FloatArray) -> FloatArray:
        gap = float(np.max(outer_radius)) - np.asarray(outer_radius, dtype=float)
        return solve_nip(e, alpha, beta, roller, gap=gap).load

    return hook
