"""Hardness readings taken on a roll: a CSV of CMD positions and values, in the instrument's units.

The start of the reverse road (readings -> stresses -> causes -> setpoints, docs/diagnosis.md).
A process engineer walks along the roll with a Rho-meter, a Schmidt hammer, a Parotester or a
tapper and writes down one value per position, often over several passes. This module reads
that sheet into :class:`Readings`: positions in m from the reference edge, every value, and
per position the mean and the scatter.

File format (CSV, ``#`` starts a comment line, a header row first)::

    # roll 4711, front side, 2026-11-20
    position [in], reading [Rho]
    3, 61
    9, 63
    3, 60          <- a repeated position: a second pass, gives the scatter

* **Position column**: ``position`` (also ``pos``, ``x``, ``z``, ``cmd``) with a length unit in
  brackets or as a suffix (``position [cm]``, ``position_in``, ``position [m]``), or ``lane``:
  a lane number 1, 2, ... with a stated lane width (``lane_width = "6 in"``: TAPPI T 834 takes
  one reading every 6 in across the roll). Lane ``k`` is centred at ``(k - 1/2) x lane_width``
  from the reference edge (assumption: lanes start at the edge; stated in docs/diagnosis.md).
* **Value columns**: the instrument's scale is the unit: ``[Rho]`` (Beloit Rho-meter),
  ``[R]`` (Schmidt rebound number), ``[L]`` (Parotester L), ``[g]`` (peak deceleration of a
  tapper). The column name may be the scale itself (``rho``, ``R``, ``L``, ``g``, ``schmidt_r``,
  ``parotester_l``) or any name with the scale in brackets (``reading [Rho]``,
  ``pass 2 [Rho]``). Several value columns are several passes (wide sheet); all must share one
  scale.
* **Passes**: a ``pass`` column numbers the passes of a long sheet; without it, the k-th reading
  at a position belongs to pass k. Repeated readings at one position give its scatter.

Every problem (no header, unknown scale, a value that is not a finite number or lies off the
instrument's scale (:func:`scale_limits`), a position outside the roll, an unreadable file)
raises :class:`~woundroll.errors.InputError` whose message names the file and the line.
"""

from __future__ import annotations

import csv
import dataclasses
import math
import re
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

__all__ = [
    "SCALES",
    "Readings",
    "DISPLAY_UNITS",
    "check_on_scale",
    "display_unit",
    "read_readings",
    "readings_from_arrays",
    "scale_limits",
]

#: Scale (unit of a reading) -> instrument readout kind (woundroll.instruments.readout.READOUTS).
SCALES: dict[str, str] = {"Rho": "rho", "R": "schmidt-r", "L": "parotester-l", "g": "g"}
#: Spellings accepted for each scale (lower case, spaces and dashes as underscores).
_SCALE_ALIASES: dict[str, str] = {
    "rho": "Rho",
    "rhos": "Rho",
    "r": "R",
    "schmidt_r": "R",
    "schmidt": "R",
    "rebound_r": "R",
    "l": "L",
    "parotester_l": "L",
    "parotester": "L",
    "g": "g",
    "peak_g": "g",
    "tapper_g": "g",
}
#: What each scale's instrument is called in an error message.
_SCALE_INSTRUMENT: dict[str, str] = {
    "Rho": "Rho-meter",
    "R": "Schmidt hammer",
    "L": "Parotester",
    "g": "tapper",
}
_POSITION_NAMES = ("position", "pos", "x", "z", "cmd", "cmd_position")
_LANE_NAMES = ("lane", "lane_number", "lane_no")
_PASS_NAMES = ("pass", "pass_number", "pass_no", "run")
_VALUE_NAMES = ("reading", "value", "hardness", "pass")
_BRACKET = re.compile(r"^\s*([^\[(]*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$")
#: Positions may lie this far outside [0, width] (rounding of hand-written positions).
EDGE_TOLERANCE = 1e-3  # m


def _key(text: str) -> str:
    return re.sub(r"[\s\-]+", "_", text.strip().lower())


def _scale_of(text: str) -> str | None:
    """``"Rho"``, ``"R"``, ``"L"``, ``"g"`` for a recognised spelling, else None."""
    if text.strip() in SCALES:
        return text.strip()
    return _SCALE_ALIASES.get(_key(text))


def scale_limits(scale: str) -> tuple[float, float]:
    """Lowest and highest value the instrument of ``scale`` can show (its dial or display).

    The ranges are the instruments' own (:data:`woundroll.instruments.definitions.READING_RANGES`:
    Rho-meter dial 0-100 Rho, Schmidt hammer rebound number R 10-100, Parotester L 0-1000);
    a tapper's peak deceleration in g has no upper end but cannot be negative (it is a
    magnitude). A measured value outside these limits is a typing or export error, never a
    reading (docs/tester-files.md, "Values off the scale").
    """
    from woundroll.instruments.definitions import READING_RANGES

    sc = _scale_of(scale)
    if sc is None:
        raise InputError(f"unknown scale {scale!r} (known: {', '.join(SCALES)})", "readings.scale")
    rng = READING_RANGES.get(SCALES[sc])
    return (0.0, math.inf) if rng is None else (float(rng[0]), float(rng[1]))


def check_on_scale(value: float, scale: str, where: str, field: str = "readings") -> None:
    """Raise :class:`InputError` naming ``where`` (file and line) and the value when
    ``value`` lies outside the instrument's scale (:func:`scale_limits`)."""
    lo, hi = scale_limits(scale)
    if lo <= value <= hi:
        return
    sc = _scale_of(scale) or scale
    span = f"{lo:g} to {hi:g} {sc}" if math.isfinite(hi) else f"{lo:g} {sc} or more"
    raise InputError(
        f"{where}: {value:g} {sc} is off the {_SCALE_INSTRUMENT[sc]}'s scale "
        f"({span}); a typing or export error?",
        field,
    )


@dataclass(frozen=True)
class Readings:
    """Hardness readings along the CMD (SI positions, values in the instrument's scale).

    Attributes
    ----------
    position : (n,) array [m]
        Distinct positions from the reference edge, increasing.
    mean : (n,) array
        Mean reading at each position.
    sd : (n,) array
        Sample standard deviation (ddof = 1) of the readings at each position; 0 where a
        position has a single reading (see :attr:`scatter` for the value to use).
    count : (n,) int array
        Readings at each position.
    scale : str
        ``"Rho"``, ``"R"``, ``"L"`` or ``"g"`` (:data:`SCALES`).
    raw_position, raw_value : (m,) arrays
        Every reading in file order ([m], scale).
    raw_pass : (m,) int array
        Pass number of each reading (1-based).
    raw_line : (m,) int array
        File line of each reading (0 for readings not read from a file).
    lane_width : float or None [m]
        Lane width when the file gives lane numbers.
    source : str
        File name (or a label).
    position_unit : str
        Length unit the file wrote its positions in (``"in"``, ``"cm"``, ``"mm"``, ``"m"``;
        ``"in"`` for a TAPPI sheet's 6 in lanes), for showing positions back in the user's
        unit; ``""`` when unknown (arrays, lane numbers of a generic file).
    """

    position: FloatArray
    mean: FloatArray
    sd: FloatArray
    count: IntArray
    scale: str
    raw_position: FloatArray
    raw_value: FloatArray
    raw_pass: IntArray
    raw_line: IntArray
    lane_width: float | None = None
    source: str = ""
    position_unit: str = ""

    # -- derived ---------------------------------------------------------------------
    @property
    def readout(self) -> str:
        """Instrument readout kind of the scale (``"rho"``, ``"schmidt-r"``, ...)."""
        return SCALES[self.scale]

    @property
    def n_positions(self) -> int:
        return int(self.position.size)

    @property
    def passes(self) -> int:
        """Number of passes (largest pass number)."""
        return int(self.raw_pass.max()) if self.raw_pass.size else 0

    @property
    def has_scatter(self) -> bool:
        """True when at least one position was read more than once."""
        return bool(np.any(self.count > 1))

    @property
    def pooled_sd(self) -> float | None:
        """Pooled within-position SD over the repeated positions (None without repeats).

        ``sqrt(sum (n_i - 1) s_i^2 / sum (n_i - 1))``: the instrument-and-roll repeatability
        estimated from the whole sheet.
        """
        dof = self.count - 1
        if not np.any(dof > 0):
            return None
        return float(math.sqrt(np.sum(dof * self.sd**2) / np.sum(dof)))

    @property
    def scatter(self) -> FloatArray:
        """SD to use at each position: its own where read >= 2 times, else the pooled SD
        (0 when no position was repeated: then the instrument's repeatability must come from
        elsewhere, e.g. the case)."""
        pooled = self.pooled_sd or 0.0
        return np.where(self.count > 1, self.sd, pooled)

    @property
    def sem(self) -> FloatArray:
        """Standard error of each position's mean, ``scatter / sqrt(count)``."""
        return self.scatter / np.sqrt(self.count)

    def values_by_pass(self) -> FloatArray:
        """(passes, n) array of readings, NaN where a pass has no reading at a position
        (the mean of repeated readings of one position within one pass)."""
        out = np.full((self.passes, self.n_positions), np.nan)
        idx = np.searchsorted(self.position, self.raw_position)
        for p in range(1, self.passes + 1):
            sel = self.raw_pass == p
            if not np.any(sel):
                continue
            s = np.bincount(idx[sel], weights=self.raw_value[sel], minlength=self.n_positions)
            c = np.bincount(idx[sel], minlength=self.n_positions)
            out[p - 1] = np.where(c > 0, s / np.maximum(c, 1), np.nan)
        return out

    # -- output ----------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (SI positions, values in :attr:`scale`)."""
        pooled = self.pooled_sd
        return {
            "source": self.source,
            "scale": self.scale,
            "readout": self.readout,
            "passes": self.passes,
            "lane_width_m": self.lane_width,
            "position_m": self.position.tolist(),
            "mean": self.mean.tolist(),
            "sd": self.sd.tolist(),
            "scatter": self.scatter.tolist(),
            "count": self.count.tolist(),
            "pooled_sd": pooled,
            "raw": {
                "position_m": self.raw_position.tolist(),
                "value": self.raw_value.tolist(),
                "pass": self.raw_pass.tolist(),
                "line": self.raw_line.tolist(),
            },
        }

    def to_table(self) -> str:
        """CSV text: ``position [m],mean [scale],sd [scale],count``."""
        rows = [f"position [m],mean [{self.scale}],sd [{self.scale}],count"]
        for x, m, s, n in zip(self.position, self.mean, self.sd, self.count, strict=True):
            rows.append(f"{x:.6g},{m:.6g},{s:.6g},{int(n)}")
        return "\n".join(rows) + "\n"

    def plot(self, path: str | Path | None = None, *, unit: str = "in") -> Any:
        """Every reading (dots, by pass) and the mean +- scatter per position; returns the Figure.

        Parameters
        ----------
        path : str, optional
            Save a PNG there.
        unit : "in", "cm" or "m"
            Position axis unit.
        """
        import matplotlib.pyplot as plt

        f = {"in": 1 / 0.0254, "cm": 100.0, "m": 1.0}[unit]
        fig, ax = plt.subplots(figsize=(7.0, 3.8))
        for p in range(1, self.passes + 1):
            sel = self.raw_pass == p
            ax.plot(
                self.raw_position[sel] * f,
                self.raw_value[sel],
                "o",
                ms=3.5,
                alpha=0.6,
                label=f"pass {p}" if self.passes <= 8 else None,
            )
        ax.errorbar(
            self.position * f,
            self.mean,
            yerr=self.scatter,
            color="k",
            lw=1.5,
            capsize=3,
            label="mean +- SD",
        )
        ax.set_xlabel(f"CMD position [{unit}]")
        ax.set_ylabel(f"reading [{self.scale}]")
        ax.set_title(f"{self.source or 'readings'}: {self.passes} pass(es)", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def readings_from_arrays(
    position: Any,
    value: Any,
    *,
    scale: str = "Rho",
    passes: Any = None,
    width: float | None = None,
    source: str = "",
    lane_width: float | None = None,
) -> Readings:
    """:class:`Readings` from arrays (positions [m], values in ``scale``), e.g. in a notebook.

    ``passes``: pass number of each reading (default: the k-th reading at a position is pass
    k). Raises :class:`InputError` for non-finite values, positions outside ``[0, width]``
    or an unknown scale.
    """
    sc = _scale_of(str(scale))
    if sc is None:
        raise InputError(f"unknown scale {scale!r} (known: {', '.join(SCALES)})", "readings.scale")
    x = np.asarray(position, dtype=float).ravel()
    v = np.asarray(value, dtype=float).ravel()
    if x.size != v.size or x.size == 0:
        raise InputError(
            f"needs as many positions as values, at least one (got {x.size} and {v.size})",
            "readings",
        )
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(v))):
        raise InputError("positions and values must be finite numbers", "readings")
    for i, val in enumerate(v):
        check_on_scale(
            float(val), sc, f"{source}, reading {i + 1}" if source else f"reading {i + 1}"
        )
    if width is not None:
        _check_inside(x, width, lambda i: f"{source or 'readings'} reading {i + 1}")
    p = None if passes is None else np.asarray(passes, dtype=int).ravel()
    return _assemble(x, v, p, np.zeros(x.size, dtype=int), sc, lane_width, source)


def _check_inside(x: FloatArray, width: float, where: Any) -> None:
    bad = np.flatnonzero((x < -EDGE_TOLERANCE) | (x > width + EDGE_TOLERANCE))
    if bad.size:
        i = int(bad[0])
        raise InputError(
            f"{where(i)}: position {x[i]:.4g} m lies outside the roll (0 to {width:.4g} m "
            "from the reference edge): same edge and units?",
            "readings",
        )


def _assemble(
    x: FloatArray,
    v: FloatArray,
    passes: IntArray | None,
    lines: IntArray,
    scale: str,
    lane_width: float | None,
    source: str,
) -> Readings:
    uniq, inv = np.unique(x, return_inverse=True)
    count = np.bincount(inv, minlength=uniq.size)
    mean = np.bincount(inv, weights=v, minlength=uniq.size) / count
    dev2 = np.bincount(inv, weights=(v - mean[inv]) ** 2, minlength=uniq.size)
    sd = np.where(count > 1, np.sqrt(dev2 / np.maximum(count - 1, 1)), 0.0)
    if passes is None:
        # k-th reading at a position (in file order) is pass k
        passes = np.zeros(x.size, dtype=int)
        seen = np.zeros(uniq.size, dtype=int)
        for i, j in enumerate(inv):
            seen[j] += 1
            passes[i] = seen[j]
    return Readings(
        position=uniq,
        mean=mean,
        sd=sd,
        count=count.astype(np.int64),
        scale=scale,
        raw_position=x,
        raw_value=v,
        raw_pass=np.asarray(passes, dtype=np.int64),
        raw_line=np.asarray(lines, dtype=np.int64),
        lane_width=lane_width,
        source=source,
    )


def _split(cell: str) -> tuple[str, str | None]:
    """Header cell -> (name, unit): ``"reading [Rho]"`` -> ``("reading", "Rho")``,
    ``"position_in"`` -> ``("position", "in")``."""
    m = _BRACKET.match(cell)
    if m:
        return _key(m.group(1)), m.group(2).strip()
    base, _, suffix = cell.strip().rpartition("_")
    if base and _key(base) in _POSITION_NAMES + _LANE_NAMES and suffix:
        return _key(base), suffix
    return _key(cell), None


def _length_scale(unit: str, where: str) -> float:
    from woundroll.units import to_si

    u = {"inch": "inch", "in": "inch", "inches": "inch", '"': "inch"}.get(unit.lower(), unit)
    try:
        return to_si(f"1 {u}", "length", "readings")
    except InputError:
        raise InputError(
            f"{where}: position unit {unit!r} is not a length (use m, cm, mm or in; or a "
            "'lane' column with a lane width)",
            "readings",
        ) from None


def read_readings(
    path: str | Path,
    *,
    width: float | None = None,
    lane_width: float | None = None,
    field: str = "readings",
) -> Readings:
    """Read a readings CSV (module docstring) into :class:`Readings`.

    Parameters
    ----------
    path : str or Path
    width : float, optional [m]
        Web width: positions outside ``[0, width]`` (1 mm tolerance) are an error.
    lane_width : float, optional [m]
        Width of one lane, needed when the file gives lane numbers (TAPPI T 834: 6 in).
    field : str
        Dotted name for error messages (``readings.file`` from a case, ``--readings`` on the
        command line).

    Raises
    ------
    InputError
        Missing or unreadable file, no header, unknown scale or position unit, a value that
        is not a finite number, a lane file without a lane width, a position outside the
        roll. The message names the file and the line.
    """
    path = Path(path)
    name = path.name
    rows = _csv_rows(path, field)
    if not rows:
        raise InputError(f"{name}: empty (needs a header row and readings)", field)
    hline, header = rows[0]
    if all(_is_number(c) for c in header if c):
        raise InputError(
            f"{name} line {hline}: no header row; the first row must name the columns with "
            "units, e.g. 'position [in],reading [Rho]'",
            field,
        )
    cols = _Columns.of(header, f"{name} line {hline}", lane_width, field)
    if len(rows) < 2:
        raise InputError(f"{name}: a header but no readings", field)
    xs: list[float] = []
    vs: list[float] = []
    ps: list[int] = []
    ls: list[int] = []
    for line, row in rows[1:]:
        at = f"{name} line {line}"
        pos = cols.position(row, header, at, width, lane_width, field)
        pass_no = cols.pass_number(row, header, at, field)
        for k, j in enumerate(cols.values):
            if len(cols.values) > 1 and (j >= len(row) or row[j] == ""):
                continue  # a wide sheet may leave a pass empty at a position
            v = _number(row, j, header, at, field)
            check_on_scale(v, cols.scale, f"{at}, column {header[j]!r}", field)
            xs.append(pos)
            vs.append(v)
            ps.append(pass_no if pass_no is not None else k + 1)
            ls.append(line)
    if not vs:
        raise InputError(f"{name}: no readings below the header", field)
    x_arr = np.asarray(xs)
    passes = np.asarray(ps, dtype=np.int64)
    # a long sheet without a pass column: the k-th reading at a position is pass k
    implicit = cols.pass_col is None and len(cols.values) == 1
    r = _assemble(
        x_arr,
        np.asarray(vs),
        None if implicit else passes,
        np.asarray(ls, dtype=np.int64),
        cols.scale,
        lane_width if cols.is_lane else None,
        name,
    )
    return replace(r, position_unit=cols.written_unit)


def _csv_rows(path: Path, field: str) -> list[tuple[int, list[str]]]:
    """The file's non-empty, non-comment rows with their line numbers, cells stripped (a
    decimal comma read as a point when the delimiter is not a comma)."""
    if not path.is_file():
        raise InputError(f"file not found: {path}", field)
    try:
        text = path.read_text(encoding="utf-8-sig")
        delimiter = _delimiter(text)
        reader = csv.reader(text.splitlines(), delimiter=delimiter)
        rows: list[tuple[int, list[str]]] = []
        for row in reader:
            if not row or not "".join(row).strip():
                continue
            if row[0].lstrip().startswith("#"):
                continue
            cells = [c.strip() for c in row]
            if delimiter != ",":  # spreadsheet exports with a decimal comma: "52,5"
                cells = [
                    c.replace(",", ".") if _is_number(c.replace(",", ".")) else c for c in cells
                ]
            rows.append((reader.line_num, cells))
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise InputError(f"cannot read {path.name}: {exc}", field) from None
    return rows


@dataclass
class _Columns:
    """What the header row says: the position column (length unit or lane numbers), the
    pass column, the reading columns and their scale."""

    pos_col: int | None = None
    pos_factor: float = 1.0
    is_lane: bool = False
    written_unit: str = ""
    pass_col: int | None = None
    values: list[int] = dataclasses.field(default_factory=list)
    scales: set[str] = dataclasses.field(default_factory=set)

    @property
    def scale(self) -> str:
        return next(iter(self.scales))

    @classmethod
    def of(cls, header: list[str], where: str, lane_width: float | None, field: str) -> _Columns:
        cols = cls()
        for j, cell in enumerate(header):
            cols._add(j, cell, where, field)
        cols._check(header, where, lane_width, field)
        return cols

    def _add(self, j: int, cell: str, where: str, field: str) -> None:
        base, unit = _split(cell)
        if base in _POSITION_NAMES and self.pos_col is None:
            if unit is None:
                raise InputError(
                    f"{where}: position column {cell!r} has no unit; write e.g. "
                    "'position [in]', 'position [cm]', 'position [m]', or a 'lane' column",
                    field,
                )
            if _key(unit) in _LANE_NAMES:
                self.is_lane = True
            else:
                self.pos_factor = _length_scale(unit, where)
                self.written_unit = display_unit(unit)
            self.pos_col = j
        elif base in _LANE_NAMES and self.pos_col is None:
            self.pos_col, self.is_lane = j, True
        elif base in _PASS_NAMES and unit is None:
            self.pass_col = j
        else:
            sc = _scale_of(unit) if unit is not None else _scale_of(base)
            if sc is None:
                what = f"unit {unit!r}" if unit is not None else "no unit"
                raise InputError(
                    f"{where}: column {cell!r}: {what}; a reading column needs the "
                    f"instrument's scale: [Rho], [R] (Schmidt), [L] (Parotester) or [g] "
                    f"(tapper), e.g. 'reading [Rho]'",
                    field,
                )
            self.values.append(j)
            self.scales.add(sc)

    def _check(self, header: list[str], where: str, lane_width: float | None, field: str) -> None:
        if self.pos_col is None:
            raise InputError(
                f"{where}: no position column ('position [in]', 'position [cm]', "
                f"'position [m]' or 'lane'); columns: {', '.join(header)}",
                field,
            )
        if not self.values:
            raise InputError(
                f"{where}: no reading column (e.g. 'reading [Rho]', 'R', 'L', 'g')", field
            )
        if len(self.scales) > 1:
            raise InputError(
                f"{where}: reading columns mix scales ({', '.join(sorted(self.scales))}); one "
                "instrument per file",
                field,
            )
        if self.pass_col is not None and len(self.values) > 1:
            raise InputError(
                f"{where}: a 'pass' column and several reading columns; use one or the other",
                field,
            )
        if self.is_lane:
            if lane_width is None:
                raise InputError(
                    f"{where}: positions are lane numbers: give the lane width "
                    '([readings] lane_width = "6 in", or --lane-width)',
                    field,
                )
            if not (math.isfinite(lane_width) and lane_width > 0):
                raise InputError(f"lane width must be positive, got {lane_width!r} m", field)

    def position(
        self,
        row: list[str],
        header: list[str],
        at: str,
        width: float | None,
        lane_width: float | None,
        field: str,
    ) -> float:
        """The row's position [m] (a lane's centre), checked to lie on the roll."""
        assert self.pos_col is not None
        x = _number(row, self.pos_col, header, at, field)
        if self.is_lane:
            if x != round(x) or x < 1:
                raise InputError(
                    f"{at}: lane {row[self.pos_col]!r} is not a lane number 1, 2, ...", field
                )
            pos = (x - 0.5) * lane_width  # type: ignore[operator]
        else:
            pos = x * self.pos_factor
        if width is not None and not (-EDGE_TOLERANCE <= pos <= width + EDGE_TOLERANCE):
            raise InputError(
                f"{at}: position {row[self.pos_col]} ({pos:.4g} m) lies outside the roll "
                f"(0 to {width:.4g} m from the reference edge): same edge and units?",
                field,
            )
        return pos

    def pass_number(self, row: list[str], header: list[str], at: str, field: str) -> int | None:
        if self.pass_col is None:
            return None
        p = _number(row, self.pass_col, header, at, field)
        if p != round(p) or p < 1:
            raise InputError(
                f"{at}: pass {row[self.pass_col]!r} is not a pass number 1, 2, ...", field
            )
        return int(p)


#: Length units positions are shown in, and their size [m].
DISPLAY_UNITS: dict[str, float] = {"in": 0.0254, "cm": 0.01, "mm": 0.001, "m": 1.0}


def display_unit(unit: str) -> str:
    """``"in"``, ``"cm"``, ``"mm"`` or ``"m"`` for a spelling of one of them, else ``""``."""
    u = unit.strip().lower()
    u = {"inch": "in", "inches": "in", '"': "in"}.get(u, u)
    return u if u in DISPLAY_UNITS else ""


def _delimiter(text: str) -> str:
    """``,`` unless the header line (first non-comment line) is split by ``;`` or a tab
    and has no comma outside a bracket (spreadsheet exports in locales with a decimal
    comma use ``;``)."""
    for line in text.splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        for d in (";", "\t"):
            if d in line and "," not in line:
                return d
        return ","
    return ","


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _number(row: list[str], j: int, header: list[str], at: str, field: str) -> float:
    if j >= len(row) or row[j] == "":
        raise InputError(f"{at}: column {header[j]!r} is empty", field)
    try:
        v = float(row[j])
    except ValueError:
        raise InputError(f"{at}: column {header[j]!r}: {row[j]!r} is not a number", field) from None
    if not math.isfinite(v):
        raise InputError(f"{at}: column {header[j]!r}: {row[j]!r} is not a finite number", field)
    return v
