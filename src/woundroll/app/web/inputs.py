"""What the web page takes in: the case as TOML text with the form's overrides, readings as
text, each checked like the CLI checks them, with the page's limits (sizes, the bundled files
a case may name; see the package docstring)."""

# and their types are imported inside create_app()

import tempfile
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from woundroll.errors import InputError

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
    "winding.friction": ("friction, web on web (nip-induced tension)", "0.3"),
    "winding.speed": ("winding speed (entrained air)", "0 m/s, 1000 ft/min"),
    "storage.temperature_change": ("temperature change in storage", "-20 K, -36 degF"),
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
        "winding.speed": (case.winding.speed, "m/s"),
        "storage.temperature_change": (
            case.storage.temperature_change if case.storage is not None else 0.0,
            "K",
        ),
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
