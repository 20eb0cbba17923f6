"""Generator of docs/report.md's print check (docs/scripts/regenerate.py runs it): the report
of ``pet1-26.7N`` with the sample readings (examples/data/readings_rho_3passes.csv), printed
to PDF by headless Chromium (the printer's default page, Letter) through the print test's
own function (tests/report/test_report_print.py ``print_to_pdf``); its page count. Needs
Chromium (``.ci/run`` installs it). Cost: the report's run (~15-40 s CPU) and the print
(~5 s)."""

from __future__ import annotations

import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
READINGS = "examples/data/readings_rho_3passes.csv"


def _print_test():  # type: ignore[no-untyped-def]
    import records

    return records.test_module("report/test_report_print.py")


def letter_pages() -> str:
    """The sentence's page count: "printed on N Letter pages"."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "out"
        cmd = [sys.executable, "-m", "woundroll", "report", "pet1-26.7N", "--readings"]
        cmd += [str(ROOT / READINGS), "--out", str(out), "-q"]
        subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)
        n = _print_test().print_to_pdf(out / "report.html", Path(tmp) / "report.pdf")
    return f"printed on {n} Letter pages"


BLOCKS: dict[str, Callable[[], str]] = {"letter_pages": letter_pages}
