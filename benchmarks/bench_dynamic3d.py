"""Benchmark of the 3D dynamic FE impact (woundroll.contact.dynamic.solid3d); not a test.

PET1 wound at 26.7 N (Hakiel profile), the Rho-meter, the 3D model's default mesh for the
depth the quasi-static 3D solve reaches. Prints, in one run:

1. the quasi-static 3D contact solve (``roll_stiffness(model="3d")``, what the 1.5D models
   use; it also gives the FD contact time and the depth that size the dynamic run);
2. one 3D dynamic impact at the default settings (400 steps per contact, modified Newton:
   factorisations reused over steps) with CPU time of the process (all threads: MKL's
   PARDISO runs threaded) and wall time, the load average, and where the time goes
   (assembly, numeric factorisations, solves, the rest: contact, stresses, Python);
3. with ``--compare``: the same impact factorising every step (``reuse=False``), for the
   ratio and the agreement of Rho;
4. the yardstick of issue 23 (the straightforward 10k-layer winding,
   :func:`yardstick.wind_per_layer`), run in the same process before the 3D runs, and the
   3D dynamic impact's CPU and wall time as multiples of it (the bar: 15x), also with its
   quasi-static 3D solve (what ``woundroll run CASE --set contact.model=3d --set
   contact.dynamic=true`` pays).

BLAS threads are pinned to one (the per-ring GEMMs of the assembly, docs/contact.md).
``--write-docs`` puts section 4's table into docs/performance.md (``<!-- bench: dynamic3d
-->``; ``make bench`` does). Run: ``.venv/bin/python benchmarks/bench_dynamic3d.py
[--compare] [--coarse] [--write-docs]``.
"""

from __future__ import annotations

import os
import sys

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")  # PARDISO: threads only contend on a loaded machine

import platform  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402


def main() -> None:
    from dataclasses import replace

    from woundroll.case import load_case
    from woundroll.contact import roll_stiffness
    from woundroll.contact.dynamic.solid3d import Dynamic3DOptions, impact_dynamic3d
    from woundroll.contact.solid3d.solver import Contact3DOptions
    from woundroll.pipeline import hardness_on_roll
    from woundroll.winding.hakiel import WindingOptions, wind

    compare = "--compare" in sys.argv
    mesh = Contact3DOptions()
    if "--coarse" in sys.argv:
        mesh = replace(mesh, n_fine=5, radial_growth=1.6, tangential_growth=1.6, axial_growth=1.6)
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    load0 = os.getloadavg()[0]
    print(f"load average {load0:.1f} on {os.cpu_count()} cores")
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
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from yardstick import wind_per_layer

    wind_per_layer()  # warm-up
    yc, yt = time.process_time(), time.perf_counter()
    wind_per_layer()
    yard_cpu, yard = time.process_time() - yc, time.perf_counter() - yt

    c0, t0 = time.process_time(), time.perf_counter()
    st = roll_stiffness(web, core, w.radius, w.sigma_r, inst, model="3d", options3d=mesh)
    cpu_qs, wall_qs = time.process_time() - c0, time.perf_counter() - t0
    h = hardness_on_roll(setup, st, r_out - core.outer_radius, web.density)
    print("\n1. quasi-static 3D contact solve")
    print(
        f"  {cpu_qs:.1f} CPU s, {wall_qs:.1f} s wall; {st.contact.n_dof} DOF, depth "
        f"{st.contact.delta[-1] * 1e3:.2f} mm; FD {h.fd.rho:.2f} Rho, contact "
        f"{h.fd.contact_time * 1e3:.3f} ms, impulse {h.fd.impulse:.4f} N s"
    )

    def dyn(**kw: object) -> tuple[object, float, float]:
        c, t = time.process_time(), time.perf_counter()
        d = impact_dynamic3d(
            web,
            core,
            w.radius,
            w.sigma_r,
            inst,
            contact_time=h.fd.contact_time,
            depth_scale=float(st.contact.delta[-1]),
            options=Dynamic3DOptions(mesh=mesh, **kw),
        )
        return d, time.process_time() - c, time.perf_counter() - t

    def show(title: str, d: object, cpu: float, wall: float) -> None:
        s = d.stats  # type: ignore[attr-defined]
        print(f"\n{title} (load average now {os.getloadavg()[0]:.1f})")
        print(
            f"  {cpu:.1f} CPU s, {wall:.1f} s wall; {d.n_steps} steps, {d.n_dof} DOF; "  # type: ignore[attr-defined]
            f"Rho {d.rho:.3f}, impulse {d.impulse:.4f} N s, contact "  # type: ignore[attr-defined]
            f"{d.contact_time * 1e3:.3f} ms, e {d.restitution:.3f}"  # type: ignore[attr-defined]
        )
        rest = wall - s["assembly_s"] - s["factor_s"] - s["solve_s"]
        print(
            f"  {s['factorisations']} factorisations ({s['factor_s']:.1f} s wall), "
            f"{s['rhs_solved']} right-hand sides ({s['solve_s']:.1f} s), assembly "
            f"{s['assembly_s']:.1f} s, rest {rest:.1f} s; {s['passes']} modified-Newton passes "
            f"(max {s['max_passes_per_step']} in a step), {s['column_refreshes']} column "
            "refreshes"
        )

    d, cpu, wall = dyn()
    show("2. one 3D dynamic impact, modified Newton (default)", d, cpu, wall)
    print(
        f"\n4. against the yardstick (10k-layer winding, {yard:.2f} s wall, {yard_cpu:.2f} s "
        f"CPU, same process): the dynamic impact {cpu / yard_cpu:.1f}x CPU, {wall / yard:.1f}x "
        f"wall; with its quasi-static 3D solve {(cpu + cpu_qs) / yard_cpu:.1f}x CPU, "
        f"{(wall + wall_qs) / yard:.1f}x wall (bar 15x)"
    )
    if "--write-docs" in sys.argv:
        from pathlib import Path

        from docs_block import load_note, write_block

        bar = "15x ok" if cpu / yard_cpu <= 15 else "15x **over**"
        lines = [
            "`benchmarks/bench_dynamic3d.py"
            + (" --coarse" if "--coarse" in sys.argv else "")
            + f"`: PET1 26.7 N, the Rho-meter, {'coarse' if '--coarse' in sys.argv else 'default'}"
            f" 3D mesh, one BLAS thread; python {platform.python_version()}, "
            f"{load_note(load0)}. The yardstick (the 10k-layer winding, "
            f"benchmarks/yardstick.py) took {yard:.2f} s wall, {yard_cpu:.2f} s CPU in the same "
            "process; times as multiples of it.",
            "",
            "| run | DOF | steps | CPU x yardstick | wall x yardstick | Rho | bar |",
            "|---|---|---|---|---|---|---|",
            f"| quasi-static 3D solve (the 1.5D models' spring) | {st.contact.n_dof} | "
            f"{st.contact.delta.size - 1} | {cpu_qs / yard_cpu:.1f}x | {wall_qs / yard:.1f}x | "
            f"{h.fd.rho:.2f} (FD) | |",
            f"| 3D dynamic impact | {d.n_dof} | {d.n_steps} | {cpu / yard_cpu:.1f}x | "  # type: ignore[attr-defined]
            f"{wall / yard:.1f}x | {d.rho:.2f} | {bar} |",  # type: ignore[attr-defined]
            f'| both (`contact.model = "3d"`, `contact.dynamic = true`) | | | '
            f"{(cpu + cpu_qs) / yard_cpu:.1f}x | {(wall + wall_qs) / yard:.1f}x | | |",
        ]
        write_block(
            Path(__file__).resolve().parent.parent / "docs" / "performance.md", "dynamic3d", lines
        )
    if compare:
        d2, cpu2, wall2 = dyn(reuse=False)
        show("3. the same, one factorisation per step", d2, cpu2, wall2)
        print(
            f"  CPU ratio {cpu2 / cpu:.2f}, wall ratio {wall2 / wall:.2f}; Rho differs by "
            f"{abs(d2.rho / d.rho - 1):.1e}"  # type: ignore[attr-defined]
        )


if __name__ == "__main__":
    main()
