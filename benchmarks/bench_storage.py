"""Storage time (radial creep) and a temperature change on the 10,000-layer benchmark roll,
in-process, as ratios to the yardstick's per-layer winding of the same roll (same run).

Issue 24's target: a 10k-layer roll with storage in <= 1 s in-process (winding plus
storage). Reported: the winding (``wind``), the temperature change (``apply_storage``),
the creep (``apply_creep``, 40 graded steps), their sum, and each as a ratio to the
yardstick (benchmarks/yardstick.py). Also PET1 26.7 N at 10 um (8,890 layers) cooled by
20 K and wetted by 0.5 %: the storage change against its own winding (the Picard
iterations on the chord modulus).

``--write-docs`` puts the results into docs/winding.md between ``<!-- bench: storage -->``
/ ``<!-- bench: storage-pet1 -->`` and ``<!-- end bench -->`` (``make bench`` does), with the
date, the load average and the yardstick's time.

Run: ``PYTHONPATH=src .venv/bin/python benchmarks/bench_storage.py [--layers 10000]
[--write-docs]``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import load_note, write_block  # noqa: E402
from yardstick import wind_per_layer  # noqa: E402

from woundroll.materials import Core, Pfeiffer, Web  # noqa: E402
from woundroll.materials.creep import PowerCreep  # noqa: E402
from woundroll.winding.creep import apply_creep  # noqa: E402
from woundroll.winding.hakiel import wind  # noqa: E402
from woundroll.winding.storage import StorageChange, apply_storage  # noqa: E402
from woundroll.winding.tension import TensionSchedule  # noqa: E402

PAGE = Path(__file__).resolve().parent.parent / "docs" / "winding.md"


def pet1_storage(repeat: int) -> dict[str, float]:
    """PET1 26.7 N at 10 um (the bundled case, thinner web) cooled by 20 K and wetted by
    0.5 %: winding and storage wall times [s], nodes and Picard iterations."""
    from woundroll.case import load_case

    case = load_case("pet1-26.7N", ["web.thickness='10 um'"])
    web, core = case.web.build(), case.core.build()
    r_out = case.winding.final_radius(web, core)
    schedule = case.winding.schedule(web)
    w, t_wind = best(lambda: wind(web, core, r_out, schedule), repeat)
    change = StorageChange(temperature_change=-20.0, moisture_change=0.005)
    st, t_store = best(lambda: apply_storage(w, web, core, change), repeat)
    return {
        "layers": round((r_out - core.outer_radius) / web.thickness),
        "nodes": w.radius.size,
        "iterations": st.iterations,
        "wind": t_wind,
        "storage": t_store,
    }


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
    ap.add_argument("--write-docs", action="store_true", help="rewrite docs/winding.md's blocks")
    args = ap.parse_args()
    load0 = os.getloadavg()[0]
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
    pet = pet1_storage(args.repeat)
    print(
        f"PET1 26.7 N at 10 um ({pet['layers']} layers, {pet['nodes']} nodes), -20 K and "
        f"+0.5 % moisture: {pet['iterations']} Picard iterations, storage {pet['storage']:.3f} s "
        f"against its winding {pet['wind']:.3f} s (ratio {pet['storage'] / pet['wind']:.3f})"
    )
    load1 = os.getloadavg()[0]
    if args.write_docs:
        when = (
            f"`benchmarks/bench_storage.py`, {datetime.date.today().isoformat()}, best of "
            f"{args.repeat}, {load_note(load0, load1)}; the yardstick (benchmarks/yardstick.py, "
            f"the per-layer winding of the {args.layers:,}-layer roll) took {t_yard:.2f} s in "
            "the same run"
        )
        roll = (
            f"the {args.layers:,}-layer benchmark roll ({w.radius.size:,} nodes): winding "
            f"{t_wind / t_yard:.3f}, a -20 K change {t_temp / t_yard:.3f}, 30 d of creep in 40 "
            f"steps {t_creep / t_yard:.3f}: {total / t_yard:.3f} of the yardstick in all "
            f"({total:.2f} s; the issue's target: 1 s)."
        )
        write_block(PAGE, "storage", [f"{when}: {roll}"])
        pet1 = (
            f"An {pet['layers']:,}-layer roll (PET1 26.7 N at 10 um, {pet['nodes']:,} nodes), "
            f"cooled by 20 K and wetted by 0.5 %: {pet['iterations']} Picard iterations, the "
            f"storage change {pet['storage'] / pet['wind']:.3f} of its winding's time in the "
            f"same process ({pet['storage'] / t_yard:.4f} and {pet['wind'] / t_yard:.3f} of "
            f"the yardstick; {when})."
        )
        write_block(PAGE, "storage-pet1", [pet1])


if __name__ == "__main__":
    main()
