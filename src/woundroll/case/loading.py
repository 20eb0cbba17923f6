"""Reading a case: a TOML file, a bundled case's name or a dict, with ``--set`` overrides,
into a validated :class:`~woundroll.case.schema.Case` (see docs/case-files.md)."""

from __future__ import annotations

import tomllib
from collections.abc import Sequence
from importlib import resources
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from woundroll.case.schema import (
    _BASE_DIR,
    FROM_CASE_FILE,
    FROM_SET,
    Case,
    _deepcopy,
    _sources_of,
)
from woundroll.errors import InputError


def _error_from_validation(exc: ValidationError) -> InputError:
    err = exc.errors(include_url=False)[0]
    loc = [str(p) for p in err["loc"] if not str(p).startswith("function-")]
    field = ".".join(loc) or None
    inner = (err.get("ctx") or {}).get("error")
    if isinstance(inner, InputError):
        if inner.field and field and not inner.field.startswith(field.split(".")[0]):
            return InputError(inner.message, f"{field}.{inner.field}" if field else inner.field)
        return InputError(inner.message, inner.field or field)
    msg = err["msg"].removeprefix("Value error, ")
    if err["type"] == "missing":
        msg = "missing (required)"
    elif err["type"] == "extra_forbidden":
        msg = "unknown key (check the spelling; see docs/case-files.md)"
    return InputError(msg, field)


def case_from_dict(
    data: dict[str, Any],
    base_dir: Path | None = None,
    *,
    overrides: Sequence[tuple[str, Any] | tuple[str, Any, str]] | None = None,
    override_source: str = FROM_SET,
    source: str = FROM_CASE_FILE,
) -> Case:
    """Validate a case given as nested dicts (TOML structure) and return a :class:`Case`.

    ``overrides``: ``(dotted key, value)`` pairs set over ``data`` (not modified), each
    recorded with ``override_source`` (``"--set"``, ``"web form"``), or ``(key, value,
    source)`` with its own; the values of ``data`` are recorded with ``source``
    (:attr:`Case.inputs`, :attr:`Case.display_title`).
    """
    from woundroll import limits
    from woundroll.winding.hakiel import WindingOptions

    if not isinstance(data, dict):
        raise InputError("a case must be a table of tables ([web], [core], [winding])", "CASE")
    # (key, value, source): an override may name its own source (a CLI flag such as
    # --no-update that sets a key), else it is override_source's
    given = [(o[0], o[1], o[2] if len(o) > 2 else override_source) for o in overrides or []]
    if given:
        data = _deepcopy(data)
        for key, value, _ in given:
            set_dotted(data, key, value)
    _BASE_DIR.value = base_dir
    try:
        case = Case.model_validate(data)
        case._base_dir = base_dir
        warnings = limits.check_case_values(case)
        web = case.web.build()
        core = case.core.build()
        r_out = case.winding.final_radius(web, core)
        schedule = case.winding.schedule(web)
        options = WindingOptions.from_dict(case.winding.options, "winding.options")
        size = "winding.length" if case.winding.length is not None else "winding.outer_radius"
        warnings += limits.check_built(web, core, r_out, schedule, options, size)
        _check_options(case)
        slow = limits.contact_time_warning(case, web)
        if slow:
            warnings.append(slow)
    except ValidationError as exc:
        raise _error_from_validation(exc) from None
    finally:
        _BASE_DIR.value = None
    case._warnings = tuple(warnings)
    case._given, case._sources = _sources_of(data, given, source)
    case._overrides = tuple(given)
    return case


def _check_options(case: Case) -> None:
    """Validate the tables owned by the models now, before any long computation."""
    from woundroll.winding.hakiel import WindingOptions

    WindingOptions.from_dict(case.winding.options, "winding.options")
    # read and validated once here (cached on the case): files and tables fail at load time
    _ = case.tester_setup
    if case.tester is not None:
        case.contact.contact_options()
        if "roll_spring" not in case.tester and case.tester_setup is not None:
            case.contact.roll_model(case.tester_setup.instrument.head_shape)
    if case.contact.dynamic or case.contact.dynamic_options:
        case.contact.dynamic_settings()
        if case.tester is None or "roll_spring" in case.tester:
            raise InputError(
                "the impact in time runs on the FE roll under the tester's head: give [tester] "
                "without [tester.roll_spring]",
                "contact.dynamic",
            )
        if case.winding.thickness_profile is not None:
            raise InputError(
                "the impact in time runs on the single roll, not per CMD sector: remove "
                "winding.thickness_profile or contact.dynamic",
                "contact.dynamic",
            )
    _read_file(case, "thickness_profile", "winding.thickness_profile")
    if case.profile.measured is not None:
        if case.winding.thickness_profile is None:
            raise InputError(
                "a measured profile is compared with a predicted one: give "
                "winding.thickness_profile too",
                "profile.measured",
            )
        _read_file(case, "measured_profile", "profile.measured")
    if case.readings is not None:
        _read_file(case, "measured_readings", "readings.file")
    if case.winding.nip_roller is not None:
        if case.winding.thickness_profile is None:
            raise InputError(
                "a nip roller beam needs a thickness profile (winding.thickness_profile); "
                "without one the nip acts through winding.nip_load and winding.friction",
                "winding.nip_roller",
            )
        case.winding.nip_roller.build(case.winding.nip_load, case.winding.friction)


def _read_file(case: Case, attr: str, field: str) -> None:
    """Read a file the case names now; a file whose content is not what it should be (text in
    a number map, a wrong encoding) is an input error naming the field, not a traceback."""
    try:
        getattr(case, attr)
    except InputError:
        raise
    except (ValueError, TypeError, OSError, UnicodeDecodeError, EOFError) as exc:
        raise InputError(f"cannot read the file: {exc}", field) from None


def bundled_cases() -> dict[str, str]:
    """Bundled case names -> titles (``woundroll cases``)."""
    out = {}
    for entry in sorted(resources.files("woundroll.data.cases").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            out[entry.name.removesuffix(".toml")] = str(data.get("title", ""))
    return out


def resolve_case_path(name_or_path: str | Path) -> Path:
    """A case file path, or the path of a bundled case named ``name_or_path``."""
    p = Path(name_or_path)
    if p.is_file():
        return p
    bundled = resources.files("woundroll.data.cases") / f"{name_or_path}.toml"
    if bundled.is_file():
        return Path(str(bundled))
    raise InputError(
        f"no case file or bundled case named {str(name_or_path)!r} "
        f"(bundled: {', '.join(bundled_cases())})",
        "CASE",
    )


def set_dotted(data: dict[str, Any], key: str, value: Any) -> None:
    """Set ``data["a"]["b"] = value`` for ``key = "a.b"`` (creating tables as needed)."""
    parts = key.split(".")
    if not all(parts):
        raise InputError(f"bad key {key!r}", "--set")
    node = data
    for p in parts[:-1]:
        nxt = node.setdefault(p, {})
        if not isinstance(nxt, dict):
            raise InputError(f"{p!r} is not a table, cannot set {key!r}", key)
        node = nxt
    node[parts[-1]] = value


def parse_override(text: str) -> tuple[str, Any]:
    """``"winding.tension=30 N"`` -> ``("winding.tension", "30 N")``; TOML values are honoured."""
    key, sep, raw = text.partition("=")
    if not sep:
        raise InputError(f"expected dotted.key=value, got {text!r}", "--set")
    raw = raw.strip()
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        value = raw
    return key.strip(), value


def load_case(
    source: str | Path | dict[str, Any],
    overrides: Sequence[str | tuple[str, str]] | None = None,
    *,
    override_source: str = FROM_SET,
) -> Case:
    """Read a case from a TOML file, a bundled case name, or a dict, with ``--set`` overrides
    (``"dotted.key=value"``, recorded as coming from ``override_source``; or
    ``("dotted.key=value", source)`` with a source of its own).

    Raises
    ------
    InputError
        For a missing file, TOML syntax, unknown keys, bad values, units or dimensions.
    """
    base_dir = None
    if isinstance(source, dict):
        data = source
    else:
        path = resolve_case_path(source)
        data = _read_toml(path)
        base_dir = path.parent
    pairs = [
        (*parse_override(o), override_source)
        if isinstance(o, str)
        else (*parse_override(o[0]), o[1])
        for o in overrides or []
    ]
    return case_from_dict(data, base_dir, overrides=pairs, override_source=override_source)


def _read_toml(path: Path) -> dict[str, Any]:
    """The TOML table of a case file: UTF-8 (a byte-order mark is skipped); a binary file, a
    UTF-16 file or a TOML syntax error is an input error naming the file (field ``CASE``)."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read {path}: {exc.strerror or exc}", "CASE") from None
    if b"\x00" in raw[:4096]:
        kind = "UTF-16/32 text" if raw[:2] in (b"\xff\xfe", b"\xfe\xff") else "binary"
        raise InputError(
            f"{path.name} is {kind}, not a UTF-8 TOML file (save it as UTF-8 text)", "CASE"
        )
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(
            f"{path.name} is not UTF-8 text (byte {exc.start}); save it as UTF-8", "CASE"
        ) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path.name} is not valid TOML: {exc}", "CASE") from None
