"""Files that hardness testers and the people holding them produce: read and write.

Three layouts (docs/tester-files.md says what public documentation showed and what not):

``generic``
    The position-value CSV of :mod:`woundroll.io.readings` (``position [in],reading [Rho]``,
    lanes, passes, several value columns). Read by :func:`woundroll.io.readings.read_readings`;
    written by :func:`write_generic` (long form: ``position [unit],pass,reading [scale]``).

``tappi``
    The TAPPI T 834 hand-reading sheet: readings every 6 in across the roll, several rolls
    (and passes) on one sheet, one row per roll and pass::

        # roll hardness, TAPPI T 834; readings every 6 in from the drive side
        roll,pass,scale,lane 1,lane 2,lane 3,lane 4
        4711-1,1,Rho,55,58,57,54
        4711-1,2,Rho,56,58,56,55
        4711-2,1,Rho,60,62,,

    Value columns are ``lane N`` (centred at ``(N - 1/2) x lane_width`` from the edge, the
    convention of :mod:`woundroll.io.readings`; lane width 6 in unless given) or positions with
    a unit (``3 in``, ``7.5 cm``). ``pass`` and ``scale`` (Rho, R, L, g; default Rho) are
    optional columns; an empty cell is a lane not read (a narrower roll). Read by
    :func:`read_tappi_sheet` into one :class:`~woundroll.io.readings.Readings` per roll;
    written by :func:`write_tappi_sheet`.

``profile``
    A dense CMD profile as automatic testers export it to a spreadsheet (many taps across
    the roll): metadata lines ``key;value`` (or ``key: value``, ``key,value``) above a
    header row with a position column and one value column per scan; separator ``;``, tab
    or ``,``; decimal comma accepted with ``;`` or tab. No vendor publishes its export
    layout (docs/tester-files.md): this is the generic shape such exports take, not a
    vendor parser. Read by :func:`read_profile_export` (:class:`ProfileExport`: readings and
    metadata), written by :func:`write_profile_export`.

:func:`read_tester_file` detects the layout (``format="auto"``) and returns the readings of
one roll. Every problem raises :class:`~woundroll.errors.InputError` naming the file and line.
"""

from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from woundroll.errors import InputError
from woundroll.io.readings import (
    SCALES,
    Readings,
    check_on_scale,
    read_readings,
    readings_from_arrays,
)

__all__ = [
    "FORMATS",
    "TAPPI_LANE_WIDTH",
    "ProfileExport",
    "detect_format",
    "read_profile_export",
    "read_tappi_sheet",
    "read_tester_file",
    "write_generic",
    "write_profile_export",
    "write_tappi_sheet",
]

FORMATS = ("auto", "generic", "tappi", "profile")
#: TAPPI T 834: one reading every 6 in across the roll.
TAPPI_LANE_WIDTH = 6 * 0.0254
_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}
_POSITION_NAMES = ("position", "pos", "x", "z", "cmd", "cmd position", "distance")
_LANE = re.compile(r"^\s*lane\s*(\d+)\s*$", re.IGNORECASE)
_AT = re.compile(r"^\s*([-+]?\d+(?:[.,]\d*)?)\s*(m|cm|mm|in)\s*$")
_BRACKET = re.compile(r"^\s*([^\[(]*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$")


def _scale(text: str, where: str) -> str:
    t = text.strip()
    for s in SCALES:
        if t.lower() == s.lower():
            return s
    raise InputError(f"unknown scale {text!r} (known: {', '.join(SCALES)})", where)


def _lines(path: Path, field: str) -> list[str]:
    try:
        return path.read_text(encoding="utf-8-sig").splitlines()
    except FileNotFoundError:
        raise InputError(f"no such file: {path}", field) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read {path.name}: {exc}", field) from None


def _first_row(lines: list[str]) -> tuple[int, str] | None:
    for i, line in enumerate(lines):
        if line.strip() and not line.lstrip().startswith("#"):
            return i, line
    return None


def detect_format(path: str | Path, field: str = "readings") -> str:
    """``"tappi"`` (first column ``roll``), ``"profile"`` (``;``/tab separated, or metadata
    lines above the header) or ``"generic"``."""
    lines = _lines(Path(path), field)
    first = _first_row(lines)
    if first is None:
        raise InputError(f"{Path(path).name} has no data", field)
    line = first[1]
    delim = ";" if ";" in line else ("\t" if "\t" in line else ",")
    head = [c.strip() for c in line.split(delim)]
    if head[0].lower() == "roll" and any(
        c.lower() in ("pass", "scale") or _LANE.match(c) or _AT.match(c) for c in head[1:]
    ):
        return "tappi"
    if ";" in line or "\t" in line:
        return "profile"
    cells = [c.strip().lower() for c in line.split(",")]
    if len(cells) == 2 and not any(_is_position_name(c) for c in cells) and cells[1]:
        try:
            float(cells[1].replace(",", "."))
        except ValueError:
            return "profile"  # "key,value" metadata above the header
    return "generic"


def _is_position_name(cell: str) -> bool:
    m = _BRACKET.match(cell)
    name = (m.group(1) if m else cell).strip().lower().replace("_", " ")
    return name in _POSITION_NAMES or name.startswith("position")


# ----------------------------------------------------------------------------- generic
def write_generic(readings: Readings, path: str | Path, *, unit: str = "in") -> Path:
    """Every reading in long form: ``position [unit],pass,reading [scale]`` (full precision),
    which :func:`woundroll.io.readings.read_readings` reads back."""
    f = _UNITS[unit]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    buf.write(f"# {readings.source or 'readings'}: written by woundroll\n")
    w.writerow([f"position [{unit}]", "pass", f"reading [{readings.scale}]"])
    for x, p, v in zip(readings.raw_position, readings.raw_pass, readings.raw_value, strict=True):
        w.writerow([repr(float(x) / f), int(p), repr(float(v))])
    return _write(path, buf.getvalue())


def _write(path: str | Path, text: str) -> Path:
    p = Path(path)
    try:
        p.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot write {p}: {exc.strerror or exc}", "--out") from None
    return p


# ------------------------------------------------------------------------ TAPPI T 834
def read_tappi_sheet(
    path: str | Path,
    *,
    lane_width: float | None = None,
    width: float | None = None,
    field: str = "readings",
) -> dict[str, Readings]:
    """A TAPPI T 834 sheet (module docstring) -> ``{roll id: Readings}`` in sheet order.

    Parameters
    ----------
    lane_width : float, optional [m]
        Width of a lane for ``lane N`` columns (default 6 in, T 834).
    width : float, optional [m]
        Web width: readings outside ``[0, width]`` are an error.
    """
    path = Path(path)
    lw = TAPPI_LANE_WIDTH if lane_width is None else lane_width
    lines = _lines(path, field)
    first = _first_row(lines)
    if first is None:
        raise InputError(f"{path.name} has no data", field)
    start, header_line = first
    delim = ";" if header_line.count(";") > header_line.count(",") else ","
    rows = list(csv.reader(lines[start:], delimiter=delim))
    header = [h.strip() for h in rows[0]]
    at = f"{path.name} line {start + 1}"
    if not header or header[0].lower() != "roll":
        raise InputError(f"{at}: the first column must be 'roll'", field)
    idx_pass = _col(header, "pass")
    idx_scale = _col(header, "scale")
    positions = _tappi_positions(header, (idx_pass, idx_scale), lw, at, field)
    data: dict[str, dict[str, list[Any]]] = {}
    for i, row in enumerate(rows[1:], start=start + 2):
        if not row or not any(c.strip() for c in row) or row[0].lstrip().startswith("#"):
            continue
        where = f"{path.name} line {i}"
        if len(row) > len(header):
            raise InputError(f"{where}: {len(row)} cells, the header has {len(header)}", field)
        roll = row[0].strip()
        if not roll:
            raise InputError(f"{where}: no roll id", field)
        p = _tappi_pass(row, idx_pass, where, field)
        sc = "Rho"
        if idx_scale is not None and idx_scale < len(row) and row[idx_scale].strip():
            sc = _scale(row[idx_scale], f"{field} ({where})")
        d = data.setdefault(roll, {"x": [], "v": [], "p": [], "scale": [sc], "n": [0]})
        if d["scale"][0] != sc:
            raise InputError(f"{where}: roll {roll} mixes scales {d['scale'][0]} and {sc}", field)
        d["n"][0] += 1
        _tappi_row_readings(d, row, header, positions, p, sc, delim == ";", where, field)
    if not data:
        raise InputError(f"{path.name}: no readings under the header", field)
    units = {m.group(2) for h in header if (m := _AT.match(h))}
    pos_unit = "in" if not units else (units.pop() if len(units) == 1 else "")
    out = {}
    for roll, d in data.items():
        if not d["v"]:
            raise InputError(f"{path.name}: roll {roll} has no readings", field)
        out[roll] = _arrays(
            field,
            d["x"],
            d["v"],
            scale=d["scale"][0],
            passes=d["p"],
            width=width,
            source=f"{path.name}: roll {roll}",
            lane_width=lw,
        )
        out[roll] = replace(out[roll], position_unit=pos_unit)
    return out


def _tappi_positions(
    header: list[str], skip: tuple[int | None, int | None], lw: float, at: str, field: str
) -> dict[int, float]:
    """Column -> position [m]: ``lane N`` (the lane's centre) or a position with a unit."""
    positions: dict[int, float] = {}
    for j, h in enumerate(header):
        if j == 0 or j in skip:
            continue
        m = _LANE.match(h)
        if m:
            k = int(m.group(1))
            if k < 1:
                raise InputError(f"{at}: lane numbers start at 1, got {h!r}", field)
            positions[j] = (k - 0.5) * lw
            continue
        m = _AT.match(h)
        if m:
            positions[j] = float(m.group(1).replace(",", ".")) * _UNITS[m.group(2)]
            continue
        raise InputError(
            f"{at}: column {h!r} is neither 'lane N' nor a position with a unit ('3 in')", field
        )
    if not positions:
        raise InputError(f"{at}: no lane columns", field)
    return positions


def _tappi_pass(row: list[str], idx_pass: int | None, where: str, field: str) -> int:
    """The row's pass number (0: none given, the row's count for its roll is used)."""
    p = 0
    if idx_pass is not None and idx_pass < len(row) and row[idx_pass].strip():
        try:
            p = int(row[idx_pass])
        except ValueError:
            msg = f"{where}: pass {row[idx_pass]!r} is not a whole number"
            raise InputError(msg, field) from None
        if p < 1:
            raise InputError(f"{where}: passes are numbered from 1", field)
    return p


def _tappi_row_readings(
    d: dict[str, list[Any]],
    row: list[str],
    header: list[str],
    positions: dict[int, float],
    p: int,
    sc: str,
    decimal_comma: bool,
    where: str,
    field: str,
) -> None:
    """The row's readings appended to its roll's lists ``d`` (an empty cell: no reading)."""
    for j, x in positions.items():
        cell = row[j].strip() if j < len(row) else ""
        if not cell:
            continue
        try:
            v = float(cell.replace(",", ".") if decimal_comma else cell)
        except ValueError:
            v = math.nan
        if not math.isfinite(v):
            raise InputError(f"{where}: {header[j]} = {cell!r} is not a number", field)
        check_on_scale(v, sc, f"{where}, {header[j]}", field)
        d["x"].append(x)
        d["v"].append(v)
        d["p"].append(p or d["n"][0])


def _arrays(field: str, *args: Any, **kw: Any) -> Readings:
    """:func:`readings_from_arrays` with its errors under ``field``."""
    try:
        return readings_from_arrays(*args, **kw)
    except InputError as exc:
        raise InputError(exc.message, field) from None


def _col(header: list[str], name: str) -> int | None:
    for j, h in enumerate(header):
        if h.strip().lower() == name:
            return j
    return None


def write_tappi_sheet(
    rolls: dict[str, Readings], path: str | Path, *, lane_width: float | None = None
) -> Path:
    """Rolls to one T 834 sheet: ``lane N`` columns when every reading sits on a lane centre
    of ``lane_width`` (default 6 in), else position columns in inches; one row per pass."""
    lw = TAPPI_LANE_WIDTH if lane_width is None else lane_width
    xs = sorted({float(x) for r in rolls.values() for x in r.raw_position})
    lanes = [(x / lw) + 0.5 for x in xs]
    on_lanes = all(abs(k - round(k)) < 1e-9 and round(k) >= 1 for k in lanes)
    cols = [f"lane {round(k)}" for k in lanes] if on_lanes else [f"{x / 0.0254!r} in" for x in xs]
    buf = io.StringIO()
    buf.write(f"# roll hardness sheet (TAPPI T 834 layout), lane width {lw / 0.0254:g} in\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["roll", "pass", "scale", *cols])
    for roll, r in rolls.items():
        for p in sorted(set(int(v) for v in r.raw_pass)):
            sel = r.raw_pass == p
            pairs = zip(r.raw_position[sel], r.raw_value[sel], strict=True)
            cells = {float(x): float(v) for x, v in pairs}
            w.writerow([roll, p, r.scale, *[repr(cells[x]) if x in cells else "" for x in xs]])
    return _write(path, buf.getvalue())


# ------------------------------------------------------------------- profile exports
@dataclass(frozen=True)
class ProfileExport:
    """A dense profile export: its readings (one pass per scan) and its metadata lines."""

    readings: Readings
    metadata: dict[str, str] = field(default_factory=dict)


def read_profile_export(
    path: str | Path,
    *,
    scale: str | None = None,
    width: float | None = None,
    field: str = "readings",
) -> ProfileExport:
    """A dense CMD profile exported by an automatic tester (module docstring).

    The header row is the first row whose first cell names a position (``position [mm]``,
    ``Position (mm)``, ``x [cm]``, ``distance_mm``); rows above it are metadata. The scale
    comes from the value columns' unit (``hardness [g]``), a ``scale``/``unit`` metadata
    entry, or ``scale``; value columns are scans (passes).
    """
    path = Path(path)
    lines = [ln for ln in _lines(path, field)]
    content = [(i, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.startswith("#")]
    if not content:
        raise InputError(f"{path.name} has no data", field)
    sample = content[-1][1]
    delim = ";" if ";" in sample else ("\t" if "\t" in sample else ",")
    meta: dict[str, str] = {}
    header_at = None
    for i, ln in content:
        cells = next(csv.reader([ln], delimiter=delim))
        if cells and _is_position_name(cells[0]):
            header_at = i
            header = [c.strip() for c in cells]
            break
        key, _, value = ln.partition(delim) if delim in ln else ln.partition(":")
        meta[key.strip().rstrip(":")] = value.strip().strip(delim).strip()
    if header_at is None:
        raise InputError(
            f"{path.name}: no header row with a position column ('position [mm]')", field
        )
    m = _BRACKET.match(header[0])
    unit = (m.group(2) if m else header[0].rsplit("_", 1)[-1] if "_" in header[0] else "").strip()
    if unit not in _UNITS:
        raise InputError(
            f"{path.name} line {header_at + 1}: position unit {unit or '(none)'!r} "
            f"(give one of {', '.join(_UNITS)})",
            field,
        )
    f = _UNITS[unit]
    if len(header) < 2:
        raise InputError(f"{path.name} line {header_at + 1}: no value column", field)
    sc = _export_scale(header, meta, scale, path.name, field)
    decimal_comma = delim != ","
    xs, vs, ps = [], [], []
    for i, ln in content:
        if i <= header_at:
            continue
        cells = next(csv.reader([ln], delimiter=delim))
        where = f"{path.name} line {i + 1}"
        try:
            x = _num(cells[0], decimal_comma) * f
        except ValueError:
            raise InputError(f"{where}: position {cells[0]!r} is not a number", field) from None
        for k, cell in enumerate(cells[1 : len(header)], start=1):
            if not cell.strip():
                continue
            try:
                v = _num(cell, decimal_comma)
            except ValueError:
                raise InputError(
                    f"{where}: {header[k]} = {cell!r} is not a number", field
                ) from None
            check_on_scale(v, sc, f"{where}, {header[k]}", field)
            xs.append(x)
            vs.append(v)
            ps.append(k)
    if not vs:
        raise InputError(f"{path.name}: no readings under the header", field)
    r = _arrays(field, xs, vs, scale=sc, passes=ps, width=width, source=path.name)
    return ProfileExport(replace(r, position_unit=unit), meta)


def _export_scale(
    header: list[str], meta: dict[str, str], scale: str | None, name: str, field: str
) -> str:
    """The export's scale: ``scale``, else the value columns' unit (``hardness [g]``), else
    a ``scale``/``unit`` metadata entry."""
    sc = scale
    for h in header[1:]:
        mh = _BRACKET.match(h)
        if sc is None and mh and mh.group(2):
            sc = mh.group(2)
    for key in ("scale", "unit", "Scale", "Unit"):
        if sc is None and key in meta:
            sc = meta[key]
    if sc is None:
        raise InputError(
            f"{name}: no scale: give the unit in the value header ('hardness [g]')", field
        )
    return _scale(sc, field)


def _num(text: str, decimal_comma: bool) -> float:
    t = text.strip()
    if decimal_comma:
        t = t.replace(",", ".")
    v = float(t)
    if not math.isfinite(v):
        raise ValueError(text)
    return v


def write_profile_export(
    readings: Readings,
    path: str | Path,
    *,
    metadata: dict[str, str] | None = None,
    decimal_comma: bool = True,
) -> Path:
    """A profile export: metadata lines, ``position [mm];scan 1 [scale];...`` with ``;`` and
    (by default) decimal commas, full precision. Scans are the readings' passes."""
    passes = sorted(set(int(p) for p in readings.raw_pass))
    xs = sorted({float(x) for x in readings.raw_position})

    def num(v: float) -> str:
        s = repr(float(v))
        return s.replace(".", ",") if decimal_comma else s

    out = io.StringIO()
    for k, v in (metadata or {}).items():
        out.write(f"{k};{v}\n")
    out.write(";".join(["position [mm]", *[f"scan {p} [{readings.scale}]" for p in passes]]))
    out.write("\n")
    table = {
        (float(x), int(p)): float(v)
        for x, p, v in zip(
            readings.raw_position, readings.raw_pass, readings.raw_value, strict=True
        )
    }
    for x in xs:
        cells = [num(x * 1e3)]
        cells += [num(table[(x, p)]) if (x, p) in table else "" for p in passes]
        out.write(";".join(cells) + "\n")
    return _write(path, out.getvalue())


# ---------------------------------------------------------------------------- dispatch
def read_tester_file(
    path: str | Path,
    *,
    format: str = "auto",  # noqa: A002 - the CLI's word
    roll: str | None = None,
    width: float | None = None,
    lane_width: float | None = None,
    field: str = "readings",
) -> Readings:
    """The readings of one roll from any of the layouts (module docstring).

    ``roll`` picks a roll of a TAPPI sheet (needed when the sheet holds several); given
    for another layout it is an input error rather than silently ignored.

    Raises
    ------
    InputError
        Unknown format, an unknown or missing roll id, or anything the reader rejects.
    """
    if format not in FORMATS:
        raise InputError(f"unknown format {format!r}; one of {', '.join(FORMATS)}", field)
    fmt = detect_format(path, field) if format == "auto" else format
    if roll is not None and fmt != "tappi":
        # a roll id picks a roll of a TAPPI sheet; on a one-roll file it would be ignored
        raise InputError(
            f"--roll {roll} picks a roll of a TAPPI sheet, but {Path(path).name} is a "
            f"{fmt} file with one roll",
            "--roll",
        )
    if fmt == "generic":
        return read_readings(path, width=width, lane_width=lane_width, field=field)
    if fmt == "profile":
        return read_profile_export(path, width=width, field=field).readings
    # the web width is the chosen roll's: check only that one
    rolls = read_tappi_sheet(path, lane_width=lane_width, field=field)
    if roll is None:
        if len(rolls) > 1:
            raise InputError(
                f"{Path(path).name} holds {len(rolls)} rolls ({', '.join(rolls)}): pick one", field
            )
        roll = next(iter(rolls))
    if roll not in rolls:
        raise InputError(f"no roll {roll!r} in {Path(path).name} ({', '.join(rolls)})", field)
    r = rolls[roll]
    if width is None:
        return r
    checked = _arrays(
        field,
        r.raw_position,
        r.raw_value,
        scale=r.scale,
        passes=r.raw_pass,
        width=width,
        source=r.source,
        lane_width=r.lane_width,
    )
    return replace(checked, position_unit=r.position_unit)
