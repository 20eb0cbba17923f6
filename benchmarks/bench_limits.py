"""Benchmark: the 1D winding's time against ``limits.winding_estimate``, the estimate of the
``long run:`` warning a case gets before it runs (src/woundroll/limits.py).

Problem: the yardstick's roll (benchmarks/bench_winding.py: 12 um film on a 7.6 cm rigid
core, Pfeiffer K1 = 10 kPa, K2 = 100, E_theta = 5 GPa, 1.5 MPa), default options (2 elements
per layer), N layers. Two paths, as ``wind`` chooses them (winding/hakiel.py,
``_kernels_for``):

* the compiled kernels (numba's machine code loaded by llvmlite; a small roll is wound
  first so that their one-off load is not counted), N = 10,000 ... 1,000,000 (``--layers``);
* the NumPy twin (``winding/_kernels_numpy.py``), which winds the small rolls and any roll
  of up to ``hakiel._BUILD_MIN_NODES`` nodes on a machine where the compiled kernels are
  not built yet; forced here for N = 500 ... 2,000 (``--numpy-layers``) by raising
  ``hakiel._NUMPY_MAX_NODES`` for the run.

Every wall time is given as a multiple of the yardstick (benchmarks/yardstick.py, the
per-layer banded winding of 10,000 layers) timed in the same run, and so is the estimate:
``limits.winding_estimate`` in seconds of the development machine, divided by
``limits.YARDSTICK_SECONDS`` (that machine's yardstick when it is quiet). Their ratio is
the fit's error on this machine whatever its speed or load. ``--write-docs`` writes the
table into docs/case-files.md (``<!-- bench: winding-estimate -->``).

Run: ``.venv/bin/python benchmarks/bench_limits.py [--layers 10000 100000 1000000]
[--numpy-layers 500 2000] [--write-docs]``
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import datetime as dt  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from docs_block import load_note, write_block  # noqa: E402
from yardstick import film, wind_per_layer  # noqa: E402

from woundroll import limits  # noqa: E402
from woundroll.winding import hakiel  # noqa: E402
from woundroll.winding.hakiel import WindingOptions, wind  # noqa: E402

WEB, CORE, SCHED = film()  # the yardstick's roll (benchmarks/yardstick.py)
H = WEB.thickness
PAGE = Path(__file__).resolve().parent.parent / "docs" / "case-files.md"


def wind_time(n: int, numpy: bool) -> float:
    """Wall time [s] of ``wind`` on the n-layer roll (the NumPy twin when ``numpy``)."""
    keep = hakiel._NUMPY_MAX_NODES
    if numpy:
        hakiel._NUMPY_MAX_NODES = 10**9
    try:
        t0 = time.perf_counter()
        wind(WEB, CORE, CORE.outer_radius + n * H, SCHED)
        return time.perf_counter() - t0
    finally:
        hakiel._NUMPY_MAX_NODES = keep


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--layers", type=int, nargs="+", default=[10_000, 100_000, 1_000_000])
    ap.add_argument("--numpy-layers", type=int, nargs="+", default=[500, 2_000])
    ap.add_argument("--write-docs", action="store_true")
    opts = ap.parse_args()
    load0 = os.getloadavg()[0]
    wind_time(3_000, numpy=False)  # load the compiled kernels (built first if missing)
    _, yard = wind_per_layer()
    nodes = WindingOptions().subdivisions
    rows = []
    for numpy, sizes in ((True, opts.numpy_layers), (False, opts.layers)):
        for n in sizes:
            wall = wind_time(n, numpy)
            est = limits.winding_estimate(n, nodes, "numpy" if numpy else "compiled")
            ratio = wall / yard
            est_ratio = est.seconds / limits.YARDSTICK_SECONDS
            rows.append((n, est.kernels, wall, ratio, est.seconds, est_ratio / ratio))
            print(
                f"{n:>9,} layers  {est.kernels:<8} {wall:8.3f} s  {ratio:8.4f} yardsticks  "
                f"estimate {est.seconds:8.3f} s = {est_ratio:8.4f} yardsticks "
                f"({est_ratio / ratio:.2f}x the measured)",
                flush=True,
            )
    head = (
        f"`benchmarks/bench_limits.py --write-docs` ({dt.date.today().isoformat()}; python "
        f"{platform.python_version()}, {load_note(load0)}): `wind` on the yardstick's roll "
        "(12 um film, 2 elements a layer) against `limits.winding_estimate`. The yardstick "
        f"(benchmarks/yardstick.py) took {yard:.2f} s in this run; the estimate is in "
        f"seconds of the development machine, whose quiet yardstick is "
        f"{limits.YARDSTICK_SECONDS:g} s, so both are compared as multiples of a yardstick."
    )
    table = [
        "| layers | kernels | wall [s] | wall / yardstick | estimate [s] | estimate / measured "
        "(in yardsticks) |",
        "|---|---|---|---|---|---|",
    ]
    for n, kern, wall, ratio, est, fit in rows:
        table.append(f"| {n:,} | {kern} | {wall:.3g} | {ratio:.3g} | {est:.3g} | {fit:.2f} |")
    if opts.write_docs:
        write_block(PAGE, "winding-estimate", [head, "", *table])


if __name__ == "__main__":
    main()
