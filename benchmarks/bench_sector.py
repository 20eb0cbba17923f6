"""The CMD profile's contact stage alone: every sector's plane-strain contact solve, in-process,
serial, against the yardstick (issue 23 item 3); a script, not a test.

The case is wound once (``woundroll run CASE`` up to the contact stage, one process); then
each round times the yardstick (the 10k-layer winding, benchmarks/yardstick.py, CPU) and the
sectors' contact solves one after the other (the exact call of
``woundroll.profile.hardness.map_sectors``: ``ContactModel(radius, sigma_r)``, one BLAS
thread). Reported: the stage's CPU time as the sum over the sectors of the smallest of the
rounds (a shared machine's load comes and goes; the smallest is the least disturbed), the
yardstick's smallest, their ratio, and the work (increments, factorisations) of the solves.

``--before REF``: the same in a fresh process on git revision REF's ``src`` (``git
archive``), run after the current tree's (each process winds once, then its rounds),
and the largest relative change of every sector's spring (alpha, beta) and contact width
between the two.

Run: ``.venv/bin/python benchmarks/bench_sector.py [--case pet3-2.3MPa] [--rounds 3]
[--before REF]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent


class _Captured(Exception):
    """Raised to stop the run once the sectors' inputs are known."""


def sector_inputs(case: str) -> tuple[list, list]:
    """The contact callables and (radius, sigma_r) profiles of every sector of ``case``."""
    import woundroll.profile.hardness as hardness
    from woundroll.case.loading import load_case
    from woundroll.pipeline.runner import run

    got: dict[str, list] = {}

    def capture(fns, profiles, **_kw):  # type: ignore[no-untyped-def]
        n = len(profiles)
        got["fns"] = list(fns) if isinstance(fns, list | tuple) else [fns] * n
        got["profiles"] = [(np.array(r), np.array(s)) for r, s in profiles]
        raise _Captured

    original = hardness.map_sectors
    hardness.map_sectors = capture
    try:
        run(load_case(case, ["profile.workers=1"]))
    except _Captured:
        pass
    finally:
        hardness.map_sectors = original
    return got["fns"], got["profiles"]


def one_round(fns: list, profiles: list) -> tuple[np.ndarray, np.ndarray, dict[str, int]]:
    """CPU time of each sector's solve, the springs (alpha, beta, width) and the work."""
    from threadpoolctl import threadpool_limits

    from woundroll.contact import roll_stiffness
    from woundroll.profile.hardness import _call

    n = len(profiles)
    cpu, out = np.empty(n), np.empty((n, 3))
    work = {"increments": 0, "factorisations": 0}
    with threadpool_limits(limits=1, user_api="blas"):
        for j, (fn, (r, s)) in enumerate(zip(fns, profiles, strict=True)):
            t0 = time.process_time()
            if getattr(fn, "instrument", None) is None:  # not the default ContactModel
                out[j] = _call(fn, r, s)
                cpu[j] = time.process_time() - t0
                continue
            # what ContactModel.__call__ does, keeping the contact result for its work
            rs = roll_stiffness(
                fn.web, fn.core, r, s, fn.instrument, start_depth=fn.depth_max,
                options=fn.options, field="profile", model=fn.model, options3d=fn.options3d,
            )  # fmt: skip
            cpu[j] = time.process_time() - t0
            out[j] = rs.alpha, rs.beta, rs.semi_contact_width
            work["increments"] += int(rs.contact.delta.size - 1)
            work["factorisations"] += int(getattr(rs.contact, "factorisations", 0) or 0)
    return cpu, out, work


def yardstick_cpu() -> float:
    sys.path.insert(0, str(HERE))
    from yardstick import wind_per_layer

    t0 = time.process_time()
    wind_per_layer()
    return time.process_time() - t0


def child(case: str, rounds: int, out: str | None) -> dict:
    fns, profiles = sector_inputs(case)
    best = np.full(len(profiles), np.inf)
    yard, springs, work = [], None, {}
    for _ in range(rounds):
        yard.append(yardstick_cpu())
        cpu, springs, work = one_round(fns, profiles)
        best = np.minimum(best, cpu)
    res = {
        "stage_cpu_s": float(best.sum()),
        "yardstick_cpu_s": float(min(yard)),
        "sectors": len(profiles),
        **work,
    }
    if out is not None:
        np.save(out, springs)
    return res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="pet3-2.3MPa")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--before", default=None, help="git revision to compare with")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--springs", default=None, help=argparse.SUPPRESS)
    opts = ap.parse_args()
    if opts.child:
        print(json.dumps(child(opts.case, opts.rounds, opts.springs)))
        return
    from woundroll.profile.hardness import WORKER_ENV

    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        trees = {"now": str(HERE.parent / "src")}
        if opts.before:
            sys.path.insert(0, str(HERE))
            from bench_startup import source_of

            trees[opts.before] = str(source_of(opts.before, Path(tmp)))
        results = {}
        # one process per tree, the trees in turn (each process winds once, then its rounds)
        for name, src in trees.items():
            springs = str(Path(tmp) / f"{name}.npy".replace("/", "_"))
            env = {**os.environ, **WORKER_ENV, "PYTHONPATH": src}  # as a sector worker runs
            cmd = [sys.executable, __file__, "--child", "--case", opts.case]
            cmd += ["--rounds", str(opts.rounds), "--springs", springs]
            proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
            results[name] = json.loads(proc.stdout.strip().splitlines()[-1])
            results[name]["springs"] = np.load(springs)
    load1 = os.getloadavg()[0]
    print(
        f"{opts.case}: contact stage alone (serial, in-process CPU, sum of per-sector minima "
        f"of {opts.rounds} rounds); load average {load0:.1f} -> {load1:.1f}"
    )
    print(
        "| tree | sectors | increments | factorisations | stage CPU s | yardstick CPU s "
        "| x yardstick |"
    )
    print("|---|---|---|---|---|---|---|")
    for name, r in results.items():
        print(
            f"| {name} | {r['sectors']} | {r['increments']} | {r['factorisations']} | "
            f"{r['stage_cpu_s']:.2f} | {r['yardstick_cpu_s']:.2f} | "
            f"{r['stage_cpu_s'] / r['yardstick_cpu_s']:.2f}x |"
        )
    if opts.before:
        a, b = results["now"]["springs"], results[opts.before]["springs"]
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.where(b != 0, np.abs(a - b) / np.abs(b), np.abs(a - b))
        rel = np.nan_to_num(rel, nan=0.0)
        print(
            "largest relative change now vs {}: alpha {:.3g}, beta {:.3g}, width {:.3g}".format(
                opts.before, *rel.max(axis=0)
            )
        )


if __name__ == "__main__":
    main()
