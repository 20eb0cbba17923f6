"""Storage time (radial creep) and a temperature change on the 10,000-layer benchmark roll,
in-process, as ratios to the yardstick's per-layer winding of the same roll (same run).

Issue 24's target: a 10k-layer roll with storage in <= 1 s in-process (winding plus
storage). Reported: the winding (``wind``), the temperature change (``apply_storage``),
the creep (``apply_creep``, 40 graded steps), their sum, and each as a ratio to the
yardstick (benchmarks/yardstick.py).

Run: ``PYTHONPATH=src .venv/bin/python benchmarks/bench_storage.py [--layers 10000]``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import time  # noqa: E402

from yardstick import wind_per_layer  # noqa: E402

from woundroll.materials import Core, Pfeiffer, Web  # noqa: E402
from woundroll.materials.creep import PowerCreep  # noqa: E402
from woundroll.winding.creep import apply_creep  # noqa: E402
from woundroll.winding.hakiel import wind  # noqa: E402
from woundroll.winding.storage import StorageChange, apply_storage  # noqa: E402
from woundroll.winding.tension import TensionSchedule  # noqa: E402


def best(fn, repeat: int) -> tuple[object, float]:  # type: ignore[no-untyped-def]
    out, t_best = None, float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        t_best = min(t_best, time.perf_counter() - t0)
    return out, t_best


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--layers", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    h = 12e-6
    web = Web(
        thickness=h,
        width=0.5,
        E_theta=5e9,
        radial_modulus=Pfeiffer(K1=1e4, K2=100.0),
        alpha_r=6e-5,
        alpha_theta=1.7e-5,
    )
    core = Core(outer_radius=0.076, thermal_expansion=1.2e-5)
    R = 0.076 + args.layers * h
    tension = TensionSchedule(web_stress=1.5e6)
    wind(web, core, 0.076 + 200 * h, tension)  # warm-up: kernels loaded
    w, t_wind = best(lambda: wind(web, core, R, tension), args.repeat)
    st, t_temp = best(
        lambda: apply_storage(w, web, core, StorageChange(temperature_change=-20.0)), args.repeat
    )
    law = PowerCreep(0.2, 60 * 86400.0)
    cr, t_creep = best(lambda: apply_creep(st.winding, web, core, law, 30 * 86400.0), args.repeat)
    _, t_yard = wind_per_layer(args.layers)
    total = t_wind + t_temp + t_creep
    print(f"{args.layers} layers ({w.radius.size} nodes), best of {args.repeat}, wall [s]:")
    for name, t in (
        ("wind", t_wind),
        ("temperature -20 K", t_temp),
        ("creep 30 d (40 steps)", t_creep),
        ("sum", total),
        ("yardstick per-layer winding", t_yard),
    ):
        print(f"  {name:30s} {t:8.3f}   ratio to yardstick {t / t_yard:.4f}")
    print(
        f"  core pressure: wound {w.core_pressure / 1e3:.2f} kPa, after -20 K "
        f"{st.winding.core_pressure / 1e3:.2f} kPa, "
        f"after 30 d {cr.winding.core_pressure / 1e3:.2f} kPa"
    )


if __name__ == "__main__":
    main()
