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

Also printed: element evaluations per increment (window, refreshes), a measure of the work
that does not depend on the machine's load (O(log N) per increment for the default).

BLAS/OpenMP threads are pinned to 1 (set before NumPy is imported; override by exporting
the variables). Timings: wall clock and process CPU time, best of N.

Run: ``.venv/bin/python benchmarks/bench_winding.py [--layers 10000 30000 100000]
[--repeat 3] [--exact-max 30000] [--reference-max 10000]``
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import platform  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402

import numpy as np  # noqa: E402

from woundroll.materials import Core, Pfeiffer, Web  # noqa: E402
from woundroll.winding.hakiel import WindingOptions, wind, wind_reference  # noqa: E402
from woundroll.winding.result import WindingResult  # noqa: E402
from woundroll.winding.tension import TensionSchedule  # noqa: E402

H = 12e-6
WEB = Web(thickness=H, width=1.0, E_theta=5e9, radial_modulus=Pfeiffer(10e3, 100.0))
CORE = Core(0.076)
SCHED = TensionSchedule(1.5e6)


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
    args = ap.parse_args()

    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs")
    if hasattr(os, "getloadavg"):
        print(f"load average at start: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")
    threads = {v: os.environ[v] for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
    print(f"options {WindingOptions().to_dict()}; threads {threads}")
    wind(WEB, CORE, 0.076 + 50 * H, SCHED)  # warm-up: numba compile (or cache load)
    wind(WEB, CORE, 0.076 + 50 * H, SCHED, options=WindingOptions(window_layers=None))

    header = (
        f"{'layers':>8} {'solver':<28} {'wall [s]':>9} {'cpu [s]':>8} {'core p [Pa]':>12} "
        f"{'max|dsr|/p_c':>12} {'evals/incr':>11}"
    )
    print(header)
    print("-" * len(header))
    for n in args.layers:
        R = 0.076 + n * H
        fast, w_fast, c_fast = timed(lambda R=R: wind(WEB, CORE, R, SCHED), args.repeat)
        ev = (
            fast.stats["element_evaluations_window"] + fast.stats["element_evaluations_refresh"]
        ) / fast.stats["increments"]
        rows = [("wind (default, levels)", fast, w_fast, c_fast, ev)]
        exact = None
        if n <= args.exact_max:
            opts = WindingOptions(window_layers=None)
            exact, w_ex, c_ex = timed(lambda R=R, o=opts: wind(WEB, CORE, R, SCHED, options=o), 1)
            ev_ex = exact.stats["element_evaluations_window"] / exact.stats["increments"]
            rows.append(("wind(window_layers=None)", exact, w_ex, c_ex, ev_ex))
        if n <= args.reference_max:
            ref, w_ref, c_ref = timed(lambda R=R: wind_reference(WEB, CORE, R, SCHED), 1)
            rows.append(("wind_reference (NumPy+banded)", ref, w_ref, c_ref, float("nan")))
        for name, res, w, c, e in rows:
            d = "-" if exact is None else f"{rel_diff(res, exact):.2e}"
            print(
                f"{n:>8} {name:<28} {w:>9.3f} {c:>8.3f} {res.core_pressure:>12.1f} "
                f"{d:>12} {e:>11.0f}"
            )
        for name, _res, w, c, _e in rows[1:]:
            print(
                f"{'':>8} speed-up of the default against {name}: {w / w_fast:.0f}x wall, "
                f"{c / c_fast:.0f}x cpu"
            )
    if hasattr(os, "getloadavg"):
        print(f"load average at end: {', '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
