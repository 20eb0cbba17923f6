"""Every example in examples/ runs as a user would run it, and prints the numbers it printed
when its reference was stored (tests/reference/examples.json).

Each number the example prints is compared with the stored one to within one unit in its
last printed digit (the print's own rounding; the arithmetic is deterministic, so a larger
change is a change of the models). Paths (``wrote ...``) are left out. After a deliberate
change of a model, regenerate the references with
``python tests/reference/regenerate.py examples`` and say why in the commit.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))
REFERENCE = ROOT / "tests" / "reference" / "examples.json"
NUMBER = re.compile(r"(?<![\w.])[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w.])")


def run_example(script: Path, out: Path) -> str:
    """The example's stdout, run in ``out`` with its output files written there."""
    env = {**os.environ, "MPLBACKEND": "Agg", "WOUNDROLL_EXAMPLE_OUT": str(out)}
    proc = subprocess.run(
        [sys.executable, str(script)],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
        cwd=out,
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout


def numbers(stdout: str) -> list[str]:
    """The numbers an example printed, as printed, lines naming files left out."""
    found = []
    for line in stdout.splitlines():
        if line.startswith("wrote"):
            continue
        found += NUMBER.findall(line)
    return found


def _last_digit(text: str) -> float:
    """One unit in the last printed digit of ``text`` ("51.2" -> 0.1, "3.7e+08" -> 1e6)."""
    mant, _, exp = text.lower().partition("e")
    decimals = len(mant.partition(".")[2])
    return 10.0 ** (-decimals + (int(exp) if exp else 0))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_prints_its_reference_numbers(script: Path, tmp_path: Path) -> None:
    got = numbers(run_example(script, tmp_path))
    want = json.loads(REFERENCE.read_text())[script.name]
    assert len(got) == len(want), (got, want)
    off = [
        (i, g, w)
        for i, (g, w) in enumerate(zip(got, want, strict=True))
        if abs(float(g) - float(w)) > 1.0001 * _last_digit(w)
    ]
    assert off == []


def test_the_comparison_can_fail() -> None:
    # a reading that moved by more than its last digit is caught; one within it is not
    assert abs(51.4 - 51.2) > 1.0001 * _last_digit("51.2")
    assert abs(51.25 - 51.2) <= 1.0001 * _last_digit("51.2")
    assert numbers("Rho 51.2 (FD), impulse 0.031 N s\nwrote /tmp/x-12/result.json") == [
        "51.2",
        "0.031",
    ]
