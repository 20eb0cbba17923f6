"""Plausibility limits of case-file quantities, and bounds on the work a run may take.

Two ranges per quantity (SI), each with its reason (docs/case-files.md lists them):

* the **hard** range: values outside it describe no web, core or tester that exists, or would
  overflow the models; they are rejected with :class:`~woundroll.errors.InputError` naming the
  field and the range;
* the **plausible** range: values outside it are legal but unusual for a production roll; the
  case loads and carries a warning (:attr:`woundroll.case.Case.warnings`), which the CLI prints
  before the run and the result records.

Work bounds: the 1D winding solves one increment per layer (``layers_per_increment`` lumps
them). :func:`winding_estimate` estimates its time on the path ``wind`` will take
(``WindingOptions.kernels``): the compiled kernels, ``a n (1 + n / n0)`` for ``n``
increments (the per-increment cost grows slowly with the roll: the lazy deep part's levels),
or the NumPy twin of a small roll, linear in ``n``; both scale with the nodes per layer. The
constants are fitted to benchmarks/bench_limits.py (its table in docs/case-files.md) as
multiples of the yardstick, converted to seconds by the development machine's quiet
yardstick. A run estimated above :data:`LONG_RUN_SECONDS` gets a warning with the estimate;
more than :data:`MAX_INCREMENTS` increments are rejected.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from woundroll.errors import InputError


@dataclass(frozen=True)
class Limit:
    """Hard and plausible SI range of one quantity, with the reason and a display unit."""

    hard: tuple[float, float]
    plausible: tuple[float, float]
    unit: str
    scale: float
    reason: str

    def fmt(self, v: float) -> str:
        return f"{v / self.scale:.3g} {self.unit}".rstrip()


_GPA, _MM, _UM = 1e9, 1e-3, 1e-6

#: Limits per dotted case key (docs/case-files.md, "Limits").
LIMITS: dict[str, Limit] = {
    "web.thickness": Limit(
        (0.1 * _UM, 50 * _MM),
        (1 * _UM, 5 * _MM),
        "um",
        _UM,
        "the thinnest wound films are about 1 um (capacitor film), board and nonwovens a few mm",
    ),
    "web.width": Limit(
        (1 * _MM, 20.0),
        (1e-2, 12.0),
        "m",
        1.0,
        "slit rolls from about 1 cm; the widest paper machines make about 11 m",
    ),
    "web.E_theta": Limit(
        (1e5, 1.2e12),
        (1e7, 3e11),
        "GPa",
        _GPA,
        "nonwovens from about 10 MPa to steel strip at 210 GPa; nothing is stiffer than "
        "diamond (1.2 TPa)",
    ),
    "web.E_z": Limit(
        (1e5, 1.2e12),
        (1e7, 3e11),
        "GPa",
        _GPA,
        "as web.E_theta",
    ),
    "web.density": Limit(
        (1.0, 25000.0),
        (50.0, 20000.0),
        "kg/m^3",
        1.0,
        "from open nonwovens (about 50 kg/m^3) to gold foil (19,300); osmium, the densest "
        "element, is 22,600",
    ),
    "web.G_r_theta": Limit((1e3, 1.2e12), (1e5, 3e11), "MPa", 1e6, "as the moduli"),
    "web.G_r_z": Limit((1e3, 1.2e12), (1e5, 3e11), "MPa", 1e6, "as the moduli"),
    "web.G_theta_z": Limit((1e3, 1.2e12), (1e5, 3e11), "MPa", 1e6, "as the moduli"),
    "web.radial_modulus": Limit(
        (0.0, 1.2e12),
        (0.0, 1e10),
        "MPa",
        1e6,
        "E_r of the unloaded stack (P = 0): a stack of sheets is far softer across its layers "
        "than a solid of the same material",
    ),
    "core.outer_radius": Limit(
        (1 * _MM, 2.5),
        (5 * _MM, 0.5),
        "cm",
        1e-2,
        "from 1 cm tape cores to large paper-reel spools (about 0.3 m)",
    ),
    "core.E": Limit((1e5, 1.2e12), (1e7, 3e11), "GPa", _GPA, "cardboard to steel"),
    "core.stiffness": Limit(
        (1e3, math.inf), (1e6, math.inf), "MPa", 1e6, "cardboard cores are about 100 MPa"
    ),
    "winding.outer_radius": Limit(
        (1 * _MM, 5.0),
        (5 * _MM, 2.0),
        "m",
        1.0,
        "the largest paper reels are about 4 m in diameter",
    ),
    "winding.nip_load": Limit(
        (0.0, 1e6),
        (0.0, 35e3),
        "pli",
        175.126835,
        "winders run up to about 200 pli (35 kN/m); calender nips about 2,000 pli",
    ),
    #: wound-on stress (tension + mu N / h) over E_theta: the web's elastic strain
    "winding.tension": Limit(
        (0.0, 0.1),
        (1e-4, 0.01),
        "%",
        1e-2,
        "webs are wound at about 0.05 to 0.5 % strain (tension / E_theta); above about 1 % "
        "films yield and paper breaks; no web stays elastic at 10 %",
    ),
    #: largest radial pressure computed in the roll
    "pressure": Limit(
        (0.0, math.inf),
        (0.0, 10e6),
        "MPa",
        1e6,
        "stack tests, to which radial-modulus laws are fitted, rarely go beyond a few MPa, and "
        "measured roll pressures stay below that",
    ),
    "tester.mass": Limit(
        (1e-3, 100.0), (1e-2, 10.0), "kg", 1.0, "hand-held strikers: 10 g to 1 kg"
    ),
    "tester.spring_stiffness": Limit(
        (1.0, 1e7), (10.0, 1e6), "N/m", 1.0, "hand-held testers' springs: 100 N/m to 10 kN/m"
    ),
    "tester.release_position": Limit(
        (0.1 * _MM, 1.0), (1 * _MM, 0.2), "cm", 1e-2, "strokes of hand-held testers: 1-10 cm"
    ),
    "tester.head_radius": Limit(
        (0.1 * _MM, 0.5), (0.5 * _MM, 0.05), "mm", _MM, "striker heads: a few mm to a few cm"
    ),
    "tester.head_length": Limit(
        (0.1 * _MM, 2.0), (1 * _MM, 0.2), "mm", _MM, "striker heads: a few mm to a few cm"
    ),
    "tester.roll_spring.alpha": Limit(
        (0.0, 1e16), (0.0, 1e14), "N/m^2", 1.0, "a steel block under the Rho-meter is ~1e12"
    ),
    "tester.roll_spring.beta": Limit(
        (0.0, 1e11), (0.0, 1e10), "N/m", 1.0, "a steel block under a cylinder head is ~1e9"
    ),
    "tester.roll_spring.effective_mass": Limit(
        (0.0, 1e3), (0.0, 100.0), "kg", 1.0, "the active mass of a roll is grams to kilograms"
    ),
}

#: FD steps per contact at most (tester.steps_per_contact, or contact time / time_step): the
#: FD error falls as 1/N^2 and is below 1e-6 of the reading at 2,000; 100,000 steps take about
#: 0.3 s per reading.
MAX_STEPS_PER_CONTACT = 100_000
#: Winding increments at most (a bound on the work and the result's size; the compiled
#: winding takes :func:`winding_estimate` of it, about 10 s, docs/case-files.md).
MAX_INCREMENTS = 1_000_000
#: A run estimated longer than this gets a warning with the estimate [s].
LONG_RUN_SECONDS = 20.0


def check(key: str, value: float, *, field: str | None = None, what: str = "") -> str | None:
    """Raise beyond the hard range of ``key``; return a warning beyond the plausible one."""
    lim = LIMITS[key]
    fld = field or key
    lo, hi = lim.hard
    name = what or "value"
    if not (lo <= value <= hi):
        raise InputError(
            f"{name} {lim.fmt(value)} is outside the physical range "
            f"[{lim.fmt(lo)}, {lim.fmt(hi)}]: {lim.reason}",
            fld,
        )
    plo, phi = lim.plausible
    if not (plo <= value <= phi):
        return (
            f"{fld}: {name} {lim.fmt(value)} is outside the usual range "
            f"[{lim.fmt(plo)}, {lim.fmt(phi)}] ({lim.reason}); check it"
        )
    return None


#: The yardstick (benchmarks/yardstick.py) on the development machine when it is quiet [s]
#: (2.46-2.76 s in the benchmarks of docs/performance.md and docs/diagnosis.md): the
#: estimates below are fitted as multiples of it and converted to seconds by it. Machines
#: differ up to 2.5x in speed from one to the next and from hour to hour (yardstick.py), so
#: an estimate may be off by that factor either way on another machine or under load: the
#: warnings say "about".
YARDSTICK_SECONDS = 2.5
#: The compiled winding per increment of 2 nodes a layer, ``a`` [s], and the increments
#: ``n0`` over which its per-increment cost doubles: fitted on 2026-11-26 to
#: benchmarks/bench_limits.py (10,000-1,000,000 layers: 2.75-3.4e-6 yardsticks a layer,
#: growing with the lazy deep part's levels), 2.9e-6 x YARDSTICK_SECONDS.
WINDING_COMPILED_SECONDS = 7.3e-6
WINDING_COMPILED_DOUBLING = 5e6
#: The NumPy twin per increment of 2 nodes a layer [s] (a small roll, or a roll of up to
#: 2,000 layers on a machine that has not built the compiled kernels): 1.8e-4 yardsticks a
#: layer over 500-4,000 layers (bench_limits.py, 2026-11-26).
WINDING_NUMPY_SECONDS = 4.5e-4


@dataclass(frozen=True)
class WindingEstimate:
    """The 1D winding's estimated time [s] and the kernels it was estimated for."""

    seconds: float
    kernels: str


def winding_estimate(
    increments: int, nodes_per_layer: int = 2, kernels: str = "compiled"
) -> WindingEstimate:
    """Estimated time of the 1D winding solve on the path ``kernels`` (what
    ``WindingOptions.kernels`` says ``wind`` will run: ``"compiled"``, ``"numpy"`` or
    ``"compiled if built, else numpy"``, estimated as the slower NumPy twin), module
    docstring. Without the compiled kernels' one-off build on a new machine (~15 s)."""
    n = float(increments)
    scale = max(nodes_per_layer, 1) / 2.0
    if kernels == "compiled":
        t = WINDING_COMPILED_SECONDS * n * (1.0 + n / WINDING_COMPILED_DOUBLING)
    else:
        t = WINDING_NUMPY_SECONDS * n
    return WindingEstimate(t * scale, kernels)


def winding_seconds(increments: int, nodes_per_layer: int = 2) -> float:
    """Estimated time [s] of the compiled 1D winding solve (:func:`winding_estimate`)."""
    return winding_estimate(increments, nodes_per_layer).seconds


def fmt_seconds(t: float) -> str:
    """``"40 s"``, ``"3.2 min"``, ``"1.5 h"``."""
    if t < 120:
        return f"{t:.0f} s"
    if t < 7200:
        return f"{t / 60:.1f} min"
    return f"{t / 3600:.1f} h"


def max_compliant_radial_modulus(
    E_theta: float, E_z: float, nu_theta_r: float, nu_z_r: float, nu_theta_z: float
) -> float:
    """Largest E_r [Pa] for which the orthotropic compliance is positive definite.

    Compliance (r, theta, z) with ``nu_ij / E_i = nu_ji / E_j`` (docs/case-files.md):
    ``S = [[1/E_r, -nu_tr/E_t, -nu_zr/E_z], [., 1/E_t, -nu_tz/E_t], [., ., 1/E_z]]``. With the
    (theta, z) block positive definite, ``det S`` is linear in ``1/E_r``:
    ``det S = M / E_r + D0`` (``M`` the block's determinant, ``D0`` det S with S_rr = 0), so S
    is positive definite for ``E_r < M / (-D0)`` (any E_r when ``D0 >= 0``). Returns 0 when the
    (theta, z) block itself is not positive definite.
    """
    s_tr, s_zr, s_tz = -nu_theta_r / E_theta, -nu_z_r / E_z, -nu_theta_z / E_theta
    M = 1.0 / (E_theta * E_z) - s_tz**2
    if not M > 0:
        return 0.0
    S0 = np.array([[0.0, s_tr, s_zr], [s_tr, 1.0 / E_theta, s_tz], [s_zr, s_tz, 1.0 / E_z]])
    D0 = float(np.linalg.det(S0))
    return math.inf if D0 >= 0 else M / -D0


def check_case_values(spec: Any) -> list[str]:
    """Hard and plausible ranges of the values a :class:`~woundroll.case.Case` holds."""
    warnings: list[str] = []

    def add(w: str | None) -> None:
        if w:
            warnings.append(w)

    web = spec.web
    for name in ("thickness", "width", "E_theta", "E_z", "density", "G_r_theta", "G_r_z"):
        v = getattr(web, name)
        if v is not None:
            add(check(f"web.{name}", v))
    if web.G_theta_z is not None:
        add(check("web.G_theta_z", web.G_theta_z))
    core = spec.core
    add(check("core.outer_radius", core.outer_radius))
    if core.E is not None:
        add(check("core.E", core.E))
    if core.stiffness is not None:
        add(check("core.stiffness", core.stiffness))
    w = spec.winding
    if w.outer_radius is not None:
        add(check("winding.outer_radius", w.outer_radius))
    add(check("winding.nip_load", w.nip_load))
    return warnings


def check_built(
    web: Any,
    core: Any,
    r_out: float,
    schedule: Any,
    options: Any,
    size_field: str = "winding.outer_radius",
) -> list[str]:
    """Limits that need the built web, core and schedule: E_r, Poisson ratios, size, tension,
    and the expected time of the winding solve. ``size_field``: the key the user gave the
    roll's size by (``winding.length`` makes ``r_out``; its errors name that key)."""
    warnings: list[str] = []

    def add(w: str | None) -> None:
        if w:
            warnings.append(w)

    _check_radial_modulus(web, warnings)
    by_length = size_field == "winding.length"
    what = "outer radius (from the length)" if by_length else "value"
    add(check("winding.outer_radius", r_out, field=size_field, what=what))
    _check_solve_size(web, core, r_out, options, size_field, warnings)
    # wound-on stress: tapered tension + mu N / h, as a strain of the web
    s = np.linspace(core.outer_radius, r_out, 64)
    T = np.asarray(
        schedule.wound_on_tension(s, core.outer_radius, r_out, web.thickness), dtype=float
    )
    strain = float(np.max(T)) / web.E_theta
    nip = schedule.friction * schedule.nip_load / web.thickness
    extra = f", of which mu N / h = {nip / 1e6:.3g} MPa" if nip > 0 else ""
    add(
        check(
            "winding.tension",
            strain,
            what=f"wound-on stress {float(np.max(T)) / 1e6:.3g} MPa{extra}, a strain of",
        )
    )
    return warnings


def _check_radial_modulus(web: Any, warnings: list[str]) -> None:
    """E_r finite at zero and at 100 MPa pressure, within its limits, below E_theta (a
    warning), and the Poisson ratios' compliance positive definite."""
    E_r0 = float(np.asarray(web.E_r(0.0)))
    if not math.isfinite(E_r0):
        raise InputError("E_r of the unloaded stack is not a finite number", "web.radial_modulus")
    w = check("web.radial_modulus", E_r0, what="E_r at zero pressure")
    if w:
        warnings.append(w)
    E_r_big = float(np.asarray(web.E_r(-100e6)))
    if not math.isfinite(E_r_big) or E_r_big > 1e15:
        raise InputError(
            f"E_r at 100 MPa pressure is {E_r_big:.3g} Pa: the law overflows within the "
            "pressures a roll can hold (check K2 and the law's units)",
            "web.radial_modulus",
        )
    if E_r0 > web.E_theta:
        warnings.append(
            f"web.radial_modulus: E_r at zero pressure ({E_r0 / 1e6:.3g} MPa) exceeds E_theta "
            f"({web.E_theta / 1e6:.3g} MPa); a stack is normally much softer across its layers"
        )
    e_max = max_compliant_radial_modulus(
        web.E_theta, web.E_z, web.nu_theta_r, web.nu_z_r, web.nu_theta_z
    )
    if e_max == 0.0:
        raise InputError(
            f"nu_theta_z = {web.nu_theta_z:g} with E_z / E_theta = {web.E_z / web.E_theta:.3g} "
            "makes the in-plane compliance not positive definite (needs nu_theta_z^2 E_z / "
            "E_theta < 1)",
            "web.nu_theta_z",
        )
    if E_r0 >= e_max:
        raise InputError(
            f"the Poisson ratios nu_theta_r = {web.nu_theta_r:g}, nu_z_r = {web.nu_z_r:g} make "
            f"the compliance not positive definite already at zero pressure (E_r = "
            f"{E_r0 / 1e6:.3g} MPa; the ratios allow E_r up to {e_max / 1e6:.3g} MPa)",
            "web.nu_theta_r",
        )


def _check_solve_size(
    web: Any, core: Any, r_out: float, options: Any, size_field: str, warnings: list[str]
) -> None:
    """The winding increments: at most MAX_INCREMENTS, a warning for a long run."""
    n = int(round((r_out - core.outer_radius) / web.thickness))
    inc = math.ceil(n / options.layers_per_increment)
    if inc > MAX_INCREMENTS:
        raise InputError(
            f"{n:.3g} layers make {inc:.3g} winding increments, more than {MAX_INCREMENTS:,} "
            f"(about {fmt_seconds(winding_seconds(MAX_INCREMENTS, options.subdivisions))} of "
            "solving): lump layers with winding.options.layers_per_increment, or wind a "
            "smaller roll",
            size_field if n else "web.thickness",
        )
    est = winding_estimate(inc, options.subdivisions, options.kernels(n))
    if est.seconds > LONG_RUN_SECONDS:
        warnings.append(
            f"long run: {n:,} layers ({inc:,} winding increments) take about "
            f"{fmt_seconds(est.seconds)} to wind with the {est.kernels} kernels "
            "(winding.options.layers_per_increment lumps layers)"
        )


#: Contact-model times measured on the development machine (2 cores, loaded), per solution:
#: PET 100 um (890 layers) 1.4 s, 50 um (1,500 layers) 1.5 s, 23 um (4,565 layers) 100 s (its
#: mesh follows the web thickness near the surface); the bundled PET3 profile (76 um, 61
#: sectors, 2 workers) 16 s whole process on a quiet machine (2026-11-23, docs/performance.md;
#: it was 2.5 min before the issue-14 work).
THIN_WEB_CONTACT = 30e-6
PROFILE_REFERENCE_SECONDS = 16.0


def contact_time_warning(case: Any, web: Any) -> str | None:
    """A warning before runs whose contact solutions will take long (constants above)."""
    if case.winding.thickness_profile is not None:
        p = case.profile
        t = PROFILE_REFERENCE_SECONDS * (p.sectors / 61) * (2 / p.workers)
        if t > LONG_RUN_SECONDS:
            return (
                f"long run: a CMD profile solves the contact model for each of {p.sectors} "
                f"sectors on {p.workers} workers: about {fmt_seconds(t)} (scaled from the "
                "bundled pet3 case; thinner webs take longer; profile.sectors and "
                "profile.workers set it)"
            )
        return None
    if case.tester is not None and "roll_spring" not in case.tester:
        if web.thickness < THIN_WEB_CONTACT:
            return (
                f"long run: the contact model's mesh follows the web thickness "
                f"({web.thickness * 1e6:.3g} um): a 23 um web took about 100 s per contact "
                "solution here, a 100 um web 1.4 s (contact.no_update = false saves one)"
            )
    return None


def pressure_warning(max_pressure: float) -> str | None:
    """A warning when the largest radial pressure in the roll is beyond the plausible range."""
    return check("pressure", max_pressure, field="winding", what="largest radial pressure")
