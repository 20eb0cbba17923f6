"""Generators of the dynamic FE impact's numbers in docs/studies.md ("Dynamic") and
docs/dynamic.md (docs/scripts/regenerate.py runs them): the seven Table 2 rolls and the
calibration block hit in time on the 2D FE roll, beside the 1.5D models, on today's presets
(each PET preset carries its typical unloading law) and, for comparison, an elastic stack.
About 16 FE impacts; a few minutes on a quiet machine. The 3D rows (minutes each) are not
regenerated here: ``woundroll study dynamic`` runs them."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

ELASTIC = ("web.radial_unloading='elastic'",)


@cache
def _study(overrides: tuple[str, ...] = ()) -> Any:
    from woundroll.studies.dynamic import dynamic_study

    return dynamic_study(overrides=overrides, block=not overrides)


def _rows(overrides: tuple[str, ...] = ()) -> dict[str, dict[str, Any]]:
    return {r["case"]: r for r in _study(overrides).rolls}


def _markdown(result: Any) -> str:
    lines = []
    for _title, header, rows in result.summary():
        lines.append("| " + " | ".join(header) + " |")
        lines.append("|" + "---|" * len(header))
        lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def study() -> str:
    """``woundroll study dynamic``'s 2D table (the Table 2 rolls and the block)."""
    return _markdown(_study())


def study_elastic() -> str:
    """The same rolls with an elastic stack (``web.radial_unloading = "elastic"``)."""
    return _markdown(_study(ELASTIC))


def _span(values: list[float], fmt: str, unit: str = "") -> str:
    """``lo-hi unit``; ``lo to hi unit`` when a bound has a sign (no "-4--2 %")."""
    lo, hi = min(values), max(values)
    a, b = format(lo, fmt), format(hi, fmt)
    if a == b:
        return f"{a}{unit}"
    return f"{a} to {b}{unit}" if "+" in fmt or lo < 0 else f"{a}-{b}{unit}"


def summary() -> str:
    """The section's short summary: FE against FD, today's presets and an elastic stack."""
    now, el = _rows(), _rows(ELASTIC)
    pet1 = [k for k in now if k.startswith("pet1")]
    pet2 = [k for k in now if k.startswith("pet2")]

    def gap(rows: dict[str, Any], keys: list[str]) -> list[float]:
        return [100 * (rows[k]["rho_dynamic"] / rows[k]["rho_fd"] - 1) for k in keys]

    p1 = now["pet1-26.7N"]
    e1 = el["pet1-26.7N"]
    blk = next(r for r in now.values() if r["material"] == "block")
    return (
        f"With today's presets (a typical unloading law on every PET web) the FE impact reads "
        f"PET1 {_span(gap(now, pet1), '+.0f', ' %')} against the FD model (PET1 26.7 N: "
        f"{p1['rho_dynamic']:.1f} against {p1['rho_fd']:.1f} Rho) and PET2 "
        f"{_span(gap(now, pet2), '+.0f', ' %')}; the striker leaves with e = "
        f"{_span([now[k]['restitution_dynamic'] for k in pet1 + pet2], '.2f')} and an impulse "
        f"of {_span([now[k]['impulse_dynamic_N_s'] for k in pet1 + pet2], '.3f')} N s (FD "
        f"{_span([now[k]['impulse_fd_N_s'] for k in pet1 + pet2], '.3f')}; the device manual's "
        f"0.267). With an elastic stack: PET1 {_span(gap(el, pet1), '+.0f', ' %')} (26.7 N: "
        f"{e1['rho_dynamic']:.1f} against {e1['rho_fd']:.1f}), PET2 "
        f"{_span(gap(el, pet2), '+.0f', ' %')}, e = "
        f"{_span([el[k]['restitution_dynamic'] for k in pet1 + pet2], '.2f')}. The block "
        f"(linear elastic) reads {blk['rho_dynamic']:.1f} Rho in the FE impact against "
        f"{blk['rho_fd']:.1f} for FD on its quasi-static curve, e = "
        f"{blk['restitution_dynamic']:.2f}"
    )


@cache
def _pet1_with(law: tuple[str, ...]) -> Any:
    import woundroll

    case = woundroll.load_case(
        "pet1-26.7N",
        ["contact.dynamic=true", "contact.dynamic_options.steps_per_contact=400", *law],
    )
    return woundroll.run(case)


def unloading() -> str:
    """PET1 26.7 N with a stiff unloading law against the elastic stack."""
    stiff = _pet1_with(("web.radial_unloading={law='pfeiffer', K1='40 kPa', K2=400}",))
    elastic = _pet1_with(ELASTIC)
    d, de = stiff.dynamic, elastic.dynamic
    return (
        f"FE e = {d.restitution:.2f} ({de.restitution:.2f} elastic), impulse {d.impulse:.3f} N s; "
        f"the FD model's e from the stack cycle is {stiff.hardness.restitution:.2f}. The FE "
        f"roll reads {d.rho:.1f} against {de.rho:.1f} Rho elastic"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "study": study,
    "study_elastic": study_elastic,
    "summary": summary,
    "unloading": unloading,
}
