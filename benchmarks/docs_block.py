"""Where a benchmark writes its table in docs/: between ``<!-- bench: NAME -->`` and
``<!-- end bench -->`` on a page (``--write-docs``; ``make bench`` passes it). One place for
the markers, so that every benchmark's block is found and replaced the same way."""

from __future__ import annotations

import os
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
END = "<!-- end bench -->"


def begin(name: str) -> str:
    return f"<!-- bench: {name} -->"


def write_block(page: Path, name: str, lines: list[str]) -> None:
    """Replace the block ``name`` of ``page`` (docs/...) by ``lines``; an error naming the
    page when the block is missing (a benchmark never adds one silently)."""
    text = page.read_text(encoding="utf-8")
    block = "\n".join([begin(name), *lines, END])
    pat = re.compile(re.escape(begin(name)) + ".*?" + re.escape(END), re.S)
    if not pat.search(text):
        raise SystemExit(f"{page}: no {begin(name)} ... {END} block")
    page.write_text(pat.sub(lambda _m: block, text), encoding="utf-8")
    print(f"wrote {page.relative_to(ROOT)} ({name})")


def load_note(load0: float, load1: float | None = None) -> str:
    """``load average A -> B`` (or ``A``) and the core count, for a block's first line."""
    load1 = os.getloadavg()[0] if load1 is None else load1
    return f"{os.cpu_count()} cores, load average {load0:.1f} -> {load1:.1f}"
