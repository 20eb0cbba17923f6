"""The report's inputs: every value with its unit and where it came from, and the case's
hash."""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from woundroll.case import Case


@dataclass(frozen=True)
class Row:
    """One input row: dotted key, value in display units, unit, and where it came from."""

    key: str
    value: str
    unit: str
    source: str


# display unit per SI kind: (unit label, factor SI -> display)
_DISPLAY: dict[str, tuple[str, float]] = {
    "thickness": ("um", 1e6),
    "length": ("mm", 1e3),
    "radius": ("cm", 1e2),
    "modulus": ("MPa", 1e-6),
    "pressure": ("kPa", 1e-3),
    "density": ("kg/m^3", 1.0),
    "force_per_length": ("N/m", 1.0),
    "force": ("N", 1.0),
    "stress": ("MPa", 1e-6),
    "dimensionless": ("", 1.0),
    "mass": ("g", 1e3),
    "stiffness": ("N/m", 1.0),
    "frequency": ("rad/s", 1.0),
    "bending": ("N m^2", 1.0),
}

_WEB_FIELDS = {
    "thickness": "thickness",
    "width": "length",
    "E_theta": "modulus",
    "E_z": "modulus",
    "density": "density",
    "nu_theta_r": "dimensionless",
    "nu_z_r": "dimensionless",
    "nu_theta_z": "dimensionless",
    "G_r_theta": "modulus",
    "G_r_z": "modulus",
    "G_theta_z": "modulus",
}
_CORE_FIELDS = {
    "outer_radius": "radius",
    "inner_radius": "radius",
    "stiffness": "modulus",
    "E": "modulus",
    "nu": "dimensionless",
}
_INSTRUMENT_FIELDS = {
    "mass": "mass",
    "spring_stiffness": "stiffness",
    "natural_frequency": "frequency",
    "release_position": "length",
    "contact_position": "length",
    "head_radius": "length",
    "head_length": "length",
    "rho_per_g": "dimensionless",
}


def _fmt(value: float, kind: str) -> tuple[str, str]:
    unit, factor = _DISPLAY[kind]
    v = value * factor
    if not math.isfinite(v):
        return ("rigid" if v > 0 else str(v)), ""
    return f"{v:.5g}", unit


def _row(key: str, value: Any, kind: str, source: str) -> Row:
    if isinstance(value, int | float):
        text, unit = _fmt(float(value), kind)
    else:
        text, unit = str(value), ""
    return Row(key, text, unit, source)


_EITHER = "case file or default"


def _web_rows(web: Any) -> list[Row]:
    """The web's values, each attributed to its preset, the case file or the default."""
    from woundroll.case import WebSpec
    from woundroll.materials.presets import list_materials

    preset_spec = None
    preset_label = ""
    if web.preset:
        table = list_materials().get(web.preset.upper(), {})
        preset_label = f"preset {web.preset.upper()} ({table.get('source', 'no source given')})"
        try:
            preset_spec = WebSpec.model_validate({"preset": web.preset})
        except Exception:  # a preset that does not validate alone: no per-field attribution
            preset_spec = None
    defaults = {n: f.default for n, f in WebSpec.model_fields.items()}

    def web_source(name: str, value: Any) -> str:
        if preset_spec is not None and getattr(preset_spec, name) == value:
            return preset_label
        if defaults.get(name) is not None and defaults[name] == value:
            return "default"
        return "case file"

    rows = []
    for name, kind in _WEB_FIELDS.items():
        v = getattr(web, name)
        if v is None:
            rows.append(
                Row(f"web.{name}", "-", "", "not given: model default (docs/case-files.md)")
            )
            continue
        rows.append(_row(f"web.{name}", v, kind, web_source(name, v)))
    law = web.radial_modulus
    law_src = (
        preset_label
        if preset_spec is not None and preset_spec.radial_modulus == law
        else "case file"
    )
    rows.append(Row("web.radial_modulus", _law_text(law), "", law_src))
    return rows


def _core_rows(core: Any) -> list[Row]:
    rows = []
    for name, kind in _CORE_FIELDS.items():
        v = getattr(core, name)
        if v is not None:
            rows.append(_row(f"core.{name}", v, kind, "case file"))
    if core.rigid:
        rows.append(Row("core.rigid", "true", "", "case file"))
    return rows


def _winding_rows(w: Any) -> list[Row]:
    kind, t = w.tension
    tkind = {"force": "force", "force_per_length": "force_per_length", "pressure": "stress"}[kind]
    rows = [_row("winding.tension", t, tkind, "case file")]
    if w.outer_radius is not None:
        rows.append(_row("winding.outer_radius", w.outer_radius, "radius", "case file"))
    if w.length is not None:
        rows.append(Row("winding.length", f"{w.length:.5g}", "m", "case file"))
    rows.append(Row("winding.taper", _taper_text(w.taper), "", _EITHER))
    rows.append(_row("winding.nip_load", w.nip_load, "force_per_length", _EITHER))
    rows.append(_row("winding.friction", w.friction, "dimensionless", _EITHER))
    if w.thickness_profile:
        rows.append(Row("winding.thickness_profile", w.thickness_profile, "", "case file"))
    return rows


def _tester_rows(case: Case, setup: Any) -> list[Row]:
    """The instrument's values, each with the preset's own source or the case file."""
    inst = setup.instrument
    rows = [Row("tester.instrument", inst.title or inst.name, "", "preset " + inst.name)]
    own = case.tester or {}
    for name, kind in _INSTRUMENT_FIELDS.items():
        v = getattr(inst, name, None)
        if v is None:
            continue
        src = "case file" if name in own else inst.sources.get(name, "preset " + inst.name)
        rows.append(_row(f"tester.{name}", v, kind, src))
    rows.append(Row("tester.readout", inst.readout, "", "preset " + inst.name))
    if not inst.calibrated:
        rows.append(Row("tester.calibrated", "false", "", "no calibration data for rolls"))
    return rows


def _contact_rows(c: Any) -> list[Row]:
    rows = [
        _row("contact.friction", c.friction, "dimensionless", _EITHER),
        Row("contact.no_update", str(c.no_update).lower(), "", _EITHER),
    ]
    if c.depth_max is not None:
        rows.append(_row("contact.depth_max", c.depth_max, "length", "case file"))
    return rows


def input_sections(case: Case) -> list[tuple[str, list[Row]]]:
    """The case's inputs in display units, by section, each with its source.

    Source of a web value: ``preset NAME (its source)`` when it equals the preset's value,
    ``case file`` when the case sets it, ``default`` when neither does. The instrument's
    values carry the preset's own ``[sources]`` entry per field.
    """
    from woundroll.case import FROM_SET, FROM_WEB_FORM

    sections = [
        ("Web", _web_rows(case.web)),
        ("Core", _core_rows(case.core)),
        ("Winding", _winding_rows(case.winding)),
    ]
    setup = case.tester_setup
    if setup is not None:
        sections.append(("Tester", _tester_rows(case, setup)))
        sections.append(("Contact model", _contact_rows(case.contact)))
    # where each value came from, as the case recorded it: a value set over the case (--set,
    # the web form) says so, and "case file or default" becomes the one that applies
    for _, rows in sections:
        for i, row in enumerate(rows):
            src = case.source_of(row.key)
            if src in (FROM_SET, FROM_WEB_FORM) or row.source in ("case file", _EITHER):
                rows[i] = Row(row.key, row.value, row.unit, src)
    return sections


def _law_text(law: Any) -> str:
    try:
        d = law.to_dict()
    except AttributeError:
        return str(law)
    parts = [str(d.get("law", type(law).__name__))]
    for k, v in d.items():
        if k == "law":
            continue
        if k.endswith("_Pa") and isinstance(v, int | float):
            parts.append(f"{k.removesuffix('_Pa')} = {v / 1e3:.5g} kPa")
        elif isinstance(v, int | float):
            parts.append(f"{k} = {v:.5g}")
        elif isinstance(v, str):
            parts.append(f"{k} = {v}")
    return ", ".join(parts)


def _taper_text(taper: Any) -> str:
    if taper.kind == "none":
        return "none"
    if taper.kind == "table":
        return f"table ({len(taper.radius)} points)"
    return f"{taper.kind}, {100 * taper.fraction:.3g} %"


def _canonical(obj: Any) -> Any:
    if hasattr(obj, "to_dict"):
        return _canonical(obj.to_dict())
    if isinstance(obj, dict):
        return {str(k): _canonical(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_canonical(v) for v in obj]
    if isinstance(obj, float):
        # 12 significant digits: a value given in other units hashes alike despite the
        # last bit of its conversion to SI
        return float(f"{obj:.12g}") if math.isfinite(obj) else repr(obj)
    if isinstance(obj, str | int | float | bool) or obj is None:
        return obj
    return repr(obj)


def case_hash(case: Case) -> str:
    """SHA-256 (first 16 hex digits) of the validated case in SI plus the bytes of the
    files it reads (thickness profile, measured profile).

    Two case files that differ only in units, comments or key order hash alike (the
    validated values are what the models see); a changed profile file changes the hash.
    """
    data = case.model_dump(exclude={"base_dir"})
    h = hashlib.sha256(json.dumps(_canonical(data), sort_keys=True).encode())
    for name in (case.winding.thickness_profile, case.profile.measured):
        if name:
            try:
                h.update(case._path(name).read_bytes())
            except OSError:  # bundled profile names are not files
                h.update(name.encode())
    return h.hexdigest()[:16]
