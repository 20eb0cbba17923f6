"""Run every benchmark script in this folder and print its report (make bench).

``bench_process.py`` also rewrites its table in docs/performance.md (against the tree before
issue 23, ``BEFORE``), ``bench_winding.py``, ``bench_storage.py`` and ``bench_air.py`` their
blocks in docs/winding.md."""

import subprocess
import sys
from pathlib import Path

BEFORE = "0b425c8"
#: the benchmarks that write their blocks into docs/winding.md
WRITE_DOCS = ("bench_winding.py", "bench_storage.py", "bench_air.py")

for script in sorted(Path(__file__).parent.glob("bench_*.py")):
    print(f"=== {script.name}", flush=True)
    extra = ["--before", BEFORE, "--write-docs"] if script.name == "bench_process.py" else []
    extra += ["--write-docs"] if script.name in WRITE_DOCS else []
    subprocess.run([sys.executable, str(script), *extra], check=False)
