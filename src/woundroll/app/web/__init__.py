"""The shop-floor web page: ``woundroll serve [--host 127.0.0.1] [--port 8000]``.

FastAPI (request validation, JSON endpoints, a test client) with Jinja2 templates, served
by uvicorn. One page: pick a bundled case or edit its TOML, set the common inputs in a
form with units, paste or upload readings across the roll, press run; a background job
runs :func:`woundroll.pipeline.run` and the page polls its progress (cancellable), then
shows the stresses, the predicted (and measured) profile, the headline numbers and a link
to the HTML report (:mod:`woundroll.app.report`).

Safety (the page may be opened by anyone who can reach the port; it listens on 127.0.0.1
unless told otherwise):

* it never takes a file path: ``winding.thickness_profile``, ``profile.measured`` and
  ``web.radial_modulus.file`` may only name the files the bundled cases use
  (:data:`BUNDLED_FILE_REFS`); readings are pasted or uploaded as text, never opened from a
  path;
* it never takes code: the case is TOML parsed by :mod:`tomllib`, readings are CSV text,
  every value goes through the same validation as the CLI;
* a case is at most :data:`MAX_CASE_BYTES`, readings at most :data:`MAX_READINGS_BYTES`;
  at most :data:`MAX_RUNNING` runs at a time and :data:`MAX_JOBS` kept;
* bad input answers 422 with the CLI's one-line message (``field: message``) and the
  offending field, which the page shows beside that field; the server keeps serving.
"""

# no "from __future__ import annotations": FastAPI reads the endpoints' annotations at runtime,
# and their types are imported inside create_app()

import math
import re
import tempfile
import threading
import time
import tomllib
import uuid
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from woundroll.errors import ConvergenceError, InputError

#: Largest case (TOML text) the page accepts [bytes].
MAX_CASE_BYTES = 64 * 1024
#: Largest readings text the page accepts [bytes] (some 10 000 readings).
MAX_READINGS_BYTES = 256 * 1024
#: Runs at a time; more get "busy".
MAX_RUNNING = 2
#: Finished jobs kept (oldest dropped first).
MAX_JOBS = 50

#: Quick inputs of the form: dotted key -> (label, example with units).
FORM_FIELDS: dict[str, tuple[str, str]] = {
    "winding.tension": ("web tension", "26.7 N, 2 pli, 1.75 MPa"),
    "winding.outer_radius": ("final outer radius", "13.34 cm, 5.25 in"),
    "winding.nip_load": ("nip load", "0 N/m, 1 pli"),
    "winding.friction": ("friction (nip)", "0.3"),
    "web.thickness": ("web thickness", "100 um, 4 mil"),
    "web.width": ("web width", "15.24 cm, 6 in"),
    "web.E_theta": ("web MD modulus E_theta", "5681 MPa"),
}

_FILE_KEYS = ("winding.thickness_profile", "profile.measured", "web.radial_modulus.file")


def _cases_dir() -> Path:
    return Path(str(resources.files("woundroll.data.cases")))


def _get(data: dict[str, Any], key: str) -> Any:
    node: Any = data
    for p in key.split("."):
        if not isinstance(node, dict) or p not in node:
            return None
        node = node[p]
    return node


def _bundled_file_refs() -> set[tuple[str, str]]:
    refs = set()
    for p in _cases_dir().glob("*.toml"):
        data = tomllib.loads(p.read_text(encoding="utf-8"))
        for key in _FILE_KEYS:
            v = _get(data, key)
            if isinstance(v, str):
                refs.add((key, v))
    return refs


#: (key, value) pairs of file references the bundled cases make: the only ones allowed.
BUNDLED_FILE_REFS = _bundled_file_refs()


class InputErrors(InputError):
    """Several independent input errors at once (one per field); the first is the
    :class:`InputError` itself, :attr:`errors` holds them all."""

    def __init__(self, errors: list[InputError]) -> None:
        super().__init__(errors[0].message, errors[0].field)
        self.errors = errors


def _parse_case_text(text: str) -> dict[str, Any]:
    size = len(text.encode("utf-8"))
    if size > MAX_CASE_BYTES:
        raise InputError(
            f"the case is {size} bytes; the page takes at most {MAX_CASE_BYTES} bytes", "case"
        )
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", "case") from None


def _case_from_data(data: dict[str, Any], overrides: dict[str, Any] | None = None) -> Any:
    """The case of ``data`` with the form's values over it, each recorded as coming from
    the ``web form`` (:meth:`woundroll.case.Case.source_of`, the report's inputs)."""
    import copy

    from woundroll.case import FROM_WEB_FORM, case_from_dict, set_dotted

    merged = copy.deepcopy(data)
    for key, value in (overrides or {}).items():
        set_dotted(merged, key, value)
    for key in _FILE_KEYS:
        v = _get(merged, key)
        if v is not None and (key, v) not in BUNDLED_FILE_REFS:
            raise InputError(
                "the web page takes no file paths (only the bundled cases' files); "
                "run such a case with the CLI",
                key,
            )
    # relative references resolve against the bundled cases (the only ones allowed)
    return case_from_dict(
        data,
        _cases_dir(),
        overrides=list((overrides or {}).items()),
        override_source=FROM_WEB_FORM,
    )


def check_inputs(
    text: str, overrides: dict[str, str] | None = None
) -> tuple[Any, list[InputError]]:
    """:func:`case_from_text`, but every form field's error at once: each override is
    checked on its own against the case, then the case with the good ones.

    Returns
    -------
    (case, errors)
        ``errors``: one per field the user wrote wrong (the case's own error once);
        ``case``: the case with the good overrides (the readings are checked against it),
        None when the case itself is wrong.

    Raises
    ------
    InputError
        ``case``: too large or not TOML (nothing else can be checked).
    """
    from woundroll.case import parse_override

    data = _parse_case_text(text)  # nothing else can be checked without the case
    errors: list[InputError] = []
    good: dict[str, str] = {}
    for key, value in (overrides or {}).items():
        if key not in FORM_FIELDS:
            errors.append(InputError("not a field of this form", key))
            continue
        if value is None or not str(value).strip():
            continue
        try:
            _case_from_data(data, {key: parse_override(f"{key}={value}")[1]})
        except InputError as exc:
            if exc.field == key:
                errors.append(exc)
                continue
        good[key] = value  # an error elsewhere is the case's own: reported below
    try:
        case = case_from_text(text, good)
    except InputError as exc:
        errors.append(exc)
        case = None
    return case, errors


def inputs_used(text: str, overrides: dict[str, str], case: Any) -> list[dict[str, Any]]:
    """The form's quantities as the run used them and where each came from: ``"web form"``
    (typed on the page), ``"case file"`` (the TOML), ``"preset"`` (the web's material
    preset) or ``"default"``. ``value`` is what the user wrote (or the SI value of a default),
    ``si`` the SI value the run used, with its unit."""
    data = tomllib.loads(text)
    kind, v = case.winding.tension
    # how a value the user did not write is shown: (unit, SI value of one unit)
    shown_in = {
        "winding.outer_radius": ("cm", 1e-2),
        "web.thickness": ("um", 1e-6),
        "web.width": ("cm", 1e-2),
        "web.E_theta": ("MPa", 1e6),
    }
    si: dict[str, tuple[float, str]] = {
        "winding.tension": (v, {"force": "N", "force_per_length": "N/m", "pressure": "Pa"}[kind]),
        "winding.outer_radius": (
            case.winding.final_radius(case.web.build(), case.core.build()),
            "m",
        ),
        "winding.nip_load": (case.winding.nip_load, "N/m"),
        "winding.friction": (case.winding.friction, ""),
        "web.thickness": (case.web.thickness, "m"),
        "web.width": (case.web.width, "m"),
        "web.E_theta": (case.web.E_theta, "Pa"),
    }
    rows = []
    for key, (label, _) in FORM_FIELDS.items():
        given = (overrides or {}).get(key)
        value, unit = si[key]
        u, f = shown_in.get(key, (unit, 1.0))
        nice = f"{value / f:.6g} {u}".strip()
        # the case records where each value came from (woundroll.case: provenance)
        source = case.source_of(key)
        if given is not None and str(given).strip():
            shown = str(given).strip()
        elif _get(data, key) is not None:
            shown = str(_get(data, key))
        else:
            shown = nice
        rows.append(
            {
                "key": key,
                "label": label,
                "value": shown,
                "si": value,
                "si_unit": unit,
                "source": source,
            }
        )
    return rows


def case_from_text(text: str, overrides: dict[str, str] | None = None) -> Any:
    """Validate a case given as TOML text plus form overrides, as the CLI would.

    Raises
    ------
    InputError
        ``case``: too large or not TOML; ``<key>``: a file path that is not one of the
        bundled cases' files; any error of :func:`woundroll.case.case_from_dict`.
    """
    from woundroll.case import parse_override

    data = _parse_case_text(text)
    given: dict[str, Any] = {}
    for key, value in (overrides or {}).items():
        if key not in FORM_FIELDS:
            raise InputError("not a field of this form", key)
        if value is not None and str(value).strip():
            given[key] = parse_override(f"{key}={value}")[1]
    return _case_from_data(data, given)


def readings_from_text(text: str, case: Any, lane_width: str = "", roll: str = "") -> Any:
    """Pasted or uploaded readings (CSV text) as :class:`woundroll.io.readings.Readings`
    in any layout of :func:`woundroll.io.tester_files.read_tester_file` (generic CSV with
    positions or lanes, passes, Rho/R/L/g scales; a TAPPI T 834 sheet, ``roll`` picking one of
    several rolls; a dense profile export); lane numbers use ``lane_width`` or the case's
    ``readings.lane_width``.

    Raises
    ------
    InputError
        field ``readings``: too large, or anything the reader rejects;
        ``readings.lane_width``: not a length.
    """
    from woundroll.io.tester_files import read_tester_file
    from woundroll.units import to_si

    size = len(text.encode("utf-8"))
    if size > MAX_READINGS_BYTES:
        raise InputError(
            f"the readings are {size} bytes; the page takes at most {MAX_READINGS_BYTES}",
            "readings",
        )
    lw = None
    if lane_width.strip():
        lw = to_si(lane_width, "length", "readings.lane_width")
        if not lw > 0:
            raise InputError(f"must be positive, got {lane_width!r}", "readings.lane_width")
    elif case.readings is not None:
        lw = case.readings.lane_width
    with tempfile.TemporaryDirectory(prefix="woundroll-web-") as tmp:
        path = Path(tmp) / "readings.csv"
        path.write_text(text, encoding="utf-8")
        try:
            r = read_tester_file(
                path, roll=roll.strip() or None, width=case.web.width, lane_width=lw
            )
        except InputError as exc:
            # the temporary directory is nobody's business: name the sheet, not the path
            msg = exc.message.replace(str(path), "readings.csv").replace(tmp, "")
            raise InputError(msg, exc.field or "readings") from None
    from dataclasses import replace

    return replace(r, source="readings pasted on the web page")


#: What the page says for the models' progress stages.
STAGE_LABELS = {
    "winding": "winding the roll",
    "contact": "contact model (roll spring under the head)",
    "impact": "impact of the striker",
    "foundation": "foundation (CMD profile)",
    "dynamic": "dynamic contact",
    "diagnosis: forward curve": "diagnosis: full forward runs over tension",
    "diagnosis: material": "diagnosis: material sensitivity",
}


class Cancelled(Exception):
    """Raised inside a run's progress callback when its job was cancelled."""


@dataclass
class Job:
    id: str
    state: str = "queued"  # queued, running, done, error, cancelled
    stage: str = ""
    fraction: float = 0.0
    #: True while work goes on that reports no fraction (the page shows a moving bar)
    indeterminate: bool = False
    inputs: list[dict[str, Any]] | None = None
    units: str | None = None
    started: float = field(default_factory=time.time)
    cancel: threading.Event = field(default_factory=threading.Event)
    result: Any = None
    readings: Any = None
    diagnose: bool = False
    diagnosis: Any = None
    defects: Any = None
    payload: dict[str, Any] | None = None
    error: dict[str, Any] | None = None
    report: str | None = None

    def status(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "id": self.id,
            "state": self.state,
            "stage": self.stage,
            "fraction": None if self.indeterminate else round(self.fraction, 4),
            "indeterminate": self.indeterminate,
            "elapsed_s": round(time.time() - self.started, 2),
        }
        if self.state == "done":
            out["result"] = self.payload
            out["report_url"] = f"/jobs/{self.id}/report"
        if self.error is not None:
            out["error"] = self.error
        return out


class JobStore:
    """Background runs in threads; progress, cancellation, a bounded history."""

    def __init__(self) -> None:
        self.jobs: dict[str, Job] = {}
        self.lock = threading.Lock()

    def running(self) -> int:
        return sum(j.state in ("queued", "running") for j in self.jobs.values())

    def start(
        self,
        case: Any,
        readings: Any,
        diagnose: bool = False,
        inputs: list[dict[str, Any]] | None = None,
        units: str | None = None,
    ) -> Job:
        with self.lock:
            if self.running() >= MAX_RUNNING:
                raise InputError(
                    f"the server is busy ({MAX_RUNNING} runs going): wait or cancel one", "run"
                )
            job = Job(
                uuid.uuid4().hex[:12],
                readings=readings,
                diagnose=diagnose,
                inputs=inputs,
                units=units,
            )
            self.jobs[job.id] = job
            done = [k for k, j in self.jobs.items() if j.state not in ("queued", "running")]
            for k in done[: max(0, len(self.jobs) - MAX_JOBS)]:
                del self.jobs[k]
        threading.Thread(target=self._run, args=(job, case), daemon=True).start()
        return job

    def get(self, job_id: str) -> Job | None:
        return self.jobs.get(job_id)

    def _run(self, job: Job, case: Any) -> None:
        from woundroll.pipeline import run

        def progress(stage: str, fraction: float, after: str = "working on the next step") -> None:
            if job.cancel.is_set():
                raise Cancelled
            label = STAGE_LABELS.get(stage, stage)
            if fraction >= 1.0:
                # the stage is done but the job is not: say what runs now, claim no per cent
                job.stage, job.fraction, job.indeterminate = f"{label} done; {after}", 1.0, True
            else:
                job.stage, job.fraction, job.indeterminate = label, float(fraction), False

        def between(stage: str) -> None:
            if job.cancel.is_set():
                raise Cancelled
            job.stage, job.indeterminate = stage, True

        job.state = "running"
        try:
            from woundroll.assess.defects import defect_report

            result = run(case, progress=progress)
            between("comparing and summing up")
            measured = _measured(job.readings)
            if measured is not None and result.profile is not None:
                from dataclasses import replace

                result = replace(result, profile=result.profile.compare(measured))
            if job.diagnose and job.readings is not None:
                from woundroll.inverse.diagnosis import diagnose

                between("diagnosis: starting the forward runs over tension")

                def diag_progress(stage: str, fraction: float) -> None:
                    progress(
                        f"diagnosis: {stage}",
                        fraction,
                        "diagnosis: checking the result with a full forward run",
                    )

                job.diagnosis = diagnose(case, job.readings, progress=diag_progress)
            between("defect risk and summary")
            job.defects = defect_report(case, job.diagnosis, winding=result.winding)
            job.result = result
            job.payload = result_payload(
                result, measured, job.diagnosis, job.defects, job.inputs, job.units
            )
            job.payload["profile_check"] = profile_check_payload(job.readings, job.units)
            job.stage, job.fraction, job.indeterminate = "", 1.0, False
            job.state = "done"
        except Cancelled:
            job.state = "cancelled"
        except (InputError, ConvergenceError) as exc:
            job.error = _error(exc)
            job.state = "error"
        except Exception as exc:  # the server keeps serving; the page shows what happened
            job.error = {"field": "run", "message": f"{type(exc).__name__}: {exc}"}
            job.error["line"] = f"run: {job.error['message']}"
            job.state = "error"


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
    from woundroll.pipeline.summary import result_summary

    d = result.to_dict()
    plots = []
    w = result.winding
    if w is not None:
        plots.append(
            {
                "id": "plot-sigma-r",
                "title": "radial stress wound into the roll",
                "xlabel": "radius [cm]",
                "ylabel": "sigma_r [kPa]",
                "series": [_series(w.radius * 100, w.sigma_r / 1e3, "sigma_r")],
            }
        )
        # the node values of sigma_theta saw-tooth with the layer period (within a layer
        # the hoop stress falls outward); the layer means from equilibrium are the field
        rm, st = w.layer_mean_hoop_stress()
        plots.append(
            {
                "id": "plot-sigma-t",
                "title": "hoop stress (mean over each layer)",
                "xlabel": "radius [cm]",
                "ylabel": "sigma_theta [kPa]",
                "series": [_series(rm * 100, st / 1e3, "sigma_theta, layer mean")],
            }
        )
    p = result.profile
    measured_rows = None
    if p is not None:
        s = [_series(p.z * 100, p.shown, "predicted (FD model, as the instrument shows it)")]
        if p.rho_energy is not None:
            s.append(_series(p.z * 100, p.rho_energy, "energy model (check, unclipped)"))
        if measured is not None:
            s.append(_series(measured.position * 100, measured.reading, "measured", "dots"))
        plots.append(
            {
                "id": "plot-profile",
                "title": "hardness across the roll (scroll to zoom into a lane)",
                "xlabel": "CMD position [cm]",
                "ylabel": "reading",
                "series": s,
            }
        )
    elif measured is not None and result.hardness is not None:
        pred = result.hardness.to_dict()["reading"]
        xs = measured.position * 100
        plots.append(
            {
                "id": "plot-profile",
                "title": "measured readings and the predicted reading",
                "xlabel": "CMD position [cm]",
                "ylabel": "reading",
                "series": [
                    _series([xs.min(), xs.max()], [pred, pred], "predicted"),
                    _series(xs, measured.reading, "measured", "dots"),
                ],
            }
        )
    if measured is not None:
        import numpy as np

        measured_rows = {
            "n": int(measured.position.size),
            "mean": float(np.mean(measured.reading)),
            "min": float(np.min(measured.reading)),
            "max": float(np.max(measured.reading)),
        }
        if result.hardness is not None:
            measured_rows["predicted_minus_measured"] = (
                float(result.hardness.to_dict()["reading"]) - measured_rows["mean"]
            )
    if result.hardness is not None:
        h = d["hardness"]
        # the FD history's clock runs from the striker's release: count from first contact
        t0 = float(result.hardness.fd.contact_start)
        plots.append(
            {
                "id": "plot-impact",
                "title": "impact: contact force against time",
                "xlabel": "time since first contact [ms]",
                "ylabel": "force [N]",
                "series": [
                    _series([(t - t0) * 1e3 for t in h["time_s"]], h["force_N"], "FD model")
                ],
            }
        )
    diag = None
    if diagnosis is not None:
        g = diagnosis
        us = units == "us"
        pos_unit, pos_scale = ("in", 1 / 0.0254) if us else ("mm", 1e3)
        rows = [list(r) for r in g.summary()]
        for i, row in enumerate(rows):
            row[0] = f"{g.position[i] * pos_scale:.{2 if us else 1}f}"
        caveats = []
        zero = [
            i
            for i in range(g.position.size)
            if math.isfinite(g.web_tension[i]) and g.web_tension_low[i] == g.web_tension_high[i]
        ]
        if zero:
            caveats.append(
                f"zero-width interval at {len(zero)} of {g.position.size} positions: one "
                "reading each and no readings.repeatability, so the scatter is unknown and the "
                "interval says nothing about it; read each position at least twice"
            )
        elif not g.readings.has_scatter:
            caveats.append(
                "no repeated readings: the intervals hold the material uncertainty only, not "
                "the tester's scatter; read each position at least twice"
            )
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
            "caveats": caveats,
        }
        ok = [i for i in range(g.position.size) if math.isfinite(g.wound_on_tension[i])]
        xs = [g.position[i] * 100 for i in ok]
        plots.append(
            {
                "id": "plot-diagnosis",
                "title": "diagnosed wound-on tension across the roll",
                "xlabel": "CMD position [cm]",
                "ylabel": "wound-on tension [MPa]",
                "series": [
                    _series(xs, [g.wound_on_tension[i] / 1e6 for i in ok], "diagnosed"),
                    _series(xs, [g.wound_on_tension_low[i] / 1e6 for i in ok], "low", "dots"),
                    _series(xs, [g.wound_on_tension_high[i] / 1e6 for i in ok], "high", "dots"),
                ],
            }
        )
    from woundroll.app.report import case_hash

    return {
        "diagnosis": diag,
        "defects": None
        if defects is None
        else {
            "risk": defects.risk,
            "rows": [{"name": n, "risk": r, "finding": f} for n, r, f in defects.summary()],
        },
        "title": result.case.title,
        "case_hash": case_hash(result.case),
        "summary": [{"label": k, "value": v} for k, v in result_summary(result)],
        "numbers": _scalars({k: v for k, v in d.items() if k not in ("case", "schema_version")}),
        "notes": list(result.notes),
        "plots": plots,
        "measured": measured_rows,
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


def _headless_plots() -> None:
    """Draw with the Agg backend: the server renders report figures from worker threads,
    and a GUI backend (the default on a desktop with a display) must only be driven from
    the main thread. The server never shows a window, so nothing is lost."""
    import matplotlib

    matplotlib.use("Agg")


def create_app() -> Any:
    """The FastAPI application (``uvicorn woundroll.app.web:create_app --factory``)."""
    from fastapi import FastAPI, Request
    from fastapi.responses import HTMLResponse, JSONResponse, PlainTextResponse
    from fastapi.templating import Jinja2Templates
    from pydantic import BaseModel, Field

    from woundroll import __version__
    from woundroll.case import bundled_cases

    _headless_plots()
    app = FastAPI(title="woundroll", version=__version__, docs_url=None, redoc_url=None)
    # Jinja2Templates autoescapes .html templates
    templates = Jinja2Templates(directory=str(resources.files("woundroll.app.web") / "templates"))
    store = JobStore()
    app.state.jobs = store

    class RunRequest(BaseModel):
        case: str = Field(max_length=MAX_CASE_BYTES * 2)
        overrides: dict[str, str] = Field(default_factory=dict, max_length=len(FORM_FIELDS) + 5)
        readings: str = Field(default="", max_length=MAX_READINGS_BYTES * 2)
        lane_width: str = Field(default="", max_length=40)
        roll: str = Field(default="", max_length=100)
        diagnose: bool = False

    def bad(exc: InputError | ConvergenceError, status: int = 422) -> JSONResponse:
        body: dict[str, Any] = {"error": _error(exc)}
        body["errors"] = [_error(e) for e in getattr(exc, "errors", [exc])]
        return JSONResponse(body, status_code=status)

    def _one(err: dict[str, Any]) -> InputError:
        loc = [str(p) for p in err.get("loc", ()) if p != "body"]
        typ = err.get("type", "")
        if typ == "json_invalid":
            pos = f" (character {loc[0]})" if loc else ""
            why = (err.get("ctx") or {}).get("error", "")
            return InputError(
                f"the request body is not JSON{pos}{': ' + str(why) if why else ''}; send "
                '{"case": TOML text, "overrides": {...}, "readings": CSV text}',
                "request",
            )
        if typ in ("model_attributes_type", "dict_type") and not loc:
            return InputError(
                'the request body must be a JSON object {"case": ..., "overrides": ...}',
                "request",
            )
        fld = ".".join(loc) if loc else "request"
        if loc and loc[0] == "overrides" and len(loc) > 1:
            fld = loc[1]  # the form field itself
        msg = str(err.get("msg", "invalid request"))
        if typ == "string_too_long":
            limit = MAX_CASE_BYTES if fld == "case" else MAX_READINGS_BYTES
            msg = f"too large: the page takes at most {limit} bytes"
        elif typ == "missing":
            msg = "missing (required)"
        return InputError(msg, fld)

    async def _unprocessable(request: Request, exc: Exception) -> JSONResponse:
        # FastAPI's own validation (not JSON, a field too long, a wrong type): one line
        # per field, in the page's {"error": ...} form
        errs = list(getattr(exc, "errors", lambda: [])())
        if not errs:
            errs = [{"loc": (), "msg": str(exc)}]
        mine, seen = [], set()
        for e in errs:
            one = _one(e)
            if one.field not in seen:
                seen.add(one.field)
                mine.append(one)
        return bad(InputErrors(mine))

    async def _http_error(request: Request, exc: Any) -> JSONResponse:
        # unknown paths and wrong methods answer in the same form as everything else
        what = {404: "no such page or API path", 405: "method not allowed here"}.get(
            exc.status_code, str(exc.detail)
        )
        return bad(
            InputError(f"{what}: {request.method} {request.url.path}", "request"), exc.status_code
        )

    from fastapi.exceptions import RequestValidationError
    from starlette.exceptions import HTTPException as StarletteHTTPException

    app.add_exception_handler(RequestValidationError, _unprocessable)
    app.add_exception_handler(StarletteHTTPException, _http_error)

    @app.get("/", response_class=HTMLResponse)
    def index(request: Request) -> Any:
        return templates.TemplateResponse(
            request,
            "index.html",
            {
                "cases": bundled_cases(),
                "fields": FORM_FIELDS,
                "version": __version__,
                "max_case": MAX_CASE_BYTES,
                "max_readings": MAX_READINGS_BYTES,
            },
        )

    @app.get("/api/cases/{name}", response_class=PlainTextResponse)
    def case_text(name: str) -> Any:
        if name not in bundled_cases():
            return bad(InputError(f"no bundled case named {name!r}", "CASE"), 404)
        return (_cases_dir() / f"{name}.toml").read_text(encoding="utf-8")

    @app.post("/api/run")
    def start_run(req: RunRequest) -> Any:
        try:
            case, errors = check_inputs(req.case, req.overrides)
            readings = None
            if req.readings.strip():
                try:
                    if case is not None:
                        readings = readings_from_text(req.readings, case, req.lane_width, req.roll)
                    elif len(req.readings.encode("utf-8")) > MAX_READINGS_BYTES:
                        readings_from_text(req.readings, None)  # the size error needs no case
                except InputError as exc:
                    errors.append(exc)
            elif req.diagnose:
                errors.append(InputError("give readings to diagnose", "readings"))
            if errors:
                raise InputErrors(errors)
            inputs = inputs_used(req.case, req.overrides, case)
            units = unit_system(next(r["value"] for r in inputs if r["key"] == "winding.tension"))
            job = store.start(case, readings, req.diagnose, inputs, units)
        except InputError as exc:
            return bad(exc, 429 if exc.field == "run" else 422)
        return {"job": job.id, "status_url": f"/api/jobs/{job.id}"}

    @app.get("/api/jobs/{job_id}")
    def job_status(job_id: str) -> Any:
        job = store.get(job_id)
        if job is None:
            return bad(InputError("no such run (finished runs are kept for a while)", "job"), 404)
        return job.status()

    @app.post("/api/jobs/{job_id}/cancel")
    def cancel(job_id: str) -> Any:
        job = store.get(job_id)
        if job is None:
            return bad(InputError("no such run", "job"), 404)
        job.cancel.set()
        return {"id": job_id, "state": job.state, "cancel_requested": True}

    @app.get("/jobs/{job_id}/report", response_class=HTMLResponse)
    def report(job_id: str) -> Any:
        job = store.get(job_id)
        if job is None or job.result is None:
            return HTMLResponse("<p>No finished run with this id.</p>", status_code=404)
        if job.report is None:
            from woundroll.app.report import build_report

            job.report = build_report(
                job.result, readings=job.readings, diagnosis=job.diagnosis, defects=job.defects
            )
        return HTMLResponse(job.report)

    return app


def serve(host: str = "127.0.0.1", port: int = 8000) -> None:
    """Run the page with uvicorn until interrupted."""
    import uvicorn

    uvicorn.run(create_app(), host=host, port=port, log_level="warning")
