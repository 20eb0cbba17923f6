"""Measured records: the numbers of the studies too slow to re-run on every docs check.

A 3D dynamic impact or the 88 runs of the layered study cost minutes to an hour, beyond what
``make docs`` and the slow currency test can re-run. Their numbers still come from a script:
a generator module of docs/scripts declares each such study as a :class:`Measurement` in its
``MEASUREMENTS``; this script runs it and stores what it measured, with the inputs it ran on,
in ``docs/data/<module>.<name>.json`` (a *record*); the page's generated blocks render the
record (cheap, so the ordinary currency check covers them). A record cannot go stale
silently:

* **inputs** (default suite, tests/test_docs.py): every run's case inputs (the resolved case,
  defaults included, as result.json records them) are stored as a hash, and the numerical
  defaults of the contact and winding models the measurement names (``models``: their option
  dataclasses; every one when it names none) as they were; a change to a preset, a default
  key or a mesh setting makes the test fail and name the record to re-measure;
* **code** (slow suite): the record's ``spot`` runs (its cheapest) are measured again and must
  agree with the record within the measurement's stated tolerance, so that a change in the
  models' code that moves the numbers is caught too.

A generator module reads a record with ``import records`` (docs/scripts is on the path of
regenerate.py and of this script) and ``records.results("module.name")``. Run::

    .venv/bin/python docs/scripts/records.py                      # list the records, state
    .venv/bin/python docs/scripts/records.py layered.study         # measure (resumable)
    .venv/bin/python docs/scripts/records.py layered.study --runs a,b   # only these runs
    .venv/bin/python docs/scripts/records.py --check               # inputs of every record
    .venv/bin/python docs/scripts/records.py --all                 # every stale run (make records)

then ``docs/scripts/regenerate.py MODULE`` to rewrite the pages. A measurement saves after
each run and skips runs already stored on today's inputs, so an interrupted one resumes
(``--fresh`` re-measures every run).
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime as _dt
import hashlib
import importlib.util
import json
import math
import os
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
DATA = HERE.parent / "data"
FORMAT = 1  # the record file's layout


@dataclass(frozen=True)
class Run:
    """One measured run: an ``id`` unique in its measurement, the bundled case and its
    ``--set`` overrides (what the inputs hash is taken of), and ``params``: anything else
    the measurement's function reads (JSON-able; hashed too)."""

    id: str
    case: str
    overrides: tuple[str, ...] = ()
    params: tuple[tuple[str, Any], ...] = ()

    def param(self, key: str, default: Any = None) -> Any:
        return dict(self.params).get(key, default)


@dataclass(frozen=True)
class Measurement:
    """An expensive study whose numbers a page shows.

    ``runs()`` lists the runs (cheap: no solve); ``measure(run)`` returns the run's numbers
    as a flat dict of floats, strings or lists (JSON-able, finite; a key starting with ``_``
    is informational, a wall time or the load, and not spot-checked); ``spot`` names the runs
    the slow test measures again, ``rtol`` the relative tolerance it allows and ``reason``
    why that tolerance (the numbers are deterministic on one machine; the tolerance covers
    BLAS and platform rounding of iterative solves). ``about`` is the one-line description
    the page and this script print. ``models`` names the option classes (keys of
    :func:`model_defaults`, e.g. ``"Contact3DOptions"``) whose defaults the runs read: a
    change to another model's defaults leaves the record current; empty: every class."""

    about: str
    runs: Callable[[], Sequence[Run]]
    measure: Callable[[Run], dict[str, Any]]
    spot: tuple[str, ...]
    rtol: float
    reason: str
    cost: str = ""
    extra: dict[str, Any] = field(default_factory=dict)
    models: tuple[str, ...] = ()


# ---------------------------------------------------------------------------------------
# the inputs a record depends on

#: The option classes a measurement may name in ``models`` (keys of :func:`model_defaults`),
#: by the models its runs read: the winding and plane strain (every reading's road: a 3D
#: run still winds the roll, and calibrations and fits pass through 2D), then each family.
PLANE: tuple[str, ...] = ("WindingOptions", "ContactOptions")
SOLID: tuple[str, ...] = (*PLANE, "Contact3DOptions")
LAYERED: tuple[str, ...] = (*PLANE, "LayeredOptions")
LAYERED_SOLID: tuple[str, ...] = (*SOLID, "LayeredOptions", "Layered3DOptions")


@cache
def model_defaults() -> dict[str, Any]:
    """The numerical defaults of every model (their option dataclasses, as dicts)."""
    from woundroll.contact.dynamic.plane_strain import DynamicOptions
    from woundroll.contact.dynamic.solid3d import Dynamic3DOptions
    from woundroll.contact.layered.roll3d import Layered3DOptions
    from woundroll.contact.layered.solver import LayeredOptions
    from woundroll.contact.plane_strain.solver import ContactOptions
    from woundroll.contact.solid3d.options import Contact3DOptions
    from woundroll.winding.hakiel import WindingOptions

    out: dict[str, Any] = {}
    for cls in (
        WindingOptions,
        ContactOptions,
        Contact3DOptions,
        LayeredOptions,
        Layered3DOptions,
        DynamicOptions,
        Dynamic3DOptions,
    ):
        out[cls.__name__] = json.loads(json.dumps(dataclasses.asdict(cls()), default=repr))
    return out


def defaults_of(m: Measurement) -> dict[str, Any]:
    """The part of :func:`model_defaults` measurement ``m`` depends on (its ``models``;
    every class when it names none). An unknown class name is an error."""
    allm = model_defaults()
    unknown = [c for c in m.models if c not in allm]
    if unknown:
        raise SystemExit(f"unknown option class {', '.join(unknown)} (known: {', '.join(allm)})")
    return {c: allm[c] for c in (m.models or tuple(allm))}


def _defaults_changed(rec: dict[str, Any], m: Measurement) -> list[str]:
    """The option classes ``m`` depends on whose defaults differ from the record's, each
    with its changed keys."""
    out = []
    for cls, opts in defaults_of(m).items():
        old = rec["model_defaults"].get(cls)
        if old != opts:
            old = old or {}
            keys = sorted(k for k in set(opts) | set(old) if opts.get(k) != old.get(k))
            out.append(f"{cls} ({', '.join(keys)})")
    return out


def _digest(obj: Any) -> str:
    text = json.dumps(obj, sort_keys=True, default=repr, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def run_inputs(run: Run) -> str:
    """Hash of what ``run`` is computed from: its case resolved today (every input value
    with its default, the whole contact section, and the instrument's definition with its
    calibrated head: a bundled instrument's data is not a case input) and its params."""
    from woundroll.case import load_case

    case = load_case(run.case, list(run.overrides))
    values = {v["key"]: v["value"] for v in case.record()["inputs"]}
    setup = case.tester_setup
    tester = None
    if setup is not None:
        tester = {f.name: getattr(setup, f.name) for f in dataclasses.fields(setup)}
    return _digest(
        {
            "inputs": values,
            # a key left unset (None) leaves the choice to the model, whose defaults
            # model_defaults() covers: a new optional key does not stale every record
            "contact": {k: v for k, v in case.contact.model_dump().items() if v is not None},
            "tester": tester,
            "params": [list(p) for p in run.params],
        }
    )


# ---------------------------------------------------------------------------------------
# the registry (every docs/scripts module's MEASUREMENTS)


def _load(stem: str) -> Any:
    name = f"docs_records_{stem}"
    spec = importlib.util.spec_from_file_location(name, HERE / f"{stem}.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


@cache
def test_module(rel: str) -> Any:
    """A test file (``rel`` relative to tests/, e.g. ``"contact/test_dynamic3d.py"``) as a
    module, loaded once: generators show the tests' own problems through it."""
    path = ROOT / "tests" / rel
    if str(path.parent) not in sys.path:  # as pytest's pythonpath (pyproject.toml): a
        sys.path.append(str(path.parent))  # test file may import another's problem
    name = "docs_tests_" + rel.removesuffix(".py").replace("/", "_")
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


@cache
def measurements() -> dict[str, Measurement]:
    """``{"module.name": Measurement}`` over docs/scripts/*.py."""
    found: dict[str, Measurement] = {}
    for path in sorted(HERE.glob("*.py")):
        if path.stem in ("regenerate", "records") or "MEASUREMENTS" not in path.read_text():
            continue
        for name, m in getattr(_load(path.stem), "MEASUREMENTS", {}).items():
            found[f"{path.stem}.{name}"] = m
    return found


def path_of(name: str) -> Path:
    return DATA / f"{name}.json"


def load(name: str) -> dict[str, Any]:
    """The stored record ``module.name`` (what a generator renders): ``{"runs": {id:
    numbers}, "measured": date, ...}``. A missing record is an error naming the command."""
    p = path_of(name)
    if not p.exists():
        raise SystemExit(f"no record {p.relative_to(ROOT)}: run docs/scripts/records.py {name}")
    return json.loads(p.read_text())


def results(name: str) -> dict[str, dict[str, Any]]:
    """``{run id: numbers}`` of record ``name``, in the measurement's run order."""
    return load(name)["runs"]


def stale_reasons(name: str, m: Measurement | None = None) -> list[str]:
    """Why record ``name`` no longer matches today's inputs ([] when it does)."""
    m = m or measurements()[name]
    p = path_of(name)
    if not p.exists():
        return [f"{name}: no record (run docs/scripts/records.py {name})"]
    rec = json.loads(p.read_text())
    out = [f"{name}: default {c} changed" for c in _defaults_changed(rec, m)]
    want = [r.id for r in m.runs()]
    if list(rec["runs"]) != want:
        out.append(f"{name}: runs changed (stored {len(rec['runs'])}, listed {len(want)})")
    for r in m.runs():
        if r.id in rec["inputs"] and rec["inputs"][r.id] != run_inputs(r):
            out.append(f"{name}: inputs of run {r.id!r} changed")
    return out


# ---------------------------------------------------------------------------------------
# measuring


def _check_numbers(name: str, run: Run, numbers: dict[str, Any]) -> None:
    def bad(v: Any) -> bool:
        if isinstance(v, float):
            return not math.isfinite(v)
        if isinstance(v, list):
            return any(bad(x) for x in v)
        return False

    wrong = [k for k, v in numbers.items() if bad(v)]
    if wrong:
        raise SystemExit(f"{name}: run {run.id!r} measured non-finite {', '.join(wrong)}")


def _commit() -> str:
    try:
        out = subprocess.run(
            ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            check=True,
        )
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def measure(name: str, only: Sequence[str] = (), fresh: bool = False) -> dict[str, Any]:
    """Measure record ``name`` (the runs in ``only``, else every run not already stored on
    today's inputs), saving after each run; return the record."""
    m = measurements()[name]
    runs = list(m.runs())
    ids = [r.id for r in runs]
    unknown = [i for i in only if i not in ids]
    if unknown:
        raise SystemExit(f"{name}: no run {', '.join(unknown)} (runs: {', '.join(ids)})")
    p = path_of(name)
    old = json.loads(p.read_text()) if p.exists() and not fresh else None
    if old is not None and _defaults_changed(old, m):
        old = None  # every run is stale
    stored: dict[str, Any] = dict(old["runs"]) if old else {}
    hashes: dict[str, str] = dict(old["inputs"]) if old else {}
    cpu: dict[str, float] = dict(old.get("cpu_s", {})) if old else {}
    rec: dict[str, Any] = {}

    def save() -> None:
        rec.update(
            {
                "format": FORMAT,
                "record": name,
                "about": m.about,
                "measured": _dt.date.today().isoformat(),
                "commit": _commit(),
                "command": f"docs/scripts/records.py {name}",
                "load_1min": round(os.getloadavg()[0], 1),
                "model_defaults": model_defaults(),
                "inputs": {i: hashes[i] for i in ids if i in hashes},
                "cpu_s": {i: cpu[i] for i in ids if i in cpu},
                "runs": {i: stored[i] for i in ids if i in stored},
            }
        )
        DATA.mkdir(exist_ok=True)
        p.write_text(json.dumps(rec, indent=1, allow_nan=False) + "\n")

    measured = False
    for k, run in enumerate(runs):
        h = run_inputs(run)
        if only and run.id not in only:
            continue
        if not only and run.id in stored and hashes.get(run.id) == h:
            continue
        print(f"[{k + 1}/{len(runs)}] {name}: {run.id} ...", file=sys.stderr, flush=True)
        t0 = time.process_time()
        numbers = m.measure(run)
        _check_numbers(name, run, numbers)
        cpu[run.id] = round(time.process_time() - t0, 1)
        stored[run.id], hashes[run.id] = numbers, h
        measured = True
        save()
    if measured:
        return rec  # saved after its last run
    if old is not None:
        return old  # none of its runs measured: it keeps its date, commit and load
    save()
    return rec


def rehash(name: str) -> list[str]:
    """Store today's input hashes for the runs of record ``name`` without measuring them;
    return the run ids rehashed. Only for a change of :func:`run_inputs` itself (what the
    hash covers), made while the inputs stayed what the record was measured on: it does not
    check that. The models' defaults must still match."""
    m = measurements()[name]
    p = path_of(name)
    rec = json.loads(p.read_text())
    if _defaults_changed(rec, m):
        raise SystemExit(f"{name}: the models' defaults changed: re-measure, do not rehash")
    ids = [r.id for r in m.runs() if r.id in rec["runs"]]
    rec["inputs"] = {r.id: run_inputs(r) for r in m.runs() if r.id in rec["runs"]}
    p.write_text(json.dumps(rec, indent=1, allow_nan=False) + "\n")
    return ids


def _agrees(was: Any, now: Any, rtol: float) -> bool:
    """``now`` equals ``was`` within ``rtol`` for numbers (element by element in lists),
    exactly for anything else (strings, flags)."""
    if isinstance(was, bool) or isinstance(now, bool):
        return type(was) is type(now) and was == now
    if isinstance(was, (int, float)):
        return isinstance(now, (int, float)) and math.isclose(now, was, rel_tol=rtol, abs_tol=1e-12)
    if isinstance(was, list):
        return (
            isinstance(now, list)
            and len(now) == len(was)
            and all(_agrees(a, b, rtol) for a, b in zip(was, now, strict=True))
        )
    return bool(now == was)


def spot_check(name: str) -> list[str]:
    """Measure the record's spot runs again; the numbers outside ``rtol`` ([] if none)."""
    m = measurements()[name]
    stored = results(name)
    by_id = {r.id: r for r in m.runs()}
    out: list[str] = []
    for rid in m.spot:
        now = m.measure(by_id[rid])
        for key, was in stored[rid].items():
            if key.startswith("_"):
                continue  # a timing or the load: stored, not compared
            if not _agrees(was, now.get(key), m.rtol):
                out.append(f"{name}: {rid}.{key} stored {was!r}, now {now.get(key)!r}")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("records", nargs="*", help="module.name (default: list them)")
    ap.add_argument("--runs", default="", help="comma-separated run ids to (re)measure")
    ap.add_argument("--fresh", action="store_true", help="re-measure every run")
    ap.add_argument("--check", action="store_true", help="only check the inputs; exit 1 if stale")
    ap.add_argument("--all", action="store_true", help="measure every record's stale runs")
    ap.add_argument(
        "--rehash",
        action="store_true",
        help="store today's input hashes without measuring (only after a change of the hash "
        "function itself; see rehash())",
    )
    opts = ap.parse_args()
    allm = measurements()
    if opts.all:
        opts.records = list(allm)
    names = opts.records or list(allm)
    unknown = [n for n in names if n not in allm]
    if unknown:
        raise SystemExit(f"no measurement {', '.join(unknown)} (known: {', '.join(allm)})")
    if opts.check or not opts.records:
        stale = [s for n in names for s in stale_reasons(n)]
        for n in names:
            print(f"{n}: {allm[n].about} ({allm[n].cost})")
        for s in stale:
            print("stale: " + s)
        sys.exit(1 if stale and opts.check else 0)
    if opts.rehash:
        for n in names:
            print(f"{n}: rehashed {len(rehash(n))} runs")
        return
    only = [s for s in opts.runs.split(",") if s]
    for n in names:
        measure(n, only, opts.fresh)


if __name__ == "__main__":
    main()
