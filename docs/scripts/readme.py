"""Generator of the README's numbers (docs/scripts/regenerate.py runs it): the example case
``examples/my_roll.toml`` on today's defaults."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def my_roll() -> str:
    """Layers, core pressure and reading of the README's example case."""
    import woundroll

    r = woundroll.run(woundroll.load_case(ROOT / "examples" / "my_roll.toml"))
    w = r.winding
    return (
        f"{w.n_layers:,} layers, a core pressure of about {w.core_pressure / 1e6:.2f} MPa, and a "
        f"reading of about {r.hardness.reading:.0f} Rho"
    )


BLOCKS: dict[str, Callable[[], str]] = {"my_roll": my_roll}
