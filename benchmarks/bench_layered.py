"""Benchmark of the layered roll (woundroll.contact.layered, issue 25 item 6); not a test.

Prints, in one run (so that all see the same machine load):

1. the yardstick (benchmarks/yardstick.py): the 10,000-layer per-layer banded winding;
2. per roll, the whole pipeline ``run`` with ``contact.model = "layered"`` (mu 0.3, the
   Rho-meter, the default zone of 1 a_geo, one sheet per shell) -- the winding, the one
   layered F(d) curve the striker needs (loaded to where the striker stops) and the
   reading: wall time, its ratio to the yardstick, the layered contact solve alone, the
   mesh (DOF, element rings x columns), factorisations and low-rank updates, Rho (FD).

Rolls: PET1 26.7 N and PET2 53.4 N (Table 2, pile 8.89 cm) and PET2 53.4 N at a 2 cm pile
(the pile-height pair of docs/studies.md). BLAS threads pinned to one, as the solver does
itself (threadpoolctl) and the other benchmarks do.

``--woodbury N`` sets the largest set change taken by a low-rank update
(``solver.WOODBURY_MAX``; 0: refactorise at every change, the algorithm before the update)
to compare; ``--quick``: PET1 only.

``--3d``: the same rolls with ``contact.model = "layered-3d"`` on the default 3D mesh (its
default shells, ``LAYERS_PER_SHELL_3D`` sheets): wall and CPU time of the whole run, the
ratio to the yardstick, the layered solve alone, the interface pairs, shells, ADMM passes,
factorisations, the process's peak resident memory so far (issue 25 item 6: one F(d) curve
in <= 10 min and <= 8 GB), Rho (FD). Minutes a roll.

Run: ``.venv/bin/python benchmarks/bench_layered.py [--woodbury N] [--quick] [--3d]``.
"""

from __future__ import annotations

import os
import sys

os.environ["OPENBLAS_NUM_THREADS"] = os.environ["OMP_NUM_THREADS"] = "1"

import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

from yardstick import wind_per_layer  # noqa: E402

#: (label, case, overrides): the PET cases' core outer radius is 4.45 cm
ROLLS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("PET1 26.7 N", "pet1-26.7N", ()),
    ("PET2 53.4 N", "pet2-53.4N", ()),
    ("PET2 53.4 N, H 2 cm", "pet2-53.4N", ("winding.outer_radius=0.0645 m",)),
)


def main3d(rolls: tuple[tuple[str, str, tuple[str, ...]], ...]) -> None:
    """The ``--3d`` table (module docstring)."""
    import resource

    from woundroll.case import load_case
    from woundroll.pipeline import run

    _, t_yard = wind_per_layer()
    print(f"yardstick: 10,000-layer per-layer banded winding {t_yard:.2f} s wall")
    print(
        f"{'roll':<22} {'run s':>7} {'cpu s':>7} {'/yard':>6} {'solve s':>8} {'pairs':>7} "
        f"{'shells':>6} {'lps':>4} {'passes':>6} {'fact':>5} {'peak GB':>7} {'Rho FD':>7}"
    )
    for label, name, extra in rolls:
        case = load_case(name, ["contact.model=layered-3d", "contact.friction=0.3", *extra])
        t0, c0 = time.perf_counter(), time.process_time()
        res = run(case)
        t, cpu = time.perf_counter() - t0, time.process_time() - c0
        c = res.contact.contact
        st = c.stats
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6  # kB -> GB
        print(
            f"{label:<22} {t:7.1f} {cpu:7.1f} {t / t_yard:6.1f} {c.solve_time_s:8.1f} "
            f"{st['interface_pairs']:7d} {st['layered_shells']:6d} {st['layers_per_shell']:4d} "
            f"{st['interface_passes']:6d} {st.get('factorisations', -1):5d} {peak:7.2f} "
            f"{res.hardness.to_dict()['rho_fd']:7.2f}",
            flush=True,
        )
    _, t_yard2 = wind_per_layer()
    print(f"yardstick again: {t_yard2:.2f} s wall (machine load drift)")


def main() -> None:
    import woundroll.contact.layered.solver as layered
    from woundroll.case import load_case
    from woundroll.pipeline import run

    if "--woodbury" in sys.argv:
        layered.WOODBURY_MAX = int(sys.argv[sys.argv.index("--woodbury") + 1])
    rolls = ROLLS[:1] if "--quick" in sys.argv else ROLLS
    if "--3d" in sys.argv:
        main3d(rolls)
        return
    updates = [0]
    init = layered._Woodbury.__init__

    def counted(self, *args, **kw):  # count the low-rank updates
        updates[0] += 1
        init(self, *args, **kw)

    layered._Woodbury.__init__ = counted
    _, t_yard = wind_per_layer()
    print(f"yardstick: 10,000-layer per-layer banded winding {t_yard:.2f} s wall")
    print(f"low-rank updates up to {layered.WOODBURY_MAX} pairs (solver.WOODBURY_MAX)")
    print(
        f"{'roll':<22} {'run s':>7} {'/yard':>6} {'contact s':>9} {'DOF':>7} {'mesh':>9} "
        f"{'fact':>5} {'upd':>5} {'Rho FD':>7}"
    )
    for label, name, extra in rolls:
        case = load_case(name, ["contact.model=layered", "contact.friction=0.3", *extra])
        updates[0] = 0
        t0 = time.perf_counter()
        res = run(case)
        t = time.perf_counter() - t0
        c = res.contact.contact
        h = res.hardness.to_dict()
        print(
            f"{label:<22} {t:7.1f} {t / t_yard:6.1f} {c.solve_time_s:9.1f} {c.n_dof:7d} "
            f"{c.mesh_shape[0]:>4}x{c.mesh_shape[1]:<4} {c.factorisations:5d} "
            f"{updates[0]:5d} {h['rho_fd']:7.2f}"
        )
    _, t_yard2 = wind_per_layer()
    print(f"yardstick again: {t_yard2:.2f} s wall (machine load drift)")


if __name__ == "__main__":
    main()
