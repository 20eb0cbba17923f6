"""The numbers in docs/ come from the code: every generated block names a generator that
exists (fast), and every block is what its generator gives today (slow: it re-runs the
studies and the model-choice table, a few minutes; ``make docs`` rewrites them)."""

from __future__ import annotations

import importlib.util
import json
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "docs" / "scripts" / "regenerate.py"


def _regenerate():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("docs_regenerate", SCRIPT)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_every_generated_block_has_a_generator() -> None:
    reg = _regenerate()
    blocks = reg.blocks()
    assert len(blocks) >= 5  # studies.md (4) and contact.md (1) at least
    names = set(reg.generators())
    assert [f"{p.name}: {n}" for p, n in blocks if n not in names] == []


def test_markers_are_balanced() -> None:
    # an opening marker without its end would swallow the rest of the page on regeneration
    for page in [*(ROOT / "docs").glob("*.md"), ROOT / "README.md"]:
        text = page.read_text()
        assert len(re.findall(r"<!-- generated: ", text)) == text.count("<!-- end generated -->")


def test_inline_and_block_markers() -> None:
    # a marker that ends its line opens a block (the body ends in a newline); a marker with
    # text after it on the same line is a number inside a sentence
    marker = _regenerate().MARKER
    text = (
        "a <!-- generated: m.x -->1.5<!-- end generated --> b\n"
        "<!-- generated: m.t -->\n| t |\n<!-- end generated -->\n"
    )
    found = [(m["name"], m["body"], m["open"].endswith("\n")) for m in marker.finditer(text)]
    assert found == [("m.x", "1.5", False), ("m.t", "| t |\n", True)]


#: The generator modules (docs/scripts/*.py with BLOCKS), one test each: a stale page names
#: its module, and the 3D-heavy ones (instruments, trust, calibration, contact3d) and the
#: layered readings (layered) run apart, each within ~10 CPU min.
MODULES = sorted(
    p.stem
    for p in (ROOT / "docs" / "scripts").glob("*.py")
    if p.name != "regenerate.py" and "BLOCKS" in p.read_text()
)


@pytest.mark.slow
@pytest.mark.parametrize("module", MODULES)
def test_generated_blocks_are_current(module: str) -> None:
    assert _regenerate().regenerate({module}, check=True) == []


# ---------------------------------------------------------------------------------------
# measured records (docs/scripts/records.py): the expensive studies' numbers


def _records():  # type: ignore[no-untyped-def]
    # imported by its name, as the generator modules import it (one module object)
    if str(ROOT / "docs" / "scripts") not in sys.path:
        sys.path.insert(0, str(ROOT / "docs" / "scripts"))
    import records

    return records


RECORDS = sorted(_records().measurements())


@pytest.mark.parametrize("name", RECORDS)
def test_record_matches_todays_inputs(name: str) -> None:
    # a preset, a default case key or a model's numerical default changed since the record
    # was measured: re-measure it (docs/scripts/records.py NAME) and regenerate its page
    assert _records().stale_reasons(name) == []


@pytest.mark.slow
@pytest.mark.parametrize("name", RECORDS)
def test_record_spot_runs_reproduce(name: str) -> None:
    # the models' code still gives the stored numbers on the record's cheapest runs, within
    # the tolerance the measurement states (its ``reason``)
    assert _records().spot_check(name) == []


def test_record_machinery(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # measure, resume, go stale on changed inputs, spot-check: on a measurement that only
    # loads cases (no solve)
    rec = _records()
    calls: list[str] = []

    def runs():  # type: ignore[no-untyped-def]
        return [rec.Run("a", "pet1-26.7N"), rec.Run("b", "pet2-53.4N", ("winding.tension=50 N",))]

    def measure(run):  # type: ignore[no-untyped-def]
        calls.append(run.id)
        return {"n": float(len(run.case)), "label": run.case}

    m = rec.Measurement("synthetic", runs, measure, spot=("a",), rtol=1e-9, reason="exact")
    monkeypatch.setattr(rec, "DATA", tmp_path)
    monkeypatch.setattr(rec, "measurements", lambda: {"x.y": m})
    assert rec.stale_reasons("x.y") == ["x.y: no record (run docs/scripts/records.py x.y)"]
    out = rec.measure("x.y")
    assert calls == ["a", "b"] and out["runs"]["b"] == {"n": 10.0, "label": "pet2-53.4N"}
    assert rec.stale_reasons("x.y") == [] and rec.results("x.y")["a"]["n"] == 10.0
    stamped = json.loads((tmp_path / "x.y.json").read_text())
    stamped.update(measured="2000-01-01", commit="0000000", load_1min=9.9)
    (tmp_path / "x.y.json").write_text(json.dumps(stamped))
    rec.measure("x.y")  # nothing to do: both runs stored on today's inputs
    assert calls == ["a", "b"]
    # ... and the record keeps the date, commit and load of its measurement
    kept = json.loads((tmp_path / "x.y.json").read_text())
    assert (kept["measured"], kept["commit"], kept["load_1min"]) == ("2000-01-01", "0000000", 9.9)
    assert rec.spot_check("x.y") == [] and calls == ["a", "b", "a"]

    def runs2():  # type: ignore[no-untyped-def]
        return [rec.Run("a", "pet1-26.7N"), rec.Run("b", "pet2-53.4N", ("winding.tension=60 N",))]

    m2 = rec.Measurement("synthetic", runs2, measure, spot=("a",), rtol=1e-9, reason="exact")
    monkeypatch.setattr(rec, "measurements", lambda: {"x.y": m2})
    assert rec.stale_reasons("x.y") == ["x.y: inputs of run 'b' changed"]
    rec.measure("x.y")  # resumes: only the stale run
    assert calls == ["a", "b", "a", "b"] and rec.stale_reasons("x.y") == []

    # a change of the hash function itself: rehash stores today's hashes, measures nothing
    stored = json.loads((tmp_path / "x.y.json").read_text())
    stored["inputs"]["a"] = "0" * 16
    (tmp_path / "x.y.json").write_text(json.dumps(stored))
    assert rec.stale_reasons("x.y") == ["x.y: inputs of run 'a' changed"]
    assert rec.rehash("x.y") == ["a", "b"] and rec.stale_reasons("x.y") == []
    assert calls == ["a", "b", "a", "b"] and rec.results("x.y") == stored["runs"]

    def drift(run):  # type: ignore[no-untyped-def]
        return {"n": 10.5, "label": run.case}

    m3 = rec.Measurement("synthetic", runs2, drift, spot=("a",), rtol=0.01, reason="test")
    monkeypatch.setattr(rec, "measurements", lambda: {"x.y": m3})
    assert rec.spot_check("x.y") == ["x.y: a.n stored 10.0, now 10.5"]


def test_record_goes_stale_only_on_the_defaults_of_the_models_it_names(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # a record names the option classes its runs read (``models``): a default changed in
    # another model leaves it current, one of its own stales every run; naming none keeps
    # the old rule (every class); an unset contact key (None) is not an input
    rec = _records()

    def runs():  # type: ignore[no-untyped-def]
        return [rec.Run("a", "pet1-26.7N")]

    def measure(run):  # type: ignore[no-untyped-def]
        return {"n": 1.0}

    plane = rec.Measurement("p", runs, measure, (), 1e-9, "exact", models=rec.PLANE)
    every = rec.Measurement("e", runs, measure, (), 1e-9, "exact")
    monkeypatch.setattr(rec, "DATA", tmp_path)
    monkeypatch.setattr(rec, "measurements", lambda: {"x.p": plane, "x.e": every})
    rec.measure("x.p"), rec.measure("x.e")
    true = rec.model_defaults()
    assert set(rec.defaults_of(plane)) == {"WindingOptions", "ContactOptions"}
    assert set(rec.defaults_of(every)) == set(true) and len(true) == 7

    def changed(cls: str, key: str, value: object) -> dict[str, object]:
        return {**true, cls: {**true[cls], key: value}}

    monkeypatch.setattr(rec, "model_defaults", lambda: changed("Layered3DOptions", "tol", 1.0))
    assert rec.stale_reasons("x.p") == []
    assert rec.stale_reasons("x.e") == ["x.e: default Layered3DOptions (tol) changed"]
    monkeypatch.setattr(rec, "model_defaults", lambda: changed("ContactOptions", "n_steps", 1))
    assert rec.stale_reasons("x.p") == ["x.p: default ContactOptions (n_steps) changed"]
    bad = rec.Measurement("b", runs, measure, (), 1e-9, "exact", models=("NoSuchOptions",))
    with pytest.raises(SystemExit, match="unknown option class NoSuchOptions"):
        rec.defaults_of(bad)
    # an unset contact key does not enter the hash; a set one does
    base = rec.run_inputs(rec.Run("a", "pet1-26.7N"))
    assert rec.run_inputs(rec.Run("a", "pet1-26.7N", ("contact.model='layered'",))) != base


def test_every_bench_block_is_written_by_make_bench() -> None:
    # a timing table in docs/ (<!-- bench: NAME -->) is rewritten by a benchmark that
    # make bench (benchmarks/run_all.py) runs with --write-docs: none is left hand-written
    bench = ROOT / "benchmarks"
    blocks = {
        (page.name, m)
        for page in [*(ROOT / "docs").glob("*.md"), ROOT / "README.md"]
        for m in re.findall(r"(?<!`)<!-- bench: ([\w-]+) -->", page.read_text())
    }
    assert len(blocks) >= 5
    run_all = (bench / "run_all.py").read_text()
    writers = {}
    for script in bench.glob("bench_*.py"):
        for name in re.findall(r'write_block\(.*?,\s*"([\w-]+)",', script.read_text(), re.S):
            writers[name] = script.name
    assert sorted(n for _, n in blocks if n not in writers) == []
    assert (
        sorted({writers[n] for _, n in blocks} - set(re.findall(r'"(bench_\w+\.py)"', run_all)))
        == []
    )
    for page in [*(ROOT / "docs").glob("*.md")]:
        text = page.read_text()
        # a marker quoted in backticks (prose about the markers) is not one
        opened = len(re.findall(r"(?<!`)<!-- bench: ", text))
        assert opened == len(re.findall(r"(?<!`)<!-- end bench -->", text)), page.name


def test_spot_check_tolerance_applies_to_each_number_of_a_list() -> None:
    agrees = _records()._agrees
    assert agrees([1.0, 2.0], [1.0, 2.0 * (1 + 1e-6)], 1e-3)
    assert not agrees([1.0, 2.0], [1.0, 2.1], 1e-3)
    assert not agrees([1.0, 2.0], [1.0], 1e-3)  # a list that changed length
    assert agrees("a", "a", 1e-3) and not agrees("a", "b", 1e-3)
    assert not agrees(True, 1.0, 1e-3)  # a flag is not a number
