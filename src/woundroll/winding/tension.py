"""Winder settings -> the tension wound into each layer.

The web tension ``T_w`` is set at the core and may be tapered as the roll grows. A nip
roller (load ``N`` per unit width, friction ``mu`` between nip and roll) adds the
nip-induced tension of center winding, so the wound-on tension (WOT) is

    WOT(r) = T_w(r) + mu N / h            (stress units; h the web thickness)

(Good, Wu and Fikes, "The internal stresses in wound rolls with the presence of a nip
roller", J. Appl. Mech. 61 (1994) 182-185; the standard center-winding estimate).

Tapers (Good and Roisum, *Winding: Machines, Mechanics and Measurements*, 2008), with
``TP`` the taper fraction, ``r_c`` the core radius and ``R`` the final radius:

``linear``      T_w(r) = T0 (1 - TP (r - r_c) / (R - r_c))
``hyperbolic``  T_w(r) = T0 (1 - TP (1 - r_c / r))
``table``       T_w(r) interpolated linearly in a (radius, tension) table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError


@dataclass(frozen=True)
class Taper:
    """A tension taper: ``kind`` in {"none", "linear", "hyperbolic", "table"}.

    ``fraction`` is TP (0.2 = 20 % drop by the end for linear taper); for ``table``,
    ``radius`` [m] and ``factor`` [-] give T_w(r)/T0 at those radii.
    """

    kind: str = "none"
    fraction: float = 0.0
    radius: tuple[float, ...] = ()
    factor: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in {"none", "linear", "hyperbolic", "table"}:
            raise InputError(
                f"unknown taper {self.kind!r}; choose none, linear, hyperbolic or table",
                "winding.taper.kind",
            )
        if not (math.isfinite(self.fraction) and 0.0 <= self.fraction <= 1.0):
            raise InputError(
                f"must lie in [0, 1] (0.2 = 20 %), got {self.fraction:g}", "winding.taper.fraction"
            )
        if self.kind == "table":
            r, f = np.asarray(self.radius, float), np.asarray(self.factor, float)
            if r.size < 2 or r.shape != f.shape:
                raise InputError("needs at least two (radius, factor) pairs", "winding.taper")
            if np.any(np.diff(r) <= 0) or np.any(f < 0) or not np.all(np.isfinite(f)):
                raise InputError("radii must increase and factors be >= 0", "winding.taper")

    def factor_at(self, r: ArrayLike, r_core: float, r_outer: float) -> NDArray[np.float64]:
        """T_w(r) / T0 at radii ``r`` [m]."""
        r = np.asarray(r, dtype=float)
        if self.kind == "linear":
            return 1.0 - self.fraction * (r - r_core) / (r_outer - r_core)
        if self.kind == "hyperbolic":
            return 1.0 - self.fraction * (1.0 - r_core / r)
        if self.kind == "table":
            return np.interp(r, self.radius, self.factor)
        return np.ones_like(r)


@dataclass(frozen=True)
class TensionSchedule:
    """Web tension and nip settings of a center winder, SI.

    Attributes
    ----------
    web_stress : float [Pa]
        Web line tension at the core, as a stress (force / (width * thickness)).
    taper : Taper
    nip_load : float [N/m]
        Nip load per unit width (0: no nip).
    friction : float [-]
        Nip-to-roll kinetic friction coefficient for the nip-induced tension.
    """

    web_stress: float
    taper: Taper = Taper()
    nip_load: float = 0.0
    friction: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.web_stress) and self.web_stress >= 0):
            raise InputError(
                f"must be zero or positive, got {self.web_stress:g} Pa", "winding.tension"
            )
        if not (math.isfinite(self.nip_load) and self.nip_load >= 0):
            raise InputError(
                f"must be zero or positive, got {self.nip_load:g} N/m", "winding.nip_load"
            )
        if not (math.isfinite(self.friction) and 0 <= self.friction <= 2):
            raise InputError(f"must lie in [0, 2], got {self.friction:g}", "winding.friction")

    def web_tension(self, r: ArrayLike, r_core: float, r_outer: float) -> NDArray[np.float64]:
        """Tapered web tension T_w(r) [Pa]."""
        return self.web_stress * self.taper.factor_at(r, r_core, r_outer)

    def nip_induced(self, thickness: float) -> float:
        """Nip-induced tension mu N / h [Pa] (Good, Wu and Fikes 1994)."""
        return self.friction * self.nip_load / thickness

    def wound_on_tension(
        self, r: ArrayLike, r_core: float, r_outer: float, thickness: float
    ) -> NDArray[np.float64]:
        """WOT(r) = T_w(r) + mu N / h [Pa] for the layer wound at radius ``r``."""
        return self.web_tension(r, r_core, r_outer) + self.nip_induced(thickness)
