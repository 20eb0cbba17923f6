"""Benchmark: 10,000-layer center-wound roll, compiled solver vs a plain banded solve.

Problem: 12 um film on a 7.6 cm rigid core, Pfeiffer K1 = 10 kPa, K2 = 100, E_theta = 5 GPa,
wound-on tension 1.5 MPa, 10,000 layers (R = 19.6 cm), default options (2 elements per
layer: 20,001 nodes; midpoint E_r iterated in every increment).

* ``wind``: the default solver (numba Riccati sweep over a 64-layer window, deep part
  frozen between flushes every 8 increments). numba compile time is excluded: a small
  roll is wound first (warm-up), then the best of ``--repeat`` (default 5) runs is reported.
* ``wind_reference``: the straightforward implementation of the same discretisation and
  E_r rule: per increment, NumPy coefficients for every element and
  ``scipy.linalg.solve_banded`` on the whole roll, iterated to the same tolerance.

BLAS/OpenMP threads are pinned to 1 (set before NumPy is imported; override by exporting
the variables): the solves are serial, and a multi-threaded BLAS only adds noise when
other jobs share the machine. Timings are best-of-N (``--repeat``) to damp that noise.

Run: ``.venv/bin/python benchmarks/bench_winding.py [--layers N] [--repeat N] [--exact]``
(``--exact`` also times the compiled solver without the lazy deep part).
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import platform  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from woundroll.materials import Core, Pfeiffer, Web  # noqa: E402
from woundroll.winding.hakiel import WindingOptions, wind, wind_reference  # noqa: E402
from woundroll.winding.tension import TensionSchedule  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--layers", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=5, help="timed runs of wind (best is kept)")
    ap.add_argument("--exact", action="store_true")
    args = ap.parse_args()

    h = 12e-6
    web = Web(thickness=h, width=1.0, E_theta=5e9, radial_modulus=Pfeiffer(10e3, 100.0))
    core = Core(0.076)
    R = 0.076 + args.layers * h
    sched = TensionSchedule(1.5e6)
    opts = WindingOptions()

    wind(web, core, 0.076 + 50 * h, sched)  # warm-up: numba compile (or cache load)

    times = []
    for _ in range(max(args.repeat, 1)):
        t0 = time.perf_counter()
        fast = wind(web, core, R, sched, options=opts)
        times.append(time.perf_counter() - t0)
    t_fast = min(times)

    t0 = time.perf_counter()
    ref = wind_reference(web, core, R, sched, options=opts)
    t_ref = time.perf_counter() - t0

    diff = np.max(np.abs(fast.sigma_r - ref.sigma_r)) / np.max(np.abs(ref.sigma_r))
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs")
    print(
        f"problem: {fast.n_layers} layers, {fast.radius.size} nodes, "
        f"{fast.stats['increments']} increments, options {opts.to_dict()}"
    )
    threads = {v: os.environ[v] for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
    print(f"timings exclude numba compilation (warm-up run first); threads {threads}")
    print(
        f"wind (compiled, lazy deep part), best of {len(times)}: {t_fast:8.3f} s   "
        f"(runs: {', '.join(f'{t:.3f}' for t in times)})"
    )
    print(f"wind_reference (NumPy + solve_banded):     {t_ref:8.3f} s")
    print(f"speed-up: {t_ref / t_fast:.1f}x")
    print(
        f"core pressure: {fast.core_pressure:.1f} Pa (compiled), {ref.core_pressure:.1f} Pa "
        f"(reference)"
    )
    print(f"max |sigma_r - sigma_r_ref| / max |sigma_r_ref| = {diff:.2e}")
    if args.exact:
        t0 = time.perf_counter()
        ex = wind(web, core, R, sched, options=WindingOptions(window_layers=None))
        t_ex = time.perf_counter() - t0
        d_ex = np.max(np.abs(ex.sigma_r - ref.sigma_r)) / np.max(np.abs(ref.sigma_r))
        print(
            f"wind without lazy part (compiled, full sweep): {t_ex:.3f} s, "
            f"max rel diff to reference {d_ex:.2e}"
        )


if __name__ == "__main__":
    main()
