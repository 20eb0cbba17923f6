"""Instrument definitions as data: the striker, its spring, its head and its readout.

Presets live in ``woundroll/data/instruments/*.toml`` (package data), one file per instrument,
every quantity with its unit and every value with its source. :func:`get_instrument` and
:func:`list_instruments` are the registry; :meth:`Instrument.with_overrides` changes fields.

Coordinates (reference paper, Fig. 11): ``x`` is the striker position from its spring's
equilibrium, positive towards the roll. The striker is released at rest at ``x = -x_in``
(``release_position``) and touches the roll at ``x = +x_gap`` (``contact_position``, past
equilibrium on the Rho-meter: Table 1's "impact position -0.24 cm", sign as in NOTES.md).

Mass: a preset may give the striker ``mass`` directly or ``natural_frequency`` instead, then
``mass = spring_stiffness / natural_frequency^2`` {1}. Mass, stiffness and natural frequency
are kept consistent with {1}:

* an instrument that carries all three must satisfy ``k/m = omega^2`` to 1e-3 (relative),
  else :class:`~woundroll.errors.InputError` on ``natural_frequency`` (a preset file that
  gives all three is checked the same way);
* :meth:`Instrument.with_overrides`: ``natural_frequency`` alone (or with ``spring_stiffness``)
  recomputes the mass, ``m = k/omega^2``; ``spring_stiffness`` and/or ``mass`` without
  ``natural_frequency`` keep the mass (the striker did not change) and recompute the natural
  frequency, ``omega = sqrt(k/m)``; giving ``mass`` and ``natural_frequency`` together is
  checked against the (new or kept) stiffness.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, fields, replace
from functools import lru_cache
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.instruments.readout import G_STANDARD, READOUTS, RHO_PER_G
from woundroll.units import to_si

__all__ = ["Instrument", "get_instrument", "list_instruments", "load_instrument_file"]

#: Instrument fields with a physical dimension (name -> unit kind for :func:`to_si`).
QUANTITY_FIELDS: dict[str, str] = {
    "mass": "mass",
    "spring_stiffness": "stiffness",
    "natural_frequency": "frequency",
    "release_position": "length",
    "contact_position": "length",
    "head_radius": "length",
    "head_length": "length",
    "head_edge_radius": "length",
    "rho_per_g": "dimensionless",
}  # "g" (an acceleration) is converted separately in _convert
_TEXT_FIELDS = ("name", "title", "readout", "head_shape", "notes", "calibration_model")
#: Relative tolerance of ``k/m = omega^2`` {1} for an instrument that gives all three.
EQ1_RTOL = 1e-3
_HEAD_SHAPES = ("cylinder", "sphere", "punch")  # punch: 3D contact model only
#: Scale of each readout (what the instrument can show): a simulated reading outside it is
#: flagged (the instrument would read its end stop or nothing). Rho-meter: dial 0-100 Rho;
#: Schmidt hammers: rebound number R 10-100; Parotester: L = 1000 v_out/v_in, 0-1000 by
#: construction; g: no fixed scale.
READING_RANGES: dict[str, tuple[float, float] | None] = {
    "rho": (0.0, 100.0),
    "schmidt-r": (10.0, 100.0),
    "parotester-l": (0.0, 1000.0),
    "g": None,
}


def beyond_scale(values: ArrayLike, scale: tuple[float, float] | None) -> NDArray[np.bool_]:
    """Where a model's reading lies beyond the instrument's ``scale`` (``(low, high)``;
    None: no scale, nothing beyond it): the device would show the scale's end there
    (*saturated*)."""
    v = np.asarray(values, dtype=float)
    if scale is None:
        return np.zeros(v.shape, dtype=bool)
    return (v < scale[0]) | (v > scale[1])


def as_shown(values: ArrayLike, scale: tuple[float, float] | None) -> NDArray[np.float64]:
    """What the instrument shows for a model's reading: the value clipped to its
    ``scale`` (unchanged without one)."""
    v = np.asarray(values, dtype=float)
    return v.copy() if scale is None else np.clip(v, scale[0], scale[1])


@dataclass(frozen=True)
class Instrument:
    """A spring-driven impact hardness tester (striker side of the 1.5D model), SI.

    Attributes
    ----------
    name : str
        Registry key ("rho-meter").
    mass : float [kg]
        Striker effective mass m_s ({1}: ``K_eff / omega_n^2``).
    spring_stiffness : float [N/m]
        Striker spring k_s.
    release_position : float [m]
        x_in: the striker starts at rest at ``x = -x_in``.
    contact_position : float [m]
        x_gap: first contact at ``x = +x_gap``; ``-x_in < x_gap < x_in``.
    head_radius : float [m]
        Radius of the head's contact surface (cylinder radius, or sphere radius).
    head_length : float or None [m]
        Cylinder length along the CMD (None for a spherical tip). Also the CMD length that
        multiplies the tapered-column volume {17} for the roll's active mass.
    head_shape : str
        "cylinder" (axis along the CMD), "sphere" or "punch" (flat face of radius
        ``head_radius``; the 3D contact model only).
    head_edge_radius : float or None [m]
        Rounding of a cylinder's ends or a punch's edge (3D contact model; None: sharp).
    readout : str
        One of :data:`woundroll.instruments.readout.READOUTS`.
    natural_frequency : float or None [rad/s]
        omega_n, if the mass came from {1}.
    rho_per_g, g : float [-], [m/s^2]
        1 Rho = ``rho_per_g`` g ({22}: 3.76 and 9.81).
    calibrated : bool
        False when no calibration data exist for rolls (readings are then model output only).
    calibration_model : str
        The model in which the head's unknown dimension was calibrated on the block: a roll
        model's registry name (``woundroll calibrate-head``), ``"hertz"`` (plane-strain Hertz
        line contact), or "" (not calibrated).
    sources : dict
        Field -> where its value comes from.
    """

    name: str
    mass: float
    spring_stiffness: float
    release_position: float
    contact_position: float
    head_radius: float
    head_length: float | None = None
    head_shape: str = "cylinder"
    readout: str = "rho"
    title: str = ""
    natural_frequency: float | None = None
    rho_per_g: float = RHO_PER_G
    g: float = G_STANDARD
    calibrated: bool = True
    notes: str = ""
    head_edge_radius: float | None = None
    calibration_model: str = ""
    sources: dict[str, str] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        p = "instrument" if not self.name else f"instrument[{self.name}]"
        for name in (
            "mass",
            "spring_stiffness",
            "release_position",
            "head_radius",
            "g",
            "rho_per_g",
        ):
            _check(getattr(self, name), f"{p}.{name}", positive=True)
        _check(self.contact_position, f"{p}.contact_position", positive=False)
        if self.head_length is not None:
            _check(self.head_length, f"{p}.head_length", positive=True)
        if self.head_edge_radius is not None:
            _check(self.head_edge_radius, f"{p}.head_edge_radius", positive=False)
        if self.natural_frequency is not None:
            _check(self.natural_frequency, f"{p}.natural_frequency", positive=True)
            w2 = self.spring_stiffness / self.mass
            if abs(w2 / (self.natural_frequency * self.natural_frequency) - 1.0) > EQ1_RTOL:
                raise InputError(
                    f"mass {self.mass:.6g} kg, spring stiffness {self.spring_stiffness:.6g} N/m "
                    f"and natural frequency {self.natural_frequency:.6g} rad/s disagree: "
                    f"{{1}} needs k/m = omega^2, but sqrt(k/m) = {math.sqrt(w2):.6g} rad/s "
                    f"(tolerance {EQ1_RTOL:g}); give two of the three",
                    f"{p}.natural_frequency",
                )
        if not -self.release_position < self.contact_position < self.release_position:
            raise InputError(
                f"contact position x_gap = {self.contact_position:g} m must lie strictly between "
                f"-x_in and x_in = {self.release_position:g} m (release position), otherwise the "
                "striker never reaches the roll with speed",
                f"{p}.contact_position",
            )
        if self.head_shape not in _HEAD_SHAPES:
            raise InputError(
                f"must be one of {', '.join(_HEAD_SHAPES)}, got {self.head_shape!r}",
                f"{p}.head_shape",
            )
        if self.head_shape == "cylinder" and self.head_length is None:
            raise InputError(
                "a cylindrical head needs its length along the CMD", f"{p}.head_length"
            )
        if self.readout not in READOUTS:
            raise InputError(
                f"must be one of {', '.join(READOUTS)}, got {self.readout!r}", f"{p}.readout"
            )

    # -- derived quantities -------------------------------------------------------------
    @property
    def reading_range(self) -> tuple[float, float] | None:
        """The scale of the readout (:data:`READING_RANGES`), or None when it has none."""
        return READING_RANGES.get(self.readout)

    @property
    def impact_speed(self) -> float:
        """Striker speed at first contact [m/s]: ``sqrt(k/m (x_in^2 - x_gap^2))``.

        Free harmonic motion from rest at ``-x_in`` {10}, {11} to ``x_gap``: the spring energy
        released, the left side of {19} minus the spring term at contact, is all kinetic.
        Rho-meter preset (m = 0.12528 kg from {1}): 1.1409 m/s; NOTES.md's 1.142 m/s uses
        Table 1's rounded 125 g.
        """
        return math.sqrt(
            self.spring_stiffness
            / self.mass
            * (self.release_position**2 - self.contact_position**2)
        )

    @property
    def impact_energy(self) -> float:
        """Kinetic energy at first contact [J]: ``k (x_in^2 - x_gap^2) / 2`` {10}, {11}, {19}.

        The striker spring's energy at release ``k x_in^2/2`` ({19}, left side) minus its energy
        at contact; independent of the mass (Rho-meter: 0.0815 J, NOTES.md).
        """
        return 0.5 * self.spring_stiffness * (self.release_position**2 - self.contact_position**2)

    @property
    def omega(self) -> float:
        """Natural frequency of the free striker sqrt(k/m) [rad/s] {1}."""
        return math.sqrt(self.spring_stiffness / self.mass)

    @property
    def rho_unit(self) -> float:
        """Deceleration of one Rho [m/s^2] (3.76 g, {22})."""
        return self.rho_per_g * self.g

    # -- changes ------------------------------------------------------------------------
    def with_overrides(self, field_prefix: str = "instrument", **changes: Any) -> Instrument:
        """A copy with some fields changed; values may be SI numbers or strings with units.

        Parameters
        ----------
        field_prefix : str
            Dotted prefix for error messages ("tester").
        **changes
            Any :class:`Instrument` field, e.g. ``head_radius="1 cm"``, ``mass=0.2``.

        Raises
        ------
        InputError
            Unknown field, wrong unit or an inconsistent instrument.
        """
        known = {f.name for f in fields(self)}
        new: dict[str, Any] = {}
        for key, value in changes.items():
            fld = f"{field_prefix}.{key}"
            if key not in known or key == "sources":
                raise InputError(
                    f"unknown instrument field (known: {', '.join(sorted(known))})", fld
                )
            new[key] = _convert(key, value, fld)
        # keep mass, stiffness and natural frequency consistent with {1} (module docstring)
        omega_given = new.get("natural_frequency") is not None
        if omega_given and not new["natural_frequency"] > 0:
            raise InputError(
                f"must be positive, got {new['natural_frequency']!r} rad/s",
                f"{field_prefix}.natural_frequency",
            )
        if omega_given and "mass" not in new:
            w2 = float(new["natural_frequency"]) * float(
                new["natural_frequency"]
            )  # no OverflowError
            if not (w2 > 0 and math.isfinite(w2)):
                raise InputError(
                    f"{new['natural_frequency']!r} rad/s gives no finite striker mass {{1}}",
                    f"{field_prefix}.natural_frequency",
                )
            new["mass"] = new.get("spring_stiffness", self.spring_stiffness) / w2
        elif not omega_given and ("mass" in new or "spring_stiffness" in new):
            k = new.get("spring_stiffness", self.spring_stiffness)
            m = new.get("mass", self.mass)
            ok = all(isinstance(v, float | int) and math.isfinite(v) and v > 0 for v in (k, m))
            if "natural_frequency" in new or self.natural_frequency is None or not ok:
                new["natural_frequency"] = None  # explicitly cleared, absent, or bad input
            else:
                new["natural_frequency"] = math.sqrt(k / m)
        try:
            return replace(self, **new)
        except InputError as exc:
            # re-point the field to the caller's prefix
            tail = exc.field.split(".", 1)[1] if exc.field and "." in exc.field else exc.field
            raise InputError(exc.message, f"{field_prefix}.{tail}") from None

    def to_dict(self) -> dict[str, Any]:
        """Plain SI dictionary (JSON-ready)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def _check(value: Any, fld: str, *, positive: bool) -> None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(f"must be a number, got {value!r}", fld)
    if not math.isfinite(value):
        raise InputError(f"must be a finite number, got {value!r}", fld)
    if positive and value <= 0:
        raise InputError(f"must be positive, got {value:g}", fld)


def _convert(key: str, value: Any, fld: str) -> Any:
    if key in _TEXT_FIELDS:
        if not isinstance(value, str):
            raise InputError(f"must be text, got {value!r}", fld)
        return value
    if key == "calibrated":
        if not isinstance(value, bool):
            raise InputError(f"must be true or false, got {value!r}", fld)
        return value
    if key == "g":
        return to_si(value, "acceleration", fld)
    if key in ("head_length", "natural_frequency", "head_edge_radius") and value is None:
        return None
    return to_si(value, QUANTITY_FIELDS[key], fld)


def _from_table(data: dict[str, Any], origin: str) -> Instrument:
    data = dict(data)
    name = data.get("name")
    if not isinstance(name, str) or not name:
        raise InputError(f"{origin}: needs a 'name'", "instrument.name")
    prefix = f"instrument[{name}]"
    sources = data.pop("sources", {})
    data.pop("calibration_block", None)
    if not isinstance(sources, dict):
        raise InputError("must be a table", f"{prefix}.sources")
    known = {f.name for f in fields(Instrument)} - {"sources"}
    kw: dict[str, Any] = {}
    for key, value in data.items():
        if key not in known:
            raise InputError(f"{origin}: unknown key", f"{prefix}.{key}")
        kw[key] = _convert(key, value, f"{prefix}.{key}")
    if "mass" not in kw:
        if "natural_frequency" not in kw or "spring_stiffness" not in kw:
            raise InputError(
                "give 'mass', or 'spring_stiffness' and 'natural_frequency' ({1})", f"{prefix}.mass"
            )
        kw["mass"] = kw["spring_stiffness"] / kw["natural_frequency"] ** 2
    for req in ("spring_stiffness", "release_position", "contact_position", "head_radius"):
        if req not in kw:
            raise InputError(f"{origin}: missing", f"{prefix}.{req}")
    return Instrument(sources={str(k): str(v) for k, v in sources.items()}, **kw)


def _data_dir():
    return resources.files("woundroll") / "data" / "instruments"


@lru_cache(maxsize=1)
def _registry() -> dict[str, tuple[Instrument, dict[str, Any]]]:
    reg: dict[str, tuple[Instrument, dict[str, Any]]] = {}
    for entry in sorted(_data_dir().iterdir(), key=lambda p: p.name):
        if not entry.name.endswith(".toml"):
            continue
        raw = tomllib.loads(entry.read_text(encoding="utf-8"))
        inst = _from_table(raw, entry.name)
        if inst.name in reg:
            raise InputError(f"instrument defined twice ({entry.name})", "instrument.name")
        reg[inst.name] = (inst, raw)
    return reg


def load_instrument_file(path: str) -> Instrument:
    """Read one instrument definition from a TOML file (same format as the presets)."""
    from pathlib import Path

    p = Path(path)
    if not p.is_file():
        raise InputError(f"file not found: {p}", "instrument")
    try:
        raw = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{p.name}: not valid TOML ({exc})", "instrument") from None
    return _from_table(raw, p.name)


def list_instruments() -> list[str]:
    """Names of the preset instruments, sorted."""
    return sorted(_registry())


def get_instrument(name: str, field: str = "tester.instrument") -> Instrument:
    """The preset instrument called ``name`` (case-insensitive).

    Raises
    ------
    InputError
        Unknown name (the message lists the known ones).
    """
    if not isinstance(name, str):
        raise InputError(f"must be an instrument name, got {name!r}", field)
    key = name.strip().lower()
    reg = _registry()
    if key not in reg:
        raise InputError(f"unknown instrument {name!r} (known: {', '.join(sorted(reg))})", field)
    return reg[key][0]


def preset_table(name: str, table: str) -> dict[str, Any] | None:
    """A raw sub-table of a preset file (e.g. its ``calibration_block``), or None."""
    get_instrument(name)
    return _registry()[name.strip().lower()][1].get(table)
