"""What the web page shows of a run: the JSON payload of the stresses, the profile, the
headline numbers and the profiler's check, in the page's unit system."""

# and their types are imported inside create_app()

import math
import re
from typing import Any

import numpy as np

from woundroll.errors import ConvergenceError, InputError


def _measured(readings: Any) -> Any:
    """Readings as the profile comparison takes them (position, mean reading), or None."""
    if readings is None:
        return None
    from woundroll.profile.compare import MeasuredProfile

    return MeasuredProfile(readings.position, readings.mean, readings.source)


def _error(exc: InputError | ConvergenceError) -> dict[str, Any]:
    fld = getattr(exc, "field", None) or ("run" if isinstance(exc, ConvergenceError) else "case")
    msg = getattr(exc, "message", str(exc))
    return {"field": fld, "message": msg, "line": str(exc)}


def _scalars(d: Any, prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    if isinstance(d, dict):
        for k, v in d.items():
            out.update(_scalars(v, f"{prefix}{k}."))
    elif isinstance(d, bool | str) or d is None:
        pass
    elif isinstance(d, int | float) and math.isfinite(d):
        out[prefix.rstrip(".")] = d
    return out


def _series(x: Any, y: Any, label: str, style: str = "line") -> dict[str, Any]:
    return {"x": [float(v) for v in x], "y": [float(v) for v in y], "label": label, "style": style}


_US_UNITS = re.compile(r"\b(pli|lbf|lb|psi|in|inch|inches|mil|mils|ft)\b")


def unit_system(text: str) -> str:
    """``"us"`` when ``text`` (the tension as the user wrote it) uses US units, else
    ``"si"``: the family the page's diagnosis sentence and positions speak."""
    return "us" if _US_UNITS.search(str(text)) else "si"


def _plot(pid: str, title: str, xlabel: str, ylabel: str, series: list[Any]) -> dict[str, Any]:
    return {"id": pid, "title": title, "xlabel": xlabel, "ylabel": ylabel, "series": series}


def _winding_plots(w: Any) -> list[dict[str, Any]]:
    """Radial stress, the layer-mean hoop stress wound into the roll and the wound-on
    tension each layer was laid on with (taper, nip, winding mode)."""
    # the node values of sigma_theta saw-tooth with the layer period (within a layer the hoop
    # stress falls outward); the layer means from equilibrium are the field
    rm, st = w.layer_mean_hoop_stress()
    return [
        _plot(
            "plot-sigma-r",
            "radial stress wound into the roll",
            "radius [cm]",
            "sigma_r [kPa]",
            [_series(w.radius * 100, w.sigma_r / 1e3, "sigma_r")],
        ),
        _plot(
            "plot-sigma-t",
            "hoop stress (mean over each layer) and wound-on tension",
            "radius [cm]",
            "sigma_theta [kPa]",
            [
                _series(rm * 100, st / 1e3, "sigma_theta, layer mean"),
                _series(w.radius * 100, w.wot / 1e3, "wound-on tension (WOT)"),
            ],
        ),
    ]


def _air_and_storage_plots(w: Any) -> list[dict[str, Any]]:
    """The roll wound with entrained air (diameter against wound length with and without
    air, pressure at winding and after the air left) and the pressure before and after a
    storage time, when the run asked for them (the same data as ``winding_air.png`` and the
    report's storage figure)."""
    plots = []
    air = w.air
    if air is not None and "wound_length_m" in air:
        L = np.asarray(air["wound_length_m"])
        plots.append(
            _plot(
                "plot-air-diameter",
                f"diameter with entrained air ({air['speed_m_per_s']:g} m/s)",
                "wound length [m]",
                "diameter [mm]",
                [
                    _series(L, np.asarray(air["diameter_no_air_m"]) * 1e3, "without air"),
                    _series(L, np.asarray(air["diameter_with_air_m"]) * 1e3, "with air"),
                ],
            )
        )
        r = np.asarray(air["air_radius_m"]) * 100.0
        plots.append(
            _plot(
                "plot-air-pressure",
                "pressure at winding and after the air has left",
                "radius [cm]",
                "-sigma_r [kPa]",
                [
                    _series(r, -np.asarray(air["sigma_r_at_winding_Pa"]) / 1e3, "at winding"),
                    _series(r, -np.asarray(air["sigma_r_after_Pa"]) / 1e3, "after the air left"),
                ],
            )
        )
    st = w.storage
    if st is not None and "pressure_before_creep_Pa" in st:
        r = w.radius * 100.0
        plots.append(
            _plot(
                "plot-storage",
                f"pressure before and after {st['storage_time_s'] / 86400:g} d of storage",
                "radius [cm]",
                "-sigma_r [kPa]",
                [
                    _series(r, np.asarray(st["pressure_before_creep_Pa"]) / 1e3, "before"),
                    _series(r, np.asarray(st["pressure_after_creep_Pa"]) / 1e3, "after"),
                ],
            )
        )
    return plots


def _profile_plot(result: Any, measured: Any) -> dict[str, Any] | None:
    """The predicted profile (or the one predicted reading) beside the measured readings."""
    p = result.profile
    if p is not None:
        s = [_series(p.z * 100, p.shown, "predicted (FD model, as the instrument shows it)")]
        if p.rho_energy is not None:
            s.append(_series(p.z * 100, p.rho_energy, "energy model (check, unclipped)"))
        if measured is not None:
            s.append(_series(measured.position * 100, measured.reading, "measured", "dots"))
        title = "hardness across the roll (scroll to zoom into a lane)"
        return _plot("plot-profile", title, "CMD position [cm]", "reading", s)
    if measured is None or result.hardness is None:
        return None
    pred = result.hardness.to_dict()["reading"]
    xs = measured.position * 100
    s = [
        _series([xs.min(), xs.max()], [pred, pred], "predicted"),
        _series(xs, measured.reading, "measured", "dots"),
    ]
    title = "measured readings and the predicted reading"
    return _plot("plot-profile", title, "CMD position [cm]", "reading", s)


def _measured_rows(result: Any, measured: Any) -> dict[str, Any] | None:
    """Count, mean, min and max of the measured readings, and the prediction's offset."""
    if measured is None:
        return None
    import numpy as np

    rows: dict[str, Any] = {
        "n": int(measured.position.size),
        "mean": float(np.mean(measured.reading)),
        "min": float(np.min(measured.reading)),
        "max": float(np.max(measured.reading)),
    }
    if result.hardness is not None:
        rows["predicted_minus_measured"] = (
            float(result.hardness.to_dict()["reading"]) - rows["mean"]
        )
    return rows


def _impact_plot(result: Any, h: dict[str, Any]) -> dict[str, Any]:
    """The FD model's contact force against time since first contact."""
    # the FD history's clock runs from the striker's release: count from first contact
    t0 = float(result.hardness.fd.contact_start)
    series = [_series([(t - t0) * 1e3 for t in h["time_s"]], h["force_N"], "FD model")]
    return _plot(
        "plot-impact",
        "impact: contact force against time",
        "time since first contact [ms]",
        "force [N]",
        series,
    )


def _diagnosis_caveats(g: Any) -> list[str]:
    """What the diagnosis' intervals cannot say (no scatter known)."""
    zero = [
        i
        for i in range(g.position.size)
        if math.isfinite(g.web_tension[i]) and g.web_tension_low[i] == g.web_tension_high[i]
    ]
    if zero:
        return [
            f"zero-width interval at {len(zero)} of {g.position.size} positions: one "
            "reading each and no readings.repeatability, so the scatter is unknown and the "
            "interval says nothing about it; read each position at least twice"
        ]
    if not g.readings.has_scatter:
        return [
            "no repeated readings: the intervals hold the material uncertainty only, not "
            "the tester's scatter; read each position at least twice"
        ]
    return []


def _diagnosis_section(g: Any, units: str | None) -> tuple[dict[str, Any], dict[str, Any]]:
    """The diagnosis (sentence, table in the page's units, notes, caveats) and its plot."""
    us = units == "us"
    pos_unit, pos_scale = ("in", 1 / 0.0254) if us else ("mm", 1e3)
    rows = [list(r) for r in g.summary()]
    for i, row in enumerate(rows):
        row[0] = f"{g.position[i] * pos_scale:.{2 if us else 1}f}"
    diag = {
        "summary": g.sentence(units),
        "header": [
            f"position [{pos_unit}]",
            f"reading [{g.curve.scale}]",
            "wound-on tension [MPa]",
            f"P at {g.pressure_depth * 1e3:.1f} mm [kPa]",
            "status",
        ],
        "rows": rows,
        "notes": list(g.notes),
        "caveats": _diagnosis_caveats(g),
    }
    ok = [i for i in range(g.position.size) if math.isfinite(g.wound_on_tension[i])]
    xs = [g.position[i] * 100 for i in ok]
    series = [
        _series(xs, [g.wound_on_tension[i] / 1e6 for i in ok], "diagnosed"),
        _series(xs, [g.wound_on_tension_low[i] / 1e6 for i in ok], "low", "dots"),
        _series(xs, [g.wound_on_tension_high[i] / 1e6 for i in ok], "high", "dots"),
    ]
    plot = _plot(
        "plot-diagnosis",
        "diagnosed wound-on tension across the roll",
        "CMD position [cm]",
        "wound-on tension [MPa]",
        series,
    )
    return diag, plot


def result_payload(
    result: Any,
    measured: Any = None,
    diagnosis: Any = None,
    defects: Any = None,
    inputs: list[dict[str, Any]] | None = None,
    units: str | None = None,
) -> dict[str, Any]:
    """What the page shows: summary rows, every scalar of the CLI's JSON, plot series, the
    diagnosis (sentence, table, caveats), the defect-risk flags and the inputs used with
    their sources."""
    from woundroll.app.report import case_hash
    from woundroll.pipeline.summary import result_summary

    d = result.to_dict()
    plots = _winding_plots(result.winding) if result.winding is not None else []
    if result.winding is not None:
        plots += _air_and_storage_plots(result.winding)
    profile = _profile_plot(result, measured)
    if profile is not None:
        plots.append(profile)
    if result.hardness is not None:
        plots.append(_impact_plot(result, d["hardness"]))
    diag = None
    if diagnosis is not None:
        diag, plot = _diagnosis_section(diagnosis, units)
        plots.append(plot)
    risk = None
    if defects is not None:
        rows = [{"name": n, "risk": r, "finding": f} for n, r, f in defects.summary()]
        risk = {"risk": defects.risk, "rows": rows}
    return {
        "diagnosis": diag,
        "defects": risk,
        "title": result.case.title,
        "case_hash": case_hash(result.case),
        "summary": [{"label": k, "value": v} for k, v in result_summary(result)],
        "numbers": _scalars({k: v for k, v in d.items() if k not in ("case", "schema_version")}),
        "notes": list(result.notes),
        "plots": plots,
        "measured": _measured_rows(result, measured),
        "inputs": inputs or [],
    }


def profile_check_payload(readings: Any, units: str | None = None) -> dict[str, Any] | None:
    """The measured profile as a hardness profiler reports it
    (:func:`woundroll.assess.profile_check.check_profile`): CoV, peak-to-peak, band verdict and the
    hard/soft bands, positions in inches (US) or millimetres; None with fewer than two
    positions (no profile) or no readings."""
    if readings is None or readings.n_positions < 2:
        return None
    from woundroll.assess.profile_check import check_profile

    try:
        c = check_profile(readings)
    except InputError as exc:  # e.g. a mean reading of 0: no CoV
        return {"verdict": exc.message, "faults": [], "header": []}
    rows = c.fault_rows("in" if units == "us" else "mm")
    return {
        "verdict": c.verdict,
        "band": c.band,
        "cov": c.cov,
        "peak_to_peak": c.peak_to_peak,
        "mean": c.mean,
        "scale": c.scale,
        "header": list(rows[0]) if rows else [],
        "faults": [list(r.values()) for r in rows],
    }
