"""Regenerate the numbers in docs/ from the code, so that they cannot go stale silently.

A page marks each generated block::

    <!-- generated: studies.tension -->
    | material | tension [N] | ...
    <!-- end generated -->

and the block's text is what the generator ``studies.tension`` returns: the function
``tension`` in ``BLOCKS`` of ``docs/scripts/studies.py``. A number inside a sentence is
marked the same way on one line, ``<!-- generated: instruments.collision -->(...)<!-- end
generated -->``: a marker followed by text on its own line is inline (a marker quoted in
backticks, as here in prose, is not one). Run::

    .venv/bin/python docs/scripts/regenerate.py            # rewrite every block
    .venv/bin/python docs/scripts/regenerate.py studies    # only the blocks of studies.py
    .venv/bin/python docs/scripts/regenerate.py --check    # exit 1 naming each stale block

(``make docs`` runs the first). tests/test_docs.py checks that every marker names a generator
and, in the slow suite, that every block is current.
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import sys
from collections.abc import Callable
from pathlib import Path

HERE = Path(__file__).resolve().parent
DOCS = HERE.parent
MARKER = re.compile(
    r"(?<!`)(?P<open><!-- generated: (?P<name>[\w.-]+) -->\n?)(?P<body>.*?)"
    r"(?P<close><!-- end generated -->)",
    re.S,
)


def generators() -> dict[str, Callable[[], str]]:
    """Every ``module.block`` generator of docs/scripts/*.py (their ``BLOCKS``)."""
    found: dict[str, Callable[[], str]] = {}
    if str(HERE) not in sys.path:  # generator modules ``import records`` (records.py)
        sys.path.insert(0, str(HERE))
    for path in sorted(HERE.glob("*.py")):
        if path.name in (Path(__file__).name, "records.py"):
            continue
        name = f"docs_scripts_{path.stem}"
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod  # dataclasses look their module up
        spec.loader.exec_module(mod)
        for name, fn in getattr(mod, "BLOCKS", {}).items():
            found[f"{path.stem}.{name}"] = fn
    return found


def pages() -> list[Path]:
    """The pages that may hold generated blocks: docs/*.md and the README."""
    return [*sorted(DOCS.glob("*.md")), DOCS.parent / "README.md"]


def blocks() -> list[tuple[Path, str]]:
    """(page, generator name) of every marked block in docs/*.md."""
    return [(p, m["name"]) for p in pages() for m in MARKER.finditer(p.read_text())]


def regenerate(only: set[str], check: bool) -> list[str]:
    """Rewrite (or with ``check`` compare) the blocks whose generator module is in ``only``
    (all when empty); return the names of the blocks that were stale."""
    gens = generators()
    stale: list[str] = []
    cache: dict[str, str] = {}
    for page in pages():
        text = page.read_text()

        def fill(m: re.Match[str], page: Path = page) -> str:
            name = m["name"]
            if only and name.split(".")[0] not in only:
                return m.group(0)
            if name not in gens:
                raise SystemExit(f"{page.name}: no generator {name!r} in docs/scripts")
            if name not in cache:
                print(f"generating {name} ...", file=sys.stderr, flush=True)
                cache[name] = gens[name]().strip("\n")
            # a block (its marker ends the line) ends in a newline; an inline value does not
            body = cache[name] + ("\n" if m["open"].endswith("\n") else "")
            if body != m["body"]:
                stale.append(f"{page.name}: {name}")
            return m["open"] + body + m["close"]

        new = MARKER.sub(fill, text)
        if new != text and not check:
            page.write_text(new)
    return stale


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("modules", nargs="*", help="generator modules (default: all)")
    ap.add_argument("--check", action="store_true", help="compare only; exit 1 if stale")
    opts = ap.parse_args()
    stale = regenerate(set(opts.modules), opts.check)
    for s in stale:
        print(("stale: " if opts.check else "updated: ") + s)
    if opts.check and stale:
        sys.exit(1)


if __name__ == "__main__":
    main()
