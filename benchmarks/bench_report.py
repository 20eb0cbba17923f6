"""Benchmark of the report and of the diagnosis a report or the web page runs; not a test.

In one process, against the yardstick (the 10k-layer winding of benchmarks/yardstick.py)
timed in the same run: the whole ``woundroll report pet1-26.7N --readings
examples/data/readings_rho_3passes.csv`` as a fresh process; in-process, the diagnosis of
those readings (``woundroll.inverse.diagnosis.diagnose``), the run of the case and the
building of its report (``woundroll.app.report.build_report``). With ``--write-docs``
(``make bench``) the sentences in docs/report.md and docs/web.md (``<!-- bench: report -->``,
``<!-- bench: report-build -->``, ``<!-- bench: web-diagnose -->``).
Run: ``.venv/bin/python benchmarks/bench_report.py [--write-docs]``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from docs_block import write_block  # noqa: E402
from yardstick import wind_per_layer  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
READINGS = ROOT / "examples" / "data" / "readings_rho_3passes.csv"


def main() -> None:
    from woundroll.app.report import build_report
    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import diagnose
    from woundroll.io.readings import read_readings
    from woundroll.pipeline import run

    load0 = os.getloadavg()[0]
    case = load_case("pet1-26.7N")
    run(case)  # warm-up: kernels, caches
    _, yard = wind_per_layer()
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, "-m", "woundroll", "report", "pet1-26.7N", "--readings"]
        cmd += [str(READINGS), "--out", tmp, "-q"]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True)
        t_report = time.perf_counter() - t0
    readings = read_readings(READINGS)
    t0 = time.perf_counter()
    diagnose(case, readings)
    t_diag = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = run(case)
    t_run = time.perf_counter() - t0
    t0 = time.perf_counter()
    build_report(res)
    t_build = time.perf_counter() - t0
    load1 = os.getloadavg()[0]
    note = (
        f"`benchmarks/bench_report.py`: multiples of the yardstick, the 10k-layer winding of "
        f"benchmarks/yardstick.py, {yard:.2f} s in the same run; load {load0:.1f} -> {load1:.1f}"
    )
    print(
        f"yardstick {yard:.2f} s; report process {t_report / yard:.1f}x, diagnosis "
        f"{t_diag / yard:.1f}x, run {t_run / yard:.2f}x, build {t_build / yard:.2f}x"
    )
    if "--write-docs" not in sys.argv:
        return
    write_block(
        ROOT / "docs" / "report.md",
        "report",
        [
            f"the whole `woundroll report` process takes about {t_report / yard:.1f} yardsticks "
            f"and the diagnosis in it about {t_diag / yard:.1f} ({note})."
        ],
    )
    write_block(
        ROOT / "docs" / "report.md",
        "report-build",
        [
            f"Building it (matplotlib's first import included) takes about {t_build / yard:.2f} "
            "yardsticks, "
            f"{t_build / t_run:.1f} times the run itself once the kernels are compiled "
            f"({note})."
        ],
    )
    write_block(
        ROOT / "docs" / "web.md",
        "web-diagnose",
        [f"for `pet1-26.7N` about {t_diag / yard:.1f} yardsticks ({note})"],
    )


if __name__ == "__main__":
    main()
