"""Benchmark of the 1.5D impact models (a script, not a test).

Run: ``python benchmarks/bench_impact.py``.

1. One finite-difference impact ({4}-{13}) at the default resolution, for the quadratic roll
   spring {3} and for the tabulated Hertz curve of the calibration block.
2. The energy model ({19}-{22}) over 1e6 (alpha, beta) pairs, vectorised in cache-sized
   chunks (``rho_energy``), against the straightforward whole-array form of the same Newton
   iteration (``_energy_max_depth_whole_array``, fresh 1e6-element temporaries each
   operation; same run) and a plain per-element scalar root finder (scipy.optimize.brentq
   on {19} in a Python loop) timed on a sample and extrapolated to the same size. The
   answers are compared. Issue 14's bar: >= 1e7 evaluations per second on one core.
"""

from __future__ import annotations

import platform
import time

import numpy as np
from scipy.optimize import brentq

from woundroll.instruments import get_instrument, impact_fd, rho_energy
from woundroll.instruments.calibration import CalibrationBlock, HertzLineContact
from woundroll.instruments.impact import _CHUNK, _energy_max_depth_whole_array


def best_of(fn, repeat: int) -> float:
    """Smallest wall time of ``repeat`` calls [s]."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    rm = get_instrument("rho-meter")
    k, xi, xg, m = rm.spring_stiffness, rm.release_position, rm.contact_position, rm.mass
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")

    # 1. single FD impacts
    quad_spring = (3.7e8, 5.4e5)
    res = impact_fd(rm, quad_spring)
    n_steps = round(res.contact_time / res.time_step)
    t = best_of(lambda: impact_fd(rm, quad_spring), 20)
    print(
        f"FD impact, quadratic spring: {n_steps} steps in contact, {t * 1e3:.2f} ms "
        f"(Rho {res.rho:.2f})"
    )
    block = CalibrationBlock.from_preset("rho-meter")
    law = HertzLineContact(rm.head_radius, rm.head_length, block).law(0.5 * k * xi * xi)
    res_h = impact_fd(rm, law)
    t_table = best_of(
        lambda: HertzLineContact(rm.head_radius, rm.head_length, block).law(0.5 * k * xi * xi), 5
    )
    t_h = best_of(lambda: impact_fd(rm, law), 20)
    print(
        f"FD impact, Hertz block curve ({law.depth.size} points): "
        f"{t_h * 1e3:.2f} ms (+ {t_table * 1e3:.2f} ms to tabulate), Rho {res_h.rho:.2f}"
    )

    # 2. energy model, 1e6 pairs
    n = 1_000_000
    rng = np.random.default_rng(0)
    alpha = 10 ** rng.uniform(6, 11, n)
    beta = 10 ** rng.uniform(3, 7, n)
    rho_energy(alpha[:10], beta[:10], rm)  # warm-up
    t_vec = best_of(lambda: rho_energy(alpha, beta, rm), 5)
    rho_vec = rho_energy(alpha, beta, rm)

    def whole() -> np.ndarray:
        d = _energy_max_depth_whole_array(alpha, beta, k, xi, xg)
        return (alpha * d + beta) * d / (rm.rho_unit * m)

    t_whole = best_of(whole, 5)
    err_whole = float(np.max(np.abs(whole() / rho_vec - 1)))

    n_loop = 5000

    def loop() -> np.ndarray:
        out = np.empty(n_loop)
        for i in range(n_loop):
            a, b = alpha[i], beta[i]
            d = brentq(
                lambda x, a=a, b=b: (
                    a * x**3 / 3 + (b + k) * x**2 / 2 + k * xg * x + k * (xg * xg - xi * xi) / 2
                ),
                0.0,
                xi,
                xtol=1e-16,
                rtol=1e-14,
            )
            out[i] = (a * d + b) * d / (rm.rho_unit * m)
        return out

    t_loop = best_of(loop, 1)
    rho_loop = loop()
    t_loop_full = t_loop * n / n_loop
    err = np.max(np.abs(rho_loop - rho_vec[:n_loop]) / rho_loop)
    print(
        f"energy model, {n:.0e} (alpha, beta) pairs, vectorised Newton in chunks of {_CHUNK}: "
        f"{t_vec * 1e3:.0f} ms ({n / t_vec:.3g} evaluations/s)"
    )
    print(
        f"whole-array form of the same iteration: {t_whole * 1e3:.0f} ms "
        f"({n / t_whole:.3g} evaluations/s): chunked is {t_whole / t_vec:.2f}x faster; "
        f"largest relative difference {err_whole:.1e}"
    )
    print(
        f"scalar brentq loop: {n_loop} pairs in {t_loop:.2f} s -> {t_loop_full:.1f} s "
        f"extrapolated to {n:.0e}"
    )
    print(f"speed-up {t_loop_full / t_vec:.0f}x; largest relative difference in Rho {err:.1e}")


if __name__ == "__main__":
    main()
