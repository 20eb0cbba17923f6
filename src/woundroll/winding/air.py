"""Winding speed and entrained air: the air film at the lay-on line, the air layer in the
roll as a gas spring in series with the stack, and the roll after the air has left.

A web running onto a roll drags air with it; above a few m/s the air film between the
incoming web and the roll is thicker than the surfaces' roughness and is wound in. The
roll then holds, per layer, the web (thickness ``h``) and an air layer ``h_a``: it is
bigger and softer, its pressure lower, and it changes again when the air bleeds out at the
roll's edges.

Model (every assumption named; docs/winding.md, "Speed and entrained air")
--------------------------------------------------------------------------
1. **Film at the lay-on line, no nip** (centre winding, the web wrapping the roll under
   tension): the self-acting foil bearing,

       h_f = 0.643 R (6 eta U / T)^(2/3)

   (Eshel and Elrod, "The theory of the infinitely wide, perfectly flexible, self-acting
   foil bearing", J. Basic Eng. 87 (1965) 831-836; Knox and Sweeney, "Fluid effects
   associated with web handling", Ind. Eng. Chem. Process Des. Dev. 10 (1971) 201-205),
   ``R`` the roll radius, ``U`` the winding speed (web and roll surface move together at
   it), ``T`` the web tension per width [N/m], ``eta`` the air's viscosity. Assumed: U is
   the winding speed, not the sum of the two surface speeds (that reading, ``12 eta U``,
   gives 2^(2/3) = 1.59 times the film); a published example (TopWeb's 3000 m PET roll,
   tests/winding/test_air.py) is within 1 % in diameter with this reading. Good and
   Holmberg ("The effect of air entrainment in centerwound rolls", Proc. IWEB 2, Oklahoma
   State University, 1993) measured the entrained film on a centre-winding roll and found
   the foil-bearing theory adequate; they wound it into a reduced radial modulus, as here.
2. **Film with a nip** (a lay-on roll): the film the nip lets through, the larger of the
   rigid-isoviscous line contact (Martin 1916: ``h = 4.9 eta U R_n / w``) and the
   isoviscous-elastic one (Herrebrugh 1968, soft EHL: ``h = 2.32 R_n (eta U / (E' R_n))^0.6
   (w / (E' R_n))^-0.2``), ``w`` the nip load per width, ``R_n = (1/R + 1/R_nip)^-1``,
   ``E' = 2 E*`` with ``E*`` the nip's contact modulus (the regime whose assumption holds
   gives the larger film; Herrebrugh's coefficient and exponents as quoted in Hamrock,
   Schmid and Jacobson, *Fundamentals of Fluid Film Lubrication*, 2004, not checked against
   the 1968 paper here). A nip only removes air: the film is ``min(h_f, h_nip)``, which
   tends to the foil-bearing film as the nip load goes to 0. Assumed: the film leaves the
   nip at ambient pressure (Forrest, "Air entrainment during film winding with layon
   rolls", Proc. IWEB 3, 1995, follows the compressed air out of the nip; not done here).
3. **Roughness**: the web's surfaces (combined Rq ``sigma`` of the two faces in contact)
   touch where the film is thinner than their summits. The stack law E_r(P) measured on
   the web already holds the air in the roughness, so the air that counts is what the film
   holds beyond the summits: ``a0 = max(h_film - 3 sigma, 0)`` (``SUMMIT_HEIGHT`` = 3: the
   full-film criterion Lambda = h / sigma >= 3 of lubrication; below it the asperities
   carry load; Ducotey and Good, "Predicting traction in web handling", J. Tribol. 121
   (1999) 618-624: traction is lost once the film exceeds three times the combined rms
   roughness). A smooth web (``sigma = 0``) keeps the whole film.
4. **The air layer in the roll** is a gas spring compressed isothermally by the pressure
   ``P`` the later layers add: ``(p_atm + P) h_a = p_atm a0``. In series with the stack,
   a layer of pitch ``p = h + a0`` has the tangent radial modulus

       1 / E_eff(P) = [h / E_r(P) + p_atm a0 / (p_atm + P)^2] / p

   and, smeared over the pitch (the air carries no hoop load), ``E_theta h / p``, the
   Poisson ratio ``nu_theta_r h / p`` and the wound-on stress ``WOT h / p`` (the same force
   per width). Hakiel's model (:func:`woundroll.winding.hakiel.wind`) winds this composite
   web unchanged: no change to the compiled kernels, and a run without air does not come
   here at all. **Assumed: one entrained film for the roll**: the kernels take one law
   for every layer, so the film ``a0`` is the length-weighted mean of each layer's lay-on
   film (which grows with the radius); the per-layer films are reported.
5. **Diameter** for a wound length ``L``: the layers of the roll with air sit at the pitch
   ``p`` (``R_0 = sqrt(r_c^2 + L p / pi)`` before compression); the outer radius is
   ``r_c + u(r_c) + sum of the layers' thicknesses at their pressure``, each
   ``h (1 - eps(P)) + h_a(P)`` with the stack strain ``eps(P) = int_0^P dP / E_r`` (E_r
   floored as the winding model floors it); Poisson's radial strain is neglected
   (``nu_theta_r sigma_theta / E_theta``, < 1e-3 of the stack's). The roll without air is
   summed the same way, so the two diameters compare like for like.
6. **After the air has left**: all the air goes, so each layer loses its air thickness
   ``h_a(P)``: a radial free strain ``-h_a(P) / p`` of the composite, solved as an
   increment on the wound-in state with the stack-only modulus (the chord of the stack
   curve, Picard; :func:`woundroll.winding.storage.solve_increment`, the same equation
   with a free strain). The air leaves the roll at its edges: the linearised Reynolds
   equation of a compressible film of height ``h_g`` at absolute pressure ``p``,
   ``dp/dt = (p h_g^2 / (12 eta)) d2p/dz2`` with ``p = p_atm`` at the edges ``z = +-W/2``,
   decays in its slowest mode with the time constant

       tau = 12 eta W^2 / (pi^2 p h_g^2),   h_g = h_a(P) + sigma

   (the flow gap: the air layer plus the roughness' valleys; Gross, *Gas Film
   Lubrication*, Wiley 1962, for the compressible Reynolds equation; Hashimoto and
   Okajima, J. Tribol. 128 (2006) 267-274, for the side leakage of entrained air). A
   stated estimate: it neglects the stack's compliance feeding the flow and the air's
   permeation through the web (a paper web loses air faster). Deep layers keep their air
   longest (tau grows with p and with 1/h_a^2). As the air goes the gap narrows and the
   flow slows: taking the layer's air to decay at the rate of its slowest mode at the
   current gap, ``dh/dt = -h / tau(h)`` (quasi-static, the layer's pressure held), the time
   for a fraction f of the air ``a`` to leave is

       t_f = C int_{(1-f) a}^{a} dh / (h (h + sigma)^2),   C = 12 eta W^2 / (pi^2 p)

   (closed form: ``[ln(h / (h + sigma)) + sigma / (h + sigma)] / sigma^2``; for sigma = 0,
   ``-1 / (2 h^2)``): 90 % of the air takes 49.5 initial time constants on a smooth web.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.materials.radial_modulus import RadialModulusLaw
from woundroll.materials.web import Core, Web
from woundroll.winding.result import WindingResult
from woundroll.winding.tension import TensionSchedule

FloatArray = NDArray[np.float64]

#: Air at 20 C: dynamic viscosity [Pa s] and the ambient pressure [Pa] (the defaults of
#: the case file's ``[air]`` section).
VISCOSITY = 1.8e-5
PRESSURE = 101_325.0
#: Contact modulus E* [Pa] of the lay-on roller's cover against the roll: a rubber cover
#: of ~70 Shore A (typical, unpublished); ``[air].nip_modulus``.
NIP_MODULUS = 10e6
#: Lay-on roller radius [m] when neither ``[air].nip_radius`` nor the nip roller's radius
#: is given (the nip roller's own default, :class:`woundroll.profile.nip.NipRoller`).
NIP_RADIUS = 0.05
#: Foil-bearing coefficient (Eshel and Elrod 1965; Knox and Sweeney 1971).
FOIL_COEFFICIENT = 0.643
#: Film over the summits: the film the roughness closes is this many combined Rq.
SUMMIT_HEIGHT = 3.0
#: Picard iterations of the after-the-air solve (chord modulus).
RTOL = 1e-8
MAX_ITERATIONS = 50


def _check(value: Any, field: str, *, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating):
        raise InputError(f"must be a number, got {value!r}", field)
    v = float(value)
    if not math.isfinite(v) or v < 0 or (positive and v == 0):
        raise InputError(
            f"must be {'positive' if positive else 'zero or positive'}, got {v!r}", field
        )
    return v


@dataclass(frozen=True)
class AirSettings:
    """The winder's speed, the web's roughness and the air's properties, SI.

    Attributes
    ----------
    speed : float [m/s]
        Winding speed (0: no air entrained, today's model exactly).
    roughness : float [m]
        Combined Rq of the two faces in contact, ``sqrt(Rq1^2 + Rq2^2)`` (0: smooth).
    viscosity : float [Pa s]
    pressure : float [Pa]
        Ambient (absolute) pressure.
    nip_modulus : float [Pa]
        Contact modulus E* of the nip (lay-on roller cover against the roll).
    nip_radius : float [m]
        Lay-on roller radius.
    time : float [s]
        Time after winding of the roll "after": ``inf`` (default) when all the air that can
        leave has left; a finite time leaves each layer the air the leakage model keeps.
    """

    speed: float = 0.0
    roughness: float = 0.0
    viscosity: float = VISCOSITY
    pressure: float = PRESSURE
    nip_modulus: float = NIP_MODULUS
    nip_radius: float = NIP_RADIUS
    time: float = math.inf

    def __post_init__(self) -> None:
        if not (isinstance(self.time, int | float) and self.time >= 0):
            raise InputError(f"must be zero or positive, got {self.time!r}", "air.time")
        _check(self.speed, "winding.speed")
        _check(self.roughness, "web.roughness")
        for name in ("viscosity", "pressure", "nip_modulus", "nip_radius"):
            _check(getattr(self, name), f"air.{name}", positive=True)

    @property
    def active(self) -> bool:
        """True when air is entrained at all (a positive speed)."""
        return self.speed > 0.0


def foil_bearing_film(
    radius: ArrayLike, speed: float, tension_per_width: ArrayLike, viscosity: float = VISCOSITY
) -> FloatArray:
    """Entrained film [m] of a web wrapping a roll (no nip):
    ``0.643 R (6 eta U / T)^(2/3)`` (Eshel and Elrod 1965; Knox and Sweeney 1971).

    ``radius`` [m], ``speed`` [m/s], ``tension_per_width`` [N/m] (> 0), ``viscosity``
    [Pa s]. A slack web (T = 0) has no foil bearing: inf."""
    R = np.asarray(radius, dtype=float)
    T = np.asarray(tension_per_width, dtype=float)
    with np.errstate(divide="ignore"):
        x = np.where(T > 0, 6.0 * viscosity * speed / np.where(T > 0, T, 1.0), np.inf)
    return FOIL_COEFFICIENT * R * x ** (2.0 / 3.0)


def nip_film(
    radius: ArrayLike,
    speed: float,
    line_load: float,
    *,
    nip_radius: float = NIP_RADIUS,
    nip_modulus: float = NIP_MODULUS,
    viscosity: float = VISCOSITY,
) -> FloatArray:
    """Film [m] a nip of ``line_load`` [N/m] lets through at ``speed`` [m/s]: the larger of
    the rigid-isoviscous (Martin) and isoviscous-elastic (Herrebrugh) line-contact films
    (module docstring, item 2); inf without load."""
    R = np.asarray(radius, dtype=float)
    Rn = 1.0 / (1.0 / R + 1.0 / nip_radius)
    if line_load <= 0:
        return np.full_like(Rn, np.inf)
    Ep = 2.0 * nip_modulus
    rigid = 4.9 * viscosity * speed * Rn / line_load
    soft = 2.32 * Rn * (viscosity * speed / (Ep * Rn)) ** 0.6 * (line_load / (Ep * Rn)) ** -0.2
    return np.maximum(rigid, soft)


def lay_on_film(
    radius: ArrayLike,
    tension_per_width: ArrayLike,
    line_load: float,
    air: AirSettings,
) -> FloatArray:
    """The film [m] at the lay-on line: the foil-bearing film, or less through a nip."""
    h = foil_bearing_film(radius, air.speed, tension_per_width, air.viscosity)
    if line_load > 0:
        hn = nip_film(
            radius,
            air.speed,
            line_load,
            nip_radius=air.nip_radius,
            nip_modulus=air.nip_modulus,
            viscosity=air.viscosity,
        )
        h = np.minimum(h, hn)
    return np.asarray(h, dtype=float)


def entrained_air(film: ArrayLike, roughness: float) -> FloatArray:
    """The air layer [m] that counts: the film beyond the summits, ``max(h - 3 sigma, 0)``."""
    return np.maximum(np.asarray(film, dtype=float) - SUMMIT_HEIGHT * roughness, 0.0)


def air_thickness(pressure: ArrayLike, a0: float, p_atm: float = PRESSURE) -> FloatArray:
    """The air layer [m] at interlayer pressure ``P`` [Pa]: ``p_atm a0 / (p_atm + P)``
    (isothermal gas spring; tension ``P < 0`` is not carried: P floored at 0)."""
    P = np.maximum(np.asarray(pressure, dtype=float), 0.0)
    return p_atm * a0 / (p_atm + P)


def leaving_time(
    air: ArrayLike,
    roughness: float,
    pressure: ArrayLike,
    width: float,
    fraction: ArrayLike,
    viscosity: float = VISCOSITY,
) -> FloatArray:
    """Time [s] for ``fraction`` of an air layer ``air`` [m] at absolute pressure
    ``pressure`` [Pa] to leave a roll of ``width`` [m] at its edges (module docstring,
    item 6): ``C int dh / (h (h + sigma)^2)`` from ``(1 - fraction) air`` to ``air``."""
    a = np.asarray(air, dtype=float)
    C = 12.0 * viscosity * width**2 / (math.pi**2 * np.asarray(pressure, dtype=float))
    lo = (1.0 - np.asarray(fraction, dtype=float)) * a

    def prim(h: FloatArray) -> FloatArray:
        # int dh / (h (h + sigma)^2) = g(sigma / h) / h^2, g(x) = (x/(1+x) - ln(1+x)) / x^2
        # (-1/2 at x = 0: the smooth web), its series below x = 0.01 (no cancellation)
        x = roughness / h
        xs = np.where(x < 1e-2, 1.0, x)
        g = np.where(
            x < 1e-2,
            -0.5 + x * (2.0 / 3.0 + x * (-0.75 + x * 0.8)),
            (xs / (1.0 + xs) - np.log1p(xs)) / xs**2,
        )
        return g / h**2

    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = C * (prim(a) - prim(lo))
    return np.where(a > 0, t, 0.0)


def remaining_air(
    air: ArrayLike,
    roughness: float,
    pressure: ArrayLike,
    width: float,
    time: float,
    viscosity: float = VISCOSITY,
) -> FloatArray:
    """The air layer [m] left after ``time`` [s] of an initial ``air`` [m] (the inverse of
    :func:`leaving_time`: ``C [F(a) - F(h)] = t``, F its antiderivative; bisection in
    log h, 80 halvings: 1e-12 of the layer)."""
    a = np.asarray(air, dtype=float)
    if math.isinf(time):
        return np.zeros_like(a)
    if time <= 0:
        return a.copy()
    lo = np.full_like(a, -40.0)  # log of the fraction left
    hi = np.zeros_like(a)
    p = np.broadcast_to(np.asarray(pressure, dtype=float), a.shape)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        frac_gone = 1.0 - np.exp(mid)
        t = leaving_time(a, roughness, p, width, frac_gone, viscosity)
        # more time than given to reach this fraction left: the fraction left is larger
        lo = np.where(t > time, mid, lo)
        hi = np.where(t > time, hi, mid)
    return np.where(a > 0, a * np.exp(0.5 * (lo + hi)), 0.0)


@dataclass(frozen=True)
class AirLayerLaw(RadialModulusLaw):
    """The composite web + air layer of pitch ``h + a0``: the stack law in series with the
    isothermal gas spring (module docstring, item 4)."""

    stack: RadialModulusLaw
    thickness: float
    air: float
    p_atm: float = PRESSURE
    floor: float = 0.0

    name = "air-layer"

    @property
    def pitch(self) -> float:
        return self.thickness + self.air

    def modulus_at_pressure(self, pressure: ArrayLike) -> FloatArray:
        P = np.maximum(np.asarray(pressure, dtype=float), 0.0)
        Es = np.maximum(self.stack.modulus_at_pressure(P), self.floor)
        comp = self.thickness / Es + self.p_atm * self.air / (self.p_atm + P) ** 2
        return self.pitch / comp

    def pressure(self, strain: ArrayLike) -> FloatArray:  # pragma: no cover - not used
        raise NotImplementedError("the air layer's stack curve is not tabulated")

    def tabulate(self, p_max: float, n: int = 401) -> tuple[FloatArray, FloatArray]:
        """Knots dense where the gas spring bends (P of the order of p_atm) and at the
        stack law's own knots."""
        p_max = max(p_max, 1.0)
        ks, _ = self.stack.tabulate(p_max, n)
        lo = min(self.p_atm * 1e-3, p_max / 10)
        p = np.union1d(np.concatenate(([0.0], np.geomspace(lo, p_max, n - 1))), ks[ks <= p_max])
        return p, self.modulus_at_pressure(p)

    def to_dict(self) -> dict[str, Any]:
        return {
            "law": self.name,
            "stack": self.stack.to_dict(),
            "thickness_m": self.thickness,
            "air_m": self.air,
            "ambient_pressure_Pa": self.p_atm,
        }


def stack_strain(law: RadialModulusLaw, pressure: ArrayLike, floor: float) -> FloatArray:
    """The stack's compressive strain ``int_0^P dP / max(E_r, floor)`` [-] at ``P``."""
    P = np.maximum(np.asarray(pressure, dtype=float), 0.0)
    top = max(float(np.max(P, initial=0.0)), 1.0)
    grid = np.concatenate(([0.0], np.geomspace(min(1e-3, top / 10), top, 2000)))
    inv = 1.0 / np.maximum(law.modulus_at_pressure(grid), floor)
    cum = np.concatenate(([0.0], np.cumsum(0.5 * (inv[1:] + inv[:-1]) * np.diff(grid))))
    return np.interp(P, grid, cum)


def _element_pressure(w: WindingResult) -> FloatArray:
    return np.maximum(-0.5 * (w.sigma_r[1:] + w.sigma_r[:-1]), 0.0)


def outer_radius_compacted(
    w: WindingResult,
    web: Web,
    core: Core,
    a0: float,
    p_atm: float,
    floor: float,
) -> float:
    """Outer radius [m] of a wound roll with its layers at their pressure (module
    docstring, item 5): the core moved by its pressure plus each element's web and air
    thickness (``a0``: the entrained layer at ambient pressure; the grid's pitch is
    ``h + a0``)."""
    P = _element_pressure(w)
    h = web.thickness
    frac = np.diff(w.radius) / (h + a0)  # each element's share of a layer
    t = h * (1.0 - stack_strain(web.radial_modulus, P, floor)) + air_thickness(P, a0, p_atm)
    p_core = max(float(-w.sigma_r[0]), 0.0)
    u_core = 0.0 if core.rigid else -core.outer_radius * p_core / core.stiffness
    return float(core.outer_radius + u_core + np.sum(frac * t))


def radius_along_length(
    w: WindingResult, web: Web, core: Core, a0: float, p_atm: float, floor: float
) -> tuple[FloatArray, FloatArray]:
    """``(L, r)`` at the nodes of the wound roll ``w``: the web length [m] wound up to a
    node (each layer as long as the circumference it was laid on) and the node's radius [m]
    in the finished, compacted roll (each element's web and
    air thickness at its pressure, as :func:`outer_radius_compacted`)."""
    P = _element_pressure(w)
    h = web.thickness
    frac = np.diff(w.radius) / (h + a0)
    t = frac * (
        h * (1.0 - stack_strain(web.radial_modulus, P, floor)) + air_thickness(P, a0, p_atm)
    )
    p_core = max(float(-w.sigma_r[0]), 0.0)
    u_core = 0.0 if core.rigid else -core.outer_radius * p_core / core.stiffness
    r = core.outer_radius + u_core + np.concatenate(([0.0], np.cumsum(t)))
    # the web's length: each layer as long as the roll's circumference where it was laid on
    rg = 0.5 * (w.radius[1:] + w.radius[:-1])
    L = np.concatenate(([0.0], np.cumsum(2.0 * math.pi * rg * frac)))
    return L, r


#: Points of the diameter-against-length curve in result.json.
CURVE_POINTS = 101


@dataclass(frozen=True)
class AirResult:
    """A roll wound with entrained air, and the same roll after the air has left.

    Attributes
    ----------
    settings : AirSettings
    film_radius, film : ndarray [m]
        The lay-on film against the roll radius (each layer's), before the roughness.
    air : float [m]
        The entrained layer a0 the roll holds (length-weighted mean, beyond the summits).
    at_winding : WindingResult
        The roll with air: sigma_r, the web's hoop stress (sigma_theta, the wound-in
        tension), the composite E_r.
    after : WindingResult
        The roll after the air has left (stack-only E_r).
    no_air : WindingResult
        Today's model (the roll wound without air, for the same length).
    outer_radius_no_air, outer_radius_at_winding, outer_radius_after : float [m]
    leakage_time : ndarray [s]
        Per node of ``at_winding``: the time constant of the air leaving at the edges.
    warnings : tuple of str
    """

    settings: AirSettings
    film_radius: FloatArray
    film: FloatArray
    air: float
    at_winding: WindingResult
    after: WindingResult
    no_air: WindingResult
    outer_radius_no_air: float
    outer_radius_at_winding: float
    outer_radius_after: float
    leakage_time: FloatArray
    warnings: tuple[str, ...] = ()
    #: per node: the time [s] for 90 % of the layer's air to leave (the gap narrowing)
    leaving_time_90: FloatArray | None = None
    #: the share of the roll's air gone in the roll ``after`` (1: all, ``settings.time`` inf)
    gone: float = 1.0
    #: the diameter against the wound length [m]: ``(L, D without air, D with air)``
    #: where metre L sits in the finished roll (radius_along_length)
    curve: tuple[FloatArray, FloatArray, FloatArray] | None = None

    @property
    def loose(self) -> bool:
        """True when, after the air has left, layers are apart (sigma_r = 0 below the
        surface): a loose roll."""
        return self.air > 0 and bool(np.any(self.after.sigma_r[:-1] >= 0.0))

    def _after_text(self) -> str:
        t = self.settings.time
        if math.isinf(t):
            return "after it left"
        return f"{_duration(t)} after winding ({100 * self.gone:.0f} % of it gone)"

    @property
    def leaves_90(self) -> float:
        """Time [s] for 90 % of the air to leave the slowest layer (0 without air)."""
        t = self.leaving_time_90
        return 0.0 if t is None else float(np.max(t, initial=0.0))

    @property
    def film_at_lay_on(self) -> float:
        """The film [m] at the lay-on line at the end of winding (the last layer's)."""
        return float(self.film[-1]) if self.film.size else 0.0

    def to_dict(self) -> dict[str, Any]:
        """The ``air`` block of result.json (SI, units in the key names)."""
        s = self.settings
        w, a = self.at_winding, self.after
        return {
            "speed_m_per_s": s.speed,
            "roughness_m": s.roughness,
            "viscosity_Pa_s": s.viscosity,
            "ambient_pressure_Pa": s.pressure,
            "nip_modulus_Pa": s.nip_modulus,
            "nip_radius_m": s.nip_radius,
            "film_at_lay_on_m": self.film_at_lay_on,
            "entrained_air_m": self.air,
            "film_radius_m": self.film_radius.tolist(),
            "film_m": self.film.tolist(),
            "outer_diameter_no_air_m": 2.0 * self.outer_radius_no_air,
            "outer_diameter_at_winding_m": 2.0 * self.outer_radius_at_winding,
            "outer_diameter_after_m": 2.0 * self.outer_radius_after,
            "core_pressure_at_winding_Pa": float(w.core_pressure),
            "core_pressure_after_Pa": float(a.core_pressure),
            "core_pressure_no_air_Pa": float(self.no_air.core_pressure),
            "air_radius_m": w.radius.tolist(),
            "sigma_r_at_winding_Pa": w.sigma_r.tolist(),
            "sigma_theta_at_winding_Pa": w.sigma_theta.tolist(),
            "sigma_r_after_Pa": a.sigma_r.tolist(),
            "sigma_theta_after_Pa": a.sigma_theta.tolist(),
            "air_leakage_time_s": float(np.max(self.leakage_time, initial=0.0)),
            "air_leaves_90_s": self.leaves_90,
            "time_after_winding_s": None if math.isinf(s.time) else s.time,
            "air_gone_fraction": self.gone,
            **(
                {}
                if self.curve is None
                else {
                    "wound_length_m": self.curve[0].tolist(),
                    "diameter_no_air_m": self.curve[1].tolist(),
                    "diameter_with_air_m": self.curve[2].tolist(),
                }
            ),
        }

    def summary(self) -> str:
        """One line for the CLI."""
        d0, d1, d2 = (
            2e3 * self.outer_radius_no_air,
            2e3 * self.outer_radius_at_winding,
            2e3 * self.outer_radius_after,
        )
        film = self.film_at_lay_on * 1e6
        return (
            f"air at {self.settings.speed:g} m/s: film at lay-on {film:.3g} um "
            f"(entrained {self.air * 1e6:.3g} um/layer); outer diameter {d1:.1f} mm with air, "
            f"{d2:.1f} mm {self._after_text()}, {d0:.1f} mm without air; core pressure "
            f"{self.at_winding.core_pressure / 1e3 + 0.0:.4g} kPa at winding, "
            f"{self.after.core_pressure / 1e3 + 0.0:.4g} kPa "
            f"{'after' if math.isinf(self.settings.time) else 'then'} "
            f"({self.no_air.core_pressure / 1e3:.4g} without air); 90 % of the air leaves in "
            f"~{_duration(self.leaves_90)}"
        )


def _duration(t: float) -> str:
    if not math.isfinite(t):
        return "never (no flow gap)"
    if t < 120:
        return f"{t:.3g} s"
    if t < 7200:
        return f"{t / 60:.3g} min"
    return f"{t / 3600:.3g} h"


def wound_length(n_layers: int, core_radius: float, pitch: float) -> float:
    """Web length [m] of ``n_layers`` concentric layers of ``pitch`` on ``core_radius``."""
    i = np.arange(n_layers)
    return float(np.sum(2.0 * math.pi * (core_radius + (i + 0.5) * pitch)))


def _lay_on_films(
    rc: float, h: float, length: float, tension: TensionSchedule, air: AirSettings
) -> tuple[FloatArray, FloatArray, float, int]:
    """The lay-on radius and film of each layer of the roll wound with air, the roll's
    entrained layer a0 (length-weighted mean beyond the summits) and its number of layers:
    a fixed point, since the layers sit at the pitch ``h + a0`` and the film grows with the
    radius (a few iterations: the film grows like R, R like sqrt(pitch))."""
    a0, n1 = 0.0, max(int(round((math.sqrt(rc * rc + length * h / math.pi) - rc) / h)), 1)
    s = rc + h * np.arange(n1)
    film = np.zeros(n1)
    if not air.active:
        return s, film, 0.0, n1
    for _ in range(100):
        pitch = h + a0
        n1 = max(int(round((math.sqrt(rc * rc + length * pitch / math.pi) - rc) / pitch)), 1)
        s = rc + pitch * np.arange(n1)
        T = tension.web_tension(s, rc, rc + n1 * pitch) * h  # N/m
        if np.any(T <= 0):
            raise InputError(
                "the web is slack at the lay-on line (zero tension): no foil bearing to say "
                "how much air it takes",
                "winding.tension",
            )
        film = lay_on_film(s, T, tension.nip_load, air)
        a_new = float(np.sum(entrained_air(film, air.roughness) * s) / np.sum(s))
        done = abs(a_new - a0) <= 1e-9 * max(a_new, 1e-30)
        a0 = a_new
        if done:
            break
    return s, film, a0, n1


def _wind_composite(
    web: Web,
    core: Core,
    tension: TensionSchedule,
    options: Any,
    air: AirSettings,
    a0: float,
    n_layers: int,
    floor: float,
) -> tuple[WindingResult, WindingResult, float]:
    """The roll wound as a composite web of pitch ``h + a0`` (web and its air layer, the
    stack's law in series with the gas spring, :class:`AirLayerLaw`) by the unchanged
    kernels: (the composite's result, the same with the web's own hoop stresses and WOT, the
    web's share ``f = h / pitch`` of the pitch)."""
    from woundroll.winding.hakiel import wind

    h = web.thickness
    pitch = h + a0
    law = AirLayerLaw(web.radial_modulus, h, a0, air.pressure, floor)
    f = h / pitch
    cweb = replace(
        web,
        thickness=pitch,
        E_theta=web.E_theta * f,
        nu_theta_r=web.nu_theta_r * f,
        radial_modulus=law,
    )
    ctension = replace(tension, web_stress=tension.web_stress * f)
    copts = replace(options, modulus_floor=options.modulus_floor / f)  # same floor in Pa
    wc = wind(cweb, core, core.outer_radius + n_layers * pitch, ctension, options=copts)
    return wc, replace(wc, sigma_theta=wc.sigma_theta / f, wot=wc.wot / f), f


def _warnings(a0: float, h: float, converged: bool, after: WindingResult) -> list[str]:
    """What a roll wound with ``a0`` of air per layer of thickness ``h`` has to be warned of:
    it floats on air; the roll after the air left did not settle; layers pulled apart."""
    warnings: list[str] = []
    if a0 > h:
        warnings.append(
            f"air: {a0 * 1e6:.3g} um of air is wound in under each {h * 1e6:.3g} um layer: the "
            "roll floats on air (it can telescope or shift while winding), and the gas spring in "
            "series with the stack is a rough model there; raise the tension, add a nip or "
            "slow down"
        )
    if not converged:
        warnings.append(
            f"air: the roll after the air has left did not settle in {MAX_ITERATIONS} "
            "iterations; its stresses are approximate"
        )
    tens = after.sigma_r[:-1] >= 0.0  # let go: sigma_r = 0 below the surface
    if np.any(tens):
        r = after.radius[:-1][tens]
        warnings.append(
            f"air: after the air has left, the layers between r = {r.min() * 100:.2f} and "
            f"{r.max() * 100:.2f} cm are pulled apart: no pressure between them, the roll is "
            "loose there (its layers can slip or telescope; the air stays in the gaps)"
        )
    return warnings


def wind_with_air(
    web: Web,
    core: Core,
    outer_radius: float,
    tension: TensionSchedule,
    air: AirSettings,
    *,
    options: Any = None,
    no_air: WindingResult | None = None,
) -> AirResult:
    """Wind the roll of ``outer_radius`` (its length, without air) at ``air.speed``.

    ``no_air``: today's roll (:func:`woundroll.winding.hakiel.wind` of the same inputs),
    when the caller has it already. Raises :class:`InputError` for a roughness that is not
    smaller than the web thickness."""
    from woundroll.winding.hakiel import WindingOptions, wind

    options = options if options is not None else WindingOptions()
    h = web.thickness
    if air.roughness >= h:
        raise InputError(
            f"the combined roughness {air.roughness * 1e6:.3g} um must be smaller than the web "
            f"thickness ({h * 1e6:.3g} um)",
            "web.roughness",
        )
    if no_air is None:
        no_air = wind(web, core, outer_radius, tension, options=options)
    rc = core.outer_radius
    n0 = no_air.n_layers
    floor = options.modulus_floor * web.E_theta
    length = wound_length(n0, rc, h)
    s, film, a0, n1 = _lay_on_films(rc, h, length, tension, air)
    r_no_air = outer_radius_compacted(no_air, web, core, 0.0, air.pressure, floor)
    if a0 <= 0.0:
        return AirResult(
            air, s, film, 0.0, no_air, no_air, no_air, r_no_air, r_no_air, r_no_air,
            np.zeros(no_air.radius.size),
        )  # fmt: skip
    wc, at_winding, f = _wind_composite(web, core, tension, options, air, a0, n1, floor)
    P0n = np.maximum(-wc.sigma_r, 0.0)
    kept = remaining_air(
        air_thickness(P0n, a0, air.pressure), air.roughness, air.pressure + P0n, web.width,
        air.time, air.viscosity,
    )  # fmt: skip
    after, _iters, converged = _air_leaves(
        wc, web, core, a0, air.pressure, floor, f, None if math.isinf(air.time) else kept
    )
    h_air = air_thickness(P0n, a0, air.pressure)
    gone = 1.0 if math.isinf(air.time) else float(1.0 - np.sum(kept) / np.sum(h_air))
    r_wind = outer_radius_compacted(wc, web, core, a0, air.pressure, floor)
    # after: the outer layer moves by its hoop strain (the layers let go keep their gap:
    # the air left there at ambient pressure)
    d_hoop = float(after.sigma_theta[-1] - at_winding.sigma_theta[-1])
    r_after = r_wind * (1.0 + d_hoop / web.E_theta)
    # the leakage time per node of the roll with air
    Pn = np.maximum(-wc.sigma_r, 0.0)
    gap = air_thickness(Pn, a0, air.pressure) + air.roughness
    tau = 12.0 * air.viscosity * web.width**2 / (math.pi**2 * (air.pressure + Pn) * gap**2)
    t90 = leaving_time(
        air_thickness(Pn, a0, air.pressure), air.roughness, air.pressure + Pn, web.width, 0.9,
        air.viscosity,
    )  # fmt: skip
    warnings = _warnings(a0, h, converged, after)
    after = replace(after, inputs={**no_air.inputs, "outer_radius_m": float(after.radius[-1])})
    L0, rn = radius_along_length(no_air, web, core, 0.0, air.pressure, floor)
    L1, ra = radius_along_length(wc, web, core, a0, air.pressure, floor)
    Lg = np.linspace(0.0, min(L0[-1], L1[-1]), CURVE_POINTS)
    curve = (Lg, 2.0 * np.interp(Lg, L0, rn), 2.0 * np.interp(Lg, L1, ra))
    return AirResult(
        air, s, film, a0, at_winding, after, no_air, r_no_air, r_wind, r_after, tau,
        tuple(warnings), leaving_time_90=t90, gone=gone, curve=curve,
    )  # fmt: skip


def _banded_increment(
    r: FloatArray,
    E_r: FloatArray,
    E_theta: float,
    nu: float,
    eps: FloatArray,
    core_stiffness: float,
    fixed: NDArray[np.bool_],
    fixed_value: FloatArray,
) -> FloatArray:
    """The increment ``s`` [Pa] of sigma_r at the nodes for a radial free strain ``eps``
    (per node): ``r^2 s'' + 3 r s' + (1 - E_theta / E_r) s = E_theta eps`` (the equation of
    :mod:`woundroll.winding.storage` with a per-node free strain), the core condition
    without free strain, ``s = 0`` at the surface, and ``s = fixed_value`` at the nodes
    ``fixed`` (layers apart: sigma_r = 0 there). Second-order differences, banded solve."""
    from scipy.linalg import solve_banded

    n = r.size
    h0 = r[1:-1] - r[:-2]
    h1 = r[2:] - r[1:-1]
    d1 = (-h1 / (h0 * (h0 + h1)), (h1 - h0) / (h0 * h1), h0 / (h1 * (h0 + h1)))
    d2 = (2.0 / (h0 * (h0 + h1)), -2.0 / (h0 * h1), 2.0 / (h1 * (h0 + h1)))
    ri = r[1:-1]
    g2 = E_theta / E_r[1:-1]
    ab = np.zeros((4, n))
    rhs = np.zeros(n)
    idx = np.arange(1, n - 1)
    ab[3, idx - 1] = ri**2 * d2[0] + 3.0 * ri * d1[0]
    ab[2, idx] = ri**2 * d2[1] + 3.0 * ri * d1[1] + (1.0 - g2)
    ab[1, idx + 1] = ri**2 * d2[2] + 3.0 * ri * d1[2]
    rhs[1:-1] = E_theta * eps[1:-1]
    a, b = r[1] - r[0], r[2] - r[1]
    c0 = -(2.0 * a + b) / (a * (a + b))
    c1 = (a + b) / (a * b)
    c2 = -a / (b * (a + b))
    inv_ec = 0.0 if math.isinf(core_stiffness) else 1.0 / core_stiffness
    ab[2, 0] = 1.0 - nu + r[0] * c0 - E_theta * inv_ec
    ab[1, 1] = r[0] * c1
    ab[0, 2] = r[0] * c2
    ab[2, n - 1] = 1.0
    # rows of the fixed nodes: s_i = value (clear the row: A[i, j] sits at ab[2 + i - j, j])
    for k in np.flatnonzero(fixed):
        for j in range(max(k - 2, 0), min(k + 2, n)):
            if 0 <= 2 + k - j <= 3:
                ab[2 + k - j, j] = 0.0
        ab[2, k] = 1.0
        rhs[k] = fixed_value[k]
    return solve_banded((1, 2), ab, rhs)


def _air_leaves(
    wc: WindingResult,
    web: Web,
    core: Core,
    a0: float,
    p_atm: float,
    floor: float,
    f: float,
    remaining: FloatArray | None = None,
) -> tuple[WindingResult, int, bool]:
    """The composite roll ``wc`` after its air has left (module docstring, item 6): the
    web's hoop stress and the stack-only E_r in the result. ``remaining``: the air layer
    [m] each node keeps (at its pressure at winding; None: none), a gas spring in series
    with the stack in the increment (its chord compliance between the two pressures).

    Layers that the loss of air would pull apart (sigma_r > 0) are let go: sigma_r = 0
    there (an active set, grown until no layer is in radial tension; a stack cannot carry
    tension), with the chord modulus of the stack between the two pressures (Picard)."""
    from woundroll.winding.storage import hoop_increment

    r = wc.radius
    n = r.size
    P0 = np.maximum(-wc.sigma_r, 0.0)
    pitch = web.thickness + a0
    rem = np.zeros(n) if remaining is None else np.asarray(remaining, dtype=float)
    eps = -(air_thickness(P0, a0, p_atm) - rem) / pitch  # free strain of the composite
    a_rem = rem * (p_atm + P0) / p_atm  # the air kept, at ambient pressure
    Et = web.E_theta * f
    law = web.radial_modulus
    h = web.thickness

    def chord(p_mid: FloatArray, p_end: FloatArray) -> FloatArray:
        """The composite's chord modulus per pitch: stack at the midpoint, gas spring's
        chord between P0 and the end pressure."""
        Es = np.maximum(law.modulus_at_pressure(p_mid), floor)
        return pitch / (h / Es + p_atm * a_rem / ((p_atm + P0) * (p_atm + p_end)))

    s = np.zeros_like(r)
    E = chord(P0, P0)
    apart = np.zeros(n, dtype=bool)
    converged, it = False, 0
    if n < 3:
        return wc, 0, True
    while not converged and it < MAX_ITERATIONS:
        it += 1
        s_new = _banded_increment(r, E, Et, web.nu_theta_r * f, eps, core.stiffness, apart, P0)
        scale = max(float(np.max(np.abs(s_new))), 1e-30)
        new_apart = apart | (P0 - s_new < 0.0)
        new_apart[-1] = False
        settled = float(np.max(np.abs(s_new - s))) <= RTOL * scale
        converged = settled and bool(np.all(new_apart == apart))
        apart = new_apart
        s = s_new
        E = chord(np.maximum(P0 - 0.5 * s, 0.0), np.maximum(P0 - s, 0.0))
    sigma_r = np.minimum(wc.sigma_r + s, 0.0)
    sigma_r[-1] = 0.0
    s = sigma_r - wc.sigma_r
    sigma_theta = (wc.sigma_theta + hoop_increment(r, s)) / f
    E_after = np.maximum(law.modulus_at_pressure(-sigma_r), floor)
    after = replace(
        wc,
        sigma_r=sigma_r,
        sigma_theta=sigma_theta,
        E_r=E_after,
        wot=wc.wot / f,
        core_pressure=float(-sigma_r[0]),
    )
    return after, it, converged
