"""Whole-process times against the import yardstick (issue 23, items 1 and 3); a script.

Times fresh processes of ``woundroll run CASE --json`` for the 10,000- and 100,000-layer rolls
(``benchmarks/cases/film-10k.toml``, ``film-100k.toml``: the yardstick's film) and one
Table 2 roll to Rho (``pet1-26.7N``), each as a ratio to ``python -c "import numpy,
scipy.linalg"`` (:func:`yardstick.import_yardstick`'s command) measured in the same run,
interleaved. With ``--before REF`` the same commands run on the source tree of git revision
REF too (interleaved with the current tree: same load). Also, in-process in fresh
interpreters: the load of the compiled winding kernels (llvmlite, ``_kernels_aot.load``) and
numba's (``import numba`` plus its cached kernels' first call), and the JSON's size.

Byte-compiled files are allowed for every tree (``PYTHONDONTWRITEBYTECODE`` is dropped) and
every command runs once unmeasured first (numba's and llvmlite's caches, .pyc files).

``--write-docs`` puts the table into docs/performance.md between ``<!-- bench: process -->``
and ``<!-- end bench -->``.

Run: ``.venv/bin/python benchmarks/bench_process.py [--repeat N] [--before REF] [--write-docs]``.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_startup import cli_module, source_of  # noqa: E402
from docs_block import write_block  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "cases"
YARD = "yardstick: import numpy, scipy.linalg"
#: label -> (arguments, bar as a multiple of the yardstick or None)
COMMANDS: dict[str, tuple[list[str], float | None]] = {
    YARD: (["-c", "import numpy, scipy.linalg"], None),
    "run film-10k --json (10,000 layers)": (
        ["-m", "{cli}", "run", str(CASES / "film-10k.toml"), "--json"],
        2.5,
    ),
    "run film-100k --json (100,000 layers)": (
        ["-m", "{cli}", "run", str(CASES / "film-100k.toml"), "--json"],
        5.0,
    ),
    "run pet1-26.7N --json (Table 2, to Rho)": (
        ["-m", "{cli}", "run", "pet1-26.7N", "--json"],
        2.5,
    ),
}
#: fresh-interpreter loads of the compiled kernels (current tree), printed seconds
LOADS = {
    "compiled kernels via llvmlite (_kernels_aot.load)": (
        "import time, numpy\nfrom woundroll.winding import _kernels_aot as A\n"
        "t = time.perf_counter(); assert A.load() is not None\nprint(time.perf_counter() - t)"
    ),
    "compiled kernels via numba (import + cached first call)": (
        "import time, numpy\nt = time.perf_counter()\nfrom woundroll.winding import _kernels as K\n"
        "K.last_slope(numpy.array([0.0, 1.0]), numpy.array([1.0, 2.0]))\n"
        "print(time.perf_counter() - t)"
    ),
}


def run(args: list[str], env: dict[str, str], cli: str) -> tuple[float, int]:
    """Wall time [s] and stdout size [bytes] of one fresh process."""
    args = [a.replace("{cli}", cli) for a in args]
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, *args], env=env, check=True, capture_output=True)
    return time.perf_counter() - t0, len(out.stdout)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--before", default=None, help="git revision to compare with")
    ap.add_argument("--write-docs", action="store_true")
    opts = ap.parse_args()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env_now = {**env, "PYTHONPATH": str(ROOT / "src")}
    trees = {"now": env_now}
    clis = {"now": cli_module(ROOT / "src")}
    loads0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        if opts.before:
            src = source_of(opts.before, Path(tmp))
            trees["before"] = {**env, "PYTHONPATH": str(src)}
            clis["before"] = cli_module(src)
        best = {(t, c): float("inf") for t in trees for c in COMMANDS}
        rounds: dict[tuple[str, str], list[float]] = {(t, c): [] for t in trees for c in COMMANDS}
        size: dict[tuple[str, str], int] = {}
        for rep in range(opts.repeat + 1):  # the first round warms the caches, unmeasured
            for cmd, (args, _) in COMMANDS.items():
                for tree, e in trees.items():
                    t, n = run(args, e, clis[tree])
                    size[tree, cmd] = n
                    if rep:
                        best[tree, cmd] = min(best[tree, cmd], t)
                        rounds[tree, cmd].append(t)
        load = {}
        for name, code in LOADS.items():
            ts = []
            for _ in range(opts.repeat + 1):
                out = subprocess.run(
                    [sys.executable, "-c", code], env=env_now, check=True, capture_output=True
                )
                ts.append(float(out.stdout))
            load[name] = min(ts[1:])
    loads1 = os.getloadavg()[0]
    lines = table(opts, trees, best, rounds, size, load, loads0, loads1)
    print("\n".join(lines))
    if opts.write_docs:
        write_block(ROOT / "docs" / "performance.md", "process", lines)


def _median_ratio(rounds: dict[tuple[str, str], list[float]], cmd: str) -> float:
    """The median over the rounds of the current tree's ``cmd`` over that round's yardstick."""
    ratios = sorted(t / y for t, y in zip(rounds["now", cmd], rounds["now", YARD], strict=True))
    n = len(ratios)
    return ratios[n // 2] if n % 2 else 0.5 * (ratios[n // 2 - 1] + ratios[n // 2])


def table(opts, trees, best, rounds, size, load, loads0, loads1) -> list[str]:  # type: ignore[no-untyped-def]
    yard_now = best["now", YARD]
    before = "before" in trees
    head = (
        "| command | "
        + (f"before ({opts.before}) | " if before else "")
        + "now | now, median of the rounds | bar | JSON |"
    )
    lines = [
        f"`benchmarks/bench_process.py{' --before ' + opts.before if before else ''}`: min of "
        f"{opts.repeat} fresh processes after one warm-up, interleaved; python "
        f"{sys.version.split()[0]}, {os.cpu_count()} cores, load average {loads0:.1f} -> "
        f'{loads1:.1f}. Ratios to the yardstick `python -c "import numpy, scipy.linalg"` '
        f"of the same run: {yard_now:.2f} s now"
        + (f", {best['before', YARD]:.2f} s in the before rounds." if before else "."),
        "",
        head,
        "|---|" + ("---|" if before else "") + "---|---|---|---|",
    ]
    for cmd, (_, bar) in COMMANDS.items():
        if cmd == YARD:
            continue
        row = f"| `{cmd}` | "
        if before:
            row += f"{best['before', cmd] / best['before', YARD]:.1f}x | "
        ok = "" if bar is None else (" ok" if best["now", cmd] / yard_now <= bar else " **over**")
        row += f"{best['now', cmd] / yard_now:.1f}x | {_median_ratio(rounds, cmd):.1f}x | "
        row += f"{bar}x{ok} | "
        row += (f"{size['before', cmd] / 1e3:,.0f} kB -> " if before else "") + (
            f"{size['now', cmd] / 1e3:,.1f} kB |"
        )
        lines.append(row)
    lines += [
        "",
        "Ratios are the smallest time of a command over the smallest time of the yardstick;"
        " the median of the rounds is the median of each round's time over that round's"
        " yardstick (a round: every command once, in order; less moved by a load that"
        " changes during the run).",
    ]
    lines += ["", "| load of the compiled winding kernels (fresh interpreter) | s | x yardstick |"]
    lines.append("|---|---|---|")
    for name, t in load.items():
        lines.append(f"| {name} | {t:.3f} | {t / yard_now:.2f}x |")
    return lines


if __name__ == "__main__":
    main()
