"""Winder settings -> the tension wound into each layer.

The web tension ``T_w`` is set at the core and may be tapered as the roll grows. A nip
roller (load ``N`` per unit width, friction ``mu`` between nip and roll) adds the
nip-induced tension of center winding, so the wound-on tension (WOT) is

    WOT(r) = T_w(r) + mu N / h            (stress units; h the web thickness)

(Good, Wu and Fikes, "The internal stresses in wound rolls with the presence of a nip
roller", J. Appl. Mech. 61 (1994) 182-185; the standard center-winding estimate; ``mu`` the
kinetic friction between web layers, ``winding.friction``).

Winding modes (``mode``; docs/winding.md "Surface and centre-surface winding"):

``center`` (default)
    ``WOT = T_w + mu N / h`` as above, exactly as before the modes existed.
``surface``
    The roll is driven by the drum through the nip. The nip-induced tension rises as
    ``mu_eff N`` at low nip load and levels off at high nip load (Pfeiffer, "Nip forces and
    their effect on wound-in tension", Tappi J. 60(2) (1977) 115-117; Good, Hartwig and
    Markum, "A comparison of center and surface winding using the wound-in-tension method",
    Proc. 5th Int. Conf. on Web Handling, Oklahoma State University (1999); Balaji and
    Good: the slope approaches the kinetic friction between web layers, and the wound-in
    tension becomes independent of the nip load at high loads). Model (the saturating form
    is a choice; its scale is an input):
    ``NIT = mu_eff N_s tanh(N / N_s)``, ``mu_eff = min(mu, mu_d)`` (the outer layer slips on
    the layer below only while the drum grips the web harder, ``mu_d`` the web-drum
    friction, ``winding.drum_friction``), ``N_s`` the nip load where it levels off
    (``winding.nip_saturation``). ``WOT = T_w + NIT / h``.
``center-surface``
    Surface winding plus a tension differential ``dT`` (force per width) that the centre
    drive's torque puts between the drum and the roll: given directly
    (``tension_differential``) or from the drum's braking torque ``M_d`` over the width
    ``w`` on its radius ``R_d``: ``dT = M_d / (w R_d)``. The drum holds the web back by
    friction over its wrap ``beta`` (capstan, Euler-Eytelwein) and in the nip, so at most
    ``dT_max = T_w h (exp(mu_d beta) - 1) + mu_d N``; beyond it the web slips on the drum and
    the differential stays at ``dT_max``. ``WOT = T_w + NIT / h + min(dT, dT_max) / h``.

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
    # --- winding modes (module docstring); the defaults are today's centre winding ---
    #: "center", "surface" or "center-surface"
    mode: str = "center"
    #: web-drum kinetic friction mu_d [-] (surface modes)
    drum_friction: float | None = None
    #: nip load N_s [N/m] where the surface-winding nip-induced tension levels off
    nip_saturation: float | None = None
    #: tension differential dT [N/m] of centre-surface winding (before the drum's limit)
    tension_differential: float = 0.0
    #: wrap angle beta [rad] of the web on the drum (the drum's holding limit)
    drum_wrap: float = math.pi / 2

    def __post_init__(self) -> None:
        self._check_mode()
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

    def _check_mode(self) -> None:
        if self.mode not in WINDING_MODES:
            raise InputError(
                f"unknown mode {self.mode!r}; choose {', '.join(WINDING_MODES)}", "winding.mode"
            )
        if self.mode == "center":
            return
        if self.drum_friction is None:
            raise InputError(
                f"needed for winding.mode = {self.mode!r}: the kinetic friction between web "
                "and drum (winding.friction is the friction between web layers)",
                "winding.drum_friction",
            )
        if not (math.isfinite(self.drum_friction) and 0 <= self.drum_friction <= 2):
            raise InputError(
                f"must lie in [0, 2], got {self.drum_friction:g}", "winding.drum_friction"
            )
        if not self.nip_load > 0:
            raise InputError(
                f"must be positive for winding.mode = {self.mode!r} (the drum drives the roll "
                "through the nip)",
                "winding.nip_load",
            )
        ns = self.nip_saturation
        if ns is None or not (math.isfinite(ns) and ns > 0):
            raise InputError(
                f"must be a positive force per width, got {ns!r}", "winding.nip_saturation"
            )
        if not math.isfinite(self.tension_differential):
            raise InputError("must be a finite number", "winding.tension_differential")
        if self.mode == "surface" and self.tension_differential != 0.0:
            raise InputError(
                "a tension differential needs winding.mode = 'center-surface'",
                "winding.tension_differential",
            )
        if not (math.isfinite(self.drum_wrap) and 0 <= self.drum_wrap <= 2 * math.pi):
            raise InputError(
                f"must lie in [0, 360] deg, got {math.degrees(self.drum_wrap):g} deg",
                "winding.drum_wrap",
            )

    def nip_induced_line(self) -> float:
        """Nip-induced tension [N/m] of the mode: ``mu N`` (centre), ``mu_eff N_s tanh(N/N_s)``
        (surface modes)."""
        if self.mode == "center":
            return self.friction * self.nip_load
        mu = min(self.friction, float(self.drum_friction))
        ns = float(self.nip_saturation)
        return mu * ns * math.tanh(self.nip_load / ns)

    def drum_limit(self, web_line: ArrayLike) -> NDArray[np.float64]:
        """Largest tension differential [N/m] the drum holds at web line tension ``web_line``
        [N/m]: ``T_w h (exp(mu_d beta) - 1) + mu_d N`` (capstan plus nip friction)."""
        mu = float(self.drum_friction or 0.0)
        return (
            np.asarray(web_line, dtype=float) * math.expm1(mu * self.drum_wrap) + mu * self.nip_load
        )

    def web_tension(self, r: ArrayLike, r_core: float, r_outer: float) -> NDArray[np.float64]:
        """Tapered web tension T_w(r) [Pa]."""
        return self.web_stress * self.taper.factor_at(r, r_core, r_outer)

    def nip_induced(self, thickness: float) -> float:
        """Nip-induced tension mu N / h [Pa] (Good, Wu and Fikes 1994)."""
        return self.friction * self.nip_load / thickness

    def wound_on_tension(
        self, r: ArrayLike, r_core: float, r_outer: float, thickness: float
    ) -> NDArray[np.float64]:
        """WOT(r) [Pa] for the layer wound at radius ``r``: ``T_w(r) + mu N / h`` in centre
        winding; the surface modes' forms in the module docstring."""
        if self.mode == "center":
            return self.web_tension(r, r_core, r_outer) + self.nip_induced(thickness)
        tw = self.web_tension(r, r_core, r_outer)
        wot = tw + self.nip_induced_line() / thickness
        if self.mode == "center-surface":
            limit = self.drum_limit(tw * thickness)
            dT = np.clip(self.tension_differential, -limit, limit)
            wot = wot + dT / thickness
        return wot

    def drum_slips(self, r: ArrayLike, r_core: float, r_outer: float, thickness: float) -> bool:
        """True when the tension differential exceeds the drum's hold somewhere (the web
        slips on the drum there and the differential is capped, module docstring)."""
        if self.mode != "center-surface":
            return False
        limit = self.drum_limit(self.web_tension(r, r_core, r_outer) * thickness)
        return bool(np.any(abs(self.tension_differential) > limit))


#: The winder types (``winding.mode``); the first is the default.
WINDING_MODES = ("center", "surface", "center-surface")
