"""Benchmark of the 3D contact model (woundroll.contact.solid3d.solver).

1. The linear solvers on the stiffness of the default mesh (PET2 26.7 N, Rho-meter head,
   2.1 mm): numeric factorisation + one solve + 50 right-hand sides, for MKL PARDISO
   (symbolic analysis reused), SciPy SuperLU and AMG-preconditioned CG (pyamg), in the
   same run. CHOLMOD (scikit-sparse) is not measured: it does not install from PyPI
   without the SuiteSparse headers.
2. One whole F(d) curve with the E_r update at the default mesh, with its work counters,
   and the peak memory of the process.
3. ``--ratio``: one Table 2 roll read with the 3D model, the user's whole process
   (``woundroll run CASE --set contact.model=3d --json``, one BLAS/MKL thread), against the
   yardstick of issue 23 (the straightforward 10k-layer winding,
   :func:`yardstick.wind_per_layer`) run just before it in the same process: wall and CPU,
   their ratios, Rho and the load average; each ``--variant`` (``name=KEY=VALUE,...``,
   keys of ``contact.options3d``) is run the same way and its Rho compared with the default;
   ``--set KEY=VALUE`` goes to every run (a pile height: ``--set "winding.outer_radius=0.0645
   m"`` winds PET2 to 2 cm); each run prints the depth its contact was solved to and its
   increments (one solve: the 3D loading extends past its first depth).
   With ``--write-docs`` (``make bench``): PET1 26.7 N and PET2 53.4 N, the table into
   docs/performance.md.
4. ``--profile CASE [--stage anchored|every-sector] [--check N]``: a CMD profile read with
   the 3D model, the user's whole process, against the yardstick (bar 100x); ``--every``:
   every sector with plane strain, the CMD-spreading stand-in and 3D, and how well any
   descriptor interpolates them (docs/profile.md, section 7).

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_contact3d.py [--case pet2-26.7N]``
or ``.venv/bin/python benchmarks/bench_contact3d.py --ratio --case pet1-26.7N
--variant coarse=n_fine=5,radial_growth=1.6,tangential_growth=1.6,axial_growth=1.6``
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy: see docs/contact.md

import resource  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402


def real_roll(name: str) -> tuple:
    from woundroll.case import load_case
    from woundroll.winding.hakiel import wind

    case = load_case(name)
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    return web, core, np.asarray(w.radius), np.asarray(w.sigma_r)


def _run_3d(case: str, sets: list[str], pinned: bool = True) -> tuple[float, float, dict]:
    """Wall and CPU seconds of one whole ``woundroll run`` with the 3D model, and its JSON;
    ``pinned``: one MKL (PARDISO) thread, else MKL's own choice (the cores), as a user's
    command runs."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1", OMP_NUM_THREADS="1")
    if not pinned:
        for key in ("MKL_NUM_THREADS", "OMP_NUM_THREADS"):
            env.pop(key, None)
    src = str(Path(__file__).resolve().parents[1] / "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    cmd = [sys.executable, "-m", "woundroll", "run", case, "--set", "contact.model=3d"]
    for s in sets:
        cmd += ["--set", s]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run([*cmd, "--json"], env=env, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, json.loads(out.stdout)


def ratio(case: str, variants: list[str], sets: tuple[str, ...] = ()) -> list[tuple]:
    """The user's 3D reading of ``case`` against the 10k-layer winding yardstick; the rows
    (case, variant, DOF, CPU ratio, wall ratio, Rho, yardstick wall, load). ``sets``:
    overrides of every run (``--set``, e.g. the pile height)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from yardstick import wind_per_layer

    runs = [("default", list(sets))]
    for v in variants:
        name, _, kv = v.partition("=")
        runs.append((name, [*sets, *(f"contact.options3d.{x}" for x in kv.split(",") if x)]))
    rho0 = None
    rows = []
    for name, sets in runs:
        c0 = time.process_time()
        _, yard = wind_per_layer()
        yard_cpu = time.process_time() - c0
        load = os.getloadavg()[0]
        wall, cpu, out = _run_3d(case, sets)
        rho = out["hardness"]["reading"]
        c = out["contact"]
        rho0 = rho if rho0 is None else rho0
        print(
            f"{case} 3D [{name}] {c['n_dof']} DOF: wall {wall:.1f} s = {wall / yard:.1f}x the "
            f"yardstick ({yard:.2f} s), CPU {cpu:.1f} s = {cpu / yard_cpu:.1f}x ({yard_cpu:.2f} "
            f"s); Rho {rho:.3f} ({rho - rho0:+.3f}); load {load:.1f}"
        )
        print(
            f"  contact solved to {c['depth_max_m'] * 1e3:.3f} mm in {len(c['depth_m']) - 1} "
            f"increments (the last solve {c['solve_time_s']:.1f} s)"
        )
        # the same command with MKL's own threads (what a user's process does): wall
        _, yard2 = wind_per_layer()
        wall2, _, out2 = _run_3d(case, sets, pinned=False)
        print(
            f"  with MKL's own threads: wall {wall2:.1f} s = {wall2 / yard2:.1f}x the yardstick "
            f"({yard2:.2f} s); Rho {out2['hardness']['reading']:.3f}"
        )
        rows.append(
            (case, name, c["n_dof"], cpu / yard_cpu, wall / yard, rho, yard, load, wall2 / yard2)
        )
    return rows


#: the rolls ``--ratio --write-docs`` reads with the 3D model (a hard and a soft roll)
DOCS_CASES = ("pet1-26.7N", "pet2-53.4N")


def write_ratio_docs(variants: list[str]) -> None:
    """``--ratio --write-docs``: :data:`DOCS_CASES` against the yardstick, the table in
    docs/performance.md (``<!-- bench: contact3d -->``)."""
    import platform
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from docs_block import load_note, write_block

    load0 = os.getloadavg()[0]
    rows = [r for case in DOCS_CASES for r in ratio(case, variants)]
    yards = [r[6] for r in rows]
    lines = [
        "`benchmarks/bench_contact3d.py --ratio --write-docs`: the user's whole process "
        "`woundroll run CASE --set contact.model=3d --json` (one BLAS/MKL thread), right after "
        "the yardstick (the 10k-layer winding, benchmarks/yardstick.py: "
        f"{min(yards):.2f}-{max(yards):.2f} s wall in this run) in the same process; python "
        f"{platform.python_version()}, {load_note(load0)}. Bar: 3x (judged on the CPU). Then "
        "the same command with MKL's own threads (two on this machine's two cores), as a "
        "user's process runs it: its wall time against a yardstick timed just before it.",
        "",
        "| roll | mesh | DOF | CPU x yardstick | wall x yardstick | wall, MKL's own threads "
        "| Rho | bar |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for case, name, dof, cpu_r, wall_r, rho, _, _, wall2_r in rows:
        bar = "3x ok" if cpu_r <= 3 else "3x **over**"
        lines.append(
            f"| {case} | {name} | {dof} | {cpu_r:.1f}x | {wall_r:.1f}x | {wall2_r:.1f}x | "
            f"{rho:.3f} | {bar} |"
        )
    write_block(Path(__file__).resolve().parents[1] / "docs" / "performance.md", "contact3d", lines)


def profile(case: str, check: int, stage: str = "anchored") -> None:
    """A CMD profile read with the 3D model, the user's whole process ``woundroll run CASE
    --set contact.model=3d --set profile.contact=STAGE --json``, against the 10k-layer
    winding yardstick of the same run (issue 23 item 4, bar 100x): ``stage`` "anchored"
    (plane strain on every sector, 3D on a few) or "every-sector" (3D on every sector);
    with ``check`` > 0 (anchored), that many of the sectors the stage interpolated (spread
    over the CMD) solved fully in 3D in this process, and the largest change of their shown
    reading (what the stage gave up there)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from yardstick import wind_per_layer

    c0 = time.process_time()
    _, yard = wind_per_layer()
    yard_cpu = time.process_time() - c0
    load = os.getloadavg()[0]
    wall, cpu, out = _run_3d(case, [f"profile.contact={stage}"])
    prof = out["profile"]
    st = prof["contact_stage"]
    how = "anchored on plane strain" if stage == "anchored" else f"stage {stage}"
    print(
        f"{case} profile, 3D {how}: {st['n_solved']} of "
        f"{len(st['solved'])} sectors solved in 3D, {st['check_rounds']} check rounds; wall "
        f"{wall:.1f} s = {wall / yard:.1f}x the yardstick ({yard:.2f} s), CPU {cpu:.1f} s = "
        f"{cpu / yard_cpu:.1f}x ({yard_cpu:.2f} s); load {load:.1f}"
    )
    if check <= 0 or stage != "anchored":
        return
    import numpy as np

    from woundroll.case import load_case
    from woundroll.contact.heads import head_length_of
    from woundroll.profile.hardness import ContactModel, FdReadout

    c = load_case(case, ["contact.model='3d'"])
    web, core = c.web.build(), c.core.build()
    ins = c.tester_setup.instrument
    model = ContactModel(
        web, core, ins.head_radius, head_length_of(ins), c.profile.depth_max, instrument=ins,
        model="3d", options3d=c.contact.contact3d_options(),
    )  # fmt: skip
    free = [j for j, s in enumerate(st["solved"]) if not s]
    pick = [free[int(i)] for i in np.linspace(0, len(free) - 1, min(check, len(free)))]
    # the sectors' stress profiles: the run's (r, z) winding again, in this process
    from woundroll.pipeline import run

    res = run(load_case(case, ["contact.model='3d'", "profile.contact='anchored'"]))
    w = res.profile.winding
    lo, hi = ins.reading_range
    worst = 0.0
    for j in pick:
        r, s = w.sector_profile(j)
        a, b = model(r, s)
        pile = np.array([w.build_radius[j] - w.core_radius[j]])
        exact = float(FdReadout(c.tester_setup, pile, web.density)(np.array([a]), np.array([b]))[0])
        got = float(res.profile.rho[j])
        change = abs(np.clip(exact, lo, hi) - np.clip(got, lo, hi))
        worst = max(worst, change)
        print(f"  sector {j}: anchored {got:.2f}, 3D {exact:.2f} (shown change {change:.3f})")
    print(f"  largest change of a shown reading on {len(pick)} checked sectors: {worst:.3f}")


def every_sector(case: str, data: str | None) -> None:
    """Every sector of a CMD profile solved with plane strain, the CMD-spreading stand-in
    and the 3D model (in-process, two workers; ~25 min on Table 3), and how well the 3D
    reading, or its correction to a cheaper model's, follows from a one-parameter
    descriptor: each on-scale sector's reading against the one interpolated linearly from
    its two neighbours in the descriptor with every other sector solved (leave one out:
    the best any interpolation in that descriptor can do; the anchored stage's tolerance is
    0.2). ``data``: an .npz of the springs, written if absent, read if present."""
    from dataclasses import replace
    from pathlib import Path

    from woundroll.case import load_case
    from woundroll.contact.heads import head_length_of
    from woundroll.pipeline import run
    from woundroll.profile.hardness import ContactModel, FdReadout, map_sectors, sector_contacts

    c = load_case(case, [])
    web, core = c.web.build(), c.core.build()
    ins = c.tester_setup.instrument
    w = run(c).profile.winding  # the (r, z) winding and plane strain on every sector
    profiles = [w.sector_profile(j) for j in range(w.z.size)]
    pile = w.build_radius - w.core_radius
    models = {"2d": "2d", "cmd": "2d+cmd-spread", "3d": "3d"}
    if data is not None and Path(data).exists():
        z = np.load(data)
        springs = {k: (z[f"a_{k}"], z[f"b_{k}"], z[f"w_{k}"]) for k in models}
    else:
        base = ContactModel(
            web, core, ins.head_radius, head_length_of(ins), c.profile.depth_max, instrument=ins
        )
        opts3d = load_case(case, ["contact.model='3d'"]).contact.contact3d_options()
        springs = {}
        for key, name in models.items():
            m = replace(base, model=name, options3d=opts3d if key == "3d" else None)
            t0 = time.perf_counter()
            s = map_sectors(sector_contacts(m, w.slack), profiles, workers=2)
            springs[key] = (s.alpha, s.beta, s.width)
            print(f"{name}: {len(profiles)} sectors in {time.perf_counter() - t0:.0f} s wall")
        if data is not None:
            arrays = {}
            for k, t in springs.items():
                arrays |= {f"a_{k}": t[0], f"b_{k}": t[1], f"w_{k}": t[2]}
            np.savez(data, **arrays)
    read = {
        k: FdReadout(c.tester_setup, pile, web.density, t[2])(t[0], t[1])
        for k, t in springs.items()
    }
    r3 = read["3d"]

    def lnp(depth: float) -> np.ndarray:
        return np.array([np.log(max(-np.interp(r[-1] - depth, r, s), 1.0)) for r, s in profiles])

    def window(d1: float) -> np.ndarray:
        return np.mean([lnp(d) for d in np.linspace(d1 / 24, d1, 24)], axis=0)

    def loo(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
        o = np.argsort(x, kind="stable")
        xs, ys = x[o], y[o]
        e = [
            abs(ys[i] - np.interp(xs[i], xs[[i - 1, i + 1]], ys[[i - 1, i + 1]]))
            for i in range(1, xs.size - 1)
        ]
        return float(np.max(e)), float(np.mean(e))

    from woundroll.profile.interpolated import descriptors

    desc = {"x (0.75 H, the stage's)": descriptors(profiles).mean(axis=1)}
    desc |= {f"ln p over 0-{d * 1e3:g} mm": window(d) for d in (2e-3, 8e-3, 32e-3)}
    desc |= {"plane-strain reading": read["2d"]}
    lo, hi = ins.reading_range

    def span(v: np.ndarray) -> str:  # over the sectors the 3D model reads on the scale
        v = v[r3 <= hi]
        return f"{np.min(v):+.2f}..{np.max(v):+.2f}"

    print(
        f"{case}, on-scale sectors: 3D reading minus plane strain's {span(r3 - read['2d'])}, minus "
        f"the CMD-spreading stand-in's {span(r3 - read['cmd'])}"
    )
    print("| sectors | descriptor | 3D reading | 3D - plane strain | 3D - CMD-spreading |")
    print("|---|---|---|---|---|")
    for label, m in (("taut, on scale", ~w.slack & (r3 <= hi)), ("slack", w.slack & (r3 <= hi))):
        for name, x in desc.items():
            cells = [loo(x[m], y[m]) for y in (r3, r3 - read["2d"], r3 - read["cmd"])]
            row = " | ".join(f"{a:.2f} ({b:.2f})" for a, b in cells)
            print(f"| {label} ({int(m.sum())}) | {name} | {row} |")
    print("(largest (mean) leave-one-out interpolation error, reading units)")
    # regressions on two or three descriptors at once (leave one out), the best of each
    import itertools

    feats = dict(desc) | {
        "ln alpha plane strain": np.log(springs["2d"][0]),
        "ln alpha CMD-spreading": np.log(springs["cmd"][0]),
    }
    for label, m in (("taut, on scale", ~w.slack & (r3 <= hi)), ("slack", w.slack & (r3 <= hi))):
        for tname, y in (("3D - plane strain", r3 - read["2d"]), ("3D - CMD", r3 - read["cmd"])):
            best = (np.inf, np.inf, ())
            for k in (2, 3):
                for combo in itertools.combinations(feats, k):
                    X = np.column_stack([np.ones(int(m.sum()))] + [feats[f][m] for f in combo])
                    ym, err = y[m], []
                    for i in range(ym.size):
                        keep = np.arange(ym.size) != i
                        coef = np.linalg.lstsq(X[keep], ym[keep], rcond=None)[0]
                        err.append(abs(ym[i] - X[i] @ coef))
                    best = min(best, (max(err), float(np.mean(err)), combo))
            print(
                f"{label}, {tname}: best regression {best[0]:.2f} ({best[1]:.2f}) on "
                f"{', '.join(best[2])}"
            )
    # the anchored stage replayed on the stored springs (its solves looked up), anchored on
    # plane strain (the stage's) and on the CMD-spreading stand-in
    from woundroll.profile.interpolated import interpolated_springs

    where = {id(p): j for j, p in enumerate(profiles)}

    def solve(fns: list, profs: list) -> tuple:
        js = [where[id(p)] for p in profs]
        return tuple(v[js] for v in springs["3d"])

    def readings(a: np.ndarray, b: np.ndarray, width: np.ndarray, sel: np.ndarray) -> np.ndarray:
        return FdReadout(c.tester_setup, pile[sel], web.density, width)(a, b)

    fns = ["slack" if s else "taut" for s in w.slack]  # the stage's groups
    for key in ("2d", "cmd"):
        st = interpolated_springs(
            fns, profiles, solve, readings, batch=4, scale=(lo, hi), base=springs[key]
        )
        got = readings(st.alpha, st.beta, st.width, np.arange(len(profiles)))
        miss = np.max(np.abs(np.clip(got, lo, hi) - np.clip(r3, lo, hi)))
        print(
            f"anchored on {models[key]}: {int(st.solved.sum())} of {len(profiles)} sectors "
            f"solved in 3D, {st.rounds} rounds; largest change of a shown reading {miss:.3f}"
        )


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--profile", default=None, help="a profile case read with 3D, anchored")
    ap.add_argument("--check", type=int, default=0, help="with --profile: sectors to check")
    ap.add_argument(
        "--every", action="store_true", help="with --profile: every sector in 2D, CMD-spread, 3D"
    )
    ap.add_argument("--data", default=None, help="with --every: .npz of the springs (cache)")
    ap.add_argument(
        "--stage",
        default="anchored",
        choices=["anchored", "every-sector"],
        help="with --profile: the profile's contact stage (every-sector: 3D on every sector)",
    )
    ap.add_argument("--ratio", action="store_true", help="whole 3D run against the yardstick")
    ap.add_argument("--variant", action="append", default=[], help="name=key=value,...")
    ap.add_argument(
        "--set", action="append", default=[], dest="sets", help="--ratio: KEY=VALUE, every run"
    )
    ap.add_argument(
        "--write-docs", action="store_true", help="with --ratio: docs/performance.md's table"
    )
    ap.add_argument("--case", default="pet2-26.7N")
    ap.add_argument("--depth", type=float, default=2.1e-3)
    ap.add_argument("--skip-solvers", action="store_true")
    ap.add_argument("--skip-curve", action="store_true")
    ap.add_argument(
        "--solver-n-fine",
        type=int,
        default=10,
        help="n_fine of the mesh the solvers are compared on (10: the default mesh)",
    )
    args = ap.parse_args()
    if args.profile and args.every:
        every_sector(args.profile, args.data)
        return
    if args.profile:
        profile(args.profile, args.check, args.stage)
        return
    if args.ratio and args.write_docs:
        write_ratio_docs(args.variant)
        return
    if args.ratio:
        ratio(args.case, args.variant, tuple(args.sets))
        return

    from woundroll.contact.heads import Head
    from woundroll.contact.solid3d.linsolve import make_solver
    from woundroll.contact.solid3d.solver import build_roll3d, indent3d
    from woundroll.instruments import get_instrument

    web, core, radius, sigma_r = real_roll(args.case)
    head = Head.from_instrument(get_instrument("rho-meter"))
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")

    if not args.skip_solvers:
        from woundroll.contact.solid3d.solver import Contact3DOptions

        opts = Contact3DOptions(n_fine=args.solver_n_fine)
        model = build_roll3d(
            web, core, radius, sigma_r, head=head, depth_max=args.depth, options=opts
        )
        D = model.moduli(model.sigma_pre)
        U = model.asm.upper(D)
        print(
            f"mesh (n_fine {args.solver_n_fine}): {model.mesh.shape} nodes, "
            f"{U.shape[0]} DOF, nnz(K upper) {U.nnz}"
        )
        rhs = np.random.default_rng(0).standard_normal((U.shape[0], 50))
        for name in ("pardiso", "splu", "amg"):
            s = make_solver(name, U)
            clock = time.process_time  # CPU seconds (all threads): less load-dependent
            w0, t0 = time.perf_counter(), clock()
            s.factor(U.data)
            t1 = clock()
            s.factor(U.data * 1.01)  # a second numeric factorisation (symbolic reused)
            t2 = clock()
            s.solve(rhs[:, 0])
            t3 = clock()
            if name != "amg":
                s.solve(rhs)
            t4 = clock()
            extra = f", CG iterations {s.iterations}" if name == "amg" else ""
            print(
                f"{name:8s} CPU s: first factor {t1 - t0:6.2f}, refactor {t2 - t1:6.2f}, "
                f"1 rhs {t3 - t2:6.3f}, 50 rhs {t4 - t3:6.2f}{extra} "
                f"(wall {time.perf_counter() - w0:.1f} s)"
            )

    if args.skip_curve:
        return
    t0, c0 = time.perf_counter(), time.process_time()
    res = indent3d(web, core, radius, sigma_r, head=head, depth_max=args.depth)
    dt, cpu = time.perf_counter() - t0, time.process_time() - c0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    print(
        f"F(d) with the E_r update, default mesh {res.mesh_shape} ({res.n_dof} DOF), "
        f"{res.delta.size - 1} steps: wall {dt:.1f} s, CPU {cpu:.1f} s, "
        f"peak RSS {rss:.2f} GB, F = {res.force[-1]:.2f} N"
    )
    print({k: round(v, 2) if isinstance(v, float) else v for k, v in res.stats.items()})


if __name__ == "__main__":
    main()
