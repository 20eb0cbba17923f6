"""Parameter sweeps: many rolls of one case with some inputs varied, as one table.

::

    woundroll sweep CASE --vary "winding.tension=20 N:80 N:13" \
                         --vary "web.radial_modulus.K2=20,60,120" --out DIR

* an **axis** is a dotted case key and its values: a range ``start:stop:count`` (values
  with units as in a case file; ``stop`` may be in another unit of the same dimension, the
  column uses ``start``'s) or a comma list (``"1 pli,2 pli,175 N/m"``, ``"linear,hyperbolic"``);
* a **design** turns the axes into rolls: ``grid`` (every combination, the default),
  ``random`` (``samples`` rolls, each input drawn uniformly over its range, or among its
  listed values) or ``lhs`` (Latin hypercube over the ranges, scipy.stats.qmc; listed
  values are drawn by stratum);
* each roll is the case with the point's values set (as ``--set`` would) and run through
  :func:`woundroll.pipeline.run`; a roll that fails (bad value, no convergence, any other
  error) gets its message in the ``error`` column and NaN results, the sweep goes on;
* the **table**: one row per roll, a column per varied input (``winding.tension [N]``) and
  per scalar result of the run's JSON, named by its dotted key with the unit its description
  in :mod:`woundroll.pipeline.vocabulary` gives (``winding.core_pressure [Pa]``,
  ``hardness.reading [rho]``), then ``error``;
* with ``uncertainty=N`` (``--uncertainty N``) each roll also propagates the case's
  ``[uncertainty]`` (:func:`woundroll.assess.uncertainty.propagate`, as ``woundroll run
  --uncertainty N``) and the table gets the 95 % bands: ``winding.core_pressure_low [Pa]``
  / ``_high``, ``hardness.reading_low [rho]`` / ``_high`` (:func:`uncertainty_columns`);
* **where it runs**: serially (``workers=1``), on the machine's cores (a process pool; by
  default when the rolls would take more than 15 s serially), or on a Dask distributed
  cluster (``scheduler="tcp://host:8786"``, or a ``distributed.Client``). The table does
  not depend on where it ran (rows in design order; wall-clock timings are left out of the
  table for that reason).
"""

from __future__ import annotations

import csv
import itertools
import math
import os
import re
import time
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from woundroll.errors import ConvergenceError, InputError

__all__ = [
    "Axis",
    "SweepResult",
    "design_points",
    "parse_vary",
    "result_columns",
    "run_point",
    "run_sweep",
    "uncertainty_columns",
]

DESIGNS = ("grid", "random", "lhs")
#: The largest number of rolls one sweep runs (a typo in a count should not start a
#: million-roll job).
MAX_ROLLS = 100_000

#: ``progress(done, total)``.
SweepProgress = Callable[[int, int], None]


@dataclass(frozen=True)
class Axis:
    """One varied input.

    Attributes
    ----------
    key : str
        Dotted case key (``winding.tension``).
    values : tuple
        Column values: floats in ``unit`` (or strings for non-numeric lists).
    unit : str
        Unit of the column (``"N"``); ``""`` for a plain number, None for text.
    continuous : bool
        True for a range (random and LHS designs draw anywhere in [start, stop]).
    """

    key: str
    values: tuple[Any, ...]
    unit: str | None
    continuous: bool = False

    @property
    def column(self) -> str:
        if self.unit is None:
            return self.key
        return f"{self.key} [{self.unit or '-'}]"

    def case_value(self, v: Any) -> Any:
        """The value as the case file takes it (a quantity string keeps its unit)."""
        if self.unit is None:
            return _toml_value(v)
        if self.unit == "":
            return float(v)
        return f"{float(v)!r} {self.unit}"


def _toml_value(raw: str) -> Any:
    try:
        return tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        return raw


def _quantity(text: str, field: str) -> tuple[float, str]:
    """``"20 N"`` -> (20.0, "N"); ``"120"`` -> (120.0, "")."""
    from woundroll.units import parse_quantity

    q = parse_quantity(text, field)
    mag = float(q.magnitude)
    if not math.isfinite(mag):
        raise InputError(f"must be a finite number, got {text!r}", field)
    unit = "" if q.unitless else text.strip()[len(_number_prefix(text)) :].strip()
    return mag, unit


_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def _number_prefix(text: str) -> str:
    m = _NUMBER.match(text)
    return m.group(0) if m else ""


def _convert(mag: float, unit: str, to_unit: str, field: str) -> float:
    from woundroll.units import parse_quantity

    if unit == to_unit:
        return mag
    q = parse_quantity(f"{mag!r} {unit}".strip(), field)
    try:
        return float(q.to(parse_quantity(f"1 {to_unit}".strip(), field).units).magnitude)
    except Exception:
        raise InputError(
            f"{mag:g} {unit} cannot be converted to {to_unit or 'a plain number'}", field
        ) from None


def parse_vary(text: str) -> Axis:
    """``"key=start:stop:count"`` or ``"key=v1,v2,..."`` -> :class:`Axis`.

    Raises
    ------
    InputError
        Field ``--vary``: no ``=``, a bad key, a count that is not a whole number >= 1,
        values that are not quantities of one dimension.
    """
    key, sep, spec = text.partition("=")
    key, spec = key.strip(), spec.strip()
    if not sep or not key or not spec:
        raise InputError(f"expected key=start:stop:count or key=v1,v2,..., got {text!r}", "--vary")
    if not re.fullmatch(r"[A-Za-z_][\w]*(\.[A-Za-z_0-9][\w]*)*", key):
        raise InputError(f"bad case key {key!r} (a dotted key such as winding.tension)", "--vary")
    where = f"--vary {key}"
    if ":" in spec and "," not in spec:
        parts = [p.strip() for p in spec.split(":")]
        if len(parts) != 3:
            raise InputError(f"a range is start:stop:count, got {spec!r}", where)
        try:
            count = int(parts[2])
        except ValueError:
            count = 0
        if count < 1 or str(count) != parts[2]:
            raise InputError(f"count must be a whole number >= 1, got {parts[2]!r}", where)
        start, unit = _quantity(parts[0], where)
        stop_mag, stop_unit = _quantity(parts[1], where)
        stop = _convert(stop_mag, stop_unit, unit, where)
        values = tuple(float(v) for v in np.linspace(start, stop, count))
        return Axis(key, values, unit, continuous=count > 1)
    tokens = [t.strip() for t in spec.split(",")]
    if any(not t for t in tokens):
        raise InputError(f"empty value in the list {spec!r}", where)
    numeric = [bool(_number_prefix(t)) for t in tokens]
    if not any(numeric):
        return Axis(key, tuple(tokens), None)
    if not all(numeric):
        raise InputError(f"mixes numbers and text: {spec!r}", where)
    first, unit = _quantity(tokens[0], where)
    values = [first]
    for t in tokens[1:]:
        mag, u = _quantity(t, where)
        values.append(_convert(mag, u, unit, where))
    return Axis(key, tuple(values), unit)


def design_points(
    axes: Sequence[Axis], design: str = "grid", samples: int | None = None, seed: int = 0
) -> list[tuple[Any, ...]]:
    """The rolls of a design: one tuple of column values per roll, in run order.

    Raises
    ------
    InputError
        Unknown design (``--design``), missing or bad ``samples`` (``--samples``), more
        than :data:`MAX_ROLLS` rolls.
    """
    if design not in DESIGNS:
        raise InputError(f"unknown design {design!r}; one of {', '.join(DESIGNS)}", "--design")
    if not axes:
        raise InputError("nothing to vary: give at least one --vary", "--vary")
    if design == "grid":
        n = math.prod(len(a.values) for a in axes)
        if n > MAX_ROLLS:
            raise InputError(f"the grid has {n} rolls, more than {MAX_ROLLS}", "--vary")
        return list(itertools.product(*(a.values for a in axes)))
    if samples is None or samples < 1:
        raise InputError(f"the {design} design needs --samples N (N >= 1)", "--samples")
    if samples > MAX_ROLLS:
        raise InputError(f"{samples} rolls, more than {MAX_ROLLS}", "--samples")
    rng = np.random.default_rng(seed)
    if design == "random":
        u = rng.random((samples, len(axes)))
    else:
        from scipy.stats import qmc

        u = qmc.LatinHypercube(d=len(axes), seed=rng).random(samples)
    cols = []
    for j, a in enumerate(axes):
        if a.continuous:
            lo, hi = a.values[0], a.values[-1]
            cols.append([float(lo + (hi - lo) * x) for x in u[:, j]])
        else:
            k = len(a.values)
            cols.append([a.values[min(int(x * k), k - 1)] for x in u[:, j]])
    return list(zip(*cols, strict=True))


# parts of the JSON that echo inputs or solver bookkeeping, or vary run to run
_SKIP = re.compile(
    r"^(schema_version|case|winding\.(inputs|options|stats)|notes)\b|solve_time|timings|\.n_dof$"
    r"|\.n_elements$"
)


def result_columns(d: dict[str, Any]) -> dict[str, Any]:
    """Scalar results of a run's JSON dict as ``{"winding.core_pressure [Pa]": value}``."""
    out: dict[str, Any] = {}
    readout = (d.get("hardness") or {}).get("readout")

    def walk(node: Any, prefix: str) -> None:
        if isinstance(node, dict):
            for k, v in node.items():
                walk(v, f"{prefix}{k}.")
            return
        key = prefix.rstrip(".")
        if _SKIP.search(key) or isinstance(node, list | str) or node is None:
            return
        out[_column_name(key, readout)] = float(node) if not isinstance(node, bool) else node

    walk(d, "")
    return out


def _column_name(key: str, readout: str | None) -> str:
    """The column of a dotted JSON key: its unit from the vocabulary
    (:func:`woundroll.pipeline.vocabulary.column_name`), not parsed from the key's name."""
    from woundroll.pipeline.vocabulary import column_name

    return column_name(key, readout)


#: Percentiles of the band columns of ``--uncertainty`` (a 95 % band).
PERCENTILES_BAND = (2.5, 97.5)


def run_point(
    case: Any, overrides: dict[str, Any], uncertainty: int = 0, seed: int = 0
) -> dict[str, Any]:
    """Run one roll: ``case`` (path, bundled name or dict) with ``overrides`` set; with
    ``uncertainty`` = N > 0 also the Monte Carlo bands of its ``[uncertainty]``
    (:func:`uncertainty_columns`, ``seed`` the same for every roll).

    Returns the result columns, or ``{"error": "field: message"}``; never raises (a sweep
    records the failures of single rolls). A roll that ran but whose propagation failed
    keeps its results and gets ``"uncertainty: message"`` in ``error``.
    """
    from woundroll.pipeline import run

    try:
        c = _load_point(case, overrides)
        d = run(c).to_dict()
        cols = result_columns(d)
    except (InputError, ConvergenceError) as exc:
        return {"error": str(exc)}
    except Exception as exc:  # a bug in one roll must not end a 10 000-roll study
        return {"error": f"{type(exc).__name__}: {exc}"}
    if uncertainty:
        from woundroll.assess.uncertainty import propagate

        try:
            uq = propagate(c, uncertainty, seed=seed)
        except (InputError, ConvergenceError) as exc:
            msg = exc.message if isinstance(exc, InputError) else str(exc)
            return {**cols, "error": f"uncertainty: {msg}"}
        except Exception as exc:
            return {**cols, "error": f"uncertainty: {type(exc).__name__}: {exc}"}
        readout = (d.get("hardness") or {}).get("readout")
        cols.update(uncertainty_columns(uq, readout))
    return cols


def uncertainty_columns(uq: Any, readout: str | None = None) -> dict[str, float]:
    """The 95 % bands (2.5 and 97.5 percentiles) of a roll's Monte Carlo
    (:class:`woundroll.assess.uncertainty.UncertaintyResult`) as table columns.

    A band with a nominal column in the table is named after it (``winding.core_pressure_low
    [Pa]``, ``hardness.reading_high [rho]``); the others under ``uncertainty.``. The reading
    band (surrogate, checked against full runs: ``uncertainty.surrogate_error``) is there
    only when the case's tester has a contact model (not an explicit roll spring).
    """
    lo, hi = PERCENTILES_BAND

    def band(key: str, unit: str, a: Any) -> dict[str, float]:
        p = np.percentile(np.asarray(a, float), [lo, hi])
        return {f"{key}_low [{unit}]": float(p[0]), f"{key}_high [{unit}]": float(p[1])}

    out = {
        **band("winding.core_pressure", "Pa", uq.core_pressure),
        **band("uncertainty.surface_pressure", "Pa", uq.surface_pressure),
        **band("uncertainty.min_hoop_stress", "Pa", uq.min_hoop),
        "uncertainty.negative_hoop_share [-]": uq.negative_hoop_share,
    }
    if uq.reading is not None:
        unit = readout or uq.scale
        out.update(band("hardness.reading", unit, uq.reading))
        err = uq.surrogate.get("max_abs_error")
        out[f"uncertainty.surrogate_error [{unit}]"] = math.nan if err is None else float(err)
    return out


@dataclass(frozen=True)
class CaseData:
    """A case file read where the sweep starts: its TOML table and the directory relative
    paths inside it are resolved against. Sent to Dask workers instead of the path, so a
    worker on another machine does not need the case file (files the case names, such as a
    thickness profile, still have to be readable there under the same path)."""

    data: dict[str, Any]
    base_dir: str | None = None


def _load_point(case: Any, overrides: dict[str, Any]) -> Any:
    """The case (path, bundled name, dict or :class:`CaseData`) with the point's values set,
    validated."""
    import copy

    from woundroll.case import case_from_dict, resolve_case_path, set_dotted

    if isinstance(case, CaseData):
        data = copy.deepcopy(case.data)
        base = Path(case.base_dir) if case.base_dir is not None else None
    elif isinstance(case, dict):
        data, base = copy.deepcopy(case), None
    else:
        path = resolve_case_path(case)
        data, base = tomllib.loads(path.read_text(encoding="utf-8")), path.parent
    for k, v in overrides.items():
        set_dotted(data, k, v)
    return case_from_dict(data, base)


@dataclass
class SweepResult:
    """The table of a sweep: ``columns`` and one ``rows`` entry per roll (design order)."""

    axes: list[Axis]
    columns: list[str]
    rows: list[list[Any]]
    design: str = "grid"
    notes: list[str] = field(default_factory=list)

    @property
    def n_failed(self) -> int:
        j = self.columns.index("error")
        return sum(1 for r in self.rows if r[j])

    def column(self, name: str) -> list[Any]:
        j = self.columns.index(name)
        return [r[j] for r in self.rows]

    def to_arrow(self) -> Any:
        """The table as a ``pyarrow.Table`` (float64 columns, ``error`` as string)."""
        import pyarrow as pa

        data = {}
        for j, name in enumerate(self.columns):
            col = [r[j] for r in self.rows]
            if name == "error" or any(isinstance(v, str) for v in col if v is not None):
                data[name] = pa.array([None if v is None else str(v) for v in col], pa.string())
            elif any(isinstance(v, bool) for v in col):
                # a failed roll has no flag: null, not NaN
                data[name] = pa.array([v if isinstance(v, bool) else None for v in col], pa.bool_())
            else:
                data[name] = pa.array([math.nan if v is None else float(v) for v in col])
        meta = {"woundroll.inverse.design": self.design}
        return pa.table(data).replace_schema_metadata(meta)

    def write(self, out_dir: str | Path) -> list[Path]:
        """``sweep.parquet``, ``sweep.csv`` and ``main_effects.png`` into ``out_dir``."""
        import pyarrow.parquet as pq

        out = Path(out_dir)
        try:
            out.mkdir(parents=True, exist_ok=True)
            pq.write_table(self.to_arrow(), out / "sweep.parquet")
            with open(out / "sweep.csv", "w", newline="", encoding="utf-8") as f:
                w = csv.writer(f)
                w.writerow(self.columns)
                for r in self.rows:
                    w.writerow(["" if v is None else _csv_cell(v) for v in r])
            written = [out / "sweep.parquet", out / "sweep.csv"]
            fig = self.plot_main_effects()
            if fig is not None:
                fig.savefig(out / "main_effects.png", dpi=110)
                written.append(out / "main_effects.png")
        except OSError as exc:
            raise InputError(f"cannot write to {out}: {exc.strerror or exc}", "--out") from None
        return written

    def results_to_plot(self) -> list[str]:
        """Up to three headline result columns for the main-effects plot."""
        prefer = (
            "hardness.reading",
            "profile.stats.reading.mean",
            "winding.core_pressure",
            "winding.max_pressure",
        )
        out = []
        for p in prefer:
            out += [c for c in self.columns if c.startswith(p + " [") and c not in out]
        return out[:3]

    def plot_main_effects(self) -> Any:
        """Mean of each headline result against each varied input (others averaged over);
        for random and LHS designs, means over eight equal-count bins of the input."""
        from matplotlib.figure import Figure

        ys = self.results_to_plot()
        if not ys:
            return None
        ok = [i for i, r in enumerate(self.rows) if not r[self.columns.index("error")]]
        if not ok:
            return None
        fig = Figure(figsize=(3.2 * len(self.axes), 2.6 * len(ys)), layout="constrained")
        axs = fig.subplots(len(ys), len(self.axes), squeeze=False)
        for i, y in enumerate(ys):
            yv = np.array([self.rows[k][self.columns.index(y)] for k in ok], float)
            for j, a in enumerate(self.axes):
                ax = axs[i, j]
                xv = [self.rows[k][self.columns.index(a.column)] for k in ok]
                xs, means = _main_effect(xv, yv, binned=self.design != "grid" and a.continuous)
                ax.plot(xs, means, "o-", color="C0")
                ax.grid(alpha=0.3)
                if i == len(ys) - 1:
                    ax.set_xlabel(a.column)
                if j == 0:
                    ax.set_ylabel(y, fontsize=8)
        fig.suptitle(f"main effects ({self.design}, {len(ok)} of {len(self.rows)} rolls ran)")
        return fig


def _main_effect(xv: list[Any], yv: np.ndarray, *, binned: bool) -> tuple[list[Any], list[float]]:
    if not binned:
        levels = list(dict.fromkeys(xv))
        xs = levels
        means = [float(np.nanmean(yv[[x == lv for x in xv]])) for lv in levels]
        if all(isinstance(v, int | float) for v in xs):
            order = np.argsort(xs)
            xs = [xs[k] for k in order]
            means = [means[k] for k in order]
        return xs, means
    x = np.asarray(xv, float)
    edges = np.quantile(x, np.linspace(0, 1, min(8, len(x)) + 1))
    idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, len(edges) - 2)
    xs, means = [], []
    for b in range(len(edges) - 1):
        sel = idx == b
        if sel.any():
            xs.append(float(x[sel].mean()))
            means.append(float(np.nanmean(yv[sel])))
    return xs, means


def _csv_cell(v: Any) -> Any:
    if isinstance(v, float):
        return "" if math.isnan(v) else repr(v)
    return v


def run_sweep(
    case: Any,
    axes: Sequence[Axis | str],
    *,
    design: str = "grid",
    samples: int | None = None,
    seed: int = 0,
    workers: int | None = None,
    scheduler: Any = None,
    progress: SweepProgress | None = None,
    uncertainty: int = 0,
) -> SweepResult:
    """Run a sweep; see the module docstring.

    Parameters
    ----------
    case : path, bundled case name, or a case dict (TOML structure)
    axes : Axis or ``"key=..."`` strings
    design, samples, seed : the design (:func:`design_points`)
    workers : int, optional
        1: in this process; N > 1: a pool of N processes; None (default): in this process
        unless the rolls would take longer than :data:`POOL_THRESHOLD` serially, then on a
        pool of all cores.
    scheduler : str or distributed.Client, optional
        A Dask scheduler address (``tcp://host:8786``) or a client: run there instead.
    progress : callable, optional
        ``progress(done, total)`` as rolls finish.
    uncertainty : int
        N > 0: propagate the case's ``[uncertainty]`` with N Monte Carlo samples for every
        roll (:func:`woundroll.assess.uncertainty.propagate`, the same ``seed`` for every roll) and
        add the band columns (:func:`uncertainty_columns`).

    Raises
    ------
    InputError
        Bad axes or design; a varied key the case does not know (checked on the first roll
        before anything runs); an unreachable scheduler (``--scheduler``); ``uncertainty``
        below 10 (``--uncertainty``) or a base case without tolerances (``uncertainty``).
    """
    from woundroll.case import load_case

    axes = [a if isinstance(a, Axis) else parse_vary(a) for a in axes]
    keys = [a.key for a in axes]
    if len(set(keys)) != len(keys):
        raise InputError(f"a key is varied twice: {', '.join(keys)}", "--vary")
    if isinstance(case, str | Path):
        from woundroll.case import resolve_case_path

        case = str(resolve_case_path(case))
    base = load_case(case)  # the base case must be valid: its errors are not a roll's
    if isinstance(uncertainty, bool) or not isinstance(uncertainty, int) or uncertainty < 0:
        raise InputError(f"must be a whole number of samples, got {uncertainty!r}", "--uncertainty")
    if uncertainty:
        from woundroll.assess.uncertainty import uncertain_parameters

        if uncertainty < 10:
            raise InputError(f"needs at least 10 samples, got {uncertainty}", "--uncertainty")
        uncertain_parameters(base)  # no [uncertainty] table: the sweep's error, not each roll's
    points = design_points(axes, design, samples, seed)
    overrides = [{a.key: a.case_value(v) for a, v in zip(axes, p, strict=True)} for p in points]
    first = run_point_check(case, overrides[0])
    if first is not None:
        raise first
    total = len(points)

    def tick(done: int) -> None:
        if progress is not None:
            progress(done, total)

    tick(0)
    if scheduler is not None:
        results = _run_dask(case, overrides, scheduler, tick, uncertainty, seed)
    else:
        results = _run_local(case, overrides, workers, tick, uncertainty, seed)
    inputs = [a.column for a in axes]
    result_cols: list[str] = []
    seen: set[str] = set()
    for r in results:
        for k in r:
            if k != "error" and k not in seen:
                seen.add(k)
                result_cols.append(k)
    columns = [*inputs, *result_cols, "error"]
    rows = [
        [*p, *(r.get(c, math.nan) for c in result_cols), r.get("error", "")]
        for p, r in zip(points, results, strict=True)
    ]
    sweep = SweepResult(axes, columns, rows, design)
    if sweep.n_failed:
        sweep.notes.append(f"{sweep.n_failed} of {total} rolls failed: see the error column")
    return sweep


def run_point_check(case: Any, overrides: dict[str, Any]) -> InputError | None:
    """An unknown varied key is the sweep's error, not a roll's: check it on one roll."""
    try:
        _load_point(case, overrides)
    except InputError as exc:
        if "unknown key" in exc.message or "is not a table" in exc.message:
            return InputError(exc.message, f"--vary {exc.field}")
    return None


#: Auto mode starts a process pool only when the rolls left would take longer than this
#: serially [s]: spawned workers import woundroll and load their compiled kernels first
#: (about 3 s each on the 2-core test machine, benchmarks/bench_sweep.py).
POOL_THRESHOLD = 15.0


def _run_local(
    case: Any,
    overrides: list[dict[str, Any]],
    workers: int | None,
    tick: Callable[[int], None],
    uncertainty: int = 0,
    seed: int = 0,
) -> list[dict[str, Any]]:
    """Serially (``workers=1``), on a pool of ``workers`` processes, or (None) automatically:
    two rolls in this process, then a pool of all cores for the rest if they would take longer
    than :data:`POOL_THRESHOLD` serially."""
    out: list[dict[str, Any]] = []
    n_cores = os.cpu_count() or 1
    if workers is None:
        for o in overrides[:2]:
            t0 = time.perf_counter()
            out.append(run_point(case, o, uncertainty, seed))
            tick(len(out))
        per_roll = time.perf_counter() - t0 if out else 0.0
        rest = overrides[len(out) :]
        if n_cores < 2 or per_roll * len(rest) < POOL_THRESHOLD:
            workers = 1
        else:
            workers = min(n_cores, len(rest))
    else:
        rest = overrides
    if workers == 1 or len(rest) < 2:
        for o in rest:
            out.append(run_point(case, o, uncertainty, seed))
            tick(len(out))
        return out
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    # spawn: numba and threads in the parent make fork unsafe; workers import woundroll once
    start = len(out)
    results: list[dict[str, Any] | None] = [None] * len(rest)
    with ProcessPoolExecutor(min(workers, len(rest)), mp_context=mp.get_context("spawn")) as pool:
        futs = {pool.submit(run_point, case, o, uncertainty, seed): i for i, o in enumerate(rest)}
        for done, fut in enumerate(as_completed(futs), 1):
            results[futs[fut]] = fut.result()
            tick(start + done)
    return out + results  # type: ignore[operator]


#: How long ``--scheduler`` waits for the scheduler to answer before it gives up.
SCHEDULER_TIMEOUT = "10s"


def _run_dask(
    case: Any,
    overrides: list[dict[str, Any]],
    scheduler: Any,
    tick: Callable[[int], None],
    uncertainty: int = 0,
    seed: int = 0,
) -> list[dict[str, Any]]:
    try:
        from distributed import Client, as_completed
    except ImportError:  # pragma: no cover - a declared dependency
        raise InputError("needs dask[distributed]", "--scheduler") from None
    own = not isinstance(scheduler, Client)
    if own:
        try:
            client = Client(str(scheduler), timeout=SCHEDULER_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(
                f"cannot reach the Dask scheduler at {scheduler!r}: {exc}", "--scheduler"
            ) from None
    else:
        client = scheduler
    if isinstance(case, str | Path):  # the workers get the case's table, not its path
        path = Path(case).resolve()
        case = CaseData(tomllib.loads(path.read_text(encoding="utf-8")), str(path.parent))
    try:
        n = len(overrides)
        futs = client.map(
            run_point, [case] * n, overrides, [uncertainty] * n, [seed] * n, pure=False
        )
        index = {f.key: i for i, f in enumerate(futs)}
        results: list[dict[str, Any] | None] = [None] * len(futs)
        # the client's own loop: this client is not the process's default client (a
        # command-line run has no other), and as_completed would look for that one
        done = 0
        for fut in as_completed(futs, loop=client.loop):
            try:
                results[index[fut.key]] = fut.result()
            except Exception as exc:  # a worker lost or killed: that roll's error, not a crash
                msg = " ".join(f"{type(exc).__name__}: {exc}".split())
                results[index[fut.key]] = {"error": f"cluster: {msg}"}
            done += 1
            tick(done)
        if all(str(r.get("error", "")).startswith("cluster: ") for r in results if r):
            # no roll reached woundroll: the cluster is the problem (workers that cannot
            # import woundroll, another Python environment), not the rolls
            first = str(results[0]["error"]).removeprefix("cluster: ")  # type: ignore[index]
            raise InputError(
                f"no roll ran on the cluster at {client.scheduler.address}: {first}", "--scheduler"
            )
        return results  # type: ignore[return-value]
    finally:
        if own:
            client.close()
