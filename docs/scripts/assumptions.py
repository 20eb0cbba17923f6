"""Generators of docs/assumptions.md's own numbers (docs/scripts/regenerate.py runs them):
the bundled Rho-meter head as the preset gives it. (The page's other numbers are generated
by docs/scripts/winding.py and studies.py, the pages that explain them.) Cost: none."""

from __future__ import annotations

from collections.abc import Callable


def head_radius() -> str:
    """The bundled Rho-meter head's radius (calibrated on the block)."""
    from woundroll.instruments import get_instrument

    ins = get_instrument("rho-meter")
    return f"{1e3 * ins.head_radius:.3f} mm in the bundled preset"


BLOCKS: dict[str, Callable[[], str]] = {"head_radius": head_radius}
