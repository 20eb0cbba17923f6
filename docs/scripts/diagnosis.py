"""Generators of docs/diagnosis.md's numbers (docs/scripts/regenerate.py runs them): the
example sentence (``woundroll diagnose pet1-26.7N --readings
examples/data/readings_rho_3passes.csv``) and the accuracy of the inversion as
tests/test_diagnosis.py measures it (its round trips, coverage and smoothness problems,
imported from the test module), on today's defaults. Cost: about 120 full forward runs
(contact solve and impact each), a few minutes on a quiet 2-core machine."""

from __future__ import annotations

import importlib.util
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

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


def _test_module(name: str) -> Any:
    """tests/<name>.py as a module: the page shows the tests' own problems."""
    path = ROOT / "tests" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"docs_{name}", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@cache
def _tests() -> Any:
    """tests/test_diagnosis.py as a module."""
    return _test_module("test_diagnosis")


@cache
def _causes_tests() -> Any:
    """tests/test_causes.py as a module."""
    return _test_module("test_causes")


def midpoints() -> str:
    """test_interpolant_against_full_forward_runs_at_midpoints: the interpolant on the
    unrefined factor-2 grid against full runs at the geometric midpoints (PET1 26.7 N)."""
    import numpy as np

    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel, forward_curve

    model = RollModel.from_case(load_case("pet1-26.7N"))
    curve = forward_curve(model)
    mids = np.sqrt(curve.web_stress[1:] * curve.web_stress[:-1])
    full = np.array([model.evaluate(t).reading for t in mids])
    err = np.abs(curve.reading_at(mids) - full)
    return (
        f"within {err.max():.2f} Rho over {full.min():.0f}-{full.max():.0f} Rho (PET1 26.7 N, "
        f"{len(curve.web_stress)} forward runs at factors "
        f"{curve.web_stress[0] / model.tension:.3g}-{curve.web_stress[-1] / model.tension:.3g})"
    )


def smoothness() -> str:
    """test_forward_chain_is_smooth_in_the_tension: steps of the reading per 1 % of tension
    near 1.65 x and 0.825 x (PET1 40 N, 30 % linear taper)."""
    import numpy as np

    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel

    case = load_case("pet1-40N", ["winding.taper.kind='linear'", "winding.taper.fraction=0.3"])
    model = RollModel.from_case(case)
    out = []
    for factors in ([1.64, 1.65, 1.66, 1.67], [0.81, 0.82, 0.83, 0.84]):
        rho = np.array([model.evaluate(f * model.tension).reading for f in factors])
        steps = np.diff(rho)
        out.append(
            f"{steps.min():.3f}-{steps.max():.3f} Rho per 1 % over {factors[0]:.2f}-"
            f"{factors[-1]:.2f} x (largest departure from the mean step "
            f"{np.max(np.abs(steps - steps.mean())):.3f} Rho)"
        )
    return "; ".join(out)


def round_trips() -> str:
    """_round_trip of tests/test_diagnosis.py on its four rolls: the largest relative error
    of the recovered tension."""
    from woundroll.case import load_case
    from woundroll.errors import InputError

    t = _tests()
    cases = [("PET1 26.7 N, Rho", load_case("pet1-26.7N"), 1.3, "Rho")]
    cases.append(("PET2 53.4 N, g", load_case("pet2-53.4N"), 0.7, "g"))
    taper = ["winding.taper.kind='linear'", "winding.taper.fraction=0.3"]
    cases.append(("PET1 40 N, taper", load_case("pet1-40N", taper), 1.6, "Rho"))
    nip = load_case("pet3-2.3MPa", ["winding.nip_load='5 pli'", "winding.friction=0.2"])
    nip = nip.model_copy(
        update={"winding": nip.winding.model_copy(update={"thickness_profile": None})}
    )
    cases.append(("PET3 with nip, g", nip, 2.5, "g"))
    cells = []
    for label, case, factor, scale in cases:
        model = t.RollModel.from_case(case, scale)
        t_true = factor * model.tension
        try:
            d, _truth = t._round_trip(case, factor, scale)
        except InputError:  # the readings are beyond the instrument's scale
            reading = model.evaluate(t_true).reading
            cells.append(
                f"{label} at {factor:g} x: reads {reading:.0f} {scale}, beyond the scale "
                "(no round trip)"
            )
            continue
        err = max(abs(w / t_true - 1) for w in d.web_tension)
        cells.append(f"{label} at {factor:g} x: {100 * err:.2f} %")
    return "; ".join(cells)


def coverage() -> str:
    """test_interval_coverage_on_synthetic_scatter and ..._with_material_uncertainty."""
    from dataclasses import replace

    import numpy as np

    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel, diagnose

    t = _tests()
    case = load_case("pet1-26.7N")
    model = RollModel.from_case(case)
    t_true = 1.2 * model.tension
    truth = model.evaluate(t_true)
    d = diagnose(case, t._coverage_readings([truth.reading] * 200, 3, 1.5, 7), verify=False)
    c95 = np.mean((d.web_tension_low < t_true) & (t_true < d.web_tension_high))
    d80 = diagnose(
        case, t._coverage_readings([truth.reading] * 200, 3, 1.5, 7), confidence=0.8, verify=False
    )
    c80 = np.mean((d80.web_tension_low < t_true) & (t_true < d80.web_tension_high))
    case_m = load_case("pet1-26.7N", ["uncertainty.K2=6"])
    model_m = RollModel.from_case(case_m)
    rng = np.random.default_rng(11)
    law = model_m.web.radial_modulus
    truths = [
        model_m.with_web(
            replace(
                model_m.web, radial_modulus=replace(law, K2=law.K2 + 6.0 * rng.standard_normal())
            )
        )
        .evaluate(t_true)
        .reading
        for _ in range(60)
    ]
    readings = t._coverage_readings(truths, 3, 1.0, 5)
    dm = diagnose(case_m, readings, verify=False)
    cm = np.mean((dm.web_tension_low < t_true) & (t_true < dm.web_tension_high))
    ds = diagnose(case, readings, verify=False)
    cs = np.mean((ds.web_tension_low < t_true) & (t_true < ds.web_tension_high))
    return (
        f"PET1 26.7 N, true tension 1.2 x the case's, reading {truth.reading:.1f} Rho from the "
        "full chain. Scatter only: 200 positions of 3 readings with normal scatter SD 1.5 Rho; "
        f"the 95 % interval holds the true tension at {100 * c95:.1f} % of them, the 80 % "
        f"interval at {100 * c80:.1f} % (binomial SD 1.5 % and 2.8 % over 200). With material "
        f"uncertainty: 60 positions, each a roll of its own K2 drawn from N({law.K2:.1f}, 6^2), "
        f"3 readings each with SD 1 Rho (spread of the true readings {np.std(truths):.1f} Rho): "
        f"the combined 95 % interval (`[uncertainty] K2 = 6`) holds the true tension at "
        f"{100 * cm:.1f} %; the scatter-only interval of the same readings at {100 * cs:.1f} %"
    )


def causes_round_trip() -> str:
    """tests/test_causes.py::test_round_trip_thickness_bands_and_tension: the fit's sentences,
    the recovered tension and the thickness error."""
    import numpy as np

    roll, m, theta, fit = _causes_tests().band_round_trip()
    zz, hf, _ = fit.thickness_profile()
    ht = m.thickness(theta[1:], zz)
    err = np.max(np.abs(hf - ht)) / roll.web.thickness
    said = "; ".join(f'"{c["sentence"]}"' for c in fit.causes[:3])
    return (
        f"{said}; the fitted thickness within {100 * err:.2f} % of h of the truth everywhere, "
        f"{fit.forward_runs} forward runs"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "sentence": sentence,
    "midpoints": midpoints,
    "smoothness": smoothness,
    "round_trips": round_trips,
    "coverage": coverage,
    "causes_round_trip": causes_round_trip,
}
