"""Benchmark of the fast path's CMD-spreading correction
(woundroll.contact.plane_strain.cmd_spread); not a test.

Prints, in one run (so that both see the same machine load):

1. in-process: one 2D contact solve (PET2 53.4 N, Rho-meter head, 1.34 mm: the pipeline's
   last solve on that roll) and the correction applied to it (best of 20);
2. ``roll_stiffness`` with ``model="2d"`` (plane strain) and ``model="auto"`` (plane strain
   + CMD spreading) on the same roll, best of 3 each, interleaved (the depth search and the
   fit included);
3. with ``--whole``: the whole process ``woundroll run pet2-53.4N --json`` with
   ``contact.model`` '2d' and 'auto', min of 3, interleaved.

Run: ``.venv/bin/python benchmarks/bench_cmd_spread.py [--whole]``.
"""

from __future__ import annotations

import os
import sys

os.environ["OPENBLAS_NUM_THREADS"] = os.environ["OMP_NUM_THREADS"] = "1"

import subprocess  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402


def main() -> None:
    from woundroll.case import load_case
    from woundroll.contact import indent, roll_stiffness
    from woundroll.contact.plane_strain.cmd_spread import apply_cmd_spread
    from woundroll.pipeline import run

    case = load_case("pet2-53.4N", ["contact.model='2d'", "contact.no_update=false"])
    res = run(case)
    web, core = case.web.build(), case.core.build()
    ins = case.tester_setup.instrument
    r, s = res.winding.radius, res.winding.sigma_r
    t0 = time.perf_counter()
    c = indent(
        web, core, r, s, head_radius=ins.head_radius, head_length=ins.head_length, depth_max=1.34e-3
    )
    t_solve = time.perf_counter() - t0
    best = float("inf")
    for _ in range(20):
        t0 = time.perf_counter()
        apply_cmd_spread(c)
        best = min(best, time.perf_counter() - t0)
    print(f"2D solve (PET2 53.4 N, 1.34 mm, {c.n_dof} DOF): {t_solve:.3f} s")
    print(f"CMD-spreading correction: {best * 1e3:.2f} ms ({best / t_solve:.2%} of the solve)")

    times: dict[str, float] = {"2d": float("inf"), "auto": float("inf")}
    for _ in range(3):
        for model in times:
            t0 = time.perf_counter()
            st = roll_stiffness(web, core, r, s, ins, model=model)
            times[model] = min(times[model], time.perf_counter() - t0)
            print(f"  roll_stiffness model={model}: {time.perf_counter() - t0:.3f} s, "
                  f"alpha {st.alpha:.3g}, impact depth {st.impact_depth * 1e3:.3f} mm")  # fmt: skip
    print(f"roll_stiffness best of 3: 2d {times['2d']:.3f} s, auto {times['auto']:.3f} s "
          f"(ratio {times['auto'] / times['2d']:.2f})")  # fmt: skip

    if "--whole" in sys.argv:
        exe = Path(sys.executable).with_name("woundroll")
        whole: dict[str, float] = {"2d": float("inf"), "auto": float("inf")}
        for _ in range(3):
            for model in whole:
                t0 = time.perf_counter()
                subprocess.run(
                    [str(exe), "run", "pet2-53.4N", "--json", "--set", f"contact.model='{model}'"],
                    check=True,
                    capture_output=True,
                )
                whole[model] = min(whole[model], time.perf_counter() - t0)
        print(f"whole process, min of 3: 2d {whole['2d']:.2f} s, auto {whole['auto']:.2f} s")
    print(f"load average: {os.getloadavg()[0]:.1f} (2 cores)")


if __name__ == "__main__":
    main()
