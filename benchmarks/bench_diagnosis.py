"""Benchmark of the inverse (woundroll.inverse.diagnosis.diagnose); not a test.

The straightforward inverse root-finds the tension of every reading position on full forward
runs (Brent in ln T0, bracket 1/4 ... 4 x the case's tension, xtol 1e-3): its cost grows with
the number of positions. woundroll tabulates the reading over tension once per case (6-8 full
runs, bracketed and refined around the readings) and inverts the monotone interpolant.

Prints, for PET1 wound at 26.7 N (``pet1-26.7N``, Rho-meter) and readings at ``n`` positions
spread over 45-60 Rho, the wall time and full forward runs of both, their ratio, and the
largest difference of the tensions they find (relative). Run:
``.venv/bin/python benchmarks/bench_diagnosis.py [--positions N]``.
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np


def main() -> None:
    from scipy.optimize import brentq

    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel, diagnose
    from woundroll.io.readings import readings_from_arrays

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


if __name__ == "__main__":
    main()
