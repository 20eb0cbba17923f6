"""The report's sections: readings, diagnosis, defects, the profiler's check, the trend,
the summary, the assumptions and warnings."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from woundroll.app.report.figures import _PLOT_LOCK, _figures, _png

if TYPE_CHECKING:
    from woundroll.pipeline import RunResult

#: Identification fields of the report header, in display order: key -> label.
ID_FIELDS: dict[str, str] = {"roll": "Roll ID", "lot": "Lot", "customer": "Customer"}
#: Equation references in captions and assumptions, explained once in the report.
EQUATION_NOTE = (
    "Numbers in braces, such as {3}, are the equation numbers of the reference paper the "
    'models follow ("The Coupling of Winding Models and Roll Quality Instruments"; '
    "woundroll's docs/assumptions.md)."
)


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
        slip = (
            "interlayer Coulomb friction between the sheets near the head (stick and slip)"
            if result.contact.model.startswith("layered")
            else "no interlayer slip in the solution (the slip factor {23} only flags it)"
        )
        out.append(
            f"Roll model {result.contact.model!r} ({title}): frictionless rigid head, "
            f"quasi-static F(d), {slip}; docs/trust.md says how far to trust it."
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
