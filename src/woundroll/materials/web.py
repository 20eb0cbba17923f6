"""The web and the core: material and geometric data, SI, validated.

Poisson-ratio convention (the reference paper's tables name nu_tr, nu_zr, nu_tz):
``nu_ij = -eps_j / eps_i`` under a uniaxial stress in direction ``i``, with the
reciprocal ratio from the symmetry of the compliance, ``nu_ij / E_i = nu_ji / E_j``.
So ``nu_theta_r`` is the radial contraction caused by MD (hoop) stretching, and
``nu_r_theta = nu_theta_r * E_r / E_theta`` is tiny because E_r << E_theta.

Shear moduli: ``G_r_theta`` and ``G_r_z`` default to ``2 E_r`` at the current pressure
(Table 2 of the reference paper, an assumption taken from its ref. [9]); ``G_theta_z``
defaults to ``E_theta / (2 (1 + nu_theta_z))``, which reproduces Table 2's 2185 MPa
(PET1) and 1904 MPa (PET2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.materials.radial_modulus import RadialModulusLaw

#: The friction coefficient mu between web layers [-] where a case does not give one
#: (``contact.friction``): the reference paper's value in its slip factor {23} (Figure 18),
#: an assumption it does not measure. The contact models' slip checks, the layered rolls,
#: the defect criteria and the studies all read it from here.
INTERLAYER_FRICTION = 0.3
#: The share of G_r_theta and G_r_z a slipped layer keeps in the paper's reduced-shear
#: emulation of interlayer slip (``contact.slip = "reduced-shear"``, Figure 19: "a very
#: small value"; the paper prints none): the 2D and 3D models, the case and the slip study.
SLIP_SHEAR_FRACTION = 0.01


def _positive(
    value: float, name: str, *, allow_zero: bool = False, allow_inf: bool = False
) -> None:
    if value is None or math.isnan(value) or (math.isinf(value) and not allow_inf):
        raise InputError(f"must be a finite number, got {value}", name)
    if value < 0 or (value == 0 and not allow_zero):
        raise InputError(f"must be positive, got {value:g}", name)


@dataclass(frozen=True)
class Web:
    """A web (film, paper, foil) as wound: SI units throughout.

    Attributes
    ----------
    thickness : float [m]
    width : float [m]
        CMD width of the roll.
    E_theta : float [Pa]
        MD (hoop) modulus.
    radial_modulus : RadialModulusLaw
        E_r(sigma_r), e.g. Pfeiffer {2}.
    E_z : float [Pa]
        CMD (axial) modulus; defaults to ``E_theta``.
    density : float [kg/m^3]
    nu_theta_r, nu_z_r, nu_theta_z : float [-]
        Poisson ratios (module docstring for the convention); defaults 0, 0, 0.3 (Table 2).
    G_r_theta, G_r_z : float or None [Pa]
        Transverse shear moduli; None means ``2 E_r`` at the current pressure (Table 2).
    G_theta_z : float or None [Pa]
        In-plane shear modulus; None means ``E_theta / (2 (1 + nu_theta_z))``.
    radial_unloading : PfeifferUnloading or None
        Unloading branch of the radial response (:mod:`woundroll.materials.unloading`);
        None: unloading follows E_r (elastic, as in the paper).
    alpha_r, alpha_theta : float [1/K]
        Thermal expansion coefficients of the wound stack (radial, i.e. through the stack)
        and of the web along the MD (hoop); 0 by default (no thermal strain).
    beta_r, beta_theta : float [-]
        Hygroscopic expansion coefficients: strain per unit change of moisture content
        (mass fraction), radial and MD; 0 by default.
    tensile_strength : float or None [Pa]
        MD tensile strength; None: not checked (:mod:`woundroll.winding.storage` flags a
        hoop stress above it).
    """

    thickness: float
    width: float
    E_theta: float
    radial_modulus: RadialModulusLaw
    E_z: float | None = None
    density: float = 1400.0
    nu_theta_r: float = 0.0
    nu_z_r: float = 0.0
    nu_theta_z: float = 0.3
    G_r_theta: float | None = None
    G_r_z: float | None = None
    G_theta_z: float | None = None
    radial_unloading: Any = None
    alpha_r: float = 0.0
    alpha_theta: float = 0.0
    beta_r: float = 0.0
    beta_theta: float = 0.0
    tensile_strength: float | None = None

    def __post_init__(self) -> None:
        for name in ("alpha_r", "alpha_theta", "beta_r", "beta_theta"):
            v = getattr(self, name)
            if not isinstance(v, int | float) or not math.isfinite(v):
                raise InputError(f"must be a finite number, got {v!r}", f"web.{name}")
        if self.tensile_strength is not None:
            _positive(self.tensile_strength, "web.tensile_strength")
        if self.E_z is None:
            object.__setattr__(self, "E_z", self.E_theta)
        for name in ("thickness", "width", "E_theta", "E_z", "density"):
            _positive(getattr(self, name), f"web.{name}")
        for name in ("G_r_theta", "G_r_z", "G_theta_z"):
            if getattr(self, name) is not None:
                _positive(getattr(self, name), f"web.{name}")
        for name in ("nu_theta_r", "nu_z_r", "nu_theta_z"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 0.0 <= v < 1.0):
                raise InputError(f"must lie in [0, 1), got {v:g}", f"web.{name}")
        if self.G_theta_z is None:
            object.__setattr__(self, "G_theta_z", self.E_theta / (2.0 * (1.0 + self.nu_theta_z)))

    @classmethod
    def isotropic(
        cls, E: float, nu: float, *, thickness: float, width: float, density: float
    ) -> Web:
        """An isotropic linear-elastic solid as a "web" (e.g. the calibration block): every
        modulus follows from ``E`` [Pa] and ``nu`` [-]: ``E_r = E_theta = E_z = E``, every
        Poisson ratio ``nu``, every shear modulus ``E / (2 (1 + nu))``. ``thickness`` [m]
        sets the FE surface ring; ``width`` [m] the extent along the CMD."""
        from woundroll.materials.radial_modulus import Constant

        G = E / (2.0 * (1.0 + nu))
        return cls(
            thickness=thickness,
            width=width,
            E_theta=E,
            radial_modulus=Constant(E),
            E_z=E,
            density=density,
            nu_theta_r=nu,
            nu_z_r=nu,
            nu_theta_z=nu,
            G_r_theta=G,
            G_r_z=G,
            G_theta_z=G,
        )

    def E_r(self, sigma_r: ArrayLike) -> NDArray[np.float64]:
        """Radial modulus [Pa] at radial stress ``sigma_r`` [Pa] (compression negative)."""
        return self.radial_modulus.modulus(sigma_r)

    def shear_r_theta(self, E_r: ArrayLike) -> NDArray[np.float64]:
        """G_r_theta [Pa] for the given radial modulus: the set value or ``2 E_r`` (Table 2)."""
        E_r = np.asarray(E_r, dtype=float)
        return np.full_like(E_r, self.G_r_theta) if self.G_r_theta is not None else 2.0 * E_r

    def shear_r_z(self, E_r: ArrayLike) -> NDArray[np.float64]:
        """G_r_z [Pa] for the given radial modulus: the set value or ``2 E_r`` (Table 2)."""
        E_r = np.asarray(E_r, dtype=float)
        return np.full_like(E_r, self.G_r_z) if self.G_r_z is not None else 2.0 * E_r


@dataclass(frozen=True)
class Core:
    """The core as the roll sees it: outer radius and radial stiffness.

    ``stiffness`` E_c [Pa] is defined by ``u(r_c) = r_c sigma_r(r_c) / E_c`` (Hakiel's core
    condition); ``math.inf`` is a rigid core. :meth:`tube` builds it from an isotropic tube.
    ``thermal_expansion`` [1/K]: the core's linear expansion coefficient (its outer radius
    grows by ``r_c alpha_c dT`` when free; 0 by default, the core does not change).
    """

    outer_radius: float
    stiffness: float = math.inf
    inner_radius: float | None = None
    E: float | None = None
    nu: float | None = None
    thermal_expansion: float = 0.0

    def __post_init__(self) -> None:
        v = self.thermal_expansion
        if not isinstance(v, int | float) or not math.isfinite(v):
            raise InputError(f"must be a finite number, got {v!r}", "core.thermal_expansion")
        _positive(self.outer_radius, "core.outer_radius")
        _positive(self.stiffness, "core.stiffness", allow_inf=True)

    @classmethod
    def tube(cls, outer_radius: float, inner_radius: float, E: float, nu: float) -> Core:
        """An isotropic tube under external pressure, plane stress (Lame).

        u(b) = -p b / E * ((b^2 + a^2) / (b^2 - a^2) - nu) for pressure p on the outer
        radius b of a tube with inner radius a, so E_c = E / ((b^2 + a^2)/(b^2 - a^2) - nu);
        a solid shaft (a = 0) gives E / (1 - nu).
        """
        _positive(outer_radius, "core.outer_radius")
        _positive(inner_radius, "core.inner_radius", allow_zero=True)
        _positive(E, "core.E")
        if not (math.isfinite(nu) and -1.0 < nu < 0.5):
            raise InputError(f"must lie in (-1, 0.5), got {nu:g}", "core.nu")
        if inner_radius >= outer_radius:
            raise InputError(
                f"must be below core.outer_radius ({outer_radius:g} m), got {inner_radius:g} m",
                "core.inner_radius",
            )
        a2, b2 = inner_radius**2, outer_radius**2
        E_c = E / ((b2 + a2) / (b2 - a2) - nu)
        return cls(outer_radius=outer_radius, stiffness=E_c, inner_radius=inner_radius, E=E, nu=nu)

    @property
    def rigid(self) -> bool:
        return math.isinf(self.stiffness)
