"""Benchmark of the 3D contact model (woundroll.contact.solid3d.solver).

1. The linear solvers on the stiffness of the default mesh (PET2 26.7 N, Rho-meter head,
   2.1 mm): numeric factorisation + one solve + 50 right-hand sides, for MKL PARDISO
   (symbolic analysis reused), SciPy SuperLU and AMG-preconditioned CG (pyamg), in the
   same run. CHOLMOD (scikit-sparse) is not measured: it does not install from PyPI
   without the SuiteSparse headers.
2. One whole F(d) curve with the E_r update at the default mesh, with its work counters,
   and the peak memory of the process.

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_contact3d.py [--case pet2-26.7N]``
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: see docs/contact.md

import resource  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402


def real_roll(name: str) -> tuple:
    from woundroll.case import load_case
    from woundroll.winding.hakiel import wind

    case = load_case(name)
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    return web, core, np.asarray(w.radius), np.asarray(w.sigma_r)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default="pet2-26.7N")
    ap.add_argument("--depth", type=float, default=2.1e-3)
    ap.add_argument("--skip-solvers", action="store_true")
    ap.add_argument("--skip-curve", action="store_true")
    ap.add_argument(
        "--solver-n-fine",
        type=int,
        default=10,
        help="n_fine of the mesh the solvers are compared on (10: the default mesh)",
    )
    args = ap.parse_args()

    from woundroll.contact.heads import Head
    from woundroll.contact.solid3d.linsolve import make_solver
    from woundroll.contact.solid3d.solver import build_roll3d, indent3d
    from woundroll.instruments import get_instrument

    web, core, radius, sigma_r = real_roll(args.case)
    head = Head.from_instrument(get_instrument("rho-meter"))
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")

    if not args.skip_solvers:
        from woundroll.contact.solid3d.solver import Contact3DOptions

        opts = Contact3DOptions(n_fine=args.solver_n_fine)
        model = build_roll3d(
            web, core, radius, sigma_r, head=head, depth_max=args.depth, options=opts
        )
        D = model.moduli(model.sigma_pre)
        U = model.asm.upper(D)
        print(
            f"mesh (n_fine {args.solver_n_fine}): {model.mesh.shape} nodes, "
            f"{U.shape[0]} DOF, nnz(K upper) {U.nnz}"
        )
        rhs = np.random.default_rng(0).standard_normal((U.shape[0], 50))
        for name in ("pardiso", "splu", "amg"):
            s = make_solver(name, U)
            clock = time.process_time  # CPU seconds (all threads): less load-dependent
            w0, t0 = time.perf_counter(), clock()
            s.factor(U.data)
            t1 = clock()
            s.factor(U.data * 1.01)  # a second numeric factorisation (symbolic reused)
            t2 = clock()
            s.solve(rhs[:, 0])
            t3 = clock()
            if name != "amg":
                s.solve(rhs)
            t4 = clock()
            extra = f", CG iterations {s.iterations}" if name == "amg" else ""
            print(
                f"{name:8s} CPU s: first factor {t1 - t0:6.2f}, refactor {t2 - t1:6.2f}, "
                f"1 rhs {t3 - t2:6.3f}, 50 rhs {t4 - t3:6.2f}{extra} "
                f"(wall {time.perf_counter() - w0:.1f} s)"
            )

    if args.skip_curve:
        return
    t0, c0 = time.perf_counter(), time.process_time()
    res = indent3d(web, core, radius, sigma_r, head=head, depth_max=args.depth)
    dt, cpu = time.perf_counter() - t0, time.process_time() - c0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    print(
        f"F(d) with the E_r update, default mesh {res.mesh_shape} ({res.n_dof} DOF), "
        f"{res.delta.size - 1} steps: wall {dt:.1f} s, CPU {cpu:.1f} s, "
        f"peak RSS {rss:.2f} GB, F = {res.force[-1]:.2f} N"
    )
    print({k: round(v, 2) if isinstance(v, float) else v for k, v in res.stats.items()})


if __name__ == "__main__":
    main()
