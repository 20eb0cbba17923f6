"""Benchmark: the 1D winding solve at 10,000 / 30,000 / 100,000 layers, against the exact
per-increment solve and the straightforward implementation, in the same run.

Problem: 12 um film on a 7.6 cm rigid core, Pfeiffer K1 = 10 kPa, K2 = 100, E_theta = 5 GPa,
wound-on tension 1.5 MPa, N layers (R = 7.6 cm + N x 12 um), default options (2 elements per
layer: 2 N + 1 nodes; midpoint E_r iterated in every increment).

* ``wind`` (default): the compiled solve with the deep part frozen in levels of doubling
  depth and refreshed in levels (O(N log N); docs/winding.md). numba compile/cache-load
  time is excluded: a small roll is wound first (warm-up), then the best of ``--repeat``
  runs is reported.
* ``wind(window_layers=None)``: the same compiled kernel re-solving the whole roll with
  current moduli in every increment (O(N^2)): the exact answer the default must match
  within 0.1 %. Run for N <= ``--exact-max`` (default 30,000; 100,000 takes minutes).
* ``wind_reference``: the straightforward implementation of the same discretisation and
  E_r rule (per increment NumPy coefficients for every element and
  ``scipy.linalg.solve_banded`` on the whole roll, iterated to the same tolerance); run for
  N <= ``--reference-max`` (default 10,000: it takes half a minute there).

Every time is also given as a ratio to the yardstick (benchmarks/yardstick.py: the
straightforward per-layer winding of the 10,000-layer roll, no compiled code) timed in the
same run. ``--write-docs`` puts the table into docs/winding.md between
``<!-- bench: winding -->`` and ``<!-- end bench -->`` (``make bench`` does).

Also printed: element evaluations per increment (window, refreshes), a measure of the work
that does not depend on the machine's load (O(log N) per increment for the default).

BLAS/OpenMP threads are pinned to 1 (set before NumPy is imported; override by exporting
the variables). Timings: wall clock and process CPU time, best of N.

Run: ``.venv/bin/python benchmarks/bench_winding.py [--layers 10000 30000 100000]
[--repeat 3] [--exact-max 30000] [--reference-max 10000] [--write-docs]``
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from docs_block import write_block  # noqa: E402
from yardstick import film, wind_per_layer  # noqa: E402

from woundroll.winding.hakiel import WindingOptions, wind, wind_reference  # noqa: E402
from woundroll.winding.result import WindingResult  # noqa: E402

WEB, CORE, SCHED = film()  # the yardstick's roll (benchmarks/yardstick.py)
H = WEB.thickness
PAGE = Path(__file__).resolve().parent.parent / "docs" / "winding.md"


def timed(fn: Callable[[], WindingResult], repeat: int) -> tuple[WindingResult, float, float]:
    """Best wall and CPU time of ``repeat`` runs of ``fn``; returns the last result."""
    walls, cpus = [], []
    res = None
    for _ in range(max(repeat, 1)):
        w0, c0 = time.perf_counter(), time.process_time()
        res = fn()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    assert res is not None
    return res, min(walls), min(cpus)


def rel_diff(a: WindingResult, b: WindingResult) -> float:
    """max |sigma_r(a) - sigma_r(b)| / core pressure of b."""
    return float(np.max(np.abs(a.sigma_r - b.sigma_r)) / b.core_pressure)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--layers", type=int, nargs="+", default=[10_000, 30_000, 100_000])
    ap.add_argument("--repeat", type=int, default=3, help="timed runs of wind (best is kept)")
    ap.add_argument("--exact-max", type=int, default=30_000)
    ap.add_argument("--reference-max", type=int, default=10_000)
    ap.add_argument("--write-docs", action="store_true", help="rewrite docs/winding.md's table")
    args = ap.parse_args()

    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs")
    load0 = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"load average at start: {load0:.2f}")
    threads = {v: os.environ[v] for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
    print(f"options {WindingOptions().to_dict()}; threads {threads}")
    wind(WEB, CORE, CORE.outer_radius + 50 * H, SCHED)  # warm-up: numba compile (or cache load)
    wind(WEB, CORE, CORE.outer_radius + 50 * H, SCHED, options=WindingOptions(window_layers=None))
    yard = min(wind_per_layer()[1] for _ in range(2))
    print(f"yardstick (per-layer banded winding, 10,000 layers, best of 2): {yard:.2f} s wall")

    header = (
        f"{'layers':>8} {'solver':<28} {'wall [s]':>9} {'cpu [s]':>8} {'x yard':>8} "
        f"{'core p [Pa]':>12} {'max|dsr|/p_c':>12} {'evals/incr':>11}"
    )
    print(header)
    print("-" * len(header))
    md = [
        "| layers | solver | wall / yardstick | wall [s] | core pressure [Pa] "
        "| max dsigma_r / p_c | evaluations / increment |",
        "|---|---|---|---|---|---|---|",
    ]
    speedups = []
    for n in args.layers:
        R = CORE.outer_radius + n * H
        fast, w_fast, c_fast = timed(lambda R=R: wind(WEB, CORE, R, SCHED), args.repeat)
        ev = (
            fast.stats["element_evaluations_window"] + fast.stats["element_evaluations_refresh"]
        ) / fast.stats["increments"]
        rows = [("`wind` (default, levels)", fast, w_fast, c_fast, ev)]
        exact = None
        if n <= args.exact_max:
            opts = WindingOptions(window_layers=None)
            exact, w_ex, c_ex = timed(lambda R=R, o=opts: wind(WEB, CORE, R, SCHED, options=o), 1)
            ev_ex = exact.stats["element_evaluations_window"] / exact.stats["increments"]
            rows.append(("`wind(window_layers=None)` (exact)", exact, w_ex, c_ex, ev_ex))
        if n <= args.reference_max:
            ref, w_ref, c_ref = timed(lambda R=R: wind_reference(WEB, CORE, R, SCHED), 1)
            rows.append(("`wind_reference`", ref, w_ref, c_ref, float("nan")))
        for name, res, w, c, e in rows:
            d = "" if exact is None else f"{rel_diff(res, exact):.1e}"
            ev_cell = "" if np.isnan(e) else f"{e:,.0f}"
            print(
                f"{n:>8} {name:<28} {w:>9.3f} {c:>8.3f} {w / yard:>8.3f} "
                f"{res.core_pressure:>12.1f} {d or '-':>12} {e:>11.0f}"
            )
            md.append(
                f"| {n:,} | {name} | {w / yard:.3g} | {w:.3g} | {res.core_pressure:,.1f} | "
                f"{d} | {ev_cell} |"
            )
        for name, _res, w, c, _e in rows[1:]:
            line = f"{w / w_fast:.0f}x against {name} at {n:,} layers"
            print(f"{'':>8} speed-up of the default: {line} (wall; {c / c_fast:.0f}x cpu)")
            speedups.append(line)
    load1 = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"load average at end: {load1:.2f}")
    if args.write_docs:
        intro = (
            f"`benchmarks/bench_winding.py --layers {' '.join(map(str, args.layers))} "
            f"--exact-max {args.exact_max} --reference-max {args.reference_max}`: best of "
            f"{args.repeat} for `wind`, one run of the others; python {sys.version.split()[0]}, "
            f"{os.cpu_count()} cores, load average {load0:.1f} -> {load1:.1f}. The yardstick "
            "(benchmarks/yardstick.py, the per-layer banded winding of the 10,000-layer roll) "
            f"took {yard:.2f} s in the same run; wall times as multiples of it."
        )
        tail = "Speed-up of the default (wall): " + "; ".join(speedups) + "."
        write_block(PAGE, "winding", [intro, "", *md, "", tail])


if __name__ == "__main__":
    main()
