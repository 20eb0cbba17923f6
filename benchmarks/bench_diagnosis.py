"""Benchmark of the inverse (woundroll.inverse.diagnosis.diagnose); not a test.

The straightforward inverse root-finds the tension of every reading position on full forward
runs (Brent in ln T0, bracket 1/4 ... 4 x the case's tension, xtol 1e-3): its cost grows with
the number of positions. woundroll tabulates the reading over tension once per case (6-8 full
runs, bracketed and refined around the readings) and inverts the monotone interpolant.

Prints, for PET1 wound at 26.7 N (``pet1-26.7N``, Rho-meter) and readings at ``n`` positions
spread over 45-60 Rho, the wall time and full forward runs of both, their ratio, and the
largest difference of the tensions they find (relative), the times also as multiples of the
yardstick (the 10k-layer winding, benchmarks/yardstick.py) run in the same process. With
``--write-docs`` (``make bench``) the paragraph in docs/diagnosis.md (``<!-- bench:
diagnosis -->``). Run: ``.venv/bin/python benchmarks/bench_diagnosis.py [--positions N]
[--write-docs]``.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np


def main() -> None:
    import os

    from scipy.optimize import brentq

    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel, diagnose
    from woundroll.io.readings import readings_from_arrays

    load0 = os.getloadavg()[0]
    n = int(sys.argv[sys.argv.index("--positions") + 1]) if "--positions" in sys.argv else 6
    case = load_case("pet1-26.7N")
    model = RollModel.from_case(case)
    model.evaluate(model.tension)  # warm-up (JIT, caches)
    values = np.linspace(45.0, 60.0, n)
    x = np.linspace(0.01, 0.14, n)
    r = readings_from_arrays(x, values, width=case.web.width)

    t0 = time.perf_counter()
    d = diagnose(case, r, verify=False)
    t_tab = time.perf_counter() - t0
    runs_tab = len(d.curve.points)

    runs = 0

    def reading(lt: float) -> float:
        nonlocal runs
        runs += 1
        return model.evaluate(math.exp(lt)).reading

    t0 = time.perf_counter()
    t_direct = []
    lo, hi = math.log(model.tension / 4), math.log(model.tension * 4)
    for v in values:
        t_direct.append(math.exp(brentq(lambda lt, v=v: reading(lt) - v, lo, hi, xtol=1e-3)))
    t_dir = time.perf_counter() - t0
    diff = np.max(np.abs(d.web_tension / np.array(t_direct) - 1.0))
    print(f"positions: {n}")
    print(f"tabulated + interpolated: {t_tab:7.1f} s, {runs_tab} full forward runs")
    print(f"root-finding on full runs: {t_dir:7.1f} s, {runs} full forward runs")
    print(f"ratio (straightforward / tabulated): {t_dir / t_tab:.1f}x")
    print(f"largest relative difference of the tensions: {diff:.2e}")
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from docs_block import load_note, write_block
    from yardstick import wind_per_layer

    _, yard = wind_per_layer()
    print(f"yardstick {yard:.2f} s: tabulated {t_tab / yard:.1f}x, direct {t_dir / yard:.1f}x")
    if "--write-docs" not in sys.argv:
        return
    line = (
        f"`benchmarks/bench_diagnosis.py` (PET1 26.7 N, {n} positions over 45-60 Rho; "
        f"{load_note(load0)}): the tabulated inverse used {runs_tab} full forward runs "
        f"({t_tab / yard:.1f} yardsticks: the 10k-layer winding of benchmarks/yardstick.py, "
        f"{yard:.2f} s in the same run), root-finding each position on full runs (Brent, "
        f"xtol 1e-3 in ln T0) {runs} runs ({t_dir / yard:.1f} yardsticks): "
        f"{runs / runs_tab:.1f}x fewer runs, {t_dir / t_tab:.1f}x in wall time. The count of "
        "runs grows with the positions for the straightforward inverse and stays at 6-8 for "
        f"the tabulated one. The tensions agree within {100 * diff:.2g} %."
    )
    write_block(Path(__file__).resolve().parents[1] / "docs" / "diagnosis.md", "diagnosis", [line])


if __name__ == "__main__":
    main()
