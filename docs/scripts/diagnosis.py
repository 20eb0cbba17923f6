"""Generator of docs/diagnosis.md's example sentence (docs/scripts/regenerate.py runs it):
``woundroll diagnose pet1-26.7N --readings examples/data/readings_rho_3passes.csv`` on
today's defaults."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
READINGS = ROOT / "examples" / "data" / "readings_rho_3passes.csv"


def sentence() -> str:
    """The first line ``woundroll diagnose`` prints for the bundled sample sheet."""
    from woundroll.inverse.diagnosis import diagnose

    d = diagnose("pet1-26.7N", str(READINGS))
    return "\n".join(
        [
            "```",
            "$ woundroll diagnose pet1-26.7N --readings examples/data/readings_rho_3passes.csv",
            d.sentence(),
            "```",
        ]
    )


BLOCKS: dict[str, Callable[[], str]] = {"sentence": sentence}
