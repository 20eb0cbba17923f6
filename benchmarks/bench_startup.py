"""Whole-process times of the CLI (issue 14, item 2); a script, not a test.

Prints the smallest wall time of ``--repeat`` runs (default 5) of

1. ``python -c "import woundroll"``,
2. ``woundroll --help`` (bar: 0.3 s),
3. ``woundroll run pet1-26.7N --json`` (bar: 1 s: winder settings to Rho, one roll),

each as a fresh process (``python -m woundroll.app.cli``, the console script's entry point).
With ``--before REF`` the same commands also run on the source tree of git revision REF
(``git archive`` into a temporary directory, put first on ``PYTHONPATH``), interleaved with
the current tree so that both see the same machine load; the ratio is printed.

Run: ``.venv/bin/python benchmarks/bench_startup.py [--repeat N] [--before REF]``.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: ``{cli}``: the module that runs the command line in that tree (``woundroll.app.cli`` since
#: the layout of docs/architecture.md, ``woundroll.cli`` before it)
COMMANDS = {
    "yardstick: import numpy, scipy.linalg": ["-c", "import numpy, scipy.linalg"],
    "import woundroll": ["-c", "import woundroll"],
    "woundroll --help": ["-m", "{cli}", "--help"],
    "woundroll run pet1-26.7N --json": ["-m", "{cli}", "run", "pet1-26.7N", "--json"],
}


def cli_module(src: Path) -> str:
    """The command line's module in the source tree ``src``."""
    return "woundroll.app.cli" if (src / "woundroll" / "app" / "cli").is_dir() else "woundroll.cli"


def wall(args: list[str], env: dict[str, str], cli: str) -> float:
    args = [a.replace("{cli}", cli) for a in args]
    t0 = time.perf_counter()
    subprocess.run([sys.executable, *args], env=env, check=True, capture_output=True)
    return time.perf_counter() - t0


def source_of(ref: str, into: Path) -> Path:
    """The ``src`` tree of git revision ``ref``, extracted under ``into``."""
    archive = into / "src.tar"
    with archive.open("wb") as fh:
        subprocess.run(["git", "archive", ref, "src"], cwd=ROOT, stdout=fh, check=True)
    with tarfile.open(archive) as tar:
        tar.extractall(into, filter="data")
    return into / "src"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--before", default=None, help="git revision to compare with")
    opts = ap.parse_args()
    env_now = dict(os.environ)
    trees = {"now": env_now}
    clis = {"now": cli_module(ROOT / "src")}
    with tempfile.TemporaryDirectory() as tmp:
        if opts.before:
            src = source_of(opts.before, Path(tmp))
            trees[opts.before] = {**env_now, "PYTHONPATH": str(src)}
            clis[opts.before] = cli_module(src)
        best = {(t, c): float("inf") for t in trees for c in COMMANDS}
        for _ in range(opts.repeat):
            for cmd, args in COMMANDS.items():
                for tree, env in trees.items():  # interleaved: same load for both trees
                    best[tree, cmd] = min(best[tree, cmd], wall(args, env, clis[tree]))
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} cores, min of {opts.repeat} runs")
    print(f"load average {os.getloadavg()[0]:.1f} (the machine's load during the runs)")
    yard = "yardstick: import numpy, scipy.linalg"
    for cmd in COMMANDS:
        line = (
            f"  {cmd:40s} {best['now', cmd]:6.2f} s  ({best['now', cmd] / best['now', yard]:4.1f}x)"
        )
        if opts.before:
            b = best[opts.before, cmd]
            line += f"   {opts.before}: {b:6.2f} s   ratio {b / best['now', cmd]:.2f}x"
        print(line)


if __name__ == "__main__":
    main()
