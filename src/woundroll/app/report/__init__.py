"""A self-contained HTML report of one run: ``woundroll report CASE --out DIR``.

One file, ``DIR/report.html``: the inputs with their units and sources (material and
instrument presets, case file, model defaults), the stresses wound into the roll, the
predicted hardness (and across the CMD the profile), the measured readings and the
diagnosis when given, the warnings and assumptions, the woundroll version and a hash of the
case. Figures are PNG embedded as base64 data URIs; the CSS is inline; nothing is fetched
from the network. The page prints on A4 and Letter (``@page`` margins, no fixed page size,
figures and tables kept whole).

Templating: Jinja2 (autoescaping of every string that comes from a user's file: titles,
file names, notes; loops and optional sections without string surgery; the same engine the
web page renders with, :mod:`woundroll.app.web`).

Readings and diagnosis come from the reverse road (``woundroll.io.readings`` and the diagnosis
module): any object with ``to_dict()`` is accepted, and the sections render what it holds
(:func:`readings_section`, :func:`diagnosis_section`), so the report needs no change when
those results grow fields.
"""

from __future__ import annotations

import base64
import hashlib
import io
import json
import math
import sys
import threading
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

from woundroll.errors import InputError

if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.pipeline import RunResult

__all__ = [
    "ID_FIELDS",
    "Row",
    "build_report",
    "case_hash",
    "defects_section",
    "diagnosis_section",
    "input_sections",
    "profile_check_section",
    "readings_section",
    "summary_section",
    "trend_section",
    "write_report",
]

#: Identification fields of the report header, in display order: key -> label.
ID_FIELDS: dict[str, str] = {"roll": "Roll ID", "lot": "Lot", "customer": "Customer"}
#: Equation references in captions and assumptions, explained once in the report.
EQUATION_NOTE = (
    "Numbers in braces, such as {3}, are the equation numbers of the reference paper the "
    'models follow ("The Coupling of Winding Models and Roll Quality Instruments"; '
    "woundroll's docs/assumptions.md)."
)


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


def input_sections(case: Case) -> list[tuple[str, list[Row]]]:
    """The case's inputs in display units, by section, each with its source.

    Source of a web value: ``preset NAME (its source)`` when it equals the preset's value,
    ``case file`` when the case sets it, ``default`` when neither does. The instrument's
    values carry the preset's own ``[sources]`` entry per field.
    """
    from woundroll.case import FROM_SET, FROM_WEB_FORM, WebSpec
    from woundroll.materials.presets import list_materials

    sections: list[tuple[str, list[Row]]] = []
    web = case.web
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
    sections.append(("Web", rows))

    rows = []
    for name, kind in _CORE_FIELDS.items():
        v = getattr(case.core, name)
        if v is not None:
            rows.append(_row(f"core.{name}", v, kind, "case file"))
    if case.core.rigid:
        rows.append(Row("core.rigid", "true", "", "case file"))
    sections.append(("Core", rows))

    w = case.winding
    kind, t = w.tension
    tkind = {"force": "force", "force_per_length": "force_per_length", "pressure": "stress"}[kind]
    rows = [_row("winding.tension", t, tkind, "case file")]
    if w.outer_radius is not None:
        rows.append(_row("winding.outer_radius", w.outer_radius, "radius", "case file"))
    if w.length is not None:
        rows.append(Row("winding.length", f"{w.length:.5g}", "m", "case file"))
    rows.append(Row("winding.taper", _taper_text(w.taper), "", "case file or default"))
    rows.append(_row("winding.nip_load", w.nip_load, "force_per_length", "case file or default"))
    rows.append(_row("winding.friction", w.friction, "dimensionless", "case file or default"))
    if w.thickness_profile:
        rows.append(Row("winding.thickness_profile", w.thickness_profile, "", "case file"))
    sections.append(("Winding", rows))

    setup = case.tester_setup
    if setup is not None:
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
        sections.append(("Tester", rows))
    c = case.contact
    rows = [
        _row("contact.friction", c.friction, "dimensionless", "case file or default"),
        Row("contact.no_update", str(c.no_update).lower(), "", "case file or default"),
    ]
    if c.depth_max is not None:
        rows.append(_row("contact.depth_max", c.depth_max, "length", "case file"))
    if setup is not None:
        sections.append(("Contact model", rows))
    # where each value came from, as the case recorded it: a value set over the case (--set,
    # the web form) says so, and "case file or default" becomes the one that applies
    for _, rows in sections:
        for i, row in enumerate(rows):
            src = case.source_of(row.key)
            if src in (FROM_SET, FROM_WEB_FORM) or row.source in ("case file", _EITHER):
                rows[i] = Row(row.key, row.value, row.unit, src)
    return sections


_EITHER = "case file or default"


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


def _png(fig: Any, dpi: int = 110) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt = sys.modules.get("matplotlib.pyplot")
    if plt is not None:  # figures made with pyplot are registered there: release them
        plt.close(fig)
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _legible(fig: Any) -> None:
    """Log axes for a printed page: labels as plain numbers (0.2, 0.5, 1, 2), the minor ones
    only at 2 and 5 and only on an axis of less than 3 decades; matplotlib's default
    ``3 x 10^-1``-style minor labels run into each other at print size."""
    from matplotlib.ticker import FuncFormatter, NullFormatter

    def plain(v: float, _pos: Any = None) -> str:
        return f"{v:g}"

    def two_five(v: float, _pos: Any = None) -> str:
        if v <= 0:
            return ""
        mant = v / 10 ** math.floor(math.log10(v) + 1e-9)
        return f"{v:g}" if round(mant, 6) in (2.0, 5.0) else ""

    for ax in fig.axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale != "log":
                continue
            lo, hi = sorted(axis.get_view_interval())
            decades = math.log10(hi / lo) if lo > 0 and hi > lo else 99.0
            if decades < 3:
                axis.set_major_formatter(FuncFormatter(plain))
                axis.set_minor_formatter(FuncFormatter(two_five))
            else:
                axis.set_minor_formatter(NullFormatter())


# pyplot keeps one global figure registry and current-figure state, which is not safe when
# two threads draw at once (the web server renders reports from its worker threads): every
# figure of a report is drawn, saved and released under this lock.
_PLOT_LOCK = threading.RLock()


def _figures(part: Any, captions: list[str]) -> list[dict[str, str]]:
    out = []
    with _PLOT_LOCK:
        figs = part.plot()
        figs = list(figs) if isinstance(figs, list | tuple) else [figs]
        for i, fig in enumerate(figs):
            _legible(fig)
            cap = captions[i] if i < len(captions) else ""
            out.append({"src": _png(fig), "caption": cap})
    return out


def readings_section(readings: Any) -> dict[str, Any]:
    """Table rows (position in mm and in, mean, SD, count) and a figure of measured readings.

    ``readings``: a :class:`woundroll.io.readings.Readings`, or any object whose ``to_dict()``
    has ``position_m``, ``mean``, ``sd``, ``count`` and ``scale``.
    """
    d = readings.to_dict()
    rows = []
    for x, m, s, n in zip(d["position_m"], d["mean"], d["sd"], d["count"], strict=True):
        rows.append(
            (f"{x * 1e3:.1f}", f"{x / 0.0254:.2f}", f"{m:.2f}", f"{s:.2f}" if n > 1 else "-", n)
        )
    figs = []
    if hasattr(readings, "plot"):
        figs = _figures(readings, ["Measured readings across the roll (dots: passes)."])
    return {
        "source": d.get("source", ""),
        "scale": d.get("scale", ""),
        "passes": d.get("passes", ""),
        "pooled_sd": d.get("pooled_sd"),
        "rows": rows,
        "figures": figs,
    }


def _flatten(d: Any, prefix: str = "") -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    if isinstance(d, dict):
        for k, v in d.items():
            out += _flatten(v, f"{prefix}{k}.")
        return out
    key = prefix.rstrip(".")
    if isinstance(d, list):
        if len(d) > 12 or any(isinstance(v, dict | list) for v in d):
            return [(key, f"({len(d)} values)")]
        return [(key, ", ".join(_short(v) for v in d))]
    return [(key, _short(d))]


def _short(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.5g}"
    return str(v)


def diagnosis_section(diagnosis: Any) -> dict[str, Any]:
    """The diagnosis: with a :class:`woundroll.inverse.diagnosis.Diagnosis` its table per position
    (reading, wound-on tension, near-surface pressure with their intervals, status), the
    check run, notes and figures; for any other object with ``to_dict()``: its ``summary``,
    defect-risk flags (a ``defect_risks``/``risks`` list of dicts with ``name``/``defect``,
    ``level``/``risk``, ``reason``/``message``, or strings) and every scalar.
    """
    if hasattr(diagnosis, "summary") and hasattr(diagnosis, "curve"):
        d = diagnosis
        header = (
            "position [in]",
            f"reading [{d.curve.scale}]",
            "wound-on tension [MPa]",
            f"P at {d.pressure_depth * 1e3:.1f} mm [kPa]",
            "status",
        )
        text = (
            f"{d.sentence().capitalize()}. Each position's mean reading inverted through the "
            f"forward chain; {100 * d.confidence:.0f} % intervals in brackets."
        )
        v = d.verification
        if v:
            text += (
                f" Check: a full forward run at {v['web_tension_Pa'] / 1e6:.3g} MPa reads "
                f"{v['full_forward_reading']:.2f} (target {v['target_reading']:.2f})."
            )
        return {
            "summary": text,
            "risks": [],
            "header": header,
            "table": [tuple(r) for r in d.summary()],
            "rows": [("note", n) for n in d.notes],
            "figures": _figures(
                d,
                [
                    "Readings on the forward curve (full forward runs).",
                    "Diagnosed wound-on tension and near-surface pressure across the CMD.",
                ],
            ),
        }
    d = diagnosis.to_dict() if hasattr(diagnosis, "to_dict") else dict(diagnosis)
    risks = []
    for item in d.get("defect_risks", d.get("risks", [])) or []:
        if isinstance(item, dict):
            risks.append(
                {
                    "name": str(item.get("name", item.get("defect", ""))),
                    "level": str(item.get("level", item.get("risk", ""))),
                    "reason": str(item.get("reason", item.get("message", ""))),
                }
            )
        else:
            risks.append({"name": str(item), "level": "", "reason": ""})
    rest = {k: v for k, v in d.items() if k not in ("defect_risks", "risks", "summary")}
    figs = []
    if hasattr(diagnosis, "plot"):
        try:
            figs = _figures(diagnosis, ["Diagnosis."])
        except TypeError:
            figs = []
    return {
        "summary": d.get("summary", ""),
        "risks": risks,
        "header": (),
        "table": [],
        "rows": _flatten(rest),
        "figures": figs,
    }


def defects_section(defects: Any) -> dict[str, Any]:
    """Defect-risk flags of a :class:`woundroll.assess.defects.DefectReport`: the overall risk, one
    row per criterion (criterion, risk, finding) and the margins figure."""
    figs = []
    if hasattr(defects, "plot"):
        figs = _figures(defects, ["Margins (capacity / demand) of the defect criteria."])
    note = defects.needs_note() if hasattr(defects, "needs_note") else ""
    return {
        "risk": defects.risk,
        "rows": [{"name": n, "level": r, "reason": f} for n, r, f in defects.summary()],
        "note": note,
        "figures": figs,
    }


def profile_check_section(check: Any) -> dict[str, Any]:
    """The hardness profiler's view of the measured profile
    (:class:`woundroll.assess.profile_check.ProfileCheck`): verdict, statistics rows, the fault
    table with positions in the file's length unit, and the profile figure with the bands."""
    unit = check.position_unit or "in"
    stats = [
        ("mean", f"{check.mean:.2f} {check.scale}"),
        ("SD (sample)", f"{check.sd:.2f} {check.scale}"),
        ("CoV", f"{100 * check.cov:.2f} %"),
        ("min / max", f"{check.min:.2f} / {check.max:.2f} {check.scale}"),
        ("peak-to-peak", f"{check.peak_to_peak:.2f} {check.scale}"),
        ("CoV band", f"{check.band} (very good < 3 %, acceptable < 6 %)"),
        ("fault threshold", f"+-{100 * check.fault_band:g} % of the roll mean"),
    ]
    rows = check.fault_rows(unit)
    with _PLOT_LOCK:
        fig = check.plot(unit=unit)
        figs = [
            {
                "src": _png(fig),
                "caption": "Mean reading per position; shaded: hard (red) and soft (blue) "
                "bands beyond the fault threshold (dashed).",
            }
        ]
    return {
        "verdict": check.verdict,
        "band": check.band,
        "stats": stats,
        "fault_header": list(rows[0].keys()) if rows else [],
        "faults": [list(r.values()) for r in rows],
        "figures": figs,
    }


def trend_section(trend: Any) -> dict[str, Any]:
    """Roll-to-roll trend (:class:`woundroll.assess.profile_check.Trend`): one row per roll, the
    X-mR limits, the rolls beyond a limit and the control-chart figure."""
    s = trend.scale
    mc, cc = trend.mean_chart, trend.cov_chart
    rows = []
    for i, c in enumerate(trend.rolls):
        flag = [n for n, ch in (("mean", mc), ("CoV", cc)) if i in ch.out_of_control]
        nh = sum(b.kind == "hard" for b in c.faults)
        rows.append(
            [
                str(i + 1),
                c.label,
                c.ids.get("lot", ""),
                f"{c.mean:.2f}",
                f"{100 * c.cov:.2f}",
                f"{c.peak_to_peak:.3g}",
                c.band,
                f"{nh} / {len(c.faults) - nh}",
                ("beyond " + ", ".join(flag)) if flag else "in control",
            ]
        )
    header = [
        "#",
        "roll",
        "lot",
        f"mean [{s}]",
        "CoV [%]",
        f"p2p [{s}]",
        "CoV band",
        "hard / soft bands",
        "control limits",
    ]
    limits = (
        f"X-mR charts, limits = centre +- 2.66 mR-bar (Montgomery, Introduction to Statistical "
        f"Quality Control, section 6.4): mean centre {mc.center:.2f} {s}, limits "
        f"{mc.lcl:.2f} to {mc.ucl:.2f} {s}; CoV centre {100 * cc.center:.2f} %, limits "
        f"{100 * cc.lcl:.2f} to {100 * cc.ucl:.2f} %."
    )
    if trend.provisional:
        from woundroll.assess.profile_check import TREND_MIN_ROLLS

        limits += (
            f" Provisional: {len(trend.rolls)} rolls, limits settle after about {TREND_MIN_ROLLS}."
        )
    return {
        "header": header,
        "rows": rows,
        "limits": limits,
        "flagged": trend.flagged(),
        "figures": _figures(trend, ["Roll means and CoVs in production order, with limits."]),
    }


def summary_section(
    result: RunResult,
    *,
    defects: Any = None,
    check: Any = None,
    readings: Any = None,
    diagnosis: Any = None,
    trend: Any = None,
    n_warnings: int = 0,
) -> dict[str, Any]:
    """The verdict first: overall defect risk and the measured profile's band as the headline,
    then one line per finding (criteria at risk, the profile's faults, predicted against
    measured reading, the diagnosed tension, the trend, warnings)."""
    import numpy as np

    head: list[dict[str, str]] = []
    lines: list[str] = []
    if defects is not None:
        head.append({"label": "defect risk", "value": defects.risk, "level": defects.risk})
        risky = [(n, r) for n, r, _ in defects.summary() if r in ("high", "watch")]
        if risky:
            lines.append(
                "Defect criteria at risk: " + ", ".join(f"{n} ({r})" for n, r in risky) + "."
            )
        else:
            lines.append("No defect criterion at risk among those checked.")
        todo = getattr(defects, "unchecked", [])
        if todo:
            lines.append(f"{len(todo)} criteria not checked for want of a limit (see Defect risk).")
    if check is not None:
        level = {"very good": "low", "acceptable": "low", "bad": "high"}.get(check.band, "")
        head.append(
            {
                "label": "measured profile",
                "value": f"{check.band} (CoV {100 * check.cov:.1f} %)",
                "level": level,
            }
        )
        lines.append(f"Measured profile: {check.verdict}.")
    h = result.hardness
    if h is not None:
        d = h.to_dict()
        from woundroll.io.readings import SCALES

        unit = {readout: sc for sc, readout in SCALES.items()}.get(d["readout"], "")
        value = f"{d['reading']:.1f} {unit}"
        if d.get("saturated"):
            value += f" (saturated: the model reads {d['reading_model']:.1f})"
        head.append({"label": "predicted reading", "value": value, "level": ""})
        model = result.contact.model if result.contact is not None else "tester.roll_spring"
        lines.append(
            f"Predicted reading read through the {model!r} roll model; the "
            "head calibrated on its block in the "
            f"{d['head_calibration']['calibrated_in'] or 'uncalibrated'!r} model "
            f"(head radius {d['head_calibration']['head_radius_m'] * 1e3:.3f} mm)."
        )
    if h is not None and readings is not None:
        try:
            rd = readings.to_dict()
            measured = float(np.mean(rd["mean"]))
            d = h.to_dict()
            unit = rd.get("scale") or d["readout"]
            lines.append(
                f"Predicted reading {d['reading']:.1f} {unit}, measured mean "
                f"{measured:.1f} {unit} (predicted - measured {d['reading'] - measured:+.1f})."
            )
        except (KeyError, TypeError, ValueError):
            pass
    if diagnosis is not None and hasattr(diagnosis, "sentence"):
        lines.append(f"Diagnosis: {diagnosis.sentence()}.")
    if diagnosis is not None and hasattr(diagnosis, "wound_on_tension"):
        wot = np.asarray(diagnosis.wound_on_tension, dtype=float)
        ok = wot[np.isfinite(wot)]
        if ok.size:
            lines.append(
                f"Diagnosed effective wound-on tension {ok.min() / 1e6:.3g} to "
                f"{ok.max() / 1e6:.3g} MPa across the CMD (see Diagnosis)."
            )
    if trend is not None:
        flagged = trend.flagged()
        lines.append(
            f"Trend over {len(trend.rolls)} rolls: "
            + (f"{len(flagged)} point(s) beyond a control limit." if flagged else "in control.")
        )
    if n_warnings:
        lines.append(f"{n_warnings} warning(s) below.")
    return {"head": head, "lines": lines}


def _assumptions(result: RunResult) -> list[str]:
    """The main modelling assumptions of the parts that ran (full list: docs/assumptions.md)."""
    out = [
        "Winding (1D, Hakiel): plane stress, axisymmetric; no air entrainment, creep or "
        "temperature; E_theta constant, E_r from the radial-modulus law at mid-increment.",
        "Nip in the 1D model acts only through the wound-on tension WOT = T_w + mu N / h.",
    ]
    if result.contact is not None:
        from woundroll.contact.models import ROLL_MODELS

        entry = ROLL_MODELS.get(result.contact.model)
        title = entry.title if entry is not None else result.contact.model
        out.append(
            f"Roll model {result.contact.model!r} ({title}): frictionless rigid head, "
            "quasi-static F(d), no interlayer slip in the solution (the slip factor {23} "
            "only flags it); docs/trust.md says how far to trust it."
        )
    if result.hardness is not None:
        out.append(
            "Striker: spring-mass {1}; roll spring F = alpha d^2 + beta d {3}; active roll "
            "mass from the tapered column {14}-{18}; elastic roll unless a restitution is given."
        )
    if result.profile is not None:
        out.append(
            "CMD profile: axisymmetric (r, z) winding; each CMD sector a plane-strain roll "
            "under the head (docs/profile.md)."
        )
    out.append("Every assumption and its effect: docs/assumptions.md of woundroll.")
    return out


def _warnings(result: RunResult) -> list[str]:
    w = list(dict.fromkeys([*getattr(result, "warnings", ()), *result.notes]))
    setup = result.case.tester_setup
    if setup is not None and not setup.instrument.calibrated:
        w.append(
            f"{setup.instrument.name}: no calibration data for rolls; the reading is model "
            "output only"
        )
    p = result.profile
    if p is not None:
        n = int(p.slack.sum())
        if n:
            w.append(f"{n} CMD sector(s) wound slack: their reading is set by the E_r floor")
    return w


def _check_of(readings: Any, ids: dict[str, Any] | None = None) -> Any:
    """The profile check of measured readings, labelled with the report's ids (None for
    fewer than 2 positions, a zero mean or an object that is not
    :class:`woundroll.io.readings.Readings`)."""
    from woundroll.assess.profile_check import check_profile
    from woundroll.io.readings import Readings

    if not isinstance(readings, Readings) or readings.n_positions < 2:
        return None
    plain = {k: (v if isinstance(v, str) else str(v[0])) for k, v in (ids or {}).items() if v}
    try:
        return check_profile(readings, ids=plain)
    except InputError:
        return None


def build_report(
    result: RunResult,
    *,
    readings: Any = None,
    diagnosis: Any = None,
    defects: Any = None,
    generated: datetime | None = None,
    ids: dict[str, str] | None = None,
    title: str | None = None,
    profile_check: Any = None,
    trend: Any = None,
    warnings: list[str] | None = None,
) -> str:
    """The report as one HTML string (no external resources).

    ``readings``: :class:`woundroll.io.readings.Readings` (or any object with its ``to_dict()``);
    ``diagnosis``: :class:`woundroll.inverse.diagnosis.Diagnosis` (or a dict-like, rendered
    generically); ``defects``: :class:`woundroll.assess.defects.DefectReport`. ``ids``: roll, lot
    and customer (:data:`ID_FIELDS`) shown in the header, each value plain text or a
    ``(value, provenance)`` pair; ``title`` replaces the case's title. ``profile_check``:
    :class:`woundroll.assess.profile_check.ProfileCheck` of the readings (computed from ``readings``
    when not given); ``trend``: :class:`woundroll.assess.profile_check.Trend` of several rolls;
    ``warnings``: more warnings to list with the run's.
    """
    import jinja2

    from woundroll import __version__
    from woundroll.pipeline.summary import result_summary

    case = result.case
    figures: list[dict[str, Any]] = []
    captions = {
        "winding": ["Stresses wound into the roll: sigma_r, sigma_theta and E_r against radius."],
        "contact": [
            "Roll under the striker: force against depth with the fitted spring {3}, and the "
            "contact half-width.",
            "Slip factor {23} at the impact's maximum depth.",
        ],
        "hardness": ["Impact: contact force and striker deceleration against time."],
        "profile": [
            "Thickness and predicted reading across the CMD.",
            "Radial stress map sigma_r(r, z).",
        ],
    }
    sections = []
    for name, sec_title in (
        ("winding", "Stresses in the roll"),
        ("contact", "Roll stiffness under the striker"),
        ("hardness", "Predicted hardness"),
        ("profile", "Across the CMD"),
    ):
        part = getattr(result, name)
        if part is None or not hasattr(part, "plot"):
            continue
        sections.append({"title": sec_title, "figures": _figures(part, captions[name])})
    check = profile_check if profile_check is not None else _check_of(readings, ids)
    id_rows = []
    for key, label in ID_FIELDS.items():
        v = (ids or {}).get(key)
        if v is None or (isinstance(v, str) and not v.strip()):
            continue
        value, origin = (v, "") if isinstance(v, str) else (str(v[0]), str(v[1]))
        id_rows.append({"label": label, "value": value, "origin": origin})
    all_warnings = _warnings(result) + list(warnings or [])
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("woundroll.app.report", "templates"),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
    )
    when = generated or datetime.now(UTC)
    return env.get_template("report.html").render(
        title=title or case.display_title or "woundroll run",
        version=__version__,
        case_hash=case_hash(case),
        generated=when.strftime("%Y-%m-%d %H:%M UTC"),
        ids=id_rows,
        overview=summary_section(
            result,
            defects=defects,
            check=check,
            readings=readings,
            diagnosis=diagnosis,
            trend=trend,
            n_warnings=len(all_warnings),
        ),
        equation_note=EQUATION_NOTE,
        inputs=input_sections(case),
        summary=result_summary(result),
        sections=sections,
        figures=figures,
        readings=None if readings is None else readings_section(readings),
        profile_check=None if check is None else profile_check_section(check),
        trend=None if trend is None else trend_section(trend),
        diagnosis=None if diagnosis is None else diagnosis_section(diagnosis),
        defects=None if defects is None else defects_section(defects),
        warnings=all_warnings,
        assumptions=_assumptions(result),
    )


def write_report(
    result: RunResult,
    out_dir: str | Path,
    *,
    readings: Any = None,
    diagnosis: Any = None,
    defects: Any = None,
    **extra: Any,
) -> Path:
    """Write ``out_dir/report.html`` and return its path; ``extra``: the keywords of
    :func:`build_report` (``ids``, ``title``, ``profile_check``, ``trend``).

    Raises
    ------
    InputError
        ``out_dir`` cannot be created or written (field ``--out``).
    """
    html = build_report(result, readings=readings, diagnosis=diagnosis, defects=defects, **extra)
    out = Path(out_dir)
    path = out / "report.html"
    try:
        out.mkdir(parents=True, exist_ok=True)
        path.write_text(html, encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot write to {out}: {exc.strerror or exc}", "--out") from None
    return path
