"""Generator of docs/winding.md's convergence table (docs/scripts/regenerate.py): the 1D
winding model (``woundroll.winding.hakiel.wind``) on the bundled PET1 26.7 N roll with 1 to
16 elements per layer, the whole roll solved every increment (no lazy deep part), one load
step, today's other defaults. Cost: a few seconds (the 16-element solve dominates)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from functools import cache
from typing import Any

SUBDIVISIONS = (1, 2, 4, 8, 16)
CASE = "pet1-26.7N"


@cache
def _roll() -> tuple[Any, Any, float, Any]:
    from woundroll.case import load_case

    case = load_case(CASE)
    web, core = case.web.build(), case.core.build()
    return web, core, case.winding.final_radius(web, core), case.winding.schedule(web)


@cache
def _core_pressure(subdivisions: int) -> float:
    from woundroll.winding.hakiel import WindingOptions, wind

    web, core, r_out, ten = _roll()
    opts = replace(WindingOptions(), subdivisions=subdivisions, window_layers=None, load_substeps=1)
    return float(wind(web, core, r_out, ten, options=opts).core_pressure)


def elements() -> str:
    """Core pressure against the elements per layer, the observed order of the last
    halvings and the default's distance from the Richardson limit."""
    from woundroll.winding.hakiel import WindingOptions

    default = WindingOptions().subdivisions
    web, core, r_out, _ = _roll()
    n = int(round((r_out - core.outer_radius) / web.thickness))
    p = [_core_pressure(s) for s in SUBDIVISIONS]
    head = " | ".join(f"{s}{' (default)' if s == default else ''}" for s in SUBDIVISIONS)
    cells = " | ".join(f"{x:,.0f}".replace(",", " ") for x in p)
    order = math.log2((p[-3] - p[-2]) / (p[-2] - p[-1]))
    limit = p[-1] + (p[-1] - p[-2]) / (2**order - 1)
    dev = 100 * abs(p[SUBDIVISIONS.index(default)] / limit - 1)
    return "\n".join(
        [
            f"`{CASE}`, {n:,} layers, the bundled core "
            f"(E_c = {core.stiffness / 1e9:.1f} GPa); core pressure, whole roll solved every "
            "increment, one load step:",
            "",
            f"| elements per layer | {head} |",
            "|---|" + "---|" * len(SUBDIVISIONS),
            f"| core pressure [Pa] | {cells} |",
            "",
            f"Observed order of the last two halvings {order:.1f}; {default} elements per layer "
            f"is {dev:.2f} % from the extrapolated limit.",
        ]
    )


BLOCKS: dict[str, Callable[[], str]] = {"elements": elements}
