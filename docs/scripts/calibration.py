"""Generators of docs/calibration.md's numbers (docs/scripts/regenerate.py runs them): the
Rho-meter head calibrated on its block in each roll model, how the Table 2 rolls move with
it, and the bundled site-calibration example, on today's presets and defaults."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
#: Table 2 rolls whose readings the section quotes (all seven enter the range).
QUOTED = ("pet1-26.7N", "pet1-46.7N", "pet2-53.4N", "pet2-80N")


@cache
def _hertz() -> Any:
    from woundroll.instruments import get_instrument
    from woundroll.instruments.calibration import calibrate_head

    return calibrate_head(get_instrument("rho-meter"))


@cache
def _in_model(model: str, unknown: str = "head_radius") -> Any:
    """The head calibrated in ``model``, starting from the Hertz head (as the bundled file
    was made)."""
    from woundroll.contact.block import calibrate_head_in_model

    return calibrate_head_in_model(_hertz().instrument, model=model, unknown=unknown)


@cache
def _block(model: str) -> Any:
    """The block read with the Hertz head through ``model``."""
    from woundroll.contact.block import read_block

    return read_block(_hertz().instrument, model=model)


def _records() -> Any:
    import records

    return records


def _head3d_runs() -> list[Any]:
    return [_records().Run("3d", "pet1-26.7N")]


def _head3d_measure(run: Any) -> dict[str, Any]:
    """The head calibrated in 3D from the Hertz head (as ``woundroll calibrate-head --model
    3d`` does from the bundled file's), the block read with the Hertz head and with the
    bundled head in 3D, and the calibration's wall time against the yardstick timed in the
    same run (benchmarks/yardstick.py ``wind_per_layer``)."""
    import os
    import sys
    import time

    from woundroll.contact.block import read_block
    from woundroll.instruments import get_instrument

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from yardstick import wind_per_layer

    yard0 = wind_per_layer()[1]
    t0 = time.perf_counter()
    cal = _in_model("3d")
    wall = time.perf_counter() - t0
    from woundroll.contact.block import calibrate_head_in_model

    t0 = time.perf_counter()
    cal2 = calibrate_head_in_model(_hertz().instrument, model="2d")
    wall2 = time.perf_counter() - t0
    yard1 = wind_per_layer()[1]
    bundled = get_instrument("rho-meter")
    return {
        "head_radius_mm": 1e3 * cal.value,
        "evaluations": float(cal.evaluations),
        "block_hertz": read_block(_hertz().instrument, model="3d").reading,
        "block_bundled": read_block(bundled, model="3d").reading,
        "bundled_radius_mm": 1e3 * bundled.head_radius,
        "_yardsticks": wall / min(yard0, yard1),
        "_solve_ratio_3d_2d": (wall / cal.evaluations) / (wall2 / cal2.evaluations),
        "_load": round(os.getloadavg()[0], 1),
    }


MEASUREMENTS: dict[str, Any] = {
    "head3d": _records().Measurement(
        models=_records().SOLID,
        about="the Rho-meter head calibrated on its block in the 3D model (docs/calibration.md)",
        runs=_head3d_runs,
        measure=_head3d_measure,
        spot=("3d",),
        rtol=1e-3,
        reason=(
            "deterministic on one machine; Brent stops at 1e-4 of the radius and the 3D "
            "solve's iterative rounding moves the block's reading by far less than 1e-3"
        ),
        cost="about 10 3D block solves and a 2D calibration, about 1 CPU min",
    ),
}


def head_models() -> str:
    """The head radius for 77 Rho in each model, and the block read with the Hertz head."""
    from woundroll.instruments import get_instrument

    hz = _hertz()
    bundled = get_instrument("rho-meter")
    r_h = f"{1e3 * hz.head_radius:.3f} mm"
    rows = [
        f"| model | head radius for {_target():g} Rho | block with the Hertz head ({r_h}) |",
        "|---|---|---|",
        f"| Hertz line contact (half-space to the block's thickness) | {r_h} | {hz.rho_fd:.2f} |",
    ]
    d2 = _in_model("2d")
    flag = (
        f' (bundled, `calibration_model = "{bundled.calibration_model}"`)'
        if abs(bundled.head_radius / d2.value - 1) < 1e-3
        else f" (the bundled file has {1e3 * bundled.head_radius:.3f} mm: recalibrate)"
    )
    rows.append(
        f"| `2d` (the default) | **{1e3 * d2.value:.3f} mm**{flag}, {d2.evaluations} block solves "
        f"| {_block('2d').reading:.2f} |"
    )
    cs = _in_model("2d+cmd-spread")
    rows.append(
        f"| `2d+cmd-spread` | {1e3 * cs.value:.3f} mm ({cs.evaluations} solves): the "
        "CMD-spreading correction makes the block too hard, and only an implausibly sharp head "
        "brings it to the target (the command warns when the dimension moves by more than 4x) "
        f"| {_block('2d+cmd-spread').reading:.2f} |"
    )
    d3 = _records().results("calibration.head3d")["3d"]
    rows.append(
        f"| `3d` | {d3['head_radius_mm']:.3f} mm ({d3['evaluations']:.0f} block solves; the "
        f"bundled {d3['bundled_radius_mm']:.3f} mm head reads the block {d3['block_bundled']:.1f} "
        f"in 3D; {_measured()}) | {d3['block_hertz']:.1f} (the block is isotropic: G_r_z of the "
        "block, not the web's) |"
    )
    return "\n".join(rows)


def _measured() -> str:
    rec = _records().load("calibration.head3d")
    return f"measured {rec['measured']} by `docs/scripts/records.py calibration.head3d`"


def head3d_cost() -> str:
    """The 3D calibration's cost from its record, against the 2D one's."""
    d3 = _records().results("calibration.head3d")["3d"]
    return (
        f"The 3D calibration took {d3['evaluations']:.0f} block solves and about "
        f"{d3['_yardsticks']:.0f} yardsticks (`wind_per_layer` of benchmarks/yardstick.py, "
        f"timed in the same run at a load average of {d3['_load']:g}; {_measured()}); "
        f"a 3D block solve cost {d3['_solve_ratio_3d_2d']:.0f} times a `2d` one (the default) "
        "in that run"
    )


def _target() -> float:
    from woundroll.instruments.calibration import CalibrationBlock

    return CalibrationBlock.from_preset("rho-meter").target_rho


def head_length() -> str:
    """The head length that calibrates the block in 2D with the Hertz radius."""
    return f"{1e3 * _in_model('2d', 'head_length').value:.2f} mm"


def rolls_move() -> str:
    """The Table 2 rolls read in 2D with the Hertz head and with the bundled head."""
    import woundroll
    from woundroll.studies._common import TABLE2 as ROLLS

    hz = _hertz().instrument
    bundled = woundroll.load_case("pet1-26.7N").tester_setup.instrument
    before, after = {}, {}
    for name in ROLLS:
        after[name] = woundroll.run(woundroll.load_case(name)).hardness.fd.rho
        case = woundroll.load_case(name, [f"tester.head_radius='{1e3 * hz.head_radius!r} mm'"])
        before[name] = woundroll.run(case).hardness.fd.rho
    change = [100 * (1 - after[n] / before[n]) for n in ROLLS]
    quoted = ", ".join(
        f"{n.replace('-', ' ').upper().replace('N', ' N')} {before[n]:.2f} -> {after[n]:.2f}"
        for n in QUOTED
    )
    return (
        f"{1e3 * hz.head_radius:.3f} -> {1e3 * bundled.head_radius:.3f} mm changes every "
        f"reading by {-max(change):+.2f} to {-min(change):+.2f} % ({quoted})"
    )


def site_example() -> str:
    """The bundled site-calibration example: the fitted head length and its check."""
    import numpy as np

    from woundroll.inverse.site_calibration import calibrate_site

    ex = ROOT / "examples" / "calibration"
    cases = [str(ex / f"roll-{c}.toml") for c in "abcd"]
    cal = calibrate_site(ex / "readings.csv", cases, ["head_length"])
    value, se = 1e3 * cal.values[0], 1e3 * cal.standard_errors[0]
    rms = float(np.sqrt(np.mean(cal.loo_error**2)))
    rep = "" if cal.scatter_repeat is None else f" and {cal.scatter_repeat:.2f} between repeats"
    verdict = (
        "every roll left out is predicted within its allowance"
        if cal.predicts
        else "NOT every roll left out is predicted within its allowance"
    )
    return (
        f"the fit finds {value:.2f} +- {se:.2f} mm (1 SE), the scatter {cal.scatter_fit:.2f} Rho "
        f"about the fit{rep}, and {verdict} (leave-one-out RMS {rms:.2f} Rho; {cal.runs} full "
        "model runs)"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "head_models": head_models,
    "head_length": head_length,
    "rolls_move": rolls_move,
    "site_example": site_example,
    "head3d_cost": head3d_cost,
}
