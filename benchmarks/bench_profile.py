"""Benchmark of the CMD hardness profile (Table 3 case); a script, not a test.

Prints
1. the axisymmetric winding model alone (61 sectors, 1,337 layers) against the number of
   layer groups, with the core pressure of the thickest and thinnest sectors (convergence),
2. the uniform-thickness check against the 1D Hakiel model (largest deviation of sigma_r,
   fraction of the core pressure),
3. the whole Rho profile (winding + 61 contact solutions + energy model) at 2.3 and 3.45 MPa
   with 1 and 2 workers, and the nip case (foundation from the contact model at every 4th
   sector),
4. the profile statistics of each case.

``--table3 [--write-docs]`` (issue 23 item 3; ``make bench``): the Table 3 profiles as
fresh processes against the 10k-layer winding yardstick, the table into docs/performance.md.

With ``--plots DIR`` the CMD figures (thickness and Rho on twin axes, sigma_r(r, z) map) are
written there. Run: ``.venv/bin/python benchmarks/bench_profile.py [--quick] [--plots out]``.

Issue 14 item 3 (the Table 3 profile in <= 10 s on 2 cores), ``--process [--before REF]``:
``woundroll run CASE --json`` as a fresh process on the current tree and, interleaved, on
git revision REF (``git archive``, first on ``PYTHONPATH``): wall time, the process's CPU
time (user + sys of the whole process tree, workers included, from ``wait4``), the stages'
wall times from the JSON, the load average, and the same-run ratios. ``--deep`` times the
axisymmetric winding alone in-process (CPU), the deep part in levels against the single
frozen stack (``levels=False``) and against the whole stack every increment, with their
differences. ``--kernel [--before REF]``: the default (r, z) winding of Table 3 alone (400
groups, 61 sectors), in-process CPU time of ``wind_axisymmetric`` (min of ``--repeat`` fresh
processes), on the current tree and, interleaved, on REF, with the largest relative change
of sigma_r (of its peak) and of the core pressure between them (same-answer speed-ups of
``winding/_axisym_fe.py``: docs/performance.md).
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

from woundroll.materials import Core, Pfeiffer, Web
from woundroll.profile import bundled_profile
from woundroll.profile.hardness import NipSpec, predict_profile
from woundroll.profile.nip import NipRoller
from woundroll.winding.axisymmetric import wind_axisymmetric
from woundroll.winding.tension import TensionSchedule

# Table 3 of the reference paper
WEB = Web(
    thickness=76e-6,
    width=0.61,
    E_theta=4999e6,
    E_z=4999e6,
    radial_modulus=Pfeiffer(0.0, 246.5),
    nu_theta_r=0.01,
    nu_z_r=0.01,
    nu_theta_z=0.3,
)
CORE = Core.tube(0.1016, 0.095, 69e9, 0.33)
R_OUT = 0.2032


CASES = [
    "pet1-26.7N",
    "pet1-33.4N",
    "pet1-40N",
    "pet1-46.7N",
    "pet2-26.7N",
    "pet2-53.4N",
    "pet2-80N",
    "pet3-2.3MPa",
    "pet3-3.45MPa",
]


def window_factorisation(repeat: int = 5) -> None:
    """The window solve of one increment (Table 3: 25 groups x 61 sectors, 3,100 unknowns):
    banded Cholesky in the mesh's order against SuperLU (fill-reducing order), same matrix,
    same run, one BLAS thread (as the winding sets it; threaded BLAS made the ratio
    meaningless under load)."""
    from scipy.linalg import cho_solve_banded, cholesky_banded
    from scipy.sparse import csc_matrix
    from scipy.sparse.linalg import splu

    from woundroll.winding import _axisym_fe as fe

    prof = bundled_profile()
    _, h = prof.sector_average(61)
    w = np.diff(prof.sector_edges(61))
    st = fe.Stack(w, CORE.stiffness, (WEB.E_theta, WEB.E_z, 0.01, 0.01, 0.3), WEB.shear_r_z)
    rn = 0.15 + np.arange(26)[:, None] * 2 * h[None, :]
    E = np.full((25, 61), 2e6)
    ab, *_ = st._system(rn, E, None)
    n = ab.shape[1]
    i, j = np.nonzero(ab)  # the lower band: ab[i, j] = A[j + i, j]
    rows, cols = j + i, j
    A = csc_matrix((ab[i, j], (rows, cols)), shape=(n, n))
    A = A + csc_matrix((ab[i, j][rows != cols], (cols[rows != cols], rows[rows != cols])), (n, n))
    b = np.ones(n)
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):  # as the winding runs it
        t_chol = min(
            timed(lambda: cho_solve_banded((cholesky_banded(ab, lower=True), True), b))[0]
            for _ in range(repeat)
        )
        t_lu = min(
            timed(lambda: splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A").solve(b))[0]
            for _ in range(repeat)
        )
    print(
        f"   window solve, {n} unknowns: banded Cholesky {1e3 * t_chol:.1f} ms, SuperLU"
        f" {1e3 * t_lu:.1f} ms (ratio {t_lu / t_chol:.2f}, same run)"
    )


def run_process(args: list[str], env: dict[str, str]) -> tuple[float, float, dict]:
    """Wall and CPU time (user + sys of the process and its children) of one fresh process,
    and its JSON output."""
    import json
    import os
    import subprocess
    import sys

    t0 = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, *args], env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
    )
    out = proc.stdout.read() if proc.stdout else b""
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    # ru_* of wait4 covers the child and its waited-for descendants (the sector workers)
    cpu = usage.ru_utime + usage.ru_stime
    if status != 0:
        raise RuntimeError(f"{args} failed with status {status}")
    return wall, cpu, json.loads(out)


def whole_process(cases: list[str], before: str | None, repeat: int) -> None:
    """``woundroll run CASE --json``: current tree and ``before``, interleaved, each run
    right after the yardstick (the 10k-layer winding, benchmarks/yardstick.py) in this
    process: the ratios to it of the same run (wall to its wall, CPU to its CPU)."""
    import os
    import sys
    import tempfile

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_startup import source_of
    from yardstick import wind_per_layer

    env_now = dict(os.environ)
    trees = {"now": env_now}
    print(f"whole process, min of {repeat} (interleaved), {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp:
        if before:
            trees[before] = {**env_now, "PYTHONPATH": str(source_of(before, Path(tmp)))}
        for case in cases:
            args = ["-m", "woundroll.app.cli", "run", case, "--json"]
            best: dict[str, tuple] = {}
            loads = [os.getloadavg()[0]]
            ratio: dict[str, tuple[float, float]] = {}
            for _ in range(repeat):
                for tree, env in trees.items():
                    c0, w0 = time.process_time(), time.perf_counter()
                    wind_per_layer()
                    y_cpu, y_wall = time.process_time() - c0, time.perf_counter() - w0
                    wall, cpu, js = run_process(args, env)
                    tm = js["profile"].get("timings_s", {})
                    if tree not in best or wall < best[tree][0]:
                        best[tree] = (wall, cpu, tm, np.asarray(js["profile"]["reading_model"]))
                    r = ratio.get(tree, (np.inf, np.inf))
                    ratio[tree] = (min(r[0], wall / y_wall), min(r[1], cpu / y_cpu))
                    loads.append(os.getloadavg()[0])
            print(f"  {case}  (load average {min(loads):.1f}-{max(loads):.1f} during the runs)")
            for tree, (wall, cpu, tm, _) in best.items():
                parts = ", ".join(f"{k} {v:.1f}" for k, v in tm.items())
                print(
                    f"    {tree:10s} wall {wall:6.1f} s  CPU {cpu:6.1f} s  ({parts});"
                    f" x yardstick: wall {ratio[tree][0]:.2f}, CPU {ratio[tree][1]:.2f}"
                )
            if before:
                (w1, c1, _, r1), (w0, c0, _, r0) = best["now"], best[before]
                dev = np.max(np.abs(r1 / r0 - 1))
                print(
                    f"    ratio {before}/now: wall {w0 / w1:.2f}x, CPU {c0 / c1:.2f}x;"
                    f" Rho per sector: max |now / {before} - 1| = {100 * dev:.3f} %"
                )


def table3(cases: list[str], repeat: int, write_docs: bool) -> None:
    """``--table3``: ``woundroll run CASE --json`` as a fresh process (the sector workers
    included in its CPU time) against the yardstick of issue 23 item 3 (the 10k-layer 1D
    winding, benchmarks/yardstick.py) run in this process just before it; min of ``repeat``.
    With ``write_docs``: the table into docs/performance.md (``<!-- bench: profile -->``)."""
    import os
    import platform
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from docs_block import load_note, write_block
    from yardstick import wind_per_layer

    load0 = os.getloadavg()[0]
    rows = []
    for case in cases:
        best = None
        for _ in range(repeat):
            c0 = time.process_time()
            _, yard = wind_per_layer()
            yard_cpu = time.process_time() - c0
            wall, cpu, js = run_process(
                ["-m", "woundroll", "run", case, "--json"], dict(os.environ)
            )
            r = (wall / yard, cpu / yard_cpu, wall, yard, js["profile"])
            best = r if best is None or r[0] < best[0] else best
        assert best is not None
        wall_r, cpu_r, wall, yard, prof = best
        st = prof.get("contact_stage", {})
        n_solved = st.get("n_solved", len(prof.get("reading_model", [])))
        rows.append((case, wall_r, cpu_r, wall, yard, n_solved))
        print(
            f"{case}: {wall:.1f} s = {wall_r:.1f}x the yardstick ({yard:.2f} s), CPU {cpu_r:.1f}x"
        )
    load1 = os.getloadavg()[0]
    if not write_docs:
        return
    lines = [
        f"`benchmarks/bench_profile.py --table3 --write-docs`: min of {repeat} fresh processes "
        "`woundroll run CASE --json` (CPU: the process and its sector workers), each right "
        "after the yardstick (the straightforward 10k-layer 1D winding, "
        "benchmarks/yardstick.py) in the benchmark's process; python "
        f"{platform.python_version()}, {load_note(load0, load1)}. Bar: 1x on a quiet machine, "
        "2x with one core busy.",
        "",
        "| case | wall x yardstick | CPU x yardstick | contact solves | bar (quiet) |",
        "|---|---|---|---|---|",
    ]
    for case, wall_r, cpu_r, _, _, n in rows:
        bar = "1x ok" if wall_r <= 1 else "1x **over**"
        lines.append(f"| `{case}` | {wall_r:.1f}x | {cpu_r:.1f}x | {n} | {bar} |")
    yards = [r[4] for r in rows]
    lines += ["", f"(yardstick {min(yards):.2f}-{max(yards):.2f} s wall in this run)"]
    write_block(
        Path(__file__).resolve().parent.parent / "docs" / "performance.md", "profile", lines
    )


def deep_part(G: int | None = None) -> None:
    """The (r, z) winding of Table 3 alone, in-process CPU time: levels, single stack and
    the whole stack every increment, with the differences of the lazy ones from it."""
    prof = bundled_profile()
    ten = TensionSchedule(web_stress=2.3e6)
    runs = {}
    for name, kw in [
        ("levels (default)", {}),
        ("single stack, 24 / 8 (before)", {"levels": False, "window": 24, "flush": 8}),
        ("whole stack every increment", {"window": None}),
    ]:
        c0 = time.process_time()
        w = wind_axisymmetric(WEB, CORE, R_OUT, ten, prof, n_groups=G, **kw)
        runs[name] = (time.process_time() - c0, w)
    ex = runs["whole stack every increment"][1]
    peak = np.max(np.abs(ex.sigma_r))
    big = np.abs(ex.sigma_r) > 0.01 * peak
    print(f"   (r, z) winding, Table 3, {ex.layers_per_group.size} groups, 61 sectors, CPU")
    for name, (t, w) in runs.items():
        d = np.abs(w.sigma_r - ex.sigma_r)
        print(
            f"   {name:32s} {t:7.2f} s  max |d sigma_r| {100 * d.max() / peak:.3f} % of peak,"
            f" pointwise {100 * np.max(d[big] / np.abs(ex.sigma_r[big])):.3f} %, core"
            f" {100 * np.max(np.abs(w.core_pressure / ex.core_pressure - 1)):.3f} %,"
            f" groups factorised in refreshes {w.info['deep_groups_factorised']}"
        )


def kernel_child(out: str) -> None:
    """One default winding of Table 3 (in a fresh process): CPU time and answers to ``out``."""
    prof = bundled_profile()
    ten = TensionSchedule(web_stress=2.3e6)
    c0 = time.process_time()
    w = wind_axisymmetric(WEB, CORE, R_OUT, ten, prof)
    cpu = time.process_time() - c0
    np.savez(out, cpu=cpu, sigma_r=w.sigma_r, core=w.core_pressure)


def kernel(before: str | None, repeat: int) -> None:
    """The (r, z) winding alone, current tree and ``before`` interleaved (:func:`kernel_child`
    in fresh processes): min CPU, same-run ratio, largest changes of the answers."""
    import os
    import subprocess
    import sys
    import tempfile

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_startup import source_of

    env_now = dict(os.environ)
    trees = {"now": env_now}
    best: dict[str, float] = {}
    res: dict[str, dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        if before:
            trees[before] = {**env_now, "PYTHONPATH": str(source_of(before, Path(tmp)))}
        loads = [os.getloadavg()[0]]
        for _ in range(repeat):
            for tree, env in trees.items():
                out = str(Path(tmp) / f"{len(res)}-{tree}.npz".replace("/", "_"))
                cmd = [sys.executable, __file__, "--kernel-child", out]
                subprocess.run(cmd, env=env, check=True)
                with np.load(out) as z:
                    res[tree] = {k: z[k] for k in z.files}
                best[tree] = min(best.get(tree, np.inf), float(res[tree]["cpu"]))
                loads.append(os.getloadavg()[0])
    print(
        f"   (r, z) winding alone, Table 3 (400 groups, 61 sectors): CPU, min of {repeat}"
        f" (interleaved; load average {min(loads):.1f}-{max(loads):.1f})"
    )
    for tree, t in best.items():
        print(f"   {tree:12s} {t:6.2f} s")
    if before:
        a, b = res["now"], res[before]
        ds = np.max(np.abs(a["sigma_r"] - b["sigma_r"])) / np.max(np.abs(b["sigma_r"]))
        dp = np.max(np.abs(a["core"] / b["core"] - 1))
        print(
            f"   ratio {before}/now {best[before] / best['now']:.2f}x; max |d sigma_r| / peak"
            f" {ds:.1e}, max |d p_core / p_core| {dp:.1e}"
        )


STAGE_CASES = ["pet3-2.3MPa", "pet3-3.45MPa", "pet3-2.3MPa-nip", "pet3-3.45MPa-nip"]


def _cpu() -> float:
    """CPU time of this process and its reaped children (the sector workers, once their
    pool is closed)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def contact_stages(cases: list[str], workers: int | None) -> None:
    """``--contact-stage``: each case in-process with ``profile.contact = "every-sector"``
    and ``"interpolated"`` (alternating which goes first), the yardstick (a 10k-layer 1D
    winding, benchmarks/yardstick.py) before each run: wall and CPU (workers included),
    their ratios to the yardstick of the same run, the full solves, and the largest change
    of any sector's shown reading and of the profile statistics (docs/profile.md, section 7;
    docs/performance.md, "CMD profile")."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from yardstick import wind_per_layer

    from woundroll.case import load_case
    from woundroll.pipeline.runner import run

    print(f"load average at the start: {os.getloadavg()}")
    print(
        f"{'case':18s} {'stage':13s} {'wall':>6} {'CPU':>6} {'yard':>5} {'wall/y':>7}"
        f" {'CPU/y':>6} {'solved':>6} {'contact':>8}  stats"
    )
    for k, name in enumerate(cases):
        out = {}
        order = ["every-sector", "interpolated"][:: 1 if k % 2 == 0 else -1]
        for stage in order:
            case = load_case(name)
            upd = {"contact": stage} | ({} if workers is None else {"workers": workers})
            case = case.model_copy(update={"profile": case.profile.model_copy(update=upd)})
            _, yard = wind_per_layer()
            c0, t0 = _cpu(), time.perf_counter()
            res = run(case)
            wall, cpu = time.perf_counter() - t0, _cpu() - c0
            p = res.profile
            st = p.rho_stats
            n = p.rho.size if p.contact_stage.solved is None else int(p.contact_stage.solved.sum())
            out[stage] = p
            print(
                f"{name:18s} {stage:13s} {wall:6.1f} {cpu:6.1f} {yard:5.2f} {wall / yard:7.1f}"
                f" {cpu / yard:6.1f} {n:6d} {p.timings['contact']:8.1f}  mean {st.mean:.3f}"
                f" CoV {st.cov:.4f} sat {int(p.saturated.sum())} slack {int(p.slack.sum())}"
                f"  load {os.getloadavg()[0]:.1f}",
                flush=True,
            )
        a, b = out["every-sector"], out["interpolated"]
        d = np.abs(a.shown - b.shown)
        print(
            f"{'':18s} largest change of a shown reading {d.max():.3f} (sector {int(d.argmax())}),"
            f" of the model's reading on the scale"
            f" {np.max(np.abs(a.rho - b.rho)[~a.saturated]):.3f}, beyond it"
            f" {np.max(np.abs(a.rho - b.rho)[a.saturated], initial=0):.2f};"
            f" mean {abs(a.rho_stats.mean - b.rho_stats.mean):.4f},"
            f" CoV {abs(a.rho_stats.cov - b.rho_stats.cov):.5f},"
            f" saturated {int(a.saturated.sum())} / {int(b.saturated.sum())},"
            f" slack {int(a.slack.sum())} / {int(b.slack.sum())}",
            flush=True,
        )


def floor(cases: list[str], repeat: int) -> None:
    """``--floor``: the share of the Table 3 profile that is dense linear algebra alone
    (issue 23 item 3). Each case in-process, serial (``profile.workers = 1``), warm, with
    the LAPACK calls timed where they are made: the banded Cholesky factorisations
    (``dpbtrf``) and triangular solves (``dpbtrs`` / ``dtbtrs``) of the (r, z) winding
    (``winding/_axisym_fe.py``) and of the sectors' plane-strain contact solves
    (``contact/plane_strain/solver.py``); the yardstick (benchmarks/yardstick.py) timed
    just before each run; min of ``repeat``. The wall floor with two sector workers is the
    winding's LAPACK time plus half the contact's (the winding runs before the sectors and
    alone). What the floor says: with these discretisations (the winding's increments and
    window, the sectors' meshes and depth increments) no implementation of the rest can
    bring the profile under that ratio; only fewer or smaller factorisations can."""
    import sys

    import scipy.linalg.lapack as lapack

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from yardstick import wind_per_layer

    from woundroll.case import load_case
    from woundroll.contact.plane_strain import solver as ps
    from woundroll.pipeline.runner import run
    from woundroll.winding import _axisym_fe as fe

    spent: dict[str, list[float]] = {}

    def timer(key: str, fn):  # type: ignore[no-untyped-def]
        def wrapped(*a, **kw):  # type: ignore[no-untyped-def]
            t0 = time.perf_counter()
            try:
                return fn(*a, **kw)
            finally:
                spent.setdefault(key, []).append(time.perf_counter() - t0)

        return wrapped

    # the winding imported its LAPACK routines by name; the contact solver imports dpbtrf
    # from scipy.linalg.lapack at each call and dtbtrs through its own helper
    saved = (fe.dpbtrf, fe.dpbtrs, lapack.dpbtrf, ps._dtbtrs)
    fe.dpbtrf = timer("winding factorisations", fe.dpbtrf)
    fe.dpbtrs = timer("winding solves", fe.dpbtrs)
    print(f"load average at the start: {os.getloadavg()}")
    try:
        for name in cases:
            case = load_case(name, ["profile.workers=1"])
            run(case)  # warm: imports, caches, the allocator
            best: dict[str, float] = {}
            for _ in range(repeat):
                spent.clear()
                lapack.dpbtrf = timer("contact factorisations", saved[2])
                ps._dtbtrs = timer("contact solves", saved[3])
                try:
                    _, yard = wind_per_layer()
                    t0 = time.perf_counter()
                    res = run(case)
                    wall = time.perf_counter() - t0
                finally:
                    lapack.dpbtrf, ps._dtbtrs = saved[2], saved[3]
                if wall / yard < best.get("ratio", np.inf):
                    best = {"ratio": wall / yard, "wall": wall, "yard": yard}
                    best |= {k: sum(v) for k, v in spent.items()}
                    best |= {f"n {k}": len(v) for k, v in spent.items()}
                    best |= dict(res.profile.timings)
            y = best["yard"]
            print(
                f"  {name}: serial, in-process: {best['wall']:.2f} s = {best['ratio']:.2f}x the"
                f" yardstick ({y:.2f} s); winding {best['winding']:.2f} s, contact"
                f" {best['contact']:.2f} s"
            )
            for key in (
                "winding factorisations",
                "winding solves",
                "contact factorisations",
                "contact solves",
            ):
                print(
                    f"    {key:24s} {best.get('n ' + key, 0):6d} calls"
                    f" {best.get(key, 0.0):6.2f} s = {best.get(key, 0.0) / y:.2f}x"
                )
            lap_w = best.get("winding factorisations", 0.0) + best.get("winding solves", 0.0)
            lap_c = best.get("contact factorisations", 0.0) + best.get("contact solves", 0.0)
            print(
                f"    LAPACK alone: {(lap_w + lap_c) / y:.2f}x serial; with two sector workers"
                f" at least {(lap_w + 0.5 * lap_c) / y:.2f}x (winding {lap_w / y:.2f}x +"
                f" contact / 2 {0.5 * lap_c / y:.2f}x), before any assembly, iteration or"
                " start-up",
                flush=True,
            )
    finally:
        fe.dpbtrf, fe.dpbtrs = saved[0], saved[1]


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="skip the 1-worker and nip runs")
    ap.add_argument("--plots", type=Path, default=None)
    ap.add_argument("--winding", action="store_true", help="sections 1-2 only (winding alone)")
    ap.add_argument("--process", action="store_true", help="whole-process runs only")
    ap.add_argument("--before", default=None, help="git revision to compare (--process, --kernel)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument(
        "--cases",
        default=None,
        help="default: pet3-2.3MPa,pet3-3.45MPa-nip (--contact-stage: the four pet3 cases)",
    )
    ap.add_argument("--deep", action="store_true", help="the deep part's schemes only")
    ap.add_argument("--kernel", action="store_true", help="the winding alone [--before REF]")
    ap.add_argument("--kernel-child", default=None, help=argparse.SUPPRESS)
    ap.add_argument(
        "--contact-stage",
        action="store_true",
        help="every-sector against interpolated on the four pet3 cases (--cases, --workers)",
    )
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--table3", action="store_true", help="Table 3 against the yardstick")
    ap.add_argument("--write-docs", action="store_true", help="with --table3: the docs table")
    ap.add_argument(
        "--floor", action="store_true", help="the LAPACK share of the profile (--cases)"
    )
    args = ap.parse_args()
    if args.floor:
        floor((args.cases or "pet3-2.3MPa,pet3-3.45MPa-nip").split(","), args.repeat)
        return
    if args.table3:
        cases = (args.cases or "pet3-2.3MPa,pet3-3.45MPa-nip").split(",")
        table3(cases, args.repeat, args.write_docs)
        return
    if args.contact_stage:
        cases = STAGE_CASES if args.cases is None else args.cases.split(",")
        contact_stages(cases, args.workers)
        return
    if args.kernel_child:
        kernel_child(args.kernel_child)
        return
    if args.kernel:
        kernel(args.before, args.repeat)
        return
    if args.process:
        cases = (args.cases or "pet3-2.3MPa,pet3-3.45MPa-nip").split(",")
        whole_process(cases, args.before, args.repeat)
        return
    if args.deep:
        deep_part(400)
        return
    prof = bundled_profile()

    print("1. axisymmetric winding alone, Table 3, 61 sectors, bundled synthetic profile")
    print(
        f"{'groups':>7} {'time [s]':>9} {'P_core thickest [kPa]':>22} {'P_core thinnest':>16}"
        f" {'sigma_r outer 1 mm, sector 20 [kPa]':>36} {'slack':>6}"
    )
    runs = {}
    for G in (200, None):  # the former default, the default (at most 2 layers per group)
        t, w = timed(
            lambda G=G: wind_axisymmetric(
                WEB, CORE, R_OUT, TensionSchedule(web_stress=2.3e6), prof, n_groups=G
            )
        )
        runs[G] = w
        jt, jn = int(np.argmax(w.thickness)), int(np.argmin(w.thickness))
        r = w.radius[:, 20]
        near = np.interp(R_OUT - 1e-3, r, w.sigma_r[:, 20])
        print(
            f"{w.layers_per_group.size:7d} {t:9.2f} {w.core_pressure[jt] / 1e3:22.1f}"
            f" {w.core_pressure[jn] / 1e3:16.1f} {-near / 1e3:36.2f} {int(w.slack.sum()):6d}"
        )
    if not args.quick:
        t, w = timed(
            lambda: wind_axisymmetric(
                WEB, CORE, R_OUT, TensionSchedule(web_stress=2.3e6), prof, shear_coupling=False
            )
        )
        print(f"   independent plane-stress sectors (shear_coupling=False): {t:.2f} s")
    window_factorisation()

    print("\n2. uniform web, nu_z_r = nu_theta_z = 0 (plane stress like the 1D model), default")
    print("   options, vs the 1D model (layer by layer) on every bundled Table 2 / 3 roll")
    n_sectors = 1 if args.quick else 5
    print(
        f"   {'case':14s} {'groups':>6} {'P_core 1D':>10} {'P_core (r,z)':>13} {'max dev':>8}"
        f" {'time':>7}   ({n_sectors} sector(s), middle one; dev pointwise at group centres)"
    )
    from dataclasses import replace

    from woundroll.case import load_case
    from woundroll.winding.hakiel import wind

    for name in CASES:
        case = load_case(name)
        web = replace(case.web.build(), nu_z_r=0.0, nu_theta_z=0.0)
        core = case.core.build()
        r_out = case.winding.final_radius(web, core)
        ten = case.winding.schedule(web)
        ref = wind(web, core, r_out, ten)
        t, a = timed(
            lambda web=web, core=core, r_out=r_out, ten=ten: wind_axisymmetric(
                web, core, r_out, ten, n_sectors=n_sectors
            )
        )
        j = n_sectors // 2
        s1 = np.interp(a.radius[:, j], ref.radius, ref.sigma_r)
        dev = np.abs(a.sigma_r[:-1, j] / s1[:-1] - 1)
        print(
            f"   {name:14s} {a.layers_per_group.size:6d} {ref.core_pressure / 1e3:10.1f}"
            f" {a.core_pressure[j] / 1e3:13.1f} {100 * dev.max():7.2f}% {t:6.2f}s"
        )
    if args.winding:
        return

    print("\n3. whole Rho profile (winding + 61 contact solutions + energy model)")
    cases = [("2.3 MPa", 2.3e6, 2, None), ("3.45 MPa", 3.45e6, 2, None)]
    if not args.quick:
        cases.insert(1, ("2.3 MPa, 1 worker", 2.3e6, 1, None))
        # nip: Table 3's "P_nip 2.3 MPa" read as the nip-induced tension mu N / h
        # (docs/profile.md): mu N = 2.3 MPa x 76 um = 174.8 N/m; mu = 0.3 assumed
        roller = NipRoller.tube(200e9, 0.05, 0.04, line_load=2.3e6 * 76e-6 / 0.3, friction=0.3)
        cases.append(("2.3 MPa + nip", 2.3e6, 2, NipSpec(roller)))
    for name, T, workers, nip in cases:
        t, res = timed(
            lambda T=T, workers=workers, nip=nip: predict_profile(
                WEB,
                CORE,
                TensionSchedule(web_stress=T),
                prof,
                outer_radius=R_OUT,
                workers=workers,
                nip=nip,
            )
        )
        st = res.rho_stats
        parts = ", ".join(f"{k} {v:.1f}" for k, v in res.timings.items())
        print(f"   {name:20s} total {t:6.1f} s ({parts})")
        print(
            f"   {'':20s} Rho mean {st.mean:6.1f}, SD {st.sd:6.1f}, CoV {100 * st.cov:5.1f} %"
            f" ({st.band}), min {st.min:6.1f}, max {st.max:6.1f}; corr(Rho, h) "
            f"{np.corrcoef(res.rho, res.thickness)[0, 1]:.2f}"
        )
        if args.plots is not None:
            args.plots.mkdir(parents=True, exist_ok=True)
            tag = name.replace(" ", "_").replace(",", "").replace("+", "nip")
            res.plot(args.plots / f"profile_{tag}")


if __name__ == "__main__":
    main()
