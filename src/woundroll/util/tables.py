"""Reading small numeric tables (CSV) whose header names each column and its unit.

Accepted header forms: ``position_m,thickness_m`` (unit after the last underscore),
``position [in],thickness [mil]`` (unit in brackets), ``strain [%]``, or a bare name
(SI). Used for stack-test curves, thickness profiles and tabulated tapers.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.units import to_si

_BRACKET = re.compile(r"^\s*([A-Za-z_ ]+?)\s*[\[(]\s*([^\])]+)\s*[\])]\s*$")
_SUFFIX_UNITS = {
    "m": "m",
    "mm": "mm",
    "um": "um",
    "in": "inch",
    "mil": "mil",
    "pa": "Pa",
    "kpa": "kPa",
    "mpa": "MPa",
    "psi": "psi",
    "n": "N",
    "npm": "N/m",
    "pli": "pli",
    "pct": "%",
    "percent": "%",
}


def parse_header(name: str) -> tuple[str, str | None]:
    """Split ``"thickness [mil]"`` or ``"thickness_mil"`` into ``("thickness", "mil")``."""
    m = _BRACKET.match(name)
    if m:
        return m.group(1).strip().lower().replace(" ", "_"), m.group(2).strip()
    base, _, suffix = name.strip().rpartition("_")
    if base and suffix.lower() in _SUFFIX_UNITS:
        return base.lower(), _SUFFIX_UNITS[suffix.lower()]
    return name.strip().lower(), None


def read_header_row(path: Path | str, field: str = "file") -> list[str]:
    """The first non-comment row of a CSV (its header), or ``[]`` for an empty file.

    Raises :class:`InputError` naming ``field`` when the file is missing or unreadable.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"file not found: {path}", field)
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            return next((r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")), [])
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read {path}: {exc}", field) from None


def read_columns(
    path: Path | str, wanted: dict[str, str], field: str = "file"
) -> dict[str, NDArray[np.float64]]:
    """Read the columns named in ``wanted`` (name -> dimension kind) from a CSV, in SI.

    Raises :class:`InputError` naming ``field`` when the file is missing, a column is
    absent, a value is not a finite number, or a unit has the wrong dimension.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"file not found: {path}", field)
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read {path}: {exc}", field) from None
    if len(rows) < 2:
        raise InputError(f"{path.name}: needs a header row and at least one data row", field)
    header = [parse_header(h) for h in rows[0]]
    names = [h[0] for h in header]
    out: dict[str, NDArray[np.float64]] = {}
    for want, kind in wanted.items():
        if want not in names:
            raise InputError(
                f"{path.name}: no column '{want}' (columns: {', '.join(rows[0])})", field
            )
        j = names.index(want)
        unit = header[j][1]
        scale = to_si(f"1 {unit}", kind, f"{field}:{rows[0][j]}") if unit else 1.0
        vals = []
        for i, row in enumerate(rows[1:], start=2):
            try:
                v = float(row[j])
            except (ValueError, IndexError):
                raise InputError(
                    f"{path.name} line {i}: column '{rows[0][j]}' is not a number", field
                ) from None
            if not np.isfinite(v):
                raise InputError(
                    f"{path.name} line {i}: column '{rows[0][j]}' is not finite", field
                )
            vals.append(v * scale)
        out[want] = np.asarray(vals, dtype=float)
    return out
