"""Generators of docs/studies.md's measured tables (docs/scripts/regenerate.py runs them):
the reference paper's studies on today's defaults, as ``woundroll study`` prints them, and
the numbers the page's prose quotes from them (the same cached runs: no extra cost)."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any


def _markdown(result: object) -> str:
    lines = []
    for _title, header, rows in result.summary():  # type: ignore[attr-defined]
        lines.append("| " + " | ".join(header) + " |")
        lines.append("|" + "---|" * len(header))
        lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


@cache
def _tension(model: str | None = None) -> Any:
    from woundroll.studies import tension

    return tension.run(workers=2) if model is None else tension.run(workers=2, model=model)


@cache
def _pile() -> Any:
    from woundroll.studies import pile_height

    return pile_height.run(workers=2)


@cache
def _slip() -> Any:
    from woundroll.studies import slip

    return slip.run(workers=2)


def tension() -> str:
    """Rho against winding tension, the seven Table 2 rolls, the default roll model."""
    return _markdown(_tension())


def tension_cmd_spread() -> str:
    """The same through the CMD-spreading fast path (``--model 2d+cmd-spread``)."""
    return _markdown(_tension("2d+cmd-spread"))


def pile_height() -> str:
    """Rho against pile height, pet2-53.4N, the default roll model."""
    return _markdown(_pile())


def slip() -> str:
    """The slip factor {23} near the head (Figure 18) and the slip emulation (Figure 19)."""
    return _markdown(_slip())


# ---------------------------------------------------------------- numbers in the prose


def _span(values: list[float], fmt: str, unit: str = "") -> str:
    lo, hi = min(values), max(values)
    a, b = format(lo, fmt), format(hi, fmt)
    if a == b:
        return f"{a}{unit}"
    return f"{a} to {b}{unit}" if "+" in fmt or lo < 0 else f"{a}-{b}{unit}"


def _steps(rows: list[dict[str, Any]]) -> list[float]:
    return [100 * (b["rho_fd"] / a["rho_fd"] - 1) for a, b in zip(rows, rows[1:], strict=False)]


def tension_prose() -> str:
    """The tension study's trend, plane strain (the default roll model)."""
    t = _tension()
    p1, p2 = t.material("PET1"), t.material("PET2")
    return (
        f"PET1 goes from {p1[0]['rho_fd']:.1f} to {p1[-1]['rho_fd']:.1f} Rho (FD; energy "
        f"{p1[0]['rho_energy']:.1f} to {p1[-1]['rho_energy']:.1f}) as the tension rises from "
        f"{p1[0]['tension_N']:.1f} to {p1[-1]['tension_N']:.1f} N, every step up by "
        f"{_span(_steps(p1), '.0f', ' %')}; PET2 goes from {p2[0]['rho_fd']:.1f} to "
        f"{p2[-1]['rho_fd']:.1f} Rho (FD; energy {p2[0]['rho_energy']:.1f} to "
        f"{p2[-1]['rho_energy']:.1f}) as the tension rises from {p2[0]['tension_N']:.1f} to "
        f"{p2[-1]['tension_N']:.1f} N, every step up by {_span(_steps(p2), '.0f', ' %')}. At the "
        f"common 26.7 N, PET1 reads {p1[0]['rho_fd']:.1f} Rho against PET2's {p2[0]['rho_fd']:.1f}"
    )


def tension_spread() -> str:
    """The same trend on the CMD-spreading fast path."""
    t = _tension("2d+cmd-spread")
    p1, p2 = t.material("PET1"), t.material("PET2")
    return (
        f"PET1 {p1[0]['rho_fd']:.1f} to {p1[-1]['rho_fd']:.1f}, PET2 {p2[0]['rho_fd']:.1f} to "
        f"{p2[-1]['rho_fd']:.1f} Rho FD"
    )


def fd_energy() -> str:
    """energy / FD - 1 over the Table 2 rolls and the pile heights."""
    rows = _tension().rows() + _pile().rows()

    def gap(rr: list[dict[str, Any]]) -> list[float]:
        return [100 * (r["rho_energy"] / r["rho_fd"] - 1) for r in rr]

    p1 = [r for r in rows if r["material"] == "PET1"]
    p2 = [r for r in rows if r["material"] == "PET2"]
    return (
        f"energy/FD - 1 between {_span(gap(rows), '+.1f', ' %').replace(' to ', ' % and ')} over "
        f"the 7 rolls and 4 pile heights (PET1: {_span(gap(p1), '+.1f', ' %')}, PET2: "
        f"{_span(gap(p2), '+.1f', ' %')})"
    )


def impulse_prose() -> str:
    """Impulse of the Table 2 rolls against the manual's 0.267 N s."""
    t = _tension()
    out = []
    for m in ("PET1", "PET2"):
        imp = [r["impulse_N_s"] for r in t.material(m)]
        rel = [100 * (x / 0.267 - 1) for x in imp]
        out.append(f"{m} {_span(imp, '.3f', ' N s')} ({_span(rel, '+.0f', ' %')} of 0.267)")
    return ", ".join(out)


def no_update_prose() -> str:
    """The no-update reading as a share of the updated one."""
    t = _tension()
    out = []
    for m in ("PET1", "PET2"):
        ratio = [r["rho_fd_no_update"] / r["rho_fd"] for r in t.material(m)]
        out.append(f"{_span(ratio, '.2f')} of the updated one for {m}")
    return " and ".join(out)


def pile_prose() -> str:
    """The pile-height readings and their decomposition (plane strain)."""
    rows = _pile().rows()
    rho = ", ".join(f"{r['rho_fd']:.1f}" for r in rows)
    hs = ", ".join(f"{100 * r['pile_height_m']:.2f}" for r in rows)
    return f"{rho} Rho (FD) for H = {hs} cm"


def pile_decomposition() -> str:
    """The thin roll read with the reference roll's mass, then also its pre-stress."""
    rows = _pile().rows()
    thin, ref = rows[0], rows[-1]
    return (
        f"with the reference roll's m_r the thin roll's reading drops from {thin['rho_fd']:.1f} "
        f"to {thin['rho_fd_ref_mass']:.1f}: mass explains only part; with the reference "
        f"roll's pre-stress as well it drops further only to "
        f"{thin['rho_fd_ref_prestress_mass']:.1f}; what remains, "
        f"{thin['rho_fd_ref_prestress_mass']:.1f} against {ref['rho_fd']:.1f} Rho, is the "
        "plane-strain geometry alone"
    )


def pile_share() -> str:
    """Share of the head's approach from deep layers, the Table 2 pile height."""
    ref = _pile().rows()[-1]
    return (
        f"{100 * ref['approach_share_deeper_1cm']:.0f} % of it comes from layers more than 1 cm "
        f"deep, {100 * ref['approach_share_deeper_2cm']:.0f} % from more than 2 cm deep"
    )


def pile_range() -> str:
    rows = _pile().rows()
    a, b = rows[0]["rho_fd"], rows[-1]["rho_fd"]
    return f"{a:.1f} to {b:.1f} Rho, {100 * (a / b - 1):.0f} % higher for the thinnest"


def contact_prose() -> str:
    """Contact times of the Table 2 rolls per material."""
    t = _tension()
    return ", ".join(
        f"{m} {_span([1e3 * r['contact_time_s'] for r in t.material(m)], '.1f', ' ms')}"
        for m in ("PET1", "PET2")
    )


def plastic_loss() -> str:
    """The share m_r / (m_s + m_r) of the striker's energy the plastic first contact loses."""
    from woundroll.instruments import get_instrument

    m_s = get_instrument("rho-meter").mass
    t = _tension()

    def share(m: str) -> list[float]:
        return [
            100 * r["effective_mass_kg"] / (m_s + r["effective_mass_kg"]) for r in t.material(m)
        ]

    return ", ".join(f"{_span(share(m), '.0f', ' %')} for {m}" for m in ("PET1", "PET2"))


def contact_pressure() -> str:
    """Peak contact pressure at the impact's depth over the Table 2 rolls."""
    rows = _tension().rows()
    return _span([r["peak_contact_pressure_Pa"] / 1e6 for r in rows], ".0f", " MPa")


def _slip_factor_row() -> dict[str, str]:
    """The slip-factor table's row (PET2 53.4 N, mu 0.3), by column header."""
    t = _slip().summary()[0]
    return dict(zip(t.header, t.rows[0], strict=True))


def slip_factor_peak() -> str:
    """The slip factor's peak and how many elements near the head reach 1 (Figure 18)."""
    row = _slip_factor_row()
    n, total = (x.strip() for x in row["SF>=1 elements (within 3a)"].split("/"))
    return (
        f"max SF {row['max SF']} within 3 a of the axis (in the surface ring: not "
        f"mesh-converged); SF >= 1 in {n} of the {total} elements within 3 a"
    )


def slip_factor_depth() -> str:
    """How deep the region with slip factor >= 1 reaches."""
    row = _slip_factor_row()
    return (
        f"{row['SF>=1 depth [mm]']} mm deep within 3 a and "
        f"{row['SF>=1 depth, whole model [mm]']} mm deep in the whole model"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "slip_factor_peak": slip_factor_peak,
    "slip_factor_depth": slip_factor_depth,
    "tension": tension,
    "tension_cmd_spread": tension_cmd_spread,
    "pile_height": pile_height,
    "slip": slip,
    "tension_prose": tension_prose,
    "tension_spread": tension_spread,
    "fd_energy": fd_energy,
    "impulse_prose": impulse_prose,
    "no_update_prose": no_update_prose,
    "pile_prose": pile_prose,
    "pile_decomposition": pile_decomposition,
    "pile_share": pile_share,
    "pile_range": pile_range,
    "contact_prose": contact_prose,
    "plastic_loss": plastic_loss,
    "contact_pressure": contact_pressure,
}
