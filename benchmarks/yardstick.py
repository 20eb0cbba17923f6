"""The fixed yardsticks that woundroll's speed is measured against (issue 23).

Machines here differ up to 2.5x in speed from one to the next and from hour to hour, so a
benchmark reports its time as a ratio to a yardstick run in the same process, on the same
machine, at the same time:

* :func:`import_yardstick` -- a fresh ``python -c "import numpy, scipy.linalg"`` (the floor
  of any process that solves a banded system), for whole-process times;
* :func:`wind_per_layer` -- a straightforward 1D winding of 10,000 layers: Hakiel's equation
  by finite differences, one node per layer, and for every layer added one banded solve of
  the whole roll with ``scipy.linalg.solve_banded`` (E_r = K2 (K1 - sigma_r) from the stress
  before the layer; no iteration, no lazy deep part, no compiled code), for the models.

This code is the yardstick: it must not change (or every ratio measured before changes with
it). It is not woundroll's model and is not used by it; its answer is a plausibility check
only: the core pressure of the 10,000-layer roll, 65.97 kPa, is within 0.4 % of
woundroll's ``wind`` on the same roll (66.19 kPa; measured 2026-11-26).

Run: ``.venv/bin/python benchmarks/yardstick.py``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: the yardstick roll (that of benchmarks/bench_winding.py): 12 um film on a rigid core of
#: radius 7.6 cm, Pfeiffer E_r
THICKNESS = 12e-6
CORE_RADIUS = 0.076
E_THETA = 5e9
E_CORE = 1e15  # rigid
NU = 0.0
K1, K2 = 10e3, 100.0
WOUND_ON_STRESS = 1.5e6


def film() -> tuple[object, object, object]:
    """The yardstick's roll as woundroll's inputs, ``(Web, Core, TensionSchedule)``: one
    definition for the benchmarks that wind it with the library (bench_winding, bench_air,
    bench_limits). woundroll is imported here only, not by the yardstick's own solve."""
    from woundroll.materials import Core, Pfeiffer, Web
    from woundroll.winding.tension import TensionSchedule

    web = Web(thickness=THICKNESS, width=1.0, E_theta=E_THETA, radial_modulus=Pfeiffer(K1, K2))
    return web, Core(CORE_RADIUS), TensionSchedule(WOUND_ON_STRESS)


def import_yardstick(repeat: int = 5) -> float:
    """The smallest wall time [s] of ``repeat`` fresh ``import numpy, scipy.linalg``."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import numpy, scipy.linalg"], check=True)
        best = min(best, time.perf_counter() - t0)
    return best


def wind_per_layer(n_layers: int = 10_000) -> tuple[np.ndarray, float]:
    """sigma_r [Pa] at the layer interfaces (core outward) after winding ``n_layers``, and
    the wall time [s] of the winding."""
    from scipy.linalg import solve_banded

    t0 = time.perf_counter()
    h = THICKNESS
    r = CORE_RADIUS + h * np.arange(n_layers + 1)
    sigma = np.zeros(n_layers + 1)
    for n in range(1, n_layers + 1):
        rr = r[: n + 1]
        g = E_THETA / (K2 * (K1 - sigma[: n + 1]))  # E_theta / E_r before this layer
        ab = np.zeros((3, n + 1))
        # interior: r^2 s'' + 3 r s' - (g - 1) s = 0
        a = rr**2 / h**2
        b = 3 * rr / (2 * h)
        ab[0, 2:] = (a + b)[1:-1]  # super-diagonal: coefficient of s[i+1] at row i
        ab[1, 1:-1] = (-2 * a - (g - 1))[1:-1]
        ab[2, :-2] = (a - b)[1:-1]  # sub-diagonal: coefficient of s[i-1] at row i
        # core: r s' = (E_theta / E_core - 1 + nu) s, one-sided difference
        c = E_THETA / E_CORE - 1 + NU
        ab[1, 0] = -rr[0] / h - c
        ab[0, 1] = rr[0] / h
        # surface: the new layer's pressure
        ab[1, n] = 1.0
        ab[2, n - 1] = 0.0
        rhs = np.zeros(n + 1)
        rhs[n] = -WOUND_ON_STRESS * h / rr[n]
        sigma[: n + 1] += solve_banded((1, 1), ab, rhs)
    return sigma, time.perf_counter() - t0


def main() -> None:
    sigma, t = wind_per_layer()
    print(f"yardstick: 10,000-layer per-layer banded winding {t:.2f} s wall")
    print(f"  core pressure {-sigma[0] / 1e3:.1f} kPa (plausibility only)")
    print(f"yardstick: python -c 'import numpy, scipy.linalg' {import_yardstick():.3f} s wall")


if __name__ == "__main__":
    main()
