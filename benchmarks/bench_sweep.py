"""Benchmark of sweeps: rolls per second serially, on a local process pool, and on a local
Dask distributed cluster (a script, not a test).

Run: ``python benchmarks/bench_sweep.py [--rolls N] [--full]``.

Workload ``fast`` (default 48 rolls): a 6 cm PET1 roll (about 310 layers) with an explicit
roll spring: the 1D winding solve and the impact models, no contact model; a roll takes a
few ms, so this measures the sweep's own overhead (task dispatch, pickling, table).
Workload ``full`` (``--full``, 4 rolls): the bundled ``pet1-26.7N`` (889 layers, the 2D
contact model, ``contact.no_update = false``): seconds per roll, where parallel runs pay.

The cluster is ``LocalCluster(n_workers=2, threads_per_worker=1)`` with worker processes;
its start-up is timed separately (a long-lived cluster pays it once), and the sweep is run
twice on it: cold (workers import woundroll and load the compiled kernels on their first
roll) and warm. The process pool's
start-up (spawned workers importing woundroll) is inside its time, as the CLI pays it.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

from woundroll.app.sweep import run_sweep

FAST = {
    "title": "fast sweep roll",
    "web": {"preset": "PET1"},
    "core": {"outer_radius": "4.45 cm", "rigid": True},
    "winding": {"outer_radius": "6 cm", "tension": "26.7 N"},
    "tester": {
        "instrument": "rho-meter",
        "roll_spring": {"alpha": "2.6e8 N/m^2", "beta": "1.05e5 N/m"},
    },
}


def timed(fn):  # type: ignore[no-untyped-def]
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def bench(label: str, case, vary: list[str], cluster_client) -> None:  # type: ignore[no-untyped-def]
    serial, t_s = timed(lambda: run_sweep(case, vary, workers=1))
    n = len(serial.rows)
    pool, t_p = timed(lambda: run_sweep(case, vary, workers=2))
    dask, t_d = timed(lambda: run_sweep(case, vary, scheduler=cluster_client))
    warm, t_w = timed(lambda: run_sweep(case, vary, scheduler=cluster_client))
    auto, t_a = timed(lambda: run_sweep(case, vary))
    same = all(r.rows == serial.rows for r in (pool, dask, warm, auto))
    print(f"{label}: {n} rolls, tables equal: {same}")
    for name, t in (
        ("serial", t_s),
        ("process pool (2)", t_p),
        ("default (auto)", t_a),
        ("dask LocalCluster (2)", t_d),
        ("dask, warm workers", t_w),
    ):
        print(f"  {name:24s} {t:7.2f} s  {n / t:8.1f} rolls/s  ({t_s / t:.2f} x serial)")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rolls", type=int, default=48)
    ap.add_argument("--full", action="store_true")
    args = ap.parse_args()
    from distributed import Client, LocalCluster

    print(f"python {platform.python_version()}, {os.cpu_count()} cores, {platform.machine()}")
    (cluster, client), t_up = timed(
        lambda: (
            c := LocalCluster(
                n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
            ),
            Client(c),
        )
    )
    print(f"LocalCluster start-up: {t_up:.2f} s")
    try:
        bench("fast", FAST, [f"winding.tension=10 N:80 N:{args.rolls}"], client)
        if args.full:
            bench(
                "full (pet1-26.7N, contact model)",
                {
                    **FAST,
                    "winding": {"outer_radius": "13.34 cm", "tension": "26.7 N"},
                    "core": {"outer_radius": "4.45 cm", "rigid": True},
                    "tester": {"instrument": "rho-meter"},
                    "contact": {"no_update": False},
                },
                ["winding.tension=20 N:40 N:4"],
                client,
            )
    finally:
        client.close()
        cluster.close()


if __name__ == "__main__":
    main()
