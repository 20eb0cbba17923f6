"""Generators of docs/studies.md's measured tables (docs/scripts/regenerate.py runs them):
the reference paper's studies on today's defaults, as ``woundroll study`` prints them."""

from __future__ import annotations

from collections.abc import Callable


def _markdown(result: object) -> str:
    lines = []
    for _title, header, rows in result.summary():  # type: ignore[attr-defined]
        lines.append("| " + " | ".join(header) + " |")
        lines.append("|" + "---|" * len(header))
        lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def tension() -> str:
    """Rho against winding tension, the seven Table 2 rolls, the default roll model."""
    from woundroll.studies import tension

    return _markdown(tension.run(workers=2))


def tension_cmd_spread() -> str:
    """The same through the CMD-spreading fast path (``--model 2d+cmd-spread``)."""
    from woundroll.studies import tension

    return _markdown(tension.run(workers=2, model="2d+cmd-spread"))


def pile_height() -> str:
    """Rho against pile height, pet2-53.4N, the default roll model."""
    from woundroll.studies import pile_height

    return _markdown(pile_height.run(workers=2))


def slip() -> str:
    """The slip factor {23} near the head (Figure 18) and the slip emulation (Figure 19)."""
    from woundroll.studies import slip

    return _markdown(slip.run(workers=2))


BLOCKS: dict[str, Callable[[], str]] = {
    "tension": tension,
    "tension_cmd_spread": tension_cmd_spread,
    "pile_height": pile_height,
    "slip": slip,
}
