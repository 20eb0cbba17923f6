"""The numerical settings of the 3D contact model (:class:`Contact3DOptions`), apart from
its solver so that a case file's ``[contact.options3d]`` is checked without loading the 3D
code (scipy.sparse and the mesh: 0.06 s of every 2D run's start-up)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from woundroll.errors import InputError
from woundroll.materials.web import SLIP_SHEAR_FRACTION

#: The sparse solvers of :func:`woundroll.contact.solid3d.linsolve.make_solver`.
SOLVERS = ("auto", "pardiso", "pardiso-mixed", "splu", "amg")


#: Growth of the element sizes away from the contact zone (radial, hoop and CMD alike).
#: 1.6, not a finer 1.3: a 3D reading is 3.7-4x cheaper (18,792 DOF against 46,535 on
#: PET1 26.7 N) for F(d) within 0.73 % of the 1.3 mesh over 0.2-1 depth_max (PET1 26.7 N;
#: 0.53 % on PET2 53.4 N) and Rho +0.11. Refining each growth to its square root (the slow
#: refinement test) moves F by < 1 %. docs/contact.md, "Refinement".
MESH_GROWTH = 1.6

#: How an increment's mid-step stress is predicted: "lagged", a trial solve on the
#: stiffness factorised for the last increment. It costs no factorisation (the trial's
#: contact is solved on that factor's exact flexibility, a partial solve) and is second
#: order where the contact spreads, which the stress rate ("rate", the default until
#: 2026-12-07) is not: F(depth_max) of PET2 26.7 N against 96 lagged increments -0.07 %
#: with 12, -0.0075 % with 24; the rate predictor -2.2 % / -0.59 % / -0.15 % with 12 / 24 /
#: 48. Rho of PET1 26.7 N 81.48 with 12 lagged increments, 81.39 with 48, 80.93 with 24 on
#: the rate; PET2 53.4 N 36.43, 36.41, 36.33 (docs/history.md, 2026-12-07).
PREDICTOR = "lagged"
#: Depth increments of a 3D loading to depth_max: 12 lagged increments read within 0.11 Rho
#: of 48 (PET1 26.7 N; 0.02 on PET2 53.4 N) at 2.84 / 3.12 CPU s, where 24 on the rate
#: predictor read 0.47 / 0.08 low at 6.6 / 7.1 s.
N_STEPS = 12


@dataclass(frozen=True)
class Contact3DOptions:
    """Numerical settings of :func:`indent3d` (defaults: docs/contact.md, 3D mesh study).

    Sizes left at None are set from the head's geometric footprint at ``depth_max``
    (:meth:`Head.footprint`: half extents a_y along the hoop, a_z along the CMD).

    Attributes
    ----------
    n_steps : int
        Depth increments; ``d_k = depth_max (k / n)^step_exponent``. 12 with the lagged
        predictor (:data:`N_STEPS`).
    step_exponent : float
    surface_size : float or None [m]
        Radial size of the outer element ring; None -> max(web thickness, a_y / 10).
    radial_growth : float
        Size ratio of neighbouring elements outside the fine zone, radially (and below,
        along the hoop and the CMD). Default 1.6 for all three (:data:`MESH_GROWTH`).
    tangential_size : float or None [m]
        Arc length of the elements in the fine zone; None -> a_y / ``n_fine``.
    fine_halfwidth : float or None [m]
        Arc half-width of the uniform fine zone; None -> a_y.
    tangential_growth : float
    axial_size : float or None [m]
        CMD size of the elements in the fine zone; None -> a_z / ``n_fine`` (sphere, punch)
        or the smaller of L / 24 and a_y / 2 for a cylinder, refined to a quarter of that
        at rounded ends.
    fine_halflength : float or None [m]
        CMD half-length of the fine zone; None -> a_z (+ a_y for a cylinder).
    axial_growth : float
    n_fine : int
        Elements across the footprint's half extent by default.
    locality_cut : bool
        The paper's cut: only 0 <= theta <= pi/2, u_theta = 0 on theta = pi/2.
    cmd_edges : {"free", "fixed"}
        The roll's CMD edge faces: free (the real roll), or held at u_z = 0 (a slab in plane
        strain: with a head as long as the roll this is the 2D model, used to verify it).
    min_modulus_ratio, max_modulus_ratio : float
        Floor (and optional cap) of E_r as a fraction of E_theta, as in 2D.
    midpoint : bool
        Mid-step modulus (midpoint rule) or forward Euler (start-of-step modulus).
    predictor : {"lagged", "rate", "trial"}
        How the mid-step stress is predicted: by a trial solve on the stiffness already
        factorised for the last increment (its moduli half a step behind; default, one
        factorisation per increment, :data:`PREDICTOR`), from the last increment's stress
        rate (one factorisation; first order where the contact spreads), or by a trial
        solve at the start-of-step modulus (two factorisations).
    slip : {"none", "reduced-shear"}
        Slip emulation (the paper's Figure 19): an element whose interlayer shear
        sqrt(tau_rt^2 + tau_rz^2) reaches mu P ({23} with the resultant shear) keeps
        ``slip_shear_fraction`` of its G_r_theta and G_r_z for the rest of the loading
        (from the next increment on; the increments resolve the spread of the slip zone).
    slip_shear_fraction : float
        Fraction of the transverse shear moduli left in a slipped element.
    solver : {"auto", "pardiso", "pardiso-mixed", "splu", "amg"}
        Linear solver (:mod:`woundroll.contact.solid3d.linsolve`); auto: PARDISO factorising
        in single precision with every solve refined in double to a relative residual of
        3e-5 (``"pardiso-mixed"``, ``linsolve.MIXED_RTOL``) if PARDISO is installed, SuperLU
        otherwise;
        ``"pardiso"``: PARDISO in double precision throughout.
    reuse_factorisation : bool
        Modified Newton: keep the factorisation of an earlier increment's K and solve with
        the current K by preconditioned conjugate gradients (False: factorise every K).
    pcg_max_iterations : int
        Conjugate-gradient iterations allowed per solve before K is factorised afresh.
    pcg_tol : float
        Relative residual of those solves.
    """

    n_steps: int = N_STEPS
    step_exponent: float = 1.5
    surface_size: float | None = None
    radial_growth: float = MESH_GROWTH
    tangential_size: float | None = None
    fine_halfwidth: float | None = None
    tangential_growth: float = MESH_GROWTH
    axial_size: float | None = None
    fine_halflength: float | None = None
    axial_growth: float = MESH_GROWTH
    n_fine: int = 10
    locality_cut: bool = False
    cmd_edges: str = "free"
    min_modulus_ratio: float = 1e-6
    max_modulus_ratio: float | None = None
    midpoint: bool = True
    predictor: str = PREDICTOR
    slip: str = "none"
    slip_shear_fraction: float = SLIP_SHEAR_FRACTION
    solver: str = "auto"
    reuse_factorisation: bool = False
    pcg_max_iterations: int = 8
    pcg_tol: float = 1e-10

    def __post_init__(self) -> None:
        if self.predictor not in ("rate", "trial", "lagged"):
            raise InputError(
                f"must be 'lagged', 'rate' or 'trial', got {self.predictor!r}",
                "options.predictor",
            )
        if self.slip not in ("none", "reduced-shear"):
            raise InputError(
                f"must be 'none' or 'reduced-shear', got {self.slip!r}", "options.slip"
            )
        if not (math.isfinite(self.slip_shear_fraction) and 0 < self.slip_shear_fraction <= 1):
            raise InputError(
                f"must lie in (0, 1], got {self.slip_shear_fraction!r}",
                "options.slip_shear_fraction",
            )
        if self.cmd_edges not in ("free", "fixed"):
            raise InputError(
                f"must be 'free' or 'fixed', got {self.cmd_edges!r}", "options.cmd_edges"
            )
        if self.solver not in SOLVERS:
            raise InputError(
                f"must be one of {', '.join(SOLVERS)}, got {self.solver!r}", "options.solver"
            )
        for name in ("n_steps", "n_fine"):
            v = getattr(self, name)
            if not isinstance(v, int | np.integer) or isinstance(v, bool) or v < 1:
                raise InputError(f"must be a positive integer, got {v!r}", f"options.{name}")
        if self.n_fine < 3:
            raise InputError(
                "must be at least 3 (the contact zone would not be resolved)", "options.n_fine"
            )
        for name in (
            "surface_size",
            "tangential_size",
            "fine_halfwidth",
            "axial_size",
            "fine_halflength",
        ):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise InputError(f"must be a positive length, got {v!r}", f"options.{name}")
        for name in ("radial_growth", "tangential_growth", "axial_growth"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 1.0 <= v <= 3.0):
                raise InputError(f"must lie in [1, 3], got {v!r}", f"options.{name}")
        if not (math.isfinite(self.step_exponent) and 1.0 <= self.step_exponent <= 3.0):
            raise InputError(
                f"must lie in [1, 3], got {self.step_exponent!r}", "options.step_exponent"
            )
        if not (math.isfinite(self.min_modulus_ratio) and 0 < self.min_modulus_ratio < 1):
            raise InputError(
                f"must lie in (0, 1), got {self.min_modulus_ratio!r}", "options.min_modulus_ratio"
            )
        if self.max_modulus_ratio is not None and not (
            math.isfinite(self.max_modulus_ratio)
            and self.min_modulus_ratio < self.max_modulus_ratio <= 10.0
        ):
            raise InputError(
                f"must lie in (min_modulus_ratio, 10], got {self.max_modulus_ratio!r}",
                "options.max_modulus_ratio",
            )
