"""Generators of docs/instruments.md's numbers (docs/scripts/regenerate.py runs them): the
striker example, the collision models, the Hertz calibration of the Rho-meter head and its
sensitivity, and the 3D readings of the rounded head and the sphere-tipped instruments, all
on today's presets and defaults."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

#: The paper's pile height and web density for the worked roll-mass example (Table 2).
PILE_HEIGHT, DENSITY, SEMI_WIDTH = 0.0889, 1400.0, 0.006

#: The coarse 3D mesh of the head-rounding and sphere tables (n_fine 5, growth 1.6).
COARSE_3D = [
    "contact.model='3d'",
    "contact.options3d.n_fine=5",
    "contact.options3d.radial_growth=1.6",
    "contact.options3d.tangential_growth=1.6",
    "contact.options3d.axial_growth=1.6",
]


def _e(x: float, digits: int = 3) -> str:
    """``x`` in the docs' short scientific form: 3.73e8, not 3.73e+08."""
    m, _, e = f"{x:.{digits - 1}e}".partition("e")
    return f"{m}e{int(e)}"


@cache
def _hertz() -> Any:
    """The Rho-meter head calibrated on the Table 1 block by Hertz line contact."""
    from woundroll.instruments import get_instrument
    from woundroll.instruments.calibration import calibrate_head

    return calibrate_head(get_instrument("rho-meter"))


@cache
def _column_mass() -> float:
    from woundroll.instruments.roll_side import roll_effective_mass

    rm = _hertz().instrument
    return roll_effective_mass(SEMI_WIDTH, PILE_HEIGHT, DENSITY, rm.head_length)


def example() -> str:
    """The section's code example with its printed values."""
    from woundroll.instruments import RollSpring, get_instrument, impact_fd

    cal = _hertz()
    alpha, beta, m = float(_e(cal.alpha, 2)), float(_e(cal.beta, 2)), _column_mass()
    m = float(f"{m:.2g}")
    fd = impact_fd(get_instrument("rho-meter"), RollSpring.quadratic(alpha, beta, m))
    return "\n".join(
        [
            "```python",
            "from woundroll.instruments import get_instrument, impact_fd, impact_energy, "
            "rho_energy, RollSpring",
            "",
            'rm = get_instrument("rho-meter")',
            f"fd = impact_fd(rm, RollSpring.quadratic(alpha={_e(alpha, 2)}, beta={_e(beta, 2)}, "
            f"effective_mass={m:.2g}))",
            f"fd.rho, fd.impulse, fd.contact_time, fd.max_depth  # {fd.rho:.1f} Rho, "
            f"{fd.impulse:.3f} N s, {1e3 * fd.contact_time:.2f} ms, {1e3 * fd.max_depth:.3f} mm",
            "rho_energy(alpha_array, beta_array, rm)  # {22}, vectorised",
            "```",
        ]
    )


def column_mass() -> str:
    """The tapered-column mass of the Table 2 rolls under the Rho-meter head."""
    from woundroll.instruments.roll_side import tapered_column_factor

    rm = _hertz().instrument
    k = float(tapered_column_factor(SEMI_WIDTH, PILE_HEIGHT))
    m = _column_mass()
    return (
        f"m_r = {k:.4f} x {DENSITY:.0f} x ({200 * SEMI_WIDTH:g} + {100 * PILE_HEIGHT:g}) cm x "
        f"{100 * PILE_HEIGHT:g} cm x {100 * rm.head_length:g} cm = **{1e3 * m:.1f} g** "
        f"({100 * m / rm.mass:.0f} % of the striker)"
    )


def collision() -> str:
    """The collision models on the block-fit spring with the Table 2 column mass."""
    from woundroll.instruments import RollSpring, impact_fd

    cal, m = _hertz(), _column_mass()
    rm = cal.instrument

    def rho(mass: float, how: str) -> float:
        return impact_fd(rm, RollSpring.quadratic(cal.alpha, cal.beta, mass), collision=how).rho

    return (
        f"(block-fit spring alpha = {_e(cal.alpha)} N/m^2, beta = {_e(cal.beta)} N/m, "
        f"m_r = {1e3 * m:.1f} g): plastic {rho(m, 'plastic'):.1f} Rho, keep-velocity "
        f"{rho(m, 'keep-velocity'):.1f} Rho, m_r = 0: {rho(0.0, 'plastic'):.1f} Rho"
    )


def hertz() -> str:
    """The Hertz calibration's results table."""
    from woundroll.instruments import get_instrument
    from woundroll.instruments.calibration import calibrate_head

    cal = _hertz()
    rm = cal.instrument
    preset = get_instrument("rho-meter")
    by_energy = calibrate_head(get_instrument("rho-meter"), model="energy")
    fd = _block_fd(rm)
    two_mv = 2 * rm.mass * fd.impact_speed
    rows = [
        "| quantity | value |",
        "|---|---|",
        f"| calibrated head radius (FD reading = {_target():g}) | **R = {1e3 * cal.head_radius:.4f}"
        f" mm** (preset, calibrated in `{_model_of(preset)}`: {1e3 * preset.head_radius:.3f} mm)"
        f" with L = {100 * rm.head_length:g} cm, h = {100 * _block().thickness:g} cm |",
        f"| block reading, FD (accelerometer) | **{cal.rho_fd:.2f} Rho** |",
        f"| block reading, energy model {{22}} | **{cal.rho_energy:.2f} Rho** (lower by the "
        f"striker spring's {cal.rho_fd - cal.rho_energy:.2f} Rho) |",
        f"| max depth / peak force / Hertz half-width | {1e3 * cal.max_depth:.3f} mm / "
        f"{cal.peak_force:.1f} N / {1e3 * cal.half_width:.2f} mm (a/R = "
        f"{cal.half_width / cal.head_radius:.2f}, a/h = {cal.half_width / _block().thickness:.2f})"
        " |",
        f"| impulse / contact time on the block | {fd.impulse:.3f} N s (< 2 m v = "
        f"{two_mv:.3f} N s; the device manual's typical impulse is 0.267 N s) / "
        f"{1e3 * fd.contact_time:.2f} ms |",
        f"| quadratic fit {{3}} over [0, d_max] | alpha = {_e(cal.alpha)} N/m^2, beta = "
        f"{_e(cal.beta)} N/m -> FD {cal.rho_fd_fit:.2f} Rho, energy {_fit_energy(cal):.2f} Rho |",
        f"| radius if the energy reading is matched instead | {1e3 * by_energy.head_radius:.2f} mm"
        f" (FD then reads {by_energy.rho_fd:.1f}) |",
    ]
    return "\n".join(rows)


def _block() -> Any:
    from woundroll.instruments.calibration import CalibrationBlock

    return CalibrationBlock.from_preset("rho-meter")


def _target() -> float:
    return _block().target_rho


def _model_of(instrument: Any) -> str:
    return instrument.calibration_model or "hertz"


def _block_fd(inst: Any) -> Any:
    from woundroll.instruments import RollSpring, impact_fd
    from woundroll.instruments.calibration import HertzLineContact

    law = HertzLineContact(inst.head_radius, inst.head_length, _block()).law(
        inst.impact_energy + 0.5 * inst.spring_stiffness * inst.contact_position**2
    )
    return impact_fd(inst, RollSpring(law, 0.0))


def _fit_energy(cal: Any) -> float:
    from woundroll.instruments import RollSpring, impact_energy

    return impact_energy(cal.instrument, RollSpring.quadratic(cal.alpha, cal.beta)).rho


def sensitivity() -> str:
    """The block reading against the head radius, and the calibrated radius against the
    assumed head length and block thickness."""
    import math
    from dataclasses import replace

    from woundroll.errors import ConvergenceError
    from woundroll.instruments import get_instrument
    from woundroll.instruments.calibration import calibrate_head

    cal = _hertz()
    rm = cal.instrument

    def block_rho(factor: float) -> float:
        return _block_fd(rm.with_overrides(head_radius=factor * cal.head_radius)).rho

    reads = ", ".join(
        f"{'R x' if i == 0 else 'x'} {f:g} -> {block_rho(f):.1f}" + (" Rho" if i == 0 else "")
        for i, f in enumerate((0.5, 1.1, 2.0))
    )

    def radius(length: float | None = None, thickness: float | None = None) -> float | None:
        inst = get_instrument("rho-meter")
        if length is not None:
            inst = inst.with_overrides(head_length=length)
        block = _block() if thickness is None else replace(_block(), thickness=thickness)
        try:
            return calibrate_head(inst, block).head_radius
        except ConvergenceError:
            return None

    def mm(x: float | None) -> str:
        return "none" if x is None else f"{1e3 * x:.2g} mm"

    L, h = rm.head_length, _block().thickness
    step = 1.01
    dL = math.log(radius(length=L * step) / cal.head_radius) / math.log(step)
    dh = math.log(radius(thickness=h * step) / cal.head_radius) / math.log(step)
    none = [
        f"{name} = {100 * v:.3g} cm"
        for name, v, r in (
            ("L", 2 * L, radius(length=2 * L)),
            ("h", h / 2, radius(thickness=h / 2)),
        )
        if r is None
    ]
    tail = f"; with {' or '.join(none)} no radius reaches {_target():g}" if none else ""
    return (
        f"({reads}) and the calibrated R is strongly sensitive to the assumed L and h "
        f"(d ln R/d ln L ~ {dL:.2g}, d ln R/d ln h ~ {dh:+.2g}: L = 2 cm -> R = "
        f"{mm(radius(length=0.02))}, L = 3 cm -> {mm(radius(length=0.03))}; h = 2 cm -> "
        f"{mm(radius(thickness=0.02))}, h = 3 cm -> {mm(radius(thickness=0.03))}{tail})"
    )


def _run(case: str, sets: list[str]) -> Any:
    import woundroll

    return woundroll.run(woundroll.load_case(case, sets))


def head_rounding() -> str:
    """Rho of pet2-53.4N under the Rho-meter head with rounded ends, coarse 3D mesh."""
    radii = (0.0, 1.0, 2.0)
    sizes = (("0.5 mm", ["contact.options3d.axial_size=5e-4"]), ("default", []))
    res = {
        (s, e): _run(
            "pet2-53.4N",
            COARSE_3D + extra + ([f"tester.head_edge_radius='{e:g} mm'"] if e else []),
        ).hardness
        for s, extra in sizes
        for e in radii
    }
    head = "| end radius [mm] | " + " | ".join(
        f"{e:g}" + (" (sharp, default)" if e == 0 else "") for e in radii
    )
    rows = [head + " |", "|---|" + "---|" * len(radii)]

    def cells(s: str, get: Callable[[Any], float], fmt: str, pct: bool) -> str:
        base = get(res[(s, 0.0)])
        out = []
        for e in radii:
            v = get(res[(s, e)])
            c = format(v, fmt)
            if pct and e:
                c += f" ({100 * (v / base - 1):+.1f} %)"
            out.append(c)
        return " | ".join(out)

    for s, _ in sizes:
        rows.append(f"| Rho FD, CMD size {s} | {cells(s, lambda h: h.fd.rho, '.2f', True)} |")
    rows.append(
        f"| Rho energy, CMD size 0.5 mm | {cells('0.5 mm', lambda h: h.energy.rho, '.2f', False)} |"
    )
    rows.append(
        "| max depth [mm], CMD size 0.5 mm | "
        f"{cells('0.5 mm', lambda h: 1e3 * h.fd.max_depth, '.3f', False)} |"
    )
    return "\n".join(rows)


def sphere_instruments() -> str:
    """Rebound readings of the sphere-tipped presets on two Table 2 rolls, 3D, coarse mesh."""
    instruments = (
        ("schmidt-l", "Schmidt L (R)"),
        ("schmidt-n", "Schmidt N (R)"),
        ("parotester", "Parotester (L)"),
    )
    rows = [
        "| case | " + " | ".join(t for _, t in instruments) + " |",
        "|---|" + "---|" * len(instruments),
    ]
    for case in ("pet2-53.4N", "pet1-26.7N"):
        cells = []
        for name, _ in instruments:
            r = _run(case, [*COARSE_3D[1:], f"tester.instrument='{name}'"])
            h = r.hardness
            extra = "; spring extrapolated" if r.flags.get("spring_extrapolated") else ""
            cells.append(
                f"{h.reading:.1f} (depth {1e3 * h.fd.max_depth:.2f} mm, m_r "
                f"{1e3 * h.effective_mass:.1f} g, e {h.restitution:.2f}{extra})"
            )
        rows.append(f"| {case} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


BLOCKS: dict[str, Callable[[], str]] = {
    "example": example,
    "column_mass": column_mass,
    "collision": collision,
    "hertz": hertz,
    "sensitivity": sensitivity,
    "head_rounding": head_rounding,
    "sphere_instruments": sphere_instruments,
}
