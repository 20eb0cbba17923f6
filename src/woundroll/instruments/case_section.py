"""The case file's ``[tester]`` table, and one hardness reading from a roll spring.

Example::

    [tester]
    instrument = "rho-meter"          # a preset (woundroll.instruments.list_instruments())
    head_radius = "1 cm"              # any instrument field, with units
    collision = "plastic"             # or "keep-velocity" (the paper's eq. {9})
    time_step = "1 us"                # optional; default: contact time / steps_per_contact
    pile_height = "8.89 cm"           # H of the tapered column {17}
    semi_contact_width = "0.6 cm"     # a of {14}-{18} (paper: 0.6 cm accepted)
    restitution = 1.0                 # energetic coefficient of restitution of the roll

    [tester.roll_spring]              # optional: bypasses the contact model
    alpha = "3.7e8 N/m^2"
    beta = "5.4e5 N/m"
    effective_mass = "0 kg"           # optional; omitted: the tapered-column mass {14}-{18}

Active roll mass
    ``[tester.roll_spring] effective_mass`` replaces the tapered-column mass (0 means a massless
    roll). Without it -- and always with the contact model -- the active mass is the tapered
    column's ``m_r = kappa rho (2a + H) H L`` {14}-{18}: pile height H and density rho from
    ``[tester] pile_height`` / ``density`` if given, else from the caller (the pipeline passes
    H = outer minus core radius and the web's density), a = ``semi_contact_width``
    (default 0.6 cm), L the head length. :meth:`TesterSetup.effective_mass` and
    :func:`hardness_from_spring` implement that rule.

The pipeline passes the JSON of :meth:`HardnessResult.to_dict` under the key ``hardness``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.instruments.definitions import Instrument, as_shown, beyond_scale, get_instrument
from woundroll.instruments.impact import (
    COLLISIONS,
    EnergyResult,
    ImpactResult,
    impact_energy,
    impact_fd,
)
from woundroll.instruments.roll_side import RollSpring, roll_effective_mass
from woundroll.limits import MAX_STEPS_PER_CONTACT
from woundroll.limits import check as check_limit
from woundroll.units import to_si

__all__ = ["HardnessResult", "TesterSetup", "hardness_from_spring", "tester_from_spec"]

#: Default semi-contact width a of the tapered column (the paper: "0.6 cm can be accepted").
DEFAULT_SEMI_CONTACT_WIDTH = 0.006

_INSTRUMENT_FIELDS = {f.name for f in fields(Instrument)} - {"name", "sources", "notes", "title"}
_OPTION_KINDS = {
    "time_step": "time",
    "pile_height": "length",
    "semi_contact_width": "length",
    "density": "density",
    "restitution": "dimensionless",
    "active_mass": "mass",
}
_ROLL_SPRING_KINDS = {
    "alpha": "force_per_area",
    "beta": "stiffness",
    "effective_mass": "mass",
    "restitution": "dimensionless",
}


@dataclass(frozen=True)
class TesterSetup:
    """Everything the impact models need besides the roll's stiffness (SI).

    Attributes
    ----------
    instrument : Instrument
        Preset with the case's overrides.
    collision : str
        "plastic" (default) or "keep-velocity".
    time_step : float or None [s]
    steps_per_contact : int
    pile_height : float or None [m]
        H of {17}; None: the pipeline supplies it (outer minus core radius).
    semi_contact_width : float [m]
        a of {14}-{18}.
    density : float or None [kg/m^3]
        Roll density for {18}; None: the pipeline supplies the web's.
    restitution : float [-]
        Energetic coefficient of restitution of the roll (1 = elastic, the paper).
    roll_spring : RollSpring or None
        Explicit roll spring from ``[tester.roll_spring]`` (bypasses the contact model).
    roll_mass_from_column : bool
        True when ``[tester.roll_spring]`` omits ``effective_mass``: the active mass is then
        the tapered column's {14}-{18}, not ``roll_spring.effective_mass`` (which is 0).
    field : str
        Dotted name of the table (for messages).
    """

    instrument: Instrument
    collision: str = COLLISIONS[0]
    time_step: float | None = None
    steps_per_contact: int = 2000
    pile_height: float | None = None
    semi_contact_width: float = DEFAULT_SEMI_CONTACT_WIDTH
    density: float | None = None
    restitution: float = 1.0
    roll_spring: RollSpring | None = None
    roll_mass_from_column: bool = False
    field: str = field(default="tester", compare=False)
    #: ``[tester] active_mass`` [kg]: replaces the tapered-column mass {14}-{18} (e.g. the
    #: active mass the dynamic FE roll shows, ``woundroll study dynamic``); an explicit
    #: ``[tester.roll_spring] effective_mass`` still wins.
    active_mass: float | None = None

    def effective_mass(
        self, pile_height: float | None = None, density: float | None = None
    ) -> float:
        """Active roll mass [kg]: the explicit one, else ``kappa rho (2a + H) H L`` {14}-{18}.

        Parameters
        ----------
        pile_height : float, optional [m]
            H of {17} when ``[tester] pile_height`` is not given (the pipeline passes the outer
            minus the core radius).
        density : float, optional [kg/m^3]
            Roll density when ``[tester] density`` is not given (the pipeline passes the web's).

        The explicit ``[tester.roll_spring] effective_mass`` (0 allowed) is returned as is.
        Otherwise the tapered column {14}-{18} with a = ``semi_contact_width``; the setup's own
        ``pile_height`` / ``density`` take precedence over the arguments; the CMD length is the
        head length, or ``2 a`` for a head without one (spherical tip).

        Raises
        ------
        InputError
            No pile height or no density for the tapered column (field ``<table>.pile_height``
            or ``<table>.density``).
        """
        if self.roll_spring is not None and not self.roll_mass_from_column:
            return self.roll_spring.effective_mass
        if self.active_mass is not None:
            return self.active_mass
        H = self.pile_height if self.pile_height is not None else pile_height
        rho = self.density if self.density is not None else density
        hint = (
            " (or give [tester.roll_spring] effective_mass)" if self.roll_spring is not None else ""
        )
        for value, name in ((H, "pile_height"), (rho, "density")):
            if value is None:
                raise InputError(
                    f"the roll's active mass (tapered column {{14}}-{{18}}) needs {name}{hint}",
                    f"{self.field}.{name}",
                )
        L = self.instrument.head_length or 2.0 * self.semi_contact_width
        return roll_effective_mass(self.semi_contact_width, H, rho, L)


def _get_str(spec: dict[str, Any], key: str, fld: str) -> str:
    v = spec[key]
    if not isinstance(v, str):
        raise InputError(f"must be text, got {v!r}", fld)
    return v


def _impact_option(spec: dict[str, Any], key: str, value: Any, fld: str) -> Any:
    """One option of the impact: the collision model, the FD resolution, or a quantity of
    :data:`_OPTION_KINDS` in SI (checked)."""
    if key == "collision":
        v = _get_str(spec, key, fld)
        if v not in COLLISIONS:
            raise InputError(f"must be one of {', '.join(COLLISIONS)}, got {v!r}", fld)
        return v
    if key == "steps_per_contact":
        if (
            isinstance(value, bool)
            or not isinstance(value, int)
            or not 20 <= value <= MAX_STEPS_PER_CONTACT
        ):
            raise InputError(
                f"must be an integer from 20 to {MAX_STEPS_PER_CONTACT:,}, got {value!r} "
                f"(the FD error falls as 1/N^2: the default 2000 is converged to 1e-6; each "
                "step is kept in the impact's history)",
                fld,
            )
        return value
    v = to_si(value, _OPTION_KINDS[key], fld)
    if key == "restitution":
        if not 0.0 < v <= 1.0:
            raise InputError(f"must lie in (0, 1], got {v:g}", fld)
    elif key == "active_mass":
        if not (math.isfinite(v) and v >= 0):
            raise InputError(f"must be zero or positive, got {v:g}", fld)
    elif v <= 0:
        raise InputError(f"must be positive, got {v:g}", fld)
    return v


def _overridden(inst: Any, overrides: dict[str, Any], field: str) -> Any:
    """The instrument with the case's overrides, every limited field checked, also those
    derived from an override (mass from omega {1})."""
    inst = inst.with_overrides(field_prefix=field, **overrides)
    for key in ("mass", "spring_stiffness", "release_position", "head_radius", "head_length"):
        if getattr(inst, key) is not None:
            fld = (
                key
                if key in overrides or "natural_frequency" not in overrides
                else ("natural_frequency")
            )
            check_limit(
                f"tester.{key}",
                getattr(inst, key),
                field=f"{field}.{fld}",
                what=key.replace("_", " "),
            )
    return inst


def tester_from_spec(spec: dict[str, Any], field: str = "tester") -> TesterSetup:
    """Read a case file's ``[tester]`` table (module docstring) into a :class:`TesterSetup`.

    Parameters
    ----------
    spec : dict
        The parsed TOML table.
    field : str
        Its dotted name, used in error messages.

    Raises
    ------
    InputError
        Unknown key, unknown instrument, wrong unit or bad value, naming the dotted field.
    """
    if not isinstance(spec, dict):
        raise InputError("must be a table", field)
    spec = dict(spec)
    name = "rho-meter"
    if "instrument" in spec:
        name = _get_str(spec, "instrument", f"{field}.instrument")
    inst = get_instrument(name, f"{field}.instrument")
    overrides: dict[str, Any] = {}
    opts: dict[str, Any] = {}
    roll_spring = None
    for key, value in spec.items():
        fld = f"{field}.{key}"
        if key == "instrument":
            continue
        if key in _INSTRUMENT_FIELDS:
            overrides[key] = value
        elif key in ("collision", "steps_per_contact") or key in _OPTION_KINDS:
            opts[key] = _impact_option(spec, key, value, fld)
        elif key == "roll_spring":
            roll_spring = value  # built below, once the restitution is known
        else:
            known = sorted(
                set(_INSTRUMENT_FIELDS)
                | set(_OPTION_KINDS)
                | {"instrument", "collision", "steps_per_contact", "roll_spring"}
            )
            raise InputError(f"unknown key (known: {', '.join(known)})", fld)
    from_column = False
    if roll_spring is not None:
        from_column = isinstance(roll_spring, dict) and "effective_mass" not in roll_spring
        roll_spring = _roll_spring(
            roll_spring, f"{field}.roll_spring", opts.get("restitution", 1.0)
        )
    if overrides:
        inst = _overridden(inst, overrides, field)
    return TesterSetup(
        instrument=inst,
        roll_spring=roll_spring,
        roll_mass_from_column=from_column,
        field=field,
        **opts,
    )


tester_from_spec.__test__ = False  # type: ignore[attr-defined]  # not a pytest test


def _check_time_step(setup: TesterSetup, spring: RollSpring, en: EnergyResult) -> None:
    """Reject a ``time_step`` that would resolve the contact with more than
    :data:`~woundroll.limits.MAX_STEPS_PER_CONTACT` steps (the FD keeps a history per step).

    Contact duration from the energy model's depth: half the period of the striker and roll
    masses on the secant stiffness ``F(d_max)/d_max + k_s`` (the estimate the FD model uses).
    """
    inst = setup.instrument
    d = float(en.max_depth)
    k_sec = (float(en.peak_force) / d if d > 0 else 0.0) + inst.spring_stiffness
    T = math.pi * math.sqrt((inst.mass + spring.effective_mass) / k_sec)
    steps = T / setup.time_step
    if steps > MAX_STEPS_PER_CONTACT:
        raise InputError(
            f"{setup.time_step:.3g} s resolves the contact of about {T:.3g} s with "
            f"{steps:.3g} steps; at most {MAX_STEPS_PER_CONTACT:,} are allowed (the FD error "
            f"falls as 1/N^2 and its history grows with N): use at least "
            f"{T / MAX_STEPS_PER_CONTACT:.3g} s, or omit time_step",
            f"{setup.field}.time_step",
        )


def _roll_spring(value: Any, fld: str, restitution: float) -> RollSpring:
    if not isinstance(value, dict):
        raise InputError("must be a table with alpha, beta and (optional) effective_mass", fld)
    for key in value:
        if key not in _ROLL_SPRING_KINDS:
            raise InputError(
                f"unknown key (known: {', '.join(_ROLL_SPRING_KINDS)})", f"{fld}.{key}"
            )
    for key in ("alpha", "beta"):
        if key not in value:
            raise InputError("missing", f"{fld}.{key}")
    vals = {k: to_si(v, _ROLL_SPRING_KINDS[k], f"{fld}.{k}") for k, v in value.items()}
    for k in ("alpha", "beta", "effective_mass"):
        if k in vals:
            check_limit(f"tester.roll_spring.{k}", vals[k], field=f"{fld}.{k}")
    e = vals.get("restitution", restitution)
    try:
        return RollSpring.quadratic(vals["alpha"], vals["beta"], vals.get("effective_mass", 0.0), e)
    except InputError as exc:
        tail = exc.field.split(".", 1)[1] if exc.field and "." in exc.field else ""
        raise InputError(exc.message, f"{fld}.{tail}" if tail else fld) from None


@dataclass(frozen=True)
class HardnessResult:
    """One simulated reading: FD and energy model for one roll spring.

    Attributes
    ----------
    instrument : Instrument
    alpha, beta : float [N/m^2], [N/m]
    effective_mass : float [kg]
    fd : ImpactResult
    energy : EnergyResult
    """

    instrument: Instrument
    alpha: float
    beta: float
    effective_mass: float
    restitution: float
    fd: ImpactResult
    energy: EnergyResult

    @property
    def reading(self) -> float:
        """The instrument's own reading (its ``readout``), from the FD model."""
        ro = self.instrument.readout
        if ro == "rho":
            return self.fd.rho
        if ro == "g":
            return self.fd.peak_g
        if ro == "schmidt-r":
            return self.fd.rebound_r
        return self.fd.rebound_l

    @property
    def saturated(self) -> bool:
        """The model's :attr:`reading` lies beyond the instrument's scale: the device
        shows the scale's end (:attr:`shown`)."""
        return bool(beyond_scale(self.reading, self.instrument.reading_range))

    @property
    def shown(self) -> float:
        """What the instrument shows: :attr:`reading` clipped to its scale."""
        return float(as_shown(self.reading, self.instrument.reading_range))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: SI scalars (unit in the key) and time histories.

        ``reading``: what the instrument shows (its scale's end when ``saturated``);
        ``reading_model``: the model's own value.
        """
        fd = self.fd

        def lst(a: NDArray[np.float64]) -> list[float]:
            return [float(x) for x in a]

        return {
            "instrument": self.instrument.name,
            "readout": self.instrument.readout,
            "reading": self.shown,
            "reading_model": float(self.reading),
            "saturated": self.saturated,
            "scale": None
            if self.instrument.reading_range is None
            else list(self.instrument.reading_range),
            "head_calibration": {
                "head_radius_m": float(self.instrument.head_radius),
                "head_length_m": self.instrument.head_length,
                "calibrated_in": self.instrument.calibration_model or None,
                "source": self.instrument.sources.get("head_radius"),
                "head_length_source": self.instrument.sources.get("head_length"),
            },
            "rho_energy": float(self.energy.rho),
            "rho_fd": float(fd.rho),
            "peak_g": float(fd.peak_g),
            "rebound_R": float(fd.rebound_r),
            "parotester_L": float(fd.rebound_l),
            "impulse_N_s": float(fd.impulse),
            "impact_depth_m": float(fd.max_depth),
            "impact_depth_energy_m": float(self.energy.max_depth),
            "peak_force_N": float(fd.peak_force),
            "peak_force_energy_N": float(self.energy.peak_force),
            "peak_deceleration_m_per_s2": float(fd.peak_deceleration),
            "contact_time_s": float(fd.contact_time),
            "impact_speed_m_per_s": float(fd.impact_speed),
            "rebound_speed_m_per_s": float(fd.rebound_speed),
            "alpha_N_per_m2": float(self.alpha),
            "beta_N_per_m": float(self.beta),
            "effective_mass_kg": float(self.effective_mass),
            "restitution": float(self.restitution),
            "rebound": (
                "elastic (no unloading law): rebound readings lose energy only to the "
                "roll's active mass"
                if self.restitution >= 1.0
                else f"roll unloading: the roll returns e^2 = {self.restitution**2:.3f} of "
                "the energy it stored"
            ),
            "collision": fd.collision,
            "time_step_s": float(fd.time_step),
            "time_s": lst(fd.time),
            "depth_m": lst(fd.position - self.instrument.contact_position),
            "velocity_m_per_s": lst(fd.velocity),
            "force_N": lst(fd.contact_force),
            "deceleration_m_per_s2": lst(fd.deceleration),
        }

    def plot(self, path: str | None = None) -> Any:
        """Contact force and striker deceleration against time, stacked; returns the Figure.

        Top panel: contact force on the striker [N]. Bottom panel: the deceleration the
        accelerometer feels [Rho, right axis in g], split into its two parts, the contact
        force ``f/m_s`` and the striker spring ``k_s x/m_s`` (the part the energy model's {22}
        leaves out). Separate panels because, with a light roll, force and deceleration are
        nearly proportional and would lie on top of each other on twin axes.

        Parameters
        ----------
        path : str, optional
            Save a PNG there.
        """
        import matplotlib.pyplot as plt

        fd = self.fd
        inst = self.instrument
        t_ms = (fd.time - fd.contact_start) * 1e3
        rho = inst.rho_unit
        a_spring = inst.spring_stiffness * fd.position / inst.mass
        a_contact = fd.contact_force / inst.mass
        fig, (ax, ax2) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
        ax.plot(t_ms, fd.contact_force, color="C0", lw=2.0, label="contact force f (FD)")
        ax.axhline(
            self.energy.peak_force,
            color="C0",
            ls=":",
            lw=1.0,
            label=f"energy model F(d_max) = {self.energy.peak_force:.0f} N",
        )
        ax.set_ylabel("contact force [N]")
        ax.set_ylim(0.0, 1.3 * max(float(fd.contact_force.max()), self.energy.peak_force))
        ax.legend(loc="upper center", fontsize=8, ncol=2)
        ax.grid(alpha=0.3)
        total = fd.deceleration / rho
        ax2.plot(t_ms, total, color="C1", lw=2.0, label="total (accelerometer), FD")
        ax2.plot(t_ms, a_contact / rho, color="C2", ls="--", lw=1.2, label="contact force f/m_s")
        ax2.fill_between(
            t_ms,
            a_contact / rho,
            total,
            color="C3",
            alpha=0.5,
            lw=0,
            label="+ striker spring (not in {22})",
        )
        ax2.plot(t_ms, a_spring / rho, color="C3", lw=1.0, label="striker spring k_s x/m_s")
        ax2.axhline(self.energy.rho, color="C4", ls=":", lw=1.0, label="energy model {22}")
        ax2.annotate(
            f"peak {fd.rho:.1f} Rho",
            (t_ms[int(fd.deceleration.argmax())], fd.rho),
            textcoords="offset points",
            xytext=(0, 6),
            ha="center",
            fontsize=8,
            color="C1",
        )
        ax2.set_ylabel("striker deceleration [Rho]")
        ax2.set_xlabel("time from contact [ms]")
        ax2.legend(loc="upper center", fontsize=7.5, ncol=2)
        ax2.set_ylim(0.0, 1.45 * max(fd.rho, self.energy.rho))
        ax2.grid(alpha=0.3)
        per_g = inst.rho_per_g
        sec = ax2.secondary_yaxis("right", functions=(lambda r: r * per_g, lambda g: g / per_g))
        sec.set_ylabel("[g]")
        ax.set_title(
            f"{inst.title or inst.name}: FD {fd.rho:.1f} Rho, energy {self.energy.rho:.1f} Rho, "
            f"impulse {fd.impulse:.3f} N s, m_r = {1e3 * self.effective_mass:.1f} g",
            fontsize=9,
        )
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def hardness_from_spring(
    setup: TesterSetup,
    alpha: float | None = None,
    beta: float | None = None,
    effective_mass: float | None = None,
    *,
    pile_height: float | None = None,
    density: float | None = None,
) -> HardnessResult:
    """Run the FD model {4}-{13} and the energy model {19}-{22} for one roll spring.

    Parameters
    ----------
    setup : TesterSetup
    alpha, beta : float, optional [N/m^2], [N/m]
        Roll spring {3}; default: the setup's ``[tester.roll_spring]``.
    effective_mass : float, optional [kg]
        Active roll mass m_r (0 allowed). Default: ``setup.effective_mass(pile_height,
        density)``, i.e. the explicit ``[tester.roll_spring] effective_mass`` if the case gives
        one, else the tapered-column mass {14}-{18}.
    pile_height, density : float, optional [m], [kg/m^3]
        H and rho for the tapered column when ``[tester]`` does not give them (the pipeline
        passes outer minus core radius and the web's density). Unused when the mass is known.

    Raises
    ------
    InputError
        No roll spring; or the tapered column is needed but has no pile height or density
        (field ``tester.pile_height`` / ``tester.density``).
    """
    if alpha is None or beta is None:
        if setup.roll_spring is None:
            raise InputError(
                "no roll spring: give alpha and beta or [tester.roll_spring]",
                f"{setup.field}.roll_spring",
            )
        law = setup.roll_spring.law
        restitution = setup.roll_spring.restitution
    else:
        law = RollSpring.quadratic(alpha, beta, 0.0, setup.restitution).law
        restitution = setup.restitution
    if effective_mass is None:
        effective_mass = setup.effective_mass(pile_height, density)
    if not math.isfinite(effective_mass):
        raise InputError("must be finite", f"{setup.field}.roll_spring.effective_mass")
    spring = RollSpring(law, effective_mass, restitution)
    en = impact_energy(setup.instrument, spring)
    if setup.time_step is not None:
        _check_time_step(setup, spring, en)
    fd = impact_fd(
        setup.instrument,
        spring,
        collision=setup.collision,
        time_step=setup.time_step,
        steps_per_contact=setup.steps_per_contact,
    )
    law = spring.law
    return HardnessResult(
        instrument=setup.instrument,
        alpha=float(getattr(law, "alpha", math.nan)),
        beta=float(getattr(law, "beta", math.nan)),
        effective_mass=spring.effective_mass,
        restitution=spring.restitution,
        fd=fd,
        energy=en,
    )
