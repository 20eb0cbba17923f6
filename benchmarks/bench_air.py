"""Benchmark: winding speed and entrained air (issue 24, item 1), as ratios to the yardstick
(:func:`yardstick.wind_per_layer`, 10,000 layers) in the same run.

* ``wind`` of the yardstick roll (10,000 layers of 12 um film on a 7.6 cm rigid core,
  1.5 MPa): today's model, the roll without air;
* ``wind_with_air`` of the same roll at 3 m/s without nip (at 8 MPa: the yardstick's
  1.5 MPa is too slack to wind at speed without a nip) and at 10 m/s with a 500 N/m nip:
  the film, the composite roll, the roll after the air has left (given the roll without
  air, as the pipeline does, and winding both);
* ``run`` of a case without air and the same case with ``winding.speed = 0`` (must take
  the same time: the air hook returns at once) and with ``winding.speed = 5 m/s``, no
  tester (winding only).

Best of ``--repeat`` wall times after a warm-up (compiled kernels loaded). ``--write-docs``
puts the results into docs/winding.md between ``<!-- bench: air -->`` and ``<!-- end bench
-->`` (``make bench`` does): times as multiples of the yardstick, with the date and load.

Run: ``.venv/bin/python benchmarks/bench_air.py [--repeat 5] [--write-docs]``
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from dataclasses import replace  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))

from docs_block import load_note, write_block  # noqa: E402
from yardstick import film, wind_per_layer  # noqa: E402

from woundroll.winding.air import AirSettings, wind_with_air  # noqa: E402
from woundroll.winding.hakiel import wind  # noqa: E402

PAGE = Path(__file__).resolve().parent.parent / "docs" / "winding.md"
WEB, CORE, SCHED = film()  # the yardstick's roll (benchmarks/yardstick.py)
H = WEB.thickness
N = 10_000
R = CORE.outer_radius + N * H

CASE = {
    "title": "bench",
    "web": {
        "thickness": "12 um",
        "width": "1 m",
        "E_theta": "5 GPa",
        "radial_modulus": {"law": "pfeiffer", "K1": "10 kPa", "K2": 100},
    },
    "core": {"outer_radius": "7.6 cm", "rigid": True},
    "winding": {"outer_radius": R, "tension": "1.5 MPa"},
}


def best(fn: Callable[[], Any], repeat: int) -> tuple[Any, float]:
    out, t = None, float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        t = min(t, time.perf_counter() - t0)
    return out, t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--write-docs", action="store_true", help="rewrite docs/winding.md's block")
    args = ap.parse_args()
    load0 = os.getloadavg()[0]
    from woundroll.case import Case
    from woundroll.pipeline import run

    wind(WEB, CORE, 0.08, SCHED)  # warm-up: compiled kernels loaded
    _, t_yard = wind_per_layer(N)
    w, t_wind = best(lambda: wind(WEB, CORE, R, SCHED), args.repeat)
    rows = [("yardstick wind_per_layer (10k layers)", t_yard), ("wind, no air", t_wind)]
    y: dict[str, float] = {}  # the times the docs quote, as multiples of the yardstick
    for label, sched, air in (
        # the yardstick's 18 N/m is too slack to wind at speed without a nip (the roll
        # floats on air): 8 MPa (96 N/m) for this one
        (
            "wind_with_air 3 m/s, no nip, 8 MPa",
            replace(SCHED, web_stress=8e6),
            AirSettings(speed=3.0),
        ),  # noqa: E501
        (
            "wind_with_air 10 m/s, 500 N/m nip",
            replace(SCHED, nip_load=500.0),
            AirSettings(speed=10.0, roughness=0.05e-6),
        ),
    ):
        w0 = wind(WEB, CORE, R, sched)
        res, t = best(
            lambda s=sched, a=air, w0=w0: wind_with_air(WEB, CORE, R, s, a, no_air=w0), args.repeat
        )  # noqa: E501
        _, t_full = best(lambda s=sched, a=air: wind_with_air(WEB, CORE, R, s, a), args.repeat)
        rows.append((f"{label} (given the roll without air)", t))
        rows.append((f"{label} (winding both rolls)", t_full))
        y[f"{air.speed:g}"], y[f"{air.speed:g} full"] = t / t_yard, t_full / t_yard
        print(f"# {label}: {res.summary()}")
    for label, speed in (("run, no speed key", None), ("run, speed 0", 0.0), ("run, 5 m/s", 5.0)):
        data = {**CASE, "winding": {**CASE["winding"]}}
        if speed is not None:
            data["winding"]["speed"] = speed
        case = Case.model_validate(data)
        _, t = best(lambda c=case: run(c), args.repeat)
        rows.append((label, t))
        y[label] = t / t_yard
    print(f"{'what':58s} {'wall [s]':>9s} {'/ yardstick':>12s}")
    for label, t in rows:
        print(f"{label:58s} {t:9.3f} {t / t_yard:12.3f}")
    load1 = os.getloadavg()[0]
    if args.write_docs:
        ratios = (
            f"`wind_with_air` given the roll without air {y['3']:.3f} (3 m/s, no nip, 8 MPa) "
            f"and {y['10']:.3f} (10 m/s, 500 N/m nip) ({y['3 full']:.3f} and "
            f"{y['10 full']:.3f} winding both rolls); a whole `run` at 5 m/s "
            f"{y['run, 5 m/s']:.3f} against {y['run, no speed key']:.3f} without air, and "
            f"with `speed = 0` {y['run, speed 0']:.3f}."
        )
        write_block(
            PAGE,
            "air",
            [
                f"`benchmarks/bench_air.py`, {datetime.date.today().isoformat()}, best of "
                f"{args.repeat}, {load_note(load0, load1)}; the yardstick's {N:,}-layer roll, "
                f"times as multiples of the yardstick ({t_yard:.2f} s in the same run): {ratios}"
            ],
        )


if __name__ == "__main__":
    main()
