"""Run every benchmark script in this folder and print its report (make bench).

The benchmarks with a table in docs/ rewrite it (``--write-docs``, benchmarks/docs_block.py):
``bench_process.py`` (against the tree before issue 23, ``BEFORE``), ``bench_profile.py
--table3``, ``bench_contact3d.py --ratio`` and ``bench_dynamic3d.py`` their tables in
docs/performance.md, ``bench_winding.py``, ``bench_storage.py`` and ``bench_air.py`` their
blocks in docs/winding.md, ``bench_diagnosis.py`` its paragraph in docs/diagnosis.md,
``bench_report.py`` its sentences in docs/report.md and docs/web.md, ``bench_limits.py`` the
winding estimate's fit in docs/case-files.md. The others print."""

import subprocess
import sys
from pathlib import Path

BEFORE = "0b425c8"
#: the arguments that make a benchmark write its docs table
DOCS = {
    "bench_process.py": ["--before", BEFORE, "--write-docs"],
    "bench_winding.py": ["--write-docs"],
    "bench_profile.py": ["--table3", "--write-docs"],
    "bench_contact3d.py": ["--ratio", "--write-docs"],
    "bench_dynamic3d.py": ["--write-docs"],
    "bench_diagnosis.py": ["--write-docs"],
    "bench_report.py": ["--write-docs"],
    "bench_storage.py": ["--write-docs"],
    "bench_air.py": ["--write-docs"],
    "bench_limits.py": ["--write-docs"],
}

for script in sorted(Path(__file__).parent.glob("bench_*.py")):
    print(f"=== {script.name}", flush=True)
    extra = DOCS.get(script.name, [])
    subprocess.run([sys.executable, str(script), *extra], check=False)
