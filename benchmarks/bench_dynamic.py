"""Benchmark of the dynamic FE impact (woundroll.contact.dynamic.plane_strain.impact_dynamic); not
a test.

BLAS threads are pinned to one, as in bench_contact.py (banded Cholesky at bandwidth ~55).

Prints, on PET1 wound at 26.7 N (Hakiel profile) with the Rho-meter (default mesh, 5306 DOF):
1. one 2D dynamic impact at the default settings (400 steps per contact, lumped mass,
   Newmark gamma = 0.6, extrapolated modulus) and its time per step, against the
   quasi-static contact solve of the same roll (``roll_stiffness``, what the 1.5D models
   use) and the FD impact, in the same run;
2. where the time goes (cProfile, functions by own time), grouped: banded assembly,
   banded Cholesky, the contact flexibility (multi right-hand-side solve), the
   complementarity solve, the stress update;
3. the time against the step count (200, 400, 800) and with the consistent mass.

Run: ``.venv/bin/python benchmarks/bench_dynamic.py [--quick]``.
"""

from __future__ import annotations

import os
import sys

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import cProfile  # noqa: E402
import platform  # noqa: E402
import pstats  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402


def main() -> None:
    from woundroll.case import load_case
    from woundroll.contact import roll_stiffness
    from woundroll.contact.dynamic.plane_strain import DynamicOptions, impact_dynamic
    from woundroll.pipeline import hardness_on_roll
    from woundroll.winding.hakiel import WindingOptions, wind

    quick = "--quick" in sys.argv
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    case = load_case("pet1-26.7N")
    web, core = case.web.build(), case.core.build()
    r_out = case.winding.final_radius(web, core)
    w = wind(
        web,
        core,
        r_out,
        case.winding.schedule(web),
        options=WindingOptions.from_dict(case.winding.options, "winding.options"),
    )
    setup = case.tester_setup
    inst = setup.instrument

    t0 = time.perf_counter()
    st = roll_stiffness(web, core, w.radius, w.sigma_r, inst)
    t_qs = time.perf_counter() - t0
    t0 = time.perf_counter()
    h = hardness_on_roll(setup, st, r_out - core.outer_radius, web.density)
    t_fd = time.perf_counter() - t0

    def dyn(**kw: object) -> object:
        return impact_dynamic(
            web,
            core,
            w.radius,
            w.sigma_r,
            inst,
            contact_time=h.fd.contact_time,
            depth_scale=float(st.contact.delta[-1]),
            options=DynamicOptions(**kw),
        )

    t0 = time.perf_counter()
    d = dyn()
    t_dyn = time.perf_counter() - t0
    print("\n1. one impact (same run)")
    print(
        f"  dynamic FE impact: {t_dyn:.2f} s, {d.n_steps} steps, {d.n_dof} DOF, "
        f"{1e3 * t_dyn / d.n_steps:.1f} ms/step; Rho {d.rho:.2f}"
    )
    print(
        f"  quasi-static contact solve (roll_stiffness): {t_qs:.2f} s "
        f"(dynamic / quasi-static = {t_dyn / t_qs:.1f})"
    )
    print(f"  FD + energy impact models: {1e3 * t_fd:.1f} ms; Rho FD {h.fd.rho:.2f}")

    print("\n2. profile of one dynamic impact (cumulative time of the named steps)")
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    dyn()
    prof.disable()
    total = time.perf_counter() - t0
    stats = pstats.Stats(prof)
    steps = {
        "cholesky_banded": "banded Cholesky of K_eff (one per step)",
        "cho_solve_banded": "banded solve of the free step",
        "values_lower": "assembly: element values",
        "banded": "assembly: scatter into band storage",
        "lcp": "complementarity (NNLS on chol(W))",
        "stress_increment": "stress update",
        "moduli": "moduli (E_r law, plane-strain reduction)",
    }
    cum: dict[str, float] = dict.fromkeys(steps, 0.0)
    for (_, _, fn), v in stats.stats.items():
        for key in cum:
            if fn == key:
                cum[key] += v[3]
    for fn, label in steps.items():
        print(f"  {label}: {cum[fn]:.2f} s ({100 * cum[fn] / total:.0f} %)")
    rest = total - sum(cum.values())
    print(
        f"  rest: {rest:.2f} s ({100 * rest / total:.0f} %): the triangular solves of the "
        "contact flexibility (LAPACK dtbtrs, which cProfile does not see) and Python glue"
    )
    print(f"  total (profiled): {total:.2f} s")

    if not quick:
        print("\n3. time against the step count, and the consistent mass")
        for kw in (
            {"steps_per_contact": 200},
            {"steps_per_contact": 800},
            {"mass": "consistent"},
        ):
            t0 = time.perf_counter()
            dd = dyn(**kw)
            t = time.perf_counter() - t0
            print(f"  {kw}: {t:.2f} s, {dd.n_steps} steps, Rho {dd.rho:.2f}")


if __name__ == "__main__":
    main()
