"""The hardness profiler's view of measured profiles: one roll's statistics, band verdict and
fault list, and the roll-to-roll trend of many rolls on control charts.

What automatic roll-hardness profilers report for a measured CMD profile, computed from the
readings of :mod:`woundroll.io.readings` / :mod:`woundroll.io.tester_files` (docs/tester-files.md,
"The profiler's view"):

* **Statistics** of the per-position means: mean, sample SD, CoV = SD / mean, min, max,
  peak-to-peak, and the **band verdict** of the CoV (very good < 3 %, acceptable < 6 %,
  bad; the bands of :func:`woundroll.profile.stats.profile_stats`, the same the model's
  predicted profile is judged by).
* **Fault list**: hard and soft bands, contiguous runs of positions whose mean reading lies
  more than ``band`` (default :data:`FAULT_BAND`, 5 % of the roll mean) above (hard) or below
  (soft) the roll mean, each with its start, end and width along the CMD, its peak reading and
  deviation. A sample stands for the CMD up to half-way to its neighbours (an outer sample
  as far outward as inward, not beyond the reference edge), so a band of one sample on a 6 in
  lane grid is 6 in wide, edge lanes included.
* **IDs**: roll, lot and customer read from the file (:func:`file_ids`): a profile export's
  metadata lines (``Roll;4711``), a TAPPI sheet's roll column, ``# roll: 4711`` comment lines.
* **Trend** (:func:`roll_trend`): the rolls in production order (the order of the files and
  of the rolls on a sheet) with an individuals and moving-range chart (X-mR) of the roll means
  and of the CoVs: centre line the average, limits ``average +- 2.66 mR-bar`` where mR-bar is
  the average moving range of successive rolls (2.66 = 3 / d2, d2 = 1.128 for ranges of two;
  moving-range chart upper limit 3.267 mR-bar, D4 for n = 2): Montgomery, *Introduction to
  Statistical Quality Control*, 6th ed., Wiley 2009, section 6.4; NIST/SEMATECH
  e-Handbook of Statistical Methods, section 6.3.2.2. A point beyond a limit is "out of
  control". Limits from fewer than :data:`TREND_MIN_ROLLS` rolls are marked provisional.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.io.readings import DISPLAY_UNITS, Readings
from woundroll.profile.stats import ProfileStats, profile_stats

FloatArray = NDArray[np.float64]

__all__ = [
    "FAULT_BAND",
    "TREND_MIN_ROLLS",
    "XMR_LIMIT",
    "ControlChart",
    "Fault",
    "ProfileCheck",
    "Trend",
    "check_profile",
    "control_chart",
    "file_ids",
    "find_faults",
    "read_rolls",
    "roll_trend",
]

#: Default fault threshold: a position whose mean reading lies more than this fraction of the
#: roll mean above (hard) or below (soft) the roll mean is part of a fault band (assumption:
#: profilers let the user set it; 5 % is 2.8 Rho on a 55 Rho roll, about twice a Rho-meter's
#: repeatability SD).
FAULT_BAND = 0.05
#: X-mR chart: limits are the average +- XMR_LIMIT x the average moving range (3 / d2, d2 = 1.128).
XMR_LIMIT = 2.66
#: Moving-range chart upper limit factor (D4 for ranges of two).
MR_LIMIT = 3.267
#: Rolls below which the control limits are provisional (Montgomery: 20-25 subgroups).
TREND_MIN_ROLLS = 20

#: Metadata keys (lower case, spaces/underscores/dashes removed) -> id.
_ID_KEYS: dict[str, str] = {
    "roll": "roll",
    "rollid": "roll",
    "rollno": "roll",
    "rollnumber": "roll",
    "rollnr": "roll",
    "reel": "roll",
    "lot": "lot",
    "lotid": "lot",
    "lotno": "lot",
    "lotnumber": "lot",
    "batch": "lot",
    "set": "lot",
    "customer": "customer",
    "client": "customer",
}
_COMMENT_ID = re.compile(r"^\s*#\s*([A-Za-z][A-Za-z _\-]*?)\s*[:=]\s*(\S.*?)\s*$")


def _unit_factor(unit: str) -> float:
    if unit not in DISPLAY_UNITS:
        raise InputError(f"unknown length unit {unit!r} (use {', '.join(DISPLAY_UNITS)})", "--unit")
    return DISPLAY_UNITS[unit]


@dataclass(frozen=True)
class Fault:
    """A hard or soft band: a contiguous run of positions beyond the fault threshold.

    Positions in m from the reference edge; ``deviation`` is the peak's signed difference
    from the roll mean as a fraction of it.
    """

    kind: str
    start_m: float
    end_m: float
    width_m: float
    peak_position_m: float
    peak: float
    deviation: float
    n_positions: int

    def to_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "start_m": self.start_m,
            "end_m": self.end_m,
            "width_m": self.width_m,
            "peak_position_m": self.peak_position_m,
            "peak": self.peak,
            "deviation": self.deviation,
            "n_positions": self.n_positions,
        }


def _extents(position: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Left and right end of the CMD each sample stands for: half-way to its neighbours; an
    outer sample as far outward as inward, not beyond the reference edge (0)."""
    x = np.asarray(position, dtype=float)
    if x.size == 1:
        return x.copy(), x.copy()
    mid = 0.5 * (x[1:] + x[:-1])
    first = max(0.0, x[0] - (mid[0] - x[0]))
    last = x[-1] + (x[-1] - mid[-1])
    return np.concatenate([[first], mid]), np.concatenate([mid, [last]])


def find_faults(
    position: Any, values: Any, *, band: float = FAULT_BAND, mean: float | None = None
) -> list[Fault]:
    """Hard and soft bands of a profile (module docstring), in CMD order.

    Parameters
    ----------
    position : (n,) array [m]
        Increasing positions.
    values : (n,) array
        Reading at each position (the per-position mean).
    band : float
        Threshold as a fraction of the mean (0.05 = +-5 %).
    mean : float, optional
        Reference level (default: the mean of ``values``).
    """
    x = np.asarray(position, dtype=float).ravel()
    v = np.asarray(values, dtype=float).ravel()
    if x.size != v.size or x.size == 0:
        raise InputError("needs as many positions as values, at least one", "profile")
    if not (math.isfinite(band) and 0 < band < 1):
        raise InputError(f"must be a fraction between 0 and 1 (got {band!r})", "--band")
    ref = float(v.mean()) if mean is None else float(mean)
    side = np.where(v > ref * (1 + band), 1, np.where(v < ref * (1 - band), -1, 0))
    left, right = _extents(x)
    out: list[Fault] = []
    i = 0
    while i < x.size:
        if side[i] == 0:
            i += 1
            continue
        j = i
        while j + 1 < x.size and side[j + 1] == side[i]:
            j += 1
        seg = slice(i, j + 1)
        k = i + int(np.argmax(v[seg]) if side[i] > 0 else np.argmin(v[seg]))
        start, end = float(left[i]), float(right[j])
        out.append(
            Fault(
                kind="hard" if side[i] > 0 else "soft",
                start_m=start,
                end_m=end,
                width_m=end - start,
                peak_position_m=float(x[k]),
                peak=float(v[k]),
                deviation=float((v[k] - ref) / ref),
                n_positions=j - i + 1,
            )
        )
        i = j + 1
    return out


@dataclass(frozen=True)
class ProfileCheck(ProfileStats):
    """One roll's measured profile as a hardness profiler reports it (module docstring): the
    statistics of its per-position means (the fields of :class:`ProfileStats`, the same the
    model's predicted profile is judged by) with the file's source, scale and ids, and the
    fault list."""

    source: str
    scale: str
    ids: dict[str, str]
    fault_band: float
    faults: tuple[Fault, ...]
    position_m: FloatArray = field(repr=False)
    values: FloatArray = field(repr=False)
    position_unit: str = ""

    @property
    def label(self) -> str:
        """Roll id when the file gives one, else the file name."""
        return self.ids.get("roll") or self.source

    @property
    def verdict(self) -> str:
        """One line: band verdict, CoV, peak-to-peak and the faults found."""
        nh = sum(f.kind == "hard" for f in self.faults)
        ns = sum(f.kind == "soft" for f in self.faults)
        faults = (
            f"{nh} hard and {ns} soft band(s) beyond +-{100 * self.fault_band:g} % of the mean"
            if self.faults
            else f"no band beyond +-{100 * self.fault_band:g} % of the mean"
        )
        return (
            f"{self.band}: CoV {100 * self.cov:.1f} %, peak-to-peak {self.peak_to_peak:.3g} "
            f"{self.scale}; {faults}"
        )

    def fault_rows(self, unit: str | None = None) -> list[dict[str, str]]:
        """Fault table rows with positions in ``unit`` (default: the file's unit, else in)."""
        u = unit or self.position_unit or "in"
        f = _unit_factor(u)
        return [
            {
                "kind": b.kind,
                f"start [{u}]": f"{b.start_m / f:.4g}",
                f"end [{u}]": f"{b.end_m / f:.4g}",
                f"width [{u}]": f"{b.width_m / f:.4g}",
                f"peak at [{u}]": f"{b.peak_position_m / f:.4g}",
                f"peak [{self.scale}]": f"{b.peak:.4g}",
                "deviation [%]": f"{100 * b.deviation:+.1f}",
            }
            for b in self.faults
        ]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (positions in m, readings in :attr:`scale`, CoV and deviations as
        fractions)."""
        return {
            "source": self.source,
            "scale": self.scale,
            "ids": dict(self.ids),
            "n_positions": self.n,
            "mean": self.mean,
            "sd": self.sd,
            "cov": self.cov,
            "min": self.min,
            "max": self.max,
            "peak_to_peak": self.peak_to_peak,
            "band": self.band,
            "verdict": self.verdict,
            "fault_band": self.fault_band,
            "faults": [b.to_dict() for b in self.faults],
        }

    def plot(self, path: str | Path | None = None, *, unit: str | None = None) -> Any:
        """Profile of the per-position means with the +-band lines and the faults shaded
        (red: hard, blue: soft); returns the Figure."""
        import matplotlib.pyplot as plt

        u = unit or self.position_unit or "in"
        f = _unit_factor(u)
        fig, ax = plt.subplots(figsize=(7.0, 3.4))
        ax.plot(self.position_m / f, self.values, "o-", color="k", ms=3.5, lw=1.2, label="mean")
        ax.axhline(self.mean, color="0.3", lw=1.0)
        for s in (1 + self.fault_band, 1 - self.fault_band):
            ax.axhline(self.mean * s, color="0.3", lw=0.8, ls="--")
        for b in self.faults:
            lo, hi = b.start_m / f, b.end_m / f
            ax.axvspan(lo, hi, color="C3" if b.kind == "hard" else "C0", alpha=0.18, lw=0)
        ax.set_xlabel(
            f"CMD position [{u}]  (red: hard band, blue: soft band, dashed: mean "
            f"+- {100 * self.fault_band:g} %)"
        )
        ax.set_ylabel(f"mean reading [{self.scale}]")
        ax.set_title(
            f"{self.label}: {self.verdict}"
            if len(self.verdict) < 90
            else f"{self.label}: {self.band}, CoV {100 * self.cov:.1f} %",
            fontsize=9,
        )
        ax.grid(alpha=0.3)
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def check_profile(
    readings: Readings, *, band: float = FAULT_BAND, ids: dict[str, str] | None = None
) -> ProfileCheck:
    """Statistics, band verdict and fault list of one roll's readings (module docstring).

    Raises
    ------
    InputError
        Fewer than two positions, a mean reading of 0 (no CoV), or a band outside (0, 1).
    """
    where = readings.source or "readings"
    if readings.n_positions < 2:
        raise InputError(
            f"{where}: a profile needs readings at 2 positions or more, got {readings.n_positions}",
            "readings",
        )
    st = profile_stats(readings.mean, field=where)
    faults = find_faults(readings.position, readings.mean, band=band, mean=st.mean)
    return ProfileCheck(
        source=readings.source,
        scale=readings.scale,
        ids=dict(ids or {}),
        **asdict(st),
        fault_band=band,
        faults=tuple(faults),
        position_m=np.asarray(readings.position, dtype=float),
        values=np.asarray(readings.mean, dtype=float),
        position_unit=readings.position_unit,
    )


# ------------------------------------------------------------------------------ ids
def _id_key(text: str) -> str | None:
    return _ID_KEYS.get(re.sub(r"[\s_\-.]+", "", text.strip().lower().rstrip(":")))


def file_ids(path: str | Path, metadata: dict[str, str] | None = None) -> dict[str, str]:
    """Roll, lot and customer named in a tester file: ``# roll: 4711`` / ``# lot = L-07``
    comment lines anywhere, and a profile export's metadata lines (``metadata``, from
    :func:`woundroll.io.tester_files.read_profile_export`). Keys: ``roll`` (also roll id, roll
    no, reel), ``lot`` (lot id, batch, set), ``customer`` (client); case and spacing are
    ignored. Returns only the ids found."""
    out: dict[str, str] = {}
    for key, value in (metadata or {}).items():
        k = _id_key(key)
        if k and value.strip() and k not in out:
            out[k] = value.strip()
    try:
        text = Path(path).read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError):
        return out
    for line in text.splitlines():
        m = _COMMENT_ID.match(line)
        if m:
            k = _id_key(m.group(1))
            if k and k not in out:
                out[k] = m.group(2).rstrip(",;").strip()
    return out


def read_rolls(
    paths: Sequence[str | Path],
    *,
    format: str = "auto",  # noqa: A002 - the CLI's word
    width: float | None = None,
    lane_width: float | None = None,
    field: str = "FILES",
) -> list[tuple[Readings, dict[str, str]]]:
    """Every roll of every file in order (a TAPPI sheet gives one per roll row group), with
    its ids (:func:`file_ids`; a sheet's roll column is the roll id).

    Raises
    ------
    InputError
        Anything the readers reject (message names the file and line), no file, or rolls
        read on different scales.
    """
    from woundroll.io.readings import read_readings
    from woundroll.io.tester_files import (
        FORMATS,
        detect_format,
        read_profile_export,
        read_tappi_sheet,
    )

    if not paths:
        raise InputError("no readings file given", field)
    if format not in FORMATS:
        raise InputError(f"unknown format {format!r}; one of {', '.join(FORMATS)}", "--format")
    out: list[tuple[Readings, dict[str, str]]] = []
    for p in paths:
        fmt = detect_format(p, field) if format == "auto" else format
        if fmt == "tappi":
            base = file_ids(p)
            for roll, r in read_tappi_sheet(
                p, lane_width=lane_width, width=width, field=field
            ).items():
                out.append((r, {**base, "roll": roll}))
        elif fmt == "profile":
            e = read_profile_export(p, width=width, field=field)
            out.append((e.readings, file_ids(p, e.metadata)))
        else:
            r = read_readings(p, width=width, lane_width=lane_width, field=field)
            out.append((r, file_ids(p)))
    scales = {r.scale for r, _ in out}
    if len(scales) > 1:
        first = out[0][0]
        other = next(r for r, _ in out if r.scale != first.scale)
        raise InputError(
            f"{other.source} reads in {other.scale}, {first.source} in {first.scale}: a trend "
            "needs one instrument",
            field,
        )
    return out


# ---------------------------------------------------------------------------- trend
@dataclass(frozen=True)
class ControlChart:
    """Individuals and moving-range (X-mR) chart of one quantity over the rolls."""

    name: str
    values: FloatArray
    center: float
    mr_bar: float
    ucl: float
    lcl: float
    mr_ucl: float
    out_of_control: tuple[int, ...]

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "values": [float(v) for v in self.values],
            "center": self.center,
            "mr_bar": self.mr_bar,
            "ucl": self.ucl,
            "lcl": self.lcl,
            "mr_ucl": self.mr_ucl,
            "out_of_control": list(self.out_of_control),
        }


def control_chart(values: Any, name: str = "value", *, floor: float | None = None) -> ControlChart:
    """X-mR chart (module docstring): centre = average, limits = average +- 2.66 mR-bar
    (``floor`` clips the lower limit, 0 for a CoV), moving-range limit 3.267 mR-bar; the
    indices of the points beyond a limit.

    Raises
    ------
    InputError
        Fewer than two values (no moving range) or a value that is not finite.
    """
    v = np.asarray(values, dtype=float).ravel()
    if v.size < 2:
        raise InputError(f"a control chart needs 2 rolls or more, got {v.size}", "--trend")
    if not np.all(np.isfinite(v)):
        raise InputError(f"{name}: a value is not finite", "--trend")
    center = float(v.mean())
    mr_bar = float(np.mean(np.abs(np.diff(v))))
    ucl = center + XMR_LIMIT * mr_bar
    lcl = center - XMR_LIMIT * mr_bar
    if floor is not None:
        lcl = max(lcl, floor)
    out = tuple(int(i) for i in np.flatnonzero((v > ucl) | (v < lcl)))
    return ControlChart(name, v, center, mr_bar, ucl, lcl, MR_LIMIT * mr_bar, out)


@dataclass(frozen=True)
class Trend:
    """Roll-to-roll trend: each roll's check and the X-mR charts of mean and CoV."""

    rolls: tuple[ProfileCheck, ...]
    mean_chart: ControlChart
    cov_chart: ControlChart

    @property
    def provisional(self) -> bool:
        """True with fewer than :data:`TREND_MIN_ROLLS` rolls (limits not yet reliable)."""
        return len(self.rolls) < TREND_MIN_ROLLS

    @property
    def scale(self) -> str:
        return self.rolls[0].scale

    def flagged(self) -> list[str]:
        """One sentence per roll beyond a limit of either chart."""
        out = []
        for chart, what, fmt in (
            (self.mean_chart, "mean", lambda v: f"{v:.3g} {self.scale}"),
            (self.cov_chart, "CoV", lambda v: f"{100 * v:.2f} %"),
        ):
            for i in chart.out_of_control:
                side = "above the upper" if chart.values[i] > chart.ucl else "below the lower"
                lim = chart.ucl if chart.values[i] > chart.ucl else chart.lcl
                out.append(
                    f"roll {self.rolls[i].label} (#{i + 1}): {what} {fmt(chart.values[i])} "
                    f"{side} control limit {fmt(lim)}"
                )
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "scale": self.scale,
            "chart": "X-mR (individuals and moving range), limits = center +- 2.66 mR-bar",
            "provisional": self.provisional,
            "rolls": [r.to_dict() for r in self.rolls],
            "mean_chart": self.mean_chart.to_dict(),
            "cov_chart": self.cov_chart.to_dict(),
            "flagged": self.flagged(),
        }

    def to_csv(self) -> str:
        """One row per roll: ``n,roll,lot,source,mean [scale],sd [scale],cov,p2p [scale],
        band,faults``."""
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        s = self.scale
        w.writerow(
            ["n", "roll", "lot", "source", f"mean [{s}]", f"sd [{s}]", "cov", f"p2p [{s}]",
             "band", "faults"]
        )  # fmt: skip
        for i, r in enumerate(self.rolls, start=1):
            w.writerow(
                [i, r.ids.get("roll", ""), r.ids.get("lot", ""), r.source, f"{r.mean:.6g}",
                 f"{r.sd:.6g}", f"{r.cov:.6g}", f"{r.peak_to_peak:.6g}", r.band, len(r.faults)]
            )  # fmt: skip
        return buf.getvalue()

    def plot(self, path: str | Path | None = None) -> Any:
        """The two individuals charts (mean and CoV against roll number) with centre line and
        limits; points beyond a limit in red. Returns the Figure."""
        import matplotlib.pyplot as plt

        n = len(self.rolls)
        k = np.arange(1, n + 1)
        fig, axes = plt.subplots(2, 1, figsize=(7.0, 5.2), sharex=True)
        for ax, chart, ylabel, f in (
            (axes[0], self.mean_chart, f"roll mean [{self.scale}]", 1.0),
            (axes[1], self.cov_chart, "CoV [%]", 100.0),
        ):
            y = chart.values * f
            ax.plot(k, y, "o-", color="k", ms=4, lw=1)
            bad = list(chart.out_of_control)
            if bad:
                ax.plot(k[bad], y[bad], "o", color="C3", ms=7, label="beyond a limit")
            ax.axhline(chart.center * f, color="C2", lw=1.2, label="centre")
            for lim in (chart.ucl, chart.lcl):
                ax.axhline(lim * f, color="C3", lw=1, ls="--")
            ax.set_ylabel(ylabel)
            ax.grid(alpha=0.3)
        axes[0].set_title(
            "X-mR charts: limits = centre +- 2.66 mR-bar"
            + (f" (provisional: {n} < {TREND_MIN_ROLLS} rolls)" if self.provisional else ""),
            fontsize=9,
        )
        axes[1].set_xlabel("roll (production order)")
        labels = [r.label for r in self.rolls]
        if n <= 24:
            axes[1].set_xticks(k, labels, rotation=45, ha="right", fontsize=7)
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def roll_trend(checks: Sequence[ProfileCheck]) -> Trend:
    """X-mR charts of the roll means and CoVs of ``checks`` in the order given.

    Raises
    ------
    InputError
        Fewer than two rolls, or rolls on different scales.
    """
    if len(checks) < 2:
        raise InputError(
            f"a trend needs 2 rolls or more (got {len(checks)}): give several files or a "
            "sheet with several rolls",
            "--trend",
        )
    if len({c.scale for c in checks}) > 1:
        raise InputError("a trend needs one instrument: the rolls mix scales", "--trend")
    return Trend(
        tuple(checks),
        control_chart([c.mean for c in checks], "mean"),
        control_chart([c.cov for c in checks], "cov", floor=0.0),
    )
