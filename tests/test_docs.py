"""The numbers in docs/ come from the code: every generated block names a generator that
exists (fast), and every block is what its generator gives today (slow: it re-runs the
studies and the model-choice table, a few minutes; ``make docs`` rewrites them)."""

from __future__ import annotations

import importlib.util
import re
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
