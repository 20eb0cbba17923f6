"""CMD thickness profiles: reading, validation, MD averaging and resampling onto sectors.

An input of the winding model, beside the web and the core: the axisymmetric model
(:mod:`woundroll.winding.axisymmetric`) winds each CMD sector at its own thickness.

Two inputs are accepted.

CMD profile (CSV)
    Two columns whose header names each column and its unit, e.g. ``position_m,thickness_m``
    or ``position [in],thickness [mil]`` (any length unit pint knows; see
    :func:`woundroll.util.tables.read_columns`). Lines starting with ``#`` are comments.
    One row per CMD position; positions measured from one edge of the web.

Full thickness map (CSV or ``.npy``), CMD x MD, averaged over MD as in Figure 20 of the
reference paper:

* CSV map: the first non-comment row is the header. Its first cell names the thickness unit
  (``thickness [um]``); every following cell is a CMD position with its unit
  (``0 mm``, ``12.5 mm``; a bare number is metres). Every following row is one MD scan:
  first cell the MD position (a number or quantity, used only to check that it is
  readable), then one thickness per CMD position, in the header's thickness unit.
* ``.npy``: a 2-D float array of shape ``(n_md, n_cmd)``, thickness in metres, one row per
  MD scan. CMD positions are not stored: pass ``width`` [m] and the columns are taken as
  equal cells over ``[0, width]`` with positions at the cell centres.

Validation (errors name the field ``winding.thickness_profile`` unless told otherwise):
positions strictly increasing, at least two of them, thickness finite and positive, no NaN,
and no gap: a spacing larger than :data:`GAP_FACTOR` times the median spacing is reported
as a gap (a missing stretch of a scan, not a coarse but even sampling).

Resampling: :meth:`ThicknessProfile.sector_average` gives the cell averages of the
piecewise-linear profile over ``n`` equal CMD sectors spanning the measured extent
(exact integrals of the linear interpolant, so a linear profile returns the values at the
sector centres exactly).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.units import to_si
from woundroll.util.tables import parse_header, read_columns, read_header_row

FloatArray = NDArray[np.float64]

#: A spacing larger than this multiple of the median spacing is a gap in the profile.
GAP_FACTOR = 3.0

FIELD = "winding.thickness_profile"


@dataclass(frozen=True)
class ThicknessProfile:
    """A CMD thickness profile, SI.

    Attributes
    ----------
    position : ndarray [m]
        CMD positions, strictly increasing.
    thickness : ndarray [m]
        Web thickness at each position (MD average when read from a map).
    source : str
        Where it came from (file name, ``"uniform"`` ...).
    """

    position: FloatArray
    thickness: FloatArray
    source: str = ""

    def __post_init__(self) -> None:
        pos = np.asarray(self.position, dtype=float)
        h = np.asarray(self.thickness, dtype=float)
        validate_profile(pos, h, FIELD)
        object.__setattr__(self, "position", pos)
        object.__setattr__(self, "thickness", h)

    @property
    def extent(self) -> float:
        """Measured CMD extent [m] (last position minus first)."""
        return float(self.position[-1] - self.position[0])

    @property
    def mean(self) -> float:
        """Width-weighted mean thickness [m] (integral of the linear interpolant / extent)."""
        return float(np.trapezoid(self.thickness, self.position) / self.extent)

    @classmethod
    def uniform(cls, thickness: float, width: float, n: int = 2) -> ThicknessProfile:
        """A constant profile ``thickness`` [m] over ``[0, width]`` [m]."""
        if not (np.isfinite(thickness) and thickness > 0):
            raise InputError(f"must be positive, got {thickness:g} m", "web.thickness")
        if not (np.isfinite(width) and width > 0):
            raise InputError(f"must be positive, got {width:g} m", "web.width")
        return cls(np.linspace(0.0, width, max(n, 2)), np.full(max(n, 2), thickness), "uniform")

    def scaled(self, mean_thickness: float) -> ThicknessProfile:
        """The same shape scaled to the mean ``mean_thickness`` [m]."""
        if not (np.isfinite(mean_thickness) and mean_thickness > 0):
            raise InputError(f"must be positive, got {mean_thickness:g} m", "web.thickness")
        return ThicknessProfile(
            self.position, self.thickness * (mean_thickness / self.mean), self.source
        )

    def sector_edges(self, n: int) -> FloatArray:
        """``n + 1`` equally spaced sector edges [m] over the measured extent."""
        if not (isinstance(n, int | np.integer) and n >= 1):
            raise InputError(f"must be a whole number >= 1, got {n!r}", "profile.n_sectors")
        return np.linspace(self.position[0], self.position[-1], int(n) + 1)

    def sector_average(self, n: int) -> tuple[FloatArray, FloatArray]:
        """Cell averages over ``n`` equal CMD sectors.

        Returns
        -------
        z : ndarray [m]
            Sector centres.
        h : ndarray [m]
            Average thickness of the piecewise-linear profile over each sector (exact).
        """
        edges = self.sector_edges(n)
        c = _cumulative_integral(self.position, self.thickness, edges)
        return 0.5 * (edges[1:] + edges[:-1]), np.diff(c) / np.diff(edges)


def _cumulative_integral(x: FloatArray, f: FloatArray, at: FloatArray) -> FloatArray:
    """Integral from x[0] to ``at`` of the piecewise-linear interpolant of (x, f), exact."""
    seg = np.diff(x)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * seg)])
    i = np.clip(np.searchsorted(x, at, side="right") - 1, 0, x.size - 2)
    t = np.clip(at - x[i], 0.0, seg[i])
    slope = (f[i + 1] - f[i]) / seg[i]
    return cum[i] + f[i] * t + 0.5 * slope * t * t


def validate_profile(position: FloatArray, thickness: FloatArray, field: str = FIELD) -> None:
    """Raise :class:`InputError` (``field``) unless the profile is usable.

    Checks: same length, at least two points, finite values, strictly increasing positions,
    positive thickness, and no gap (a spacing > :data:`GAP_FACTOR` x median spacing).
    """
    if position.ndim != 1 or position.shape != thickness.shape:
        raise InputError("position and thickness must be 1-D arrays of equal length", field)
    if position.size < 2:
        raise InputError(f"needs at least 2 CMD positions, got {position.size}", field)
    if not np.all(np.isfinite(position)):
        raise InputError("a CMD position is missing or not finite (NaN)", field)
    bad = np.flatnonzero(~np.isfinite(thickness))
    if bad.size:
        raise InputError(
            f"thickness is missing or not finite (NaN) at CMD position "
            f"{position[bad[0]]:.6g} m (row {bad[0] + 1})",
            field,
        )
    step = np.diff(position)
    if np.any(step <= 0):
        k = int(np.argmax(step <= 0))
        raise InputError(
            f"CMD positions must increase strictly; row {k + 2} "
            f"({position[k + 1]:.6g} m) follows {position[k]:.6g} m",
            field,
        )
    if np.any(thickness <= 0):
        k = int(np.argmax(thickness <= 0))
        raise InputError(
            f"thickness must be positive; got {thickness[k]:.4g} m at CMD "
            f"position {position[k]:.6g} m (row {k + 1})",
            field,
        )
    med = float(np.median(step))
    if np.any(step > GAP_FACTOR * med):
        k = int(np.argmax(step > GAP_FACTOR * med))
        raise InputError(
            f"gap in the profile between {position[k]:.6g} m and "
            f"{position[k + 1]:.6g} m ({step[k]:.4g} m, more than {GAP_FACTOR:g} x "
            f"the median spacing {med:.4g} m)",
            field,
        )


def read_thickness_profile(path: Path | str, field: str = FIELD) -> ThicknessProfile:
    """Read a CMD profile CSV (``position``, ``thickness`` columns with units), SI.

    Raises
    ------
    InputError
        Missing file or column, unreadable number, wrong unit, or a profile failing
        :func:`validate_profile`; ``field`` names the input.
    """
    cols = read_columns(path, {"position": "length", "thickness": "length"}, field)
    return _checked(cols["position"], cols["thickness"], Path(path).name, field)


def _checked(pos: FloatArray, h: FloatArray, source: str, field: str) -> ThicknessProfile:
    try:
        validate_profile(pos, h, field)
    except InputError as exc:
        raise InputError(f"{source}: {exc.message}", field) from None
    return ThicknessProfile(pos, h, source)


def read_thickness_map(
    path: Path | str, *, width: float | None = None, field: str = FIELD
) -> ThicknessProfile:
    """Read a full CMD x MD thickness map (CSV or ``.npy``) and average it over MD.

    See the module docstring for both layouts. The MD average at each CMD position is the
    arithmetic mean of the scans (Figure 20 of the reference paper); every cell must be a
    finite positive number (a NaN cell is an error, not skipped).

    Parameters
    ----------
    path : path
        ``.csv`` or ``.npy`` file.
    width : float, optional [m]
        Web width; required for ``.npy`` (CMD cell centres over ``[0, width]``).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"file not found: {path}", field)
    if path.suffix.lower() == ".npy":
        if width is None or not (np.isfinite(width) and width > 0):
            raise InputError("a .npy map needs the web width (CMD cells over [0, width])", field)
        try:
            arr = np.load(path, allow_pickle=False)
        except (OSError, ValueError) as exc:
            raise InputError(f"cannot read {path.name}: {exc}", field) from None
        if arr.ndim != 2 or arr.shape[1] < 2 or arr.shape[0] < 1:
            raise InputError(
                f"{path.name}: expected a 2-D array (n_md, n_cmd) with n_cmd >= 2, "
                f"got shape {arr.shape}",
                field,
            )
        arr = np.asarray(arr, dtype=float)
        n = arr.shape[1]
        pos = (np.arange(n) + 0.5) * (width / n)
        return _map_average(pos, arr, path.name, field)
    try:
        with path.open(newline="", encoding="utf-8-sig") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read {path}: {exc}", field) from None
    if len(rows) < 2 or len(rows[0]) < 3:
        raise InputError(
            f"{path.name}: a map needs a header (thickness unit, then >= 2 CMD "
            "positions) and at least one MD scan",
            field,
        )
    _, unit = parse_header(rows[0][0])
    scale = to_si(f"1 {unit}", "length", f"{field}:{rows[0][0]}") if unit else 1.0
    pos = np.array(
        [to_si(c, "length", f"{field}:header[{j + 1}]") for j, c in enumerate(rows[0][1:])]
    )
    n = pos.size
    data = np.empty((len(rows) - 1, n))
    for i, row in enumerate(rows[1:], start=2):
        if len(row) != n + 1:
            raise InputError(f"{path.name} line {i}: expected {n + 1} cells, got {len(row)}", field)
        to_si(row[0], "length", f"{field}:line {i} (MD position)")
        try:
            data[i - 2] = [float(c) if c.strip() else np.nan for c in row[1:]]
        except ValueError:
            raise InputError(f"{path.name} line {i}: a thickness is not a number", field) from None
    return _map_average(pos, data * scale, path.name, field)


def _map_average(pos: FloatArray, data: FloatArray, source: str, field: str) -> ThicknessProfile:
    bad = ~np.isfinite(data)
    if np.any(bad):
        i, j = np.argwhere(bad)[0]
        raise InputError(
            f"{source}: thickness missing or not finite at MD scan {i + 1}, "
            f"CMD position {pos[j]:.6g} m",
            field,
        )
    if np.any(data <= 0):
        i, j = np.argwhere(data <= 0)[0]
        raise InputError(
            f"{source}: thickness must be positive; got {data[i, j]:.4g} m at MD "
            f"scan {i + 1}, CMD position {pos[j]:.6g} m",
            field,
        )
    return _checked(
        pos, data.mean(axis=0), f"{source} (MD average of {data.shape[0]} scans)", field
    )


def load_thickness(
    path: Path | str, *, width: float | None = None, field: str = FIELD
) -> ThicknessProfile:
    """Read ``winding.thickness_profile``: a CMD profile CSV, a CMD x MD map (CSV or ``.npy``).

    The layout is told from the file: ``.npy`` is a map; a CSV whose first header cell
    names a position column (``position_m``, ``position [in]``) is a profile, any other CSV
    a map (module docstring). With ``width`` [m] (the web width) the profile's measured
    extent must match it within 5 % or two sample spacings (a scan that covers only part
    of the web would silently narrow the roll: the line force is spread over the extent).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"file not found: {path}", field)
    if path.suffix.lower() == ".npy":
        prof = read_thickness_map(path, width=width, field=field)
    else:
        first = read_header_row(path, field)
        is_profile = bool(first) and parse_header(first[0])[0].lower().startswith("position")
        if is_profile:
            prof = read_thickness_profile(path, field)
        else:
            prof = read_thickness_map(path, width=width, field=field)
    if width is not None:
        spacing = float(np.median(np.diff(prof.position)))
        if abs(prof.extent - width) > max(0.05 * width, 2.0 * spacing):
            raise InputError(
                f"{path.name} spans {prof.extent:.4g} m across the web but web.width is "
                f"{width:.4g} m; the profile must cover the web (positions from one edge)",
                field,
            )
    return prof


def bundled_profile(name: str = "table3_synthetic_pet") -> ThicknessProfile:
    """A thickness profile shipped in ``woundroll/data/profiles/`` (``name`` without ``.csv``)."""
    ref = resources.files("woundroll.data").joinpath("profiles", f"{name}.csv")
    if not ref.is_file():
        avail = sorted(
            p.name[:-4]
            for p in resources.files("woundroll.data").joinpath("profiles").iterdir()
            if p.name.endswith(".csv")
        )
        raise InputError(f"no bundled profile {name!r}; available: {', '.join(avail)}", FIELD)
    with resources.as_file(ref) as p:
        return read_thickness_profile(p)
