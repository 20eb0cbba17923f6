"""Indentation of a wound roll by a rigid cylindrical head: plane strain, hypoelastic, FE.

This is the "2D contact algorithm" the reference paper takes from its ref. [9] to obtain
the roll spring F(x_r) = alpha x_r^2 + beta x_r, {3}, and the semi-contact width ``a`` of
its effective-mass formula {14}-{18}. Ref. [9] is described only in outline; the model
here is built from mechanics (docs/contact.md lists every choice):

* the whole annulus between the core and the outer surface (meshed as the half
  0 <= theta <= pi with symmetry conditions), plane strain in the CMD
  (:mod:`woundroll.contact.plane_strain.fem` for the reduced orthotropic compliance);
* hypoelastic radial modulus: each depth increment uses the tangent E_r of the radial-modulus
  law at the element's current total radial stress (pre-impact stress from the winding model
  plus the contact increments so far), taken at the mid-step stress of a trial increment
  (or at the start of the step: forward Euler); ``update_modulus=False`` freezes E_r at its
  pre-impact value (the paper's Figure 8 "no update" comparison);
* frictionless contact with a rigid cylinder (head radius ``head_radius``, axis along the
  CMD), displacement controlled, by an exact linear complementarity solve per increment on
  the surface nodes (flexibility of the candidate nodes from the banded Cholesky factor);
* core: rigid (u = 0) or a radial Winkler spring of stiffness E_c / r_c per unit area with
  zero tangential displacement (Hakiel's axisymmetric core condition applied pointwise).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np
import scipy.linalg as la
from numpy.typing import NDArray

from woundroll.contact.plane_strain.fem import (
    ELEMENTS,
    Assembler,
    element_basis,
    plane_strain_moduli,
)
from woundroll.contact.plane_strain.mesh import RollMesh, build_mesh
from woundroll.contact.result import ContactResult
from woundroll.contact.stepping import (
    LoadHistory,
    depth_schedule,
    result_fields,
)
from woundroll.contact.stepping import check_profile as _check_profile
from woundroll.contact.stepping import check_scalar as _check_scalar
from woundroll.contact.stepping import half_width as _half_width
from woundroll.contact.stepping import solve_lcp as _solve_lcp
from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.web import INTERLAYER_FRICTION, SLIP_SHEAR_FRACTION, Core, Web
from woundroll.units import to_si
from woundroll.util.blas import one_blas_thread

FloatArray = NDArray[np.float64]
_S = TypeVar("_S", bound=Any)


@dataclass(frozen=True)
class ContactOptions:
    """Numerical settings of :func:`indent`; the defaults meet the project's 2 % mesh bar.

    Attributes
    ----------
    n_steps : int
        Number of depth increments up to ``depth_max`` [-].
    step_exponent : float
        Depths ``d_k = depth_max (k / n_steps)^step_exponent`` [-]: > 1 makes the first
        increments, where the modulus under the head changes fastest, smaller.
    surface_size : float or None
        Radial size of the outermost element ring [m]; None -> half the web thickness (two
        rings per outer layer: the edge of the contact, and so the semi-contact width ``a``
        of {14}-{18}, is decided by the surface ring; one ring per layer left ``a`` 11 % low,
        docs/contact.md, "Semi-contact width").
    radial_growth : float
        Ratio of neighbouring radial element sizes toward the core [-].
    tangential_size : float or None
        Arc length of the surface elements near the contact [m]; None -> the larger of
        ``surface_size / 4`` (the web thickness / 4 when ``surface_size`` is None) and
        ``a_geo / 40``, with ``a_geo = sqrt(2 R_eff depth_max)`` the
        half-chord of the head's geometric intersection with the undeformed roll at
        ``depth_max`` (1/R_eff = 1/head_radius + 1/R_out).
    fine_halfwidth : float or None
        Arc half-width of the uniform fine zone around the contact axis [m];
        None -> ``a_geo / 2`` (:data:`FINE_ZONE`; an orthotropic roll's contact is much
        narrower, at most 0.43 a_geo on the bundled rolls; a contact wider than the fine
        zone is still solved exactly, on the coarser elements).
    tangential_growth : float
        Ratio of neighbouring tangential element sizes away from the fine zone [-].
    max_element_angle : float or None
        Largest angle one element may span [rad]; None (default): no cap beyond what
        ``tangential_growth`` gives (about 0.41 rad at 1.15, 0.29 at 1.1). With the default
        locking-free element the far field needs no cap (docs/contact.md, mesh study); it
        is there to check that, and for the ``"flat"`` element without ``assumed_hoop``.
    element : {"curved", "flat"}
        ``"curved"`` (default): exact annular-sector bilinear element with polar strains;
        ``"flat"``: the straight-edged chord quadrilateral of earlier versions
        (:mod:`woundroll.contact.plane_strain.fem`).
    assumed_hoop : bool
        Hoop strain taken on each element's tangential mid-line (True, default): removes the
        membrane locking that made the far field of a hoop-stiff roll too stiff (docs).
    reduced_shear : bool
        One-point integration of the shear term (module :mod:`woundroll.contact.plane_strain.fem`).
    min_modulus_ratio : float
        Floor of E_r as a fraction of E_theta [-]: keeps a law with K1 = 0 (E_r = 0 at zero
        pressure, Table 3) from giving a singular stiffness.
    max_modulus_ratio : float or None
        Optional cap of E_r as a fraction of E_theta [-]. None (default) follows the law
        without limit, as the paper does; under the head the pressure reaches 10-100 MPa,
        far beyond the stack tests a Pfeiffer fit comes from (docs/contact.md).
    midpoint : bool
        The modulus of an increment at the mid-step stress (second order in the step).
        False: plain forward Euler (the start-of-step tangent modulus).
    predictor : bool
        With ``midpoint``: the mid-step stress predicted from the previous increment
        (scaled to this step's size), the increment solved once with the modulus there, and
        redone with the modulus at its own mid-step stress only when the two moduli differ
        by more than ``step_tol`` (one factorisation per step instead of two; docs/contact.md,
        step control). False: always a trial increment at the start-of-step modulus first.
    step_tol : float
        Tolerance of the predictor [-]: the relative difference of the predicted and the
        achieved mid-step E_r, weighted by each element's strain-energy increment.
    secant : bool
        With ``predictor`` (default True): an increment's E_r is the law's secant modulus
        over the element's radial stress change in the step, ``dP / deps(dP)`` with
        ``deps = integral dP / E_r(P)`` (exact for a uniaxial step of any size; for a law
        linear in pressure, Pfeiffer {2} with the floor and cap, in closed form) instead of the
        tangent at the mid-step stress. With K1 = 0 (Table 3) E_r grows exponentially in
        the strain from the floor, and the mid-step tangent then needs 100-200 steps for a
        reading within 0.5 % (docs/contact.md, step control). Laws not linear in pressure
        keep the mid-step tangent.
    half_model : bool
        Mesh the half 0 <= theta <= pi with symmetry conditions (u_theta = 0 on theta = 0,
        pi): exact for this symmetric problem, and its banded stiffness is solved by banded
        Cholesky. False: the whole annulus with a sparse LU (used to verify the symmetry).
    slip : {"none", "reduced-shear"}
        Slip emulation (the paper's Figure 19, docs/contact.md): an element whose
        interlayer shear reaches Coulomb's limit, |tau_r_theta| >= mu P (the slip factor
        {23} reaching 1, mu = ``friction``), keeps ``slip_shear_fraction`` of its G_r_theta
        for the rest of the loading. Within each increment the slip zone is iterated to
        consistency (same names as :class:`~woundroll.contact.solid3d.solver.Contact3DOptions`).
    slip_shear_fraction : float
        Fraction of G_r_theta left in a slipped element, in (0, 1] (1: no change).
    slip_max_passes : int
        Passes of the slip-zone iteration per increment before ConvergenceError.
    shear_ratio : float or None
        Other explanations of the readings (issue 25, docs/contact.md "Other explanations"):
        G_r_theta = ``shear_ratio`` x E_r in every element instead of the web's rule (its
        set G_r_theta, or 2 E_r, Table 2) [-]; None: the web's rule.
    shear_frozen : bool
        G_r_theta of each element kept at its pre-impact value (the rule at E_r of the
        wound-in stress) while E_r stiffens under the head; False: G follows E_r.
    """

    n_steps: int = 16
    surface_size: float | None = None
    radial_growth: float = 1.25
    tangential_size: float | None = None
    fine_halfwidth: float | None = None
    tangential_growth: float = 1.15
    max_element_angle: float | None = None
    element: str = "curved"
    assumed_hoop: bool = True
    reduced_shear: bool = True
    min_modulus_ratio: float = 1e-6
    max_modulus_ratio: float | None = None
    midpoint: bool = True
    predictor: bool = True
    step_tol: float = 0.002
    secant: bool = True
    newton: bool = True
    half_model: bool = True
    step_exponent: float = 1.5
    slip: str = "none"
    slip_shear_fraction: float = SLIP_SHEAR_FRACTION
    slip_max_passes: int = 50
    shear_ratio: float | None = None
    shear_frozen: bool = False

    def __post_init__(self) -> None:
        _check_slip_options(self)
        _check_shear_options(self)
        if self.element not in ELEMENTS:
            raise InputError(
                f"must be one of {', '.join(ELEMENTS)}, got {self.element!r}", "options.element"
            )
        if self.max_element_angle is not None and not (
            isinstance(self.max_element_angle, int | float | np.number)
            and not isinstance(self.max_element_angle, bool)
            and 0 < self.max_element_angle <= math.pi / 2
        ):
            raise InputError(
                f"must lie in (0, pi/2] rad, got {self.max_element_angle!r}",
                "options.max_element_angle",
            )
        if not (
            isinstance(self.step_tol, int | float | np.number)
            and math.isfinite(self.step_tol)
            and 0 < self.step_tol <= 1
        ):
            raise InputError(f"must lie in (0, 1], got {self.step_tol!r}", "options.step_tol")
        for name in (
            "reduced_shear",
            "assumed_hoop",
            "midpoint",
            "predictor",
            "secant",
            "newton",
            "half_model",
        ):
            if not isinstance(getattr(self, name), bool | np.bool_):
                raise InputError(
                    f"must be true or false, got {getattr(self, name)!r}", f"options.{name}"
                )
        if not (math.isfinite(self.step_exponent) and 1.0 <= self.step_exponent <= 3.0):
            raise InputError(
                f"must lie in [1, 3], got {self.step_exponent!r}", "options.step_exponent"
            )
        if (
            not isinstance(self.n_steps, int | np.integer)
            or isinstance(self.n_steps, bool)
            or self.n_steps < 1
        ):
            raise InputError(f"must be a positive integer, got {self.n_steps!r}", "options.n_steps")
        for name in ("surface_size", "tangential_size", "fine_halfwidth"):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise InputError(f"must be a positive length, got {v!r}", f"options.{name}")
        for name in ("radial_growth", "tangential_growth"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 1.0 <= v <= 3.0):
                raise InputError(f"must lie in [1, 3], got {v!r}", f"options.{name}")
        if self.max_modulus_ratio is not None and not (
            math.isfinite(self.max_modulus_ratio)
            and self.min_modulus_ratio < self.max_modulus_ratio <= 10.0
        ):
            raise InputError(
                f"must lie in (min_modulus_ratio, 10], got {self.max_modulus_ratio!r}",
                "options.max_modulus_ratio",
            )
        if not (math.isfinite(self.min_modulus_ratio) and 0 < self.min_modulus_ratio < 1):
            raise InputError(
                f"must lie in (0, 1), got {self.min_modulus_ratio!r}", "options.min_modulus_ratio"
            )


SLIP_MODES = ("none", "reduced-shear")
#: The slip-zone iteration has settled when no element's slipping share of the increment
#: grows by more than this.
SLIP_TOL = 0.05


def _check_shear_options(opts: Any) -> None:
    """The other explanations' shear options (``shear_ratio``, ``shear_frozen``)."""
    q = opts.shear_ratio
    if q is not None and not (
        isinstance(q, int | float | np.number)
        and not isinstance(q, bool)
        and math.isfinite(q)
        and q > 0
    ):
        raise InputError(f"must be a positive number, got {q!r}", "options.shear_ratio")
    if not isinstance(opts.shear_frozen, bool | np.bool_):
        raise InputError(
            f"must be true or false, got {opts.shear_frozen!r}", "options.shear_frozen"
        )


def _check_slip_options(opts: Any) -> None:
    """The slip emulation's options (shared with the 3D options: one spelling)."""
    if opts.slip not in SLIP_MODES:
        raise InputError(f"must be 'none' or 'reduced-shear', got {opts.slip!r}", "options.slip")
    f = opts.slip_shear_fraction
    if not (
        isinstance(f, int | float | np.number)
        and not isinstance(f, bool)
        and math.isfinite(f)
        and 0 < f <= 1
    ):
        raise InputError(f"must lie in (0, 1], got {f!r}", "options.slip_shear_fraction")
    n = getattr(opts, "slip_max_passes", 1)
    if not isinstance(n, int | np.integer) or isinstance(n, bool) or n < 1:
        raise InputError(f"must be a positive integer, got {n!r}", "options.slip_max_passes")


def _gap(pos: FloatArray, centre: FloatArray, head_radius: float) -> tuple[FloatArray, FloatArray]:
    """Signed gap [m] of points ``pos`` (n, 2) to the head circle and the unit normals (n, 2)
    pointing from the head axis to the points."""
    d = pos - centre
    dist = np.hypot(d[:, 0], d[:, 1])
    return dist - head_radius, d / dist[:, None]


class _Roll:
    """Mesh, element data, boundary conditions and pre-impact state of one roll section."""

    def __init__(
        self,
        web: Web,
        core: Core,
        radius: FloatArray,
        sigma_r: FloatArray,
        mesh: RollMesh,
        opts: ContactOptions,
    ) -> None:
        self.web = web
        self.mesh = mesh
        self.basis = element_basis(
            mesh,
            element=opts.element,
            reduced_shear=opts.reduced_shear,
            assumed_hoop=opts.assumed_hoop,
        )
        n_dof = 2 * mesh.n_nodes
        free = np.ones(n_dof, dtype=bool)
        core_nodes = mesh.core_nodes()
        free[2 * core_nodes + 1] = False  # no tangential slip on the core
        free[2 * mesh.edge_nodes() + 1] = False  # symmetry lines of the half model
        diagonal = None
        if core.rigid:
            free[2 * core_nodes] = False
        else:
            # Winkler spring E_c / r_c per unit area, lumped on the tributary arc r_c dtheta
            th = mesh.theta
            if mesh.periodic:
                dth = np.diff(np.concatenate([th, [th[0] + 2 * math.pi]]))
                trib = 0.5 * (dth + np.roll(dth, 1))
            else:
                dth = np.diff(th)
                trib = 0.5 * (np.concatenate([[0.0], dth]) + np.concatenate([dth, [0.0]]))
            diagonal = np.zeros(n_dof)
            diagonal[2 * core_nodes] = core.stiffness * trib
        self.free = free
        self.assembler = Assembler(self.basis, free, diagonal)
        self.xy = mesh.node_xy()
        self.angle = mesh.node_angle()
        self.surface = mesh.surface_nodes()
        self.area = self.basis.area
        r_c = np.hypot(self.basis.centre_xy[:, 0], self.basis.centre_xy[:, 1])
        self.r_centre = r_c
        #: pre-impact radial stress at element centres [Pa] (winding model, interpolated)
        self.sigma_pre = np.interp(r_c, radius, sigma_r)
        self.E_floor = opts.min_modulus_ratio * web.E_theta
        self.E_cap = (
            math.inf if opts.max_modulus_ratio is None else opts.max_modulus_ratio * web.E_theta
        )
        #: slip emulation (None: off): per element the share of the current increment
        #: it spends slipped (1: slipped since an earlier increment, 0: sticking)
        self.slip_weight: FloatArray | None = None
        self.slip_fraction = float(getattr(opts, "slip_shear_fraction", 1.0))
        #: other explanations (issue 25): G_r_theta = ratio x E_r (None: the web's rule),
        #: and G_r_theta frozen at the pre-impact E_r (None: G follows E_r)
        self.shear_ratio: float | None = getattr(opts, "shear_ratio", None)
        self.G_pre: FloatArray | None = None
        if getattr(opts, "shear_frozen", False):
            self.G_pre = self._shear(self.radial_modulus(self.sigma_pre))
        #: (E0, slope) of a law linear in pressure, for the secant modulus (None: the
        #: mid-step tangent)
        lin = getattr(getattr(web, "radial_modulus", None), "linear_in_pressure", lambda: None)()
        use = bool(getattr(opts, "secant", False))
        self.linear_law: tuple[float, float] | None = (
            (float(lin[0]), float(lin[1])) if use and lin is not None else None
        )
        #: the last increment's contact geometry (:class:`_ContactGeometry`)
        self._contact_geometry: Any = None
        #: ``(start, eps(start))`` of the last :meth:`secant_modulus` (``start`` kept
        #: alive, so ``is`` recognises it)
        self._start_strain: tuple[FloatArray, FloatArray] | None = None

    def radial_modulus(self, sigma_r_total: FloatArray) -> FloatArray:
        """E_r [Pa] of the elements at total radial stress ``sigma_r_total`` (law {2},
        floored and capped as the options say)."""
        return np.clip(self.web.E_r(sigma_r_total), self.E_floor, self.E_cap)

    def secant_modulus(self, start: FloatArray, end: FloatArray) -> FloatArray:
        """Secant E_r [Pa] of the elements between total radial stresses ``start`` and
        ``end``: ``(P1 - P0) / (eps(P1) - eps(P0))`` with ``eps(P) = integral_0^P dP / E_r``
        for E_r = clip(E0 + b P, floor, cap) (pressure clipped at 0 as the law does), so that a
        uniaxial step at it lands on the law {2} exactly whatever its size.
        Needs :attr:`linear_law`."""
        assert self.linear_law is not None
        e0, b = self.linear_law
        p0, p1 = -start, -end
        dp = p1 - p0
        # the passes of an increment share its start (the same array): its strain once
        last = self._start_strain
        if last is not None and last[0] is start:
            eps0 = last[1]
        else:
            eps0 = self._strain_of_pressure(p0, e0, b)
            self._start_strain = (start, eps0)
        eps = self._strain_of_pressure(p1, e0, b) - eps0
        small = np.abs(dp) <= 1e-9 * (np.abs(p0) + np.abs(p1) + 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            sec = np.where(small, 1.0, dp / np.where(small, 1.0, eps))
        return np.where(small, self.radial_modulus(-0.5 * (p0 + p1)), sec)

    def _strain_of_pressure(self, p: FloatArray, e0: float, b: float) -> FloatArray:
        """``integral_0^P dP / E_r(P)`` for E_r = clip(E0 + b max(P, 0), floor, cap)."""
        f, cap = self.E_floor, self.E_cap
        E_zero = min(max(e0, f), cap)
        neg = np.minimum(p, 0.0) / E_zero  # tension side: E_r(0)
        q = np.maximum(p, 0.0)
        if b <= 0 or e0 >= cap:
            return neg + q / E_zero
        p_f = max((f - e0) / b, 0.0)  # end of the floored range
        p_c = (cap - e0) / b if math.isfinite(cap) else math.inf  # start of the capped one
        floored = np.minimum(q, p_f) / f if p_f > 0 else np.zeros_like(q)
        E_f = e0 + b * p_f
        law = np.log((e0 + b * np.clip(q, p_f, p_c)) / E_f) / b
        capped = np.maximum(q - p_c, 0.0) / cap if math.isfinite(p_c) else 0.0
        return neg + floored + law + capped

    def moduli(self, sigma_r_total: FloatArray) -> tuple[FloatArray, ...]:
        return self.moduli_at(self.radial_modulus(sigma_r_total))

    def moduli_at(self, E_r: FloatArray) -> tuple[FloatArray, ...]:
        """Plane-strain moduli of the elements at per-element radial modulus ``E_r``."""
        C11, C12, C22, G = plane_strain_moduli(self.web, E_r)
        if self.G_pre is not None:
            G = self.G_pre
        elif self.shear_ratio is not None:
            G = self.shear_ratio * np.asarray(E_r, dtype=float)
        if self.slip_weight is not None and np.any(self.slip_weight > 0):
            # slip emulation (Figure 19): a slipped element keeps a fraction of G_r_theta
            G = G * self.shear_factor()
        return C11, C12, C22, G

    def _shear(self, E_r: FloatArray) -> FloatArray:
        """G_r_theta [Pa] of the elements at radial modulus ``E_r`` by the shear rule
        (``shear_ratio`` x E_r, or the web's)."""
        if self.shear_ratio is not None:
            return self.shear_ratio * np.asarray(E_r, dtype=float)
        return plane_strain_moduli(self.web, E_r)[3]

    def shear_factor(self) -> FloatArray:
        """G_r_theta used / G_r_theta of the law, per element (slip emulation)."""
        assert self.slip_weight is not None
        return 1.0 - self.slip_weight * (1.0 - self.slip_fraction)

    def cartesian(self, u: FloatArray, nodes: NDArray[np.int64]) -> FloatArray:
        """Cartesian displacement (n, 2) of ``nodes`` from the polar nodal DOFs ``u``."""
        ur, ut = u[2 * nodes], u[2 * nodes + 1]
        c, s = np.cos(self.angle[nodes]), np.sin(self.angle[nodes])
        return np.stack([c * ur - s * ut, s * ur + c * ut], axis=1)

    def polar(self, vec: FloatArray, nodes: NDArray[np.int64]) -> tuple[FloatArray, FloatArray]:
        """Polar components at ``nodes`` of Cartesian vectors ``vec`` (n, 2)."""
        c, s = np.cos(self.angle[nodes]), np.sin(self.angle[nodes])
        return c * vec[:, 0] + s * vec[:, 1], -s * vec[:, 0] + c * vec[:, 1]

    def strain_increment(self, du: FloatArray) -> FloatArray:
        """Strain increments ``(eps_r, eps_theta, gamma_r_theta)`` at the element centres."""
        return np.einsum("eij,ej->ei", self.basis.B_centre, du[self.basis.dofs])

    def stress_increment(self, moduli: tuple[FloatArray, ...], du: FloatArray) -> FloatArray:
        """Stress increments ``(sigma_r, sigma_theta, tau_r_theta)`` [Pa] at the element
        centres for the displacement increment ``du`` at per-element ``moduli``."""
        return self.stress_of_strain(moduli, self.strain_increment(du))

    @staticmethod
    def stress_of_strain(moduli: tuple[FloatArray, ...], e: FloatArray) -> FloatArray:
        """Stress increments (n_el, 3) [Pa] of centre strain increments ``e`` (n_el, 3)."""
        C11, C12, C22, G = moduli
        return np.stack(
            [C11 * e[:, 0] + C12 * e[:, 1], C12 * e[:, 0] + C22 * e[:, 1], G * e[:, 2]], axis=1
        )


@dataclass
class _Step:
    du: FloatArray
    dsig: FloatArray
    lam: FloatArray  # total contact force magnitude per surface node [N/m]
    normal: FloatArray  # unit normals (n_surf, 2) the forces act along
    gap: FloatArray  # gaps of the surface nodes after the step [m]


class _Factor:
    """A factorised stiffness: banded Cholesky (half model) or sparse LU (whole annulus).

    The banded factor is of K in the reversed DOF order: the contact axis (tangential index
    0, the first nodes of the mesh's numbering) comes last, so the flexibility of the contact
    candidates needs the forward substitution over the trailing rows only
    (:meth:`flexibility`), a few percent of a full multi-column solve.
    """

    def __init__(self, banded: FloatArray | None = None, lu: Any = None) -> None:
        self._cb = banded
        self._lu = lu
        #: the last ``(B, Y, G)`` of :meth:`flexibility` (banded): a modified-Newton pass
        #: on this factor asks again for the same contact columns
        self._flex: tuple[FloatArray, FloatArray, FloatArray] | None = None

    def solve(self, b: FloatArray) -> FloatArray:
        if self._cb is not None:
            x = la.cho_solve_banded((self._cb, True), b[::-1], check_finite=False)
            return x[::-1]
        assert self._lu is not None
        return self._lu.solve(b)

    def forward(self, b: FloatArray) -> FloatArray:
        """The first half of the solve of a load ``b`` spread over all the unknowns, for
        :meth:`flexibility`'s ``pre``: banded, ``L^-1 b`` in the reversed order (forward
        substitution); sparse LU, the whole solution."""
        if self._cb is None:
            assert self._lu is not None
            return self._lu.solve(b)
        y, info = _dtbtrs(self._cb, b[::-1], uplo="L", trans="N", diag="N")
        if info != 0:
            raise ConvergenceError(f"banded triangular solve failed (LAPACK info {info})")
        return y

    def flexibility(
        self, rows: NDArray[np.int64], B: FloatArray, n: int, pre: FloatArray | None = None
    ) -> tuple[FloatArray, FloatArray | None, Callable[[FloatArray], FloatArray]]:
        """``G = B^T K^-1 B`` for a right-hand side whose leading rows are ``B`` (top, m),
        zero below them and outside ``rows`` (n the number of unknowns); with ``pre``
        (:meth:`forward` of a further load ``e``) also ``B^T K^-1 e``; and a function giving
        ``K^-1 (B c + e)`` for coefficients ``c`` (m,).

        Banded: with ``K = L L^T`` (reversed order) ``Y = L^-1 B`` lives on the trailing
        rows only, ``G = Y^T Y``, ``B^T K^-1 e = Y^T (L^-1 e)`` and the displacement is one
        backward substitution of ``Y c + L^-1 e``: one triangular solve per pass on top of
        the factorisation, where solving the load and the contact separately took two full
        solves."""
        top = B.shape[0]
        if self._cb is None:
            b = np.zeros((n, B.shape[1]))
            b[:top] = B
            X = self.solve(b)
            if pre is None:
                return B[rows].T @ X[rows], None, lambda c: X @ c
            return B[rows].T @ X[rows], B[rows].T @ pre[rows], lambda c: X @ c + pre
        # the leading rows are the trailing ones of the reversed order
        last = self._flex
        if last is not None and (last[0] is B or np.array_equal(last[0], B)):
            Y, G = last[1], last[2]  # the same columns on the same factor: the same numbers
        else:
            Br = np.asfortranarray(B[::-1])
            ab = np.asfortranarray(self._cb[:, n - top :])
            Y, info = _dtbtrs(ab, Br, uplo="L", trans="N", diag="N")
            if info != 0:
                raise ConvergenceError(f"banded triangular solve failed (LAPACK info {info})")
            G = Y.T @ Y
            Y.flags.writeable = G.flags.writeable = False  # shared by the passes
            self._flex = (B, Y, G)
        cb = self._cb

        def solve_for(c: FloatArray) -> FloatArray:
            v = np.zeros(n) if pre is None else pre.copy()
            v[n - top :] += Y @ c
            x, info = _dtbtrs(cb, v, uplo="L", trans="T", diag="N")
            if info != 0:
                raise ConvergenceError(f"banded triangular solve failed (LAPACK info {info})")
            return x[::-1]

        return G, (None if pre is None else Y.T @ pre[n - top :]), solve_for


def _dtbtrs(*args: Any, **kw: Any) -> tuple[FloatArray, int]:
    from scipy.linalg.lapack import dtbtrs

    return dtbtrs(*args, **kw)


def _factorize(roll: _Roll, moduli: tuple[FloatArray, ...]) -> _Factor:
    """Assemble K for per-element ``(C11, C12, C22, G)`` [Pa] and factorise it."""
    asm = roll.assembler
    if not roll.mesh.periodic:
        ab = asm.band(*moduli, reverse=True)
        from scipy.linalg.lapack import dpbtrf

        cb, info = dpbtrf(ab, lower=1, overwrite_ab=1)
        if info != 0:
            raise ConvergenceError("stiffness matrix is not positive definite")
        return _Factor(banded=cb)
    import scipy.sparse.linalg as spla

    try:
        lu = spla.splu(asm.csc(asm.values(*moduli)), permc_spec="MMD_AT_PLUS_A")
    except RuntimeError as exc:
        raise ConvergenceError(f"stiffness matrix is singular ({exc})") from None
    return _Factor(lu=lu)


class _ContactGeometry:
    """What :func:`_step` derives from the start of an increment (displacements ``u``,
    contact forces ``f_contact`` and ``lam_old``, head centre): the surface nodes'
    positions, predicted gaps and normals, the first candidates, the release load, and the
    right-hand sides of each candidate set. The passes of one increment share them (the
    last one is kept on the roll, recognised by equal inputs): the same numbers, built
    once."""

    def __init__(
        self,
        roll: _Roll,
        u: FloatArray,
        f_contact: FloatArray,
        lam_old: FloatArray,
        centre: FloatArray,
        head_radius: float,
    ) -> None:
        self.roll = roll
        self.key = (u.copy(), f_contact.copy(), lam_old.copy(), np.array(centre), head_radius)
        surf = roll.surface
        self.pos = roll.xy[surf] + roll.cartesian(u, surf)
        self.g_pred, self.normal = _gap(self.pos, centre, head_radius)
        self.cand = (self.g_pred < 0) | (lam_old > 0)
        # the old contact forces are released and re-applied along the current normals
        self.release = -f_contact[roll.assembler.free_dofs]
        self.released = np.flatnonzero(self.release)
        self._columns: dict[bytes, tuple[NDArray[np.int64], NDArray[np.int64], FloatArray]] = {}

    @classmethod
    def of(
        cls,
        roll: _Roll,
        u: FloatArray,
        f_contact: FloatArray,
        lam_old: FloatArray,
        centre: FloatArray,
        head_radius: float,
    ) -> _ContactGeometry:
        """The geometry of these inputs: the roll's last one if they are equal."""
        last = getattr(roll, "_contact_geometry", None)
        if last is not None:
            ku, kf, kl, kc, kh = last.key
            if (
                kh == head_radius
                and np.array_equal(kc, centre)
                and np.array_equal(kl, lam_old)
                and np.array_equal(ku, u)
                and np.array_equal(kf, f_contact)
            ):
                return last
        geo = cls(roll, u, f_contact, lam_old, centre, head_radius)
        roll._contact_geometry = geo
        return geo

    def columns(
        self, cand: NDArray[np.bool_]
    ) -> tuple[NDArray[np.int64], NDArray[np.int64], FloatArray]:
        """The candidate set ``cand`` widened by two nodes each side (``idx``), the unknowns
        its loads touch (``rows``) and the right-hand sides: a unit load along each
        candidate's normal, and the release load last."""
        key = cand.tobytes()
        got = self._columns.get(key)
        if got is not None:
            return got
        roll = self.roll
        fi = roll.assembler.free_index
        surf = roll.surface
        band = np.flatnonzero(cand)
        idx = np.unique(
            np.clip(np.concatenate([band + k for k in (-2, -1, 0, 1, 2)]), 0, surf.size - 1)
        )
        nodes = surf[idx]
        n_r, n_t = roll.polar(self.normal[idx], nodes)
        m = idx.size
        rows_r, rows_t = fi[2 * nodes], fi[2 * nodes + 1]
        # a node on the symmetry line has no tangential DOF (free index -1; its normal is
        # radial there)
        t_ok = rows_t >= 0
        # the release forces sit on nodes in contact before, all among the candidates
        rows = np.unique(np.concatenate([rows_r, rows_t[t_ok], self.released]))
        # the right-hand sides touch the leading rows only (the contact axis's nodes come
        # first in the mesh's numbering)
        rhs = np.zeros((int(rows.max()) + 1, m + 1))
        rhs[rows_r, np.arange(m)] = n_r
        rhs[rows_t[t_ok], np.arange(m)[t_ok]] = n_t[t_ok]
        rhs[:, m] = self.release[: rhs.shape[0]]
        rhs.flags.writeable = False  # shared by the passes (and the factor's cache)
        self._columns[key] = got = (idx, rows, rhs)
        return got


def _step(
    roll: _Roll,
    moduli: tuple[FloatArray, ...],
    lu: _Factor,
    u: FloatArray,
    f_contact: FloatArray,
    lam_old: FloatArray,
    centre: FloatArray,
    head_radius: float,
    tol_gap: float,
    extra: FloatArray | None = None,
) -> _Step:
    """One depth increment at fixed moduli (``lu`` their factorised stiffness): candidate
    flexibility and exact LCP. ``extra`` (free DOFs, optional): a further load on the
    roll, the modified-Newton correction of :func:`_newton_increment` (``moduli`` are then
    those of ``lu``, and the returned ``dsig`` is empty: the caller computes it at its own
    moduli)."""
    pre = lu.forward(extra) if extra is not None else None
    geo = _ContactGeometry.of(roll, u, f_contact, lam_old, centre, head_radius)
    surf, pos, g_pred, normal = roll.surface, geo.pos, geo.g_pred, geo.normal
    cand = geo.cand.copy()
    n_free = roll.assembler.n_free
    for _ in range(8):
        idx, rows, rhs = geo.columns(cand)
        m = idx.size
        G, gq, solve_for = lu.flexibility(rows, rhs, n_free, pre)
        W, q = G[:m, :m], g_pred[idx] + G[:m, m]
        if gq is not None:  # the extra load's displacement along the normals
            q = q + gq[:m]
        lam_c = _solve_lcp(W, q, start=lam_old[idx] > 0)
        du_free = solve_for(np.append(lam_c, 1.0))
        du = np.zeros(u.size)
        du[roll.assembler.free_dofs] = du_free
        gap, _ = _gap(pos + roll.cartesian(du, surf), centre, head_radius)
        outside = np.ones(surf.size, dtype=bool)
        outside[idx] = False
        bad = outside & (gap < -tol_gap)
        if not np.any(bad):
            lam = np.zeros(surf.size)
            lam[idx] = lam_c
            # a modified-Newton pass's stresses are the caller's (at its own moduli)
            dsig = roll.stress_increment(moduli, du) if extra is None else np.empty((0, 3))
            return _Step(du=du, dsig=dsig, lam=lam, normal=normal, gap=gap)
        cand |= bad
    raise ConvergenceError(
        "contact set did not settle in 8 enlargements of the candidate "
        "nodes; refine options.tangential_size or use more n_steps"
    )


def _hypoelastic_increment(
    roll: _Roll,
    sigma_r: FloatArray,
    midpoint: bool,
    solve: Callable[[tuple[FloatArray, ...], _Factor], _S],
) -> _S:
    """One load increment with the hypoelastic radial modulus (Pfeiffer {2} or the web's law).

    ``solve(moduli, factor)`` solves the increment at fixed per-element moduli and returns an
    object with the stress increments ``dsig`` (n_el, 3). Forward Euler (``midpoint=False``):
    the moduli at the start-of-step total radial stress ``sigma_pre + sigma_r``. Midpoint: a
    trial increment at those moduli gives the mid-step stress
    ``sigma_pre + sigma_r + dsig_r / 2``, and the increment is solved again at the moduli
    there (second order in the step for a smooth law).

    Parameters
    ----------
    roll : _Roll
    sigma_r : ndarray
        Contact-induced radial stress so far [Pa] (the pre-impact part is ``roll.sigma_pre``).
    midpoint : bool
    solve : callable
    """
    mod = roll.moduli(roll.sigma_pre + sigma_r)
    if midpoint:
        trial = solve(mod, _factorize(roll, mod))
        mod = roll.moduli(roll.sigma_pre + sigma_r + 0.5 * trial.dsig[:, 0])
    return solve(mod, _factorize(roll, mod))


def _predicted_increment(
    roll: _Roll,
    sigma_r: FloatArray,
    predicted: FloatArray | None,
    tol: float,
    solve: Callable[[tuple[FloatArray, ...], _Factor], _S],
) -> tuple[_S, int]:
    """One load increment at the modulus of a predicted mid-step stress, with error control.

    The increment is solved at E_r of ``sigma_pre + predicted`` (the mid-step radial stress
    extrapolated from the previous increment; None: the start-of-step stress). Its own
    mid-step stress ``sigma_r + dsig_r / 2`` gives E_r again; where the two differ by more
    than ``tol`` (relative, averaged over the elements with their strain-energy increments as
    weights) the increment is redone at the achieved mid-step stress, at most three times.
    A converged pass is the implicit midpoint rule; the prediction makes the first pass
    enough in most steps, so a step costs one factorisation instead of the two of the
    explicit midpoint scheme (:func:`_hypoelastic_increment`).

    With ``roll.linear_law`` (the default for Pfeiffer {2} and constant laws) the
    modulus of a pass is instead the law's secant over the step, from the start-of-step
    stress to the end ``2 target - sigma_r`` (:meth:`_Roll.secant_modulus`), compared with
    the secant over the achieved increment: a converged pass then integrates the law
    exactly for a uniaxial step of any size, which the mid-step tangent does not where E_r
    grows from its floor (K1 = 0). The caller predicts the end-of-step stress by the
    parabola through the last three states.

    Returns the step and the number of factorisations it took.
    """
    target = sigma_r if predicted is None else predicted
    pre = roll.sigma_pre
    for n in range(1, 5):
        if roll.linear_law is not None:
            # the secant over the step: from the start to the end 2 target - start
            E_used = roll.secant_modulus(pre + sigma_r, pre + 2.0 * target - sigma_r)
        else:
            E_used = roll.radial_modulus(pre + target)
        mod = roll.moduli_at(E_used)
        step = solve(mod, _factorize(roll, mod))
        mid = sigma_r + 0.5 * step.dsig[:, 0]
        if roll.linear_law is not None:
            E_mid = roll.secant_modulus(pre + sigma_r, pre + sigma_r + step.dsig[:, 0])
        else:
            E_mid = roll.radial_modulus(pre + mid)
        w = np.abs(np.sum(step.dsig * roll.strain_increment(step.du), axis=1)) * roll.area
        total = float(np.sum(w))
        err = float(np.sum(w * np.abs(E_used / E_mid - 1.0))) / total if total > 0 else 0.0
        if err <= tol:
            return step, n
        target = mid
    return step, n


#: Passes of one increment on one factorised stiffness before it is factorised again at the
#: current moduli (:func:`_newton_increment`) ...
NEWTON_ITERATIONS = 10
#: ... or sooner, where an element's modulus has moved further than this (relative) from
#: the factorised one (beyond twice K0 a modified-Newton pass no longer contracts surely;
#: a growing mismatch re-factorises too). 1.0 and 10 passes (were 0.5 and 6): 1,493 ->
#: 1,262 factorisations on the 61 Table 3 sectors for 2,876 -> 3,021 passes, 5 % less CPU,
#: the same readings within 0.03 % (docs/contact.md, "Session 12").
NEWTON_REACH = 1.0

#: Default half-width of the uniform fine zone around the contact axis, as a fraction of
#: ``a_geo``, the half-chord of the head's geometric intersection with the undeformed roll
#: at ``depth_max`` (:class:`ContactOptions`, ``fine_halfwidth``). The hoop-stiff rolls'
#: contact is far narrower than a_geo: at the deepest depth solved (the loading may extend
#: past ``depth_max``; the mesh is sized there) at most 0.14 a_geo on the 61 Table 3
#: sectors, 0.15 on the PET1 and 0.43 on the PET2 rolls of Table 2 (at 2.1-2.8 mm). Was 1.0
#: until session 12, a zone of equal elements up to ten times wider than the contact
#: (docs/contact.md, "Session 12").
FINE_ZONE = 0.5
#: Depth of the Anderson mixing of the passes' moduli (0: plain fixed-point passes).
ANDERSON = 3
#: Where an increment's moduli do not settle (a very hard roll whose E_r under the head
#: grows several-fold in one of the default increments: contact.md assumption 2b's roll,
#: K2 = 2000 with nu_z_r = 0.3), the loading is solved again from the start with twice the
#: increments, at most this many times (16 -> 32 -> 64; the curve's depths are then the
#: finer schedule's). 32 and 64 increments read that roll 762.5 and 761.8 Rho (FD, beyond
#: the dial's 100), tests/contact/test_contact.py.
STEP_RETRIES = 2


class _ModuliNotSettled(ConvergenceError):
    """An increment's moduli did not settle (:func:`_newton_increment`): more, smaller
    increments help, unlike a contact set or a stiffness that fails."""


def _newton_increment(
    roll: _Roll,
    sigma_r: FloatArray,
    predicted: FloatArray | None,
    tol: float,
    solve: Callable[..., _Step],
) -> tuple[_Step, int]:
    """One load increment with the secant modulus of the law {2}, its passes on one
    factorisation.

    The fixed point is that of :func:`_predicted_increment`: a pass solves the increment at
    moduli E_used, its radial stress change gives the law's secant E_mid over the step
    (:meth:`_Roll.secant_modulus`), and the increment is accepted when the two agree within
    ``tol`` (relative, weighted by the elements' strain-energy increments). Three things
    make a pass cheaper than that function's re-solve at the new moduli:

    * **Modified Newton.** A pass after the first does not factorise K(E_used): it takes
      one step on the stiffness K0 already factorised,
      ``K0 du = contact + (K0 - K(E_used)) du_prev`` (the contact by the exact LCP each
      time; :meth:`Assembler.matvec` forms the out-of-balance load), two triangular solves
      instead of an assembly and a factorisation. An increment is then accepted only once
      two passes' displacements also agree within ``tol`` (the pass converged to the
      solution at E_used). K0 is factorised again at the current moduli after
      :data:`NEWTON_ITERATIONS` passes, when the mismatch grew, or when an element's
      modulus moved by more than :data:`NEWTON_REACH` from K0's (a pass contracts only
      while K(E_used) < 2 K0).
    * **Anderson mixing** of the moduli in log E (depth :data:`ANDERSON`, least squares
      weighted by the strain-energy increments): where E_r grows from its floor (K1 = 0,
      Table 3) the plain passes converged linearly at a rate 0.5-0.7 in the first
      increments; mixing needs about half the passes there.
    * the first pass at the predicted secant (the caller's parabolic predictor), as before.

    Returns the step and the number of factorisations it took.
    """
    pre = roll.sigma_pre
    start = pre + sigma_r
    target = sigma_r if predicted is None else predicted
    E_used = roll.secant_modulus(start, pre + 2.0 * target - sigma_r)
    E_0 = E_used
    mod0 = mod_used = roll.moduli_at(E_used)
    lu0 = _factorize(roll, mod0)
    n_fact = 1
    step = solve(mod0, lu0)
    exact = True  # the last solve was at the moduli it was factorised at
    du_prev: FloatArray | None = None
    err_prev = math.inf
    since = 0  # passes on the current factor
    hist_x: list[FloatArray] = []  # log E_used of the passes
    hist_f: list[FloatArray] = []  # log E_mid - log E_used
    for _ in range(8 * NEWTON_ITERATIONS):
        # an exact pass was solved at mod_used and _step already has its stresses
        dsig, E_mid, w, total, err = _secant_mismatch(roll, step, mod_used, exact, start, E_used)
        if du_prev is not None:
            scale = max(float(np.max(np.abs(step.du))), 1e-300)
            err = max(err, float(np.max(np.abs(step.du - du_prev))) / scale)
        if err <= tol and (exact or du_prev is not None):
            step.dsig = dsig
            return step, n_fact
        since += 1
        x_new = _mixed_log_modulus(hist_x, hist_f, E_used, E_mid, w, total)
        E_used = np.clip(np.exp(x_new), roll.E_floor, roll.E_cap)
        mod_used = roll.moduli_at(E_used)
        if (
            since >= NEWTON_ITERATIONS
            or err > err_prev
            or float(np.max(np.abs(E_used / E_0 - 1.0))) > NEWTON_REACH
        ):
            E_0, mod0 = E_used, mod_used
            lu0 = _factorize(roll, mod0)
            n_fact += 1
            since, err_prev, du_prev = 0, math.inf, None
            step = solve(mod0, lu0)
            exact = True
            continue
        err_prev, du_prev = err, step.du
        dm = tuple(a - b for a, b in zip(mod0, mod_used, strict=True))
        step = solve(mod0, lu0, extra=roll.assembler.matvec(*dm, step.du[roll.assembler.free_dofs]))
        exact = False
    raise _ModuliNotSettled(
        f"an increment's moduli did not settle in {8 * NEWTON_ITERATIONS} passes; use more n_steps"
    )


def _secant_mismatch(
    roll: _Roll,
    step: _Step,
    mod_used: tuple[FloatArray, ...],
    exact: bool,
    start: FloatArray,
    E_used: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray, float, float]:
    """A pass of :func:`_newton_increment` judged: its stresses at ``mod_used`` (``step``'s
    own for an exact pass), the law's secant E_mid over them, the elements' strain-energy
    increments (weights) and their total, and the weighted mismatch |E_used / E_mid - 1|."""
    deps = roll.strain_increment(step.du)
    dsig = step.dsig if exact else roll.stress_of_strain(mod_used, deps)
    E_mid = roll.secant_modulus(start, start + dsig[:, 0])
    w = np.abs(np.sum(dsig * deps, axis=1)) * roll.area
    total = float(np.sum(w))
    err = float(np.sum(w * np.abs(E_used / E_mid - 1.0))) / total if total > 0 else 0.0
    return dsig, E_mid, w, total, err


def _mixed_log_modulus(
    hist_x: list[FloatArray],
    hist_f: list[FloatArray],
    E_used: FloatArray,
    E_mid: FloatArray,
    w: FloatArray,
    total: float,
) -> FloatArray:
    """The next pass's log E: the fixed-point update log E_mid with Anderson mixing over
    the last :data:`ANDERSON` passes (``hist_x``, ``hist_f`` kept here), weighted by the
    strain-energy increments ``w``, the step limited to a factor e^3."""
    x = np.log(E_used)
    f = np.log(E_mid) - x
    hist_x.append(x)
    hist_f.append(f)
    x_new = x + f
    if ANDERSON > 0 and len(hist_x) >= 2:
        del hist_x[: -ANDERSON - 1], hist_f[: -ANDERSON - 1]
        sw = np.sqrt(w / total) if total > 0 else np.ones_like(w)
        dF = np.diff(np.stack(hist_f, axis=1), axis=1)
        dX = np.diff(np.stack(hist_x, axis=1), axis=1)
        gamma = np.linalg.lstsq(dF * sw[:, None], f * sw, rcond=None)[0]
        x_new = np.clip(x + f - (dX + dF) @ gamma, x - 3.0, x + 3.0)
    return x_new


def _slip_weight(
    roll: _Roll, sig: FloatArray, dsig: FloatArray, friction: float, before: FloatArray
) -> FloatArray:
    """Share of the increment each element spends slipped, from the increment's solution.

    The trial shear is the start-of-step shear plus the increment at the full G_r_theta
    (``dsig`` divided by the shear factor used): an element slips where it reaches Coulomb's
    limit mu P (the slip factor {23} reaching 1; P = max(-sigma_r, 0) the total interlayer
    pressure at the end of the step). Linear in the increment, it reaches the limit after
    the share x = (mu P - |tau_0|) / (|tau_trial| - |tau_0|) of it, and slips for 1 - x;
    ``before`` (1: slipped in an earlier increment) stays.
    """
    tau0 = sig[:, 2]
    trial = tau0 + dsig[:, 2] / roll.shear_factor()
    a0, a1 = np.abs(tau0), np.abs(trial)
    limit = friction * np.maximum(-(roll.sigma_pre + sig[:, 0] + dsig[:, 0]), 0.0)
    slips = (a1 >= limit) & (a1 > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(a1 > a0, np.clip((limit - a0) / (a1 - a0), 0.0, 1.0), 0.0)
    return np.maximum(np.where(slips, 1.0 - x, 0.0), before)


class _Loading:
    """The head pressed into the roll increment by increment: the state between the
    increments (displacements, contact-induced stresses, contact forces), the frozen
    stiffness of ``update_modulus=False`` and the work counters."""

    def __init__(
        self,
        roll: _Roll,
        opts: ContactOptions,
        delta: FloatArray,
        head_radius: float,
        friction: float,
        update_modulus: bool,
    ) -> None:
        self.roll, self.opts, self.delta = roll, opts, delta
        self.head_radius, self.friction = head_radius, friction
        mesh = roll.mesh
        self.r_out = float(mesh.r[-1])
        self.history = LoadHistory.start(delta, mesh.n_elements, roll.surface.size)
        n_dof = 2 * mesh.n_nodes
        self.u = np.zeros(n_dof)
        self.sig = np.zeros((mesh.n_elements, 3))  # contact-induced (r, theta, r-theta) [Pa]
        self.lam = np.zeros(roll.surface.size)
        self.f_contact = np.zeros(n_dof)
        self.centre = np.zeros(2)
        self.slip_on = opts.slip == "reduced-shear"
        if self.slip_on:
            roll.slip_weight = np.zeros(mesh.n_elements)
        self.frozen = roll.moduli(roll.sigma_pre) if not update_modulus else None
        self.tol_gap = 1e-3 * delta[1]
        self.step: _Step | None = None
        self.lu_frozen = _factorize(roll, self.frozen) if self.frozen is not None else None
        self.factorisations = int(self.lu_frozen is not None)
        self.slip_passes = 0

    def solve(
        self, mod: tuple[FloatArray, ...], lu: _Factor, extra: FloatArray | None = None
    ) -> _Step:
        """The increment at fixed moduli (``lu`` their factorised stiffness)."""
        return _step(
            self.roll,
            mod,
            lu,
            self.u,
            self.f_contact,
            self.lam,
            self.centre,
            self.head_radius,
            self.tol_gap,
            extra,
        )

    def _predicted_stress(self, k: int) -> FloatArray | None:
        """The mid-step radial stress predicted from the last increments (None: none yet):
        the parabola through the last three states for a law linear in pressure (the
        stress under the head stiffens exponentially in depth), else the last increment's
        rate."""
        roll, delta, last, sig = self.roll, self.delta, self.step, self.sig
        if last is None:
            return None
        if roll.linear_law is not None and k >= 3:
            x0, x1, x2, x = delta[k - 3], delta[k - 2], delta[k - 1], delta[k]
            l0 = (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2))
            l1 = (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2))
            l2 = (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1))
            h = self.history.stress[:, :, 0]
            end = l0 * h[k - 3] + l1 * h[k - 2] + l2 * h[k - 1]
            return 0.5 * (sig[:, 0] + end)
        ratio = (delta[k] - delta[k - 1]) / (delta[k - 1] - delta[k - 2])
        return sig[:, 0] + 0.5 * ratio * last.dsig[:, 0]

    def increment(self, k: int) -> tuple[_Step, int]:
        """The increment at the current slip zone; (step, factorisations)."""
        roll, opts = self.roll, self.opts
        if self.frozen is not None and self.lu_frozen is not None:
            return self.solve(self.frozen, self.lu_frozen), 0  # one factorisation for all
        if opts.midpoint and opts.predictor:
            predicted = self._predicted_stress(k)
            if roll.linear_law is not None and opts.newton:
                return _newton_increment(roll, self.sig[:, 0], predicted, opts.step_tol, self.solve)
            return _predicted_increment(roll, self.sig[:, 0], predicted, opts.step_tol, self.solve)
        step = _hypoelastic_increment(roll, self.sig[:, 0], opts.midpoint, self.solve)
        return step, 2 if opts.midpoint else 1

    def _refreeze(self) -> None:
        """The frozen stiffness again at the new slip zone."""
        self.frozen = self.roll.moduli(self.roll.sigma_pre)
        self.lu_frozen = _factorize(self.roll, self.frozen)
        self.factorisations += 1

    def slip_increment(self, k: int) -> _Step:
        """The increment with the slip emulation (Figure 19): the zone where the interlayer
        shear reaches mu P, {23}, and each element's slipping share of the increment,
        iterated until no share grows by more than SLIP_TOL (monotone: it cannot cycle)."""
        roll, opts = self.roll, self.opts
        assert roll.slip_weight is not None
        before = roll.slip_weight.copy()
        for _ in range(opts.slip_max_passes):
            step, n_fact = self.increment(k)
            self.factorisations += n_fact
            self.slip_passes += 1
            w = np.maximum(
                _slip_weight(roll, self.sig, step.dsig, self.friction, before), roll.slip_weight
            )
            if np.max(w - roll.slip_weight) <= SLIP_TOL:
                break
            roll.slip_weight = w
            if self.frozen is not None:
                self._refreeze()
        else:
            raise ConvergenceError(
                f"the slip zone did not settle in {opts.slip_max_passes} passes at depth "
                f"{self.delta[k] * 1e3:.3g} mm ({int(np.count_nonzero(roll.slip_weight))} "
                "elements slipping); raise options.slip_max_passes or use more n_steps"
            )
        # slipped within this increment: slipped for the rest of the loading
        settled = np.where(roll.slip_weight > 0, 1.0, 0.0)
        changed = not np.array_equal(settled, roll.slip_weight)
        roll.slip_weight = settled
        if self.frozen is not None and changed and k < self.delta.size - 1:
            self._refreeze()
        return step

    def advance(self, k: int) -> _Step:
        """Press the head to ``delta[k]``: the increment solved, the state updated."""
        roll = self.roll
        self.centre = np.array([self.r_out + self.head_radius - self.delta[k], 0.0])
        if not self.slip_on:
            step, n_fact = self.increment(k)
            self.factorisations += n_fact
        else:
            step = self.slip_increment(k)
        self.u += step.du
        self.sig += step.dsig
        self.lam = step.lam
        self.f_contact = np.zeros(self.u.size)
        fr, ft = roll.polar(step.normal * self.lam[:, None], roll.surface)
        self.f_contact[2 * roll.surface] = fr
        self.f_contact[2 * roll.surface + 1] = ft
        self.step = step
        return step


def _indent_inputs(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    sizes: tuple[float | str, float | str, float | str, float | None],
    friction: float,
    options: ContactOptions | None,
) -> tuple[tuple[float, float, float, float], float, FloatArray, FloatArray, ContactOptions]:
    """The checked inputs of :func:`indent`: (head radius, head length, depth_max, deepest
    depth), friction, the profile arrays and the options."""
    if not isinstance(web, Web):
        raise InputError("must be a woundroll.materials.Web", "web")
    if not isinstance(core, Core):
        raise InputError("must be a woundroll.materials.Core", "core")
    head_radius = _check_scalar(sizes[0], "head_radius")
    head_length = _check_scalar(sizes[1], "head_length")
    depth_max = _check_scalar(sizes[2], "depth_max")
    deepest = depth_max
    if sizes[3] is not None:
        deepest = max(_check_scalar(sizes[3], "extend_to"), depth_max)
    friction = to_si(friction, "dimensionless", "friction")
    if friction < 0:
        raise InputError(f"must be zero or positive, got {friction:g}", "friction")
    r, s = _check_profile(web, core, radius, sigma_r)
    opts = options if options is not None else ContactOptions()
    if not isinstance(opts, ContactOptions):
        raise InputError("must be a ContactOptions", "options")
    r_in, r_out = core.outer_radius, float(r[-1])
    for value, name in ((depth_max, "depth_max"), (deepest, "extend_to")):
        if value >= 0.5 * head_radius:
            raise InputError(
                f"must be below half the head radius ({0.5 * head_radius:g} m), got {value:g} m",
                name,
            )
        if value >= 0.25 * (r_out - r_in):
            raise InputError(
                f"must be below a quarter of the wound thickness "
                f"({0.25 * (r_out - r_in):g} m), got {value:g} m",
                name,
            )
    return (head_radius, head_length, depth_max, deepest), friction, r, s, opts


def contact_mesh(
    web: Web,
    core: Core,
    r_out: float,
    head_radius: float,
    depth_max: float,
    opts: ContactOptions,
    *,
    surface_layers: float = 0.5,
    fine_zone: float = FINE_ZONE,
    field: str = "options.surface_size",
) -> RollMesh:
    """The mesh for a head pressed to ``depth_max``: the surface ring ``surface_layers``
    web layers thick, a fine zone of ``fine_zone`` a_geo (the geometric half-chord at
    ``depth_max``), tangential size max(h/4, a_geo/40) there with h the web thickness
    (:class:`ContactOptions` may set each). The dynamic model meshes with one layer and the
    whole a_geo (:func:`woundroll.contact.dynamic.plane_strain.impact_dynamic`)."""
    r_in = core.outer_radius
    R_eff = 1.0 / (1.0 / head_radius + 1.0 / r_out)
    a_geo = math.sqrt(2.0 * R_eff * depth_max)
    given = opts.surface_size
    surface_size = given if given is not None else surface_layers * web.thickness
    t_ref = given if given is not None else web.thickness
    t_size = (
        opts.tangential_size
        if opts.tangential_size is not None
        else max(0.25 * t_ref, a_geo / 40.0)
    )
    fine = opts.fine_halfwidth if opts.fine_halfwidth is not None else fine_zone * a_geo
    if surface_size >= 0.5 * (r_out - r_in):
        raise InputError("is too large for the wound thickness", field)
    return build_mesh(
        r_in,
        r_out,
        surface_size=surface_size,
        radial_growth=opts.radial_growth,
        tangential_size=t_size,
        fine_halfwidth=max(fine, t_size),
        tangential_growth=opts.tangential_growth,
        max_element_angle=opts.max_element_angle,
        periodic=not opts.half_model,
    )


def _press(
    load: _Loading,
    sym: float,
    head_length: float,
    stop: Callable[[FloatArray, FloatArray], bool] | None,
) -> tuple[LoadHistory, FloatArray, FloatArray]:
    """The loading: every depth of ``load.delta`` in turn, recorded, until ``stop`` says
    so. Returns the history, the surface deflection history and the surface nodes' arc
    length."""
    roll, delta, h = load.roll, load.delta, load.history
    mesh = roll.mesh
    half_model = not mesh.periodic
    n = delta.size - 1
    n_surf = roll.surface.size
    s_surf = load.r_out * mesh.theta
    trib = 0.5 * (np.roll(s_surf, -1) - np.roll(s_surf, 1))
    if half_model:
        trib[0] = 0.5 * s_surf[1]
    u_hist = np.zeros((n + 1, n_surf))  # inward radial displacement of the surface nodes
    for k in range(1, n + 1):
        step = load.advance(k)
        lam = step.lam
        h.record(
            k,
            sym * float(np.sum(-lam * step.normal[:, 0])),
            _half_width(s_surf, lam, step.gap, mesh.j0, (1,) if half_model else (1, -1)),
            float(np.max(lam / trib)),
            load.sig,
            lam / trib,
        )
        u_hist[k] = -load.u[2 * roll.surface]
        if stop is not None and k < n and stop(delta[: k + 1], h.force[: k + 1] * head_length):
            # stopped early: the curve ends at the last depth solved
            return h.up_to(k + 1), u_hist[: k + 1], s_surf
    return h, u_hist, s_surf


def _result2d(
    load: _Loading,
    h: LoadHistory,
    u_hist: FloatArray,
    s_surf: FloatArray,
    head_length: float,
    update_modulus: bool,
    t0: float,
) -> ContactResult:
    """The result of :func:`indent` (``t0``: when it started)."""
    roll, friction, head_radius = load.roll, load.friction, load.head_radius
    mesh, r_out = roll.mesh, load.r_out
    sig = load.sig
    xy = roll.basis.centre_xy
    return ContactResult(
        **result_fields(
            h,
            force=h.force * head_length,
            stress=(sig[:, 0], sig[:, 1], sig[:, 2]),
            sigma_pre=roll.sigma_pre,
            friction=friction,
            elements=(xy[:, 0], xy[:, 1], roll.r_centre, np.arctan2(xy[:, 1], xy[:, 0])),
            contact_s=s_surf,
        ),
        force_per_length=h.force,
        head_radius=head_radius,
        head_length=head_length,
        outer_radius=r_out,
        update_modulus=update_modulus,
        n_elements=mesh.n_elements,
        n_dof=int(roll.free.sum()),
        mesh_shape=(mesh.n_r - 1, mesh.n_theta),
        solve_time_s=time.perf_counter() - t0,
        factorisations=load.factorisations,
        slipped=None if roll.slip_weight is None else roll.slip_weight > 0,
        slip_passes=load.slip_passes,
        surface_deflection_history=u_hist,
    )


def indent(
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
    options: ContactOptions | None = None,
    stop: Callable[[FloatArray, FloatArray], bool] | None = None,
    extend_to: float | None = None,
) -> ContactResult:
    """Press a rigid cylindrical head into the wound roll and return F(d), a(d) and the fields.

    Parameters
    ----------
    web : Web
        Web data; E_r follows ``web.radial_modulus`` {2}, G_r_theta ``web.shear_r_theta``.
    core : Core
        Core radius [m] and stiffness E_c [Pa] (``inf`` = rigid).
    radius : ndarray
        Radii [m] of the pre-impact stress profile, core to outside; ``radius[-1]`` is the
        roll's outer radius.
    sigma_r : ndarray
        Pre-impact radial stress [Pa] at ``radius`` (compression negative), e.g. from
        :mod:`woundroll.winding`.
    head_radius : float or str
        Radius of the instrument's cylindrical head [m] (axis along the CMD). Here and for
        ``head_length`` and ``depth_max`` a string with a unit (``"10 mm"``) is accepted.
    head_length : float
        Length of the head along the CMD [m]; it multiplies the plane-strain force per unit
        length.
    depth_max : float
        Largest depth [m] the head is pressed to (displacement control).
    friction : float
        Interlayer friction coefficient mu >= 0 [-] for the slip factor {23} (0: every
        sheared element slips, SF = inf).
    update_modulus : bool
        True: hypoelastic E_r at the current stress. False: E_r frozen at its pre-impact
        value (the paper's "no update").
    options : ContactOptions, optional
        Mesh and step settings.
    stop : callable, optional
        ``stop(delta, force)`` [m], [N], called after each increment with the curve so far
        (origin included): True ends the loading there (the result then ends at that
        depth). :func:`woundroll.contact.roll_stiffness` uses it to stop well past the
        depths the striker can reach.
    extend_to : float, optional
        With ``stop``: the loading goes on past ``depth_max`` by the same step law
        (``d_k = depth_max (k / n_steps)^step_exponent``) until ``stop`` says so or the
        depth reaches ``extend_to`` [m] (the increments up to ``depth_max`` are the same
        as without it). :func:`woundroll.contact.roll_stiffness` uses it instead of
        solving again from the start when the striker turns out to go deeper.

    Returns
    -------
    ContactResult

    Raises
    ------
    InputError
        Bad geometry, profile arrays or options (field names as in the signature).
    ConvergenceError
        The contact set does not settle or the stiffness is singular.
    """
    t0 = time.perf_counter()
    sizes, friction, r, s, opts = _indent_inputs(
        web,
        core,
        radius,
        sigma_r,
        (head_radius, head_length, depth_max, extend_to if stop is not None else None),
        friction,
        options,
    )
    head_radius, head_length, depth_max, deepest = sizes
    r_out = float(r[-1])
    mesh = contact_mesh(web, core, r_out, head_radius, depth_max, opts)
    sym = 2.0 if opts.half_model else 1.0  # the half model carries half the load
    for retry in range(STEP_RETRIES + 1):
        roll = _Roll(web, core, r, s, mesh, opts)
        delta = depth_schedule(depth_max, int(opts.n_steps), opts.step_exponent, deepest)
        load = _Loading(roll, opts, delta, head_radius, friction, update_modulus)
        try:
            with one_blas_thread():  # woundroll.util.blas: OpenBLAS's threads only wait here
                h, u_hist, s_surf = _press(load, sym, head_length, stop)
            break
        except _ModuliNotSettled as exc:
            if retry == STEP_RETRIES:
                raise ConvergenceError(
                    f"{exc} (also with {opts.n_steps} increments); set "
                    "contact.options.n_steps higher"
                ) from None
            opts = dataclasses.replace(opts, n_steps=2 * int(opts.n_steps))
    return _result2d(load, h, u_hist, s_surf, head_length, update_modulus, t0)
