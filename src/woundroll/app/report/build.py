"""The report put together (:func:`build_report`) and written (:func:`write_report`)."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

from woundroll.app.report.figures import _figures, storage_and_mode_figures
from woundroll.app.report.inputs import case_hash, input_sections
from woundroll.app.report.sections import (
    EQUATION_NOTE,
    ID_FIELDS,
    _assumptions,
    _warnings,
    defects_section,
    diagnosis_section,
    profile_check_section,
    readings_section,
    summary_section,
    trend_section,
)
from woundroll.errors import InputError

if TYPE_CHECKING:
    from woundroll.pipeline import RunResult


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
        "winding": [
            "Stresses wound into the roll: sigma_r, sigma_theta and E_r against radius.",
            "Winding speed: diameter against wound length with and without entrained air; "
            "pressure and wound-in stress at winding and after the air has left.",
        ],
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
        if name == "winding":  # storage time, surface winding: before/after, WOT(r)
            sections[-1]["figures"] += storage_and_mode_figures(result)
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
