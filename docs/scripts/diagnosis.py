"""Generators of docs/diagnosis.md's numbers (docs/scripts/regenerate.py runs them): the
example sentence (``woundroll diagnose pet1-26.7N --readings
examples/data/readings_rho_3passes.csv``) and the accuracy of the inversion as
tests/test_diagnosis.py measures it (its round trips, coverage and smoothness problems,
imported from the test module), on today's defaults. Cost: about 120 full forward runs
(contact solve and impact each), a few minutes on a quiet 2-core machine."""

from __future__ import annotations

from collections.abc import Callable
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
    """tests/<name>.py as a module (records.test_module): the page shows the tests' own
    problems."""
    import records

    return records.test_module(f"{name}.py")


def _tests() -> Any:
    """tests/test_diagnosis.py as a module."""
    return _test_module("test_diagnosis")


def _causes_tests() -> Any:
    """tests/test_causes.py as a module."""
    return _test_module("test_causes")


def softer_message() -> str:
    """test_sentence_beyond_the_chain_says_softer's message: a reading 5 Rho below the
    slackest run (1/64 of a 1.75 MPa set point) of the test's synthetic chain (Rho = 50 +
    10 ln(T / 1 MPa)); cheap: no forward run."""
    import math

    from woundroll.inverse.diagnosis import RollModel, diagnose
    from woundroll.io.readings import readings_from_arrays

    t = _tests()
    case = t._sentence_case("1.75 MPa")
    r_min = 50 + 10 * math.log(1.75e6 / 64 / 1e6)
    real = RollModel.evaluate
    RollModel.evaluate = t._fake_evaluate  # the test's fake_chain fixture
    try:
        d = diagnose(case, readings_from_arrays([0.05], [r_min - 5]), verify=False)
    finally:
        RollModel.evaluate = real
    return f"`{d.sentence()}`"


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


# ---------------------------------------------------------------------------------------
# negative hoop stress on the PET rolls (live: a dozen 1D windings)


def _wind(name: str, sets: tuple[str, ...] = ()) -> Any:
    """The case's 1D winding (as ``woundroll run`` winds it), with its web."""
    from woundroll.case import load_case
    from woundroll.winding.hakiel import WindingOptions, wind

    case = load_case(name, list(sets))
    web, core = case.web.build(), case.core.build()
    w = wind(
        web,
        core,
        case.winding.final_radius(web, core),
        case.winding.schedule(web),
        options=WindingOptions.from_dict(case.winding.options, "winding.options"),
    )
    return w, web


def _hoop_min(name: str, sets: tuple[str, ...] = ()) -> float:
    """The smallest layer-mean hoop stress [Pa]."""
    return float(_wind(name, sets)[0].layer_mean_hoop_stress()[1].min())


def _taper(kind: str, fraction: float) -> tuple[str, ...]:
    return (f"winding.taper.kind='{kind}'", f"winding.taper.fraction={fraction}")


def parotester_readout() -> str:
    """The Rho-meter's striker read out as a Parotester L on PET1 26.7 N at 1/4-4 times the
    tension: the curve the inversion refuses (not monotone)."""
    import numpy as np

    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel

    model = RollModel.from_case(load_case("pet1-26.7N", ["tester.readout='parotester-l'"]))
    ls = np.array([model.evaluate(f * model.tension).reading for f in (0.25, 0.5, 1, 2, 4)])
    mono = bool(np.all(np.diff(ls) > 0) or np.all(np.diff(ls) < 0))
    return (
        f"L stays at {ls.mean():.0f} +- {np.ptp(ls) / 2:.1g} over 1/4 ... 4 times the tension"
        f"{'' if not mono else ' (monotone on these five points)'}"
    )


def negative_hoop() -> str:
    """The first paragraph's numbers: PET1 26.7 N untapered, refined, elastic new layer,
    tapered; PET2 53.4 N."""
    import numpy as np

    w, web = _wind("pet1-26.7N")
    r, hoop = w.layer_mean_hoop_stress()
    k = int(np.argmin(hoop))
    neg = r[hoop < 0]
    wot = float(w.wot[-1])
    p = -np.asarray(w.sigma_r)
    law = web.radial_modulus
    e_r = np.asarray(law.modulus_at_pressure(np.clip(p, 0, None)))
    fine = _hoop_min("pet1-26.7N", ("winding.options.subdivisions=4",))
    elastic = _hoop_min("pet1-26.7N", ("winding.options.new_layer='elastic'",))
    lin90 = _hoop_min("pet1-26.7N", _taper("linear", 0.9))
    lin60 = _hoop_min("pet1-26.7N", _taper("linear", 0.6))
    pet2 = _hoop_min("pet2-53.4N")
    pet2h = _hoop_min("pet2-53.4N", _taper("hyperbolic", 0.9))
    return (
        f"{hoop[k] / 1e3:.1f} kPa at its lowest (r = {100 * r[k]:.1f} cm), negative on r = "
        f"{100 * neg.min():.1f}-{100 * neg.max():.1f} cm, against a wound-on tension of "
        f"{wot / 1e6:.2f} MPa ({100 * abs(hoop[k]) / wot:.1f} %). It is not numerical: 2 and 4 "
        f"sub-layer elements give {hoop[k] / 1e3:.2f} and {fine / 1e3:.2f} kPa. It is what "
        "Hakiel's model does with a radial modulus far below the hoop one (E_r = K2 (K1 + P) is "
        f"{e_r.min() / 1e6:.2g}-{e_r.max() / 1e6:.2g} MPa here, E_theta "
        f"{web.E_theta / 1e9:.2g} GPa): each later layer compresses the pile, the layers beneath "
        "move inward and lose the strain they were wound with. Its size depends on how a new "
        "layer enters the model (the `new_layer` assumption, docs/assumptions.md: "
        f"{hoop[k] / 1e3:.0f} kPa laid on, {elastic / 1e3:.0f} kPa as Hakiel's elastic boundary "
        f"condition). A strong taper reduces it: at the case's tension a linear taper of 90 % "
        f"leaves {lin90 / 1e3:+.1f} kPa, 60 % {lin60 / 1e3:+.1f} kPa (PET2 53.4 N: "
        f"{pet2 / 1e3:.0f} kPa untapered, {pet2h / 1e3:+.1f} kPa with a hyperbolic 90 % taper)"
    )


def buckling() -> str:
    """The buckling estimate against the compression on PET1 26.7 N (the defects report)."""
    from woundroll.assess.defects import defect_report
    from woundroll.case import load_case

    rep = defect_report(load_case("pet1-26.7N"))
    b = next(c for c in rep.roll if c.name == "buckling")
    return f"{-abs(b.demand) / 1e3:.0f} kPa against a critical {b.capacity / 1e6:.0f} MPa"


# ---------------------------------------------------------------------------------------
# measured records (docs/scripts/records.py): the studies too slow for every docs check


def _records() -> Any:
    import records

    return records


#: the design table's rows: (run id, case, CLI arguments of ``woundroll design``)
DESIGNS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    (
        "pet1_hyperbolic",
        "pet1-26.7N",
        ("--target", "55 Rho", "--pressure", "10 kPa..200 kPa", "--tension", "0.5 pli..4 pli",
         "--taper", "hyperbolic", "--max-taper", "0.9"),
    ),
    (
        "pet1_table",
        "pet1-26.7N",
        ("--target", "55 Rho", "--pressure", "10 kPa..200 kPa", "--tension", "0.5 pli..4 pli",
         "--taper", "table", "--max-taper", "0.9"),
    ),
    (
        "pet2_linear",
        "pet2-53.4N",
        ("--target", "30 Rho", "--pressure", "20 kPa..400 kPa", "--tension", "1 pli..8 pli",
         "--taper", "linear", "--max-taper", "0.6"),
    ),
    (
        "pet2_negative_hoop",
        "pet2-53.4N",
        ("--target", "30 Rho", "--pressure", "10 kPa..400 kPa", "--tension", "1 pli..8 pli",
         "--taper", "linear", "--max-taper", "0.6", "--allow-negative-hoop"),
    ),
    (
        "pet3_hyperbolic",
        "pet3-2.3MPa-nip",
        ("--target", "110 Rho", "--pressure", "20 kPa..600 kPa", "--tension", "1 pli..6 pli",
         "--nip", "0 pli..5 pli", "--taper", "hyperbolic", "--max-taper", "0.9"),
    ),
    (
        "pet3_table",
        "pet3-2.3MPa-nip",
        ("--target", "110 Rho", "--pressure", "20 kPa..600 kPa", "--tension", "1 pli..6 pli",
         "--nip", "0 pli..5 pli", "--taper", "table", "--max-taper", "0.9"),
    ),
)  # fmt: skip


def _design_runs() -> list[Any]:
    Run = _records().Run
    return [Run(rid, case, (), (("args", list(args)),)) for rid, case, args in DESIGNS]


def _design_measure(run: Any) -> dict[str, Any]:
    """``woundroll design CASE ARGS --json`` (the CLI itself): the numbers of the table."""
    import json

    from typer.testing import CliRunner

    from woundroll.app.cli import app

    res = CliRunner().invoke(app, ["design", run.case, *run.param("args"), "--json"])
    if res.exit_code != 0:
        raise SystemExit(f"woundroll design {run.case}: exit {res.exit_code}: {res.output}")
    d = json.loads(res.output)["design"]
    s, m = d["setpoints"], d["margins"]
    out: dict[str, Any] = {
        "feasible": d["feasible"],
        "binding": d["binding_constraint"] or "",
        "slack": d["slacks"][d["binding_constraint"]] if d["binding_constraint"] else 0.0,
        "relaxation": d["relaxations"][0]["sentence"] if d["relaxations"] else "",
        "tension_pli": s["web_tension_pli"],
        "tension_MPa": s["web_tension_Pa"] / 1e6,
        "taper_kind": s["taper_kind"],
        "taper_fraction": s["taper_fraction"],
        "nip_pli": s["nip_load_pli"],
        "reading": d["reading"],
        "pressure_min_kPa": m["min_pressure_Pa"] / 1e3,
        "pressure_max_kPa": m["max_pressure_Pa"] / 1e3,
        "hoop_min_kPa": m["min_hoop_stress_Pa"] / 1e3,
        "full_runs": float(d["full_forward_runs"]),
        "knots": float(len(s.get("table", []))),
    }
    for k, row in enumerate(s.get("table", [])):
        out[f"table_pli_{k}"] = row["web_tension_pli"]
        out[f"table_diameter_cm_{k}"] = 100 * row["diameter_m"]
    return out


def _uncertainty_tests() -> Any:
    """tests/test_uncertainty.py as a module."""
    return _test_module("test_uncertainty")


def _uncertainty_runs() -> list[Any]:
    Run = _records().Run
    t = _uncertainty_tests()
    sens = tuple(t.SENSITIVITY_SETS)
    return [
        Run("surrogate", "pet1-26.7N", tuple(t.SURROGATE_SETS)),
        Run("profile_brute", "pet3-2.3MPa", tuple(t.BRUTE_SETS)),
        Run("sensitivity_pet3", "pet3-2.3MPa", sens, (("minus_half", True),)),
        Run("sensitivity_pet3_nip", "pet3-2.3MPa-nip", sens),
    ]


def _uncertainty_measure(run: Any) -> dict[str, Any]:
    """The uncertainty section's checks, each on its test's own problem."""
    import numpy as np

    t = _uncertainty_tests()
    if run.id == "surrogate":
        res = t.surrogate_against_full_runs()
        checks = res.surrogate["checks"]
        full = np.array([c["reading_full"] for c in checks])
        return {
            "max_error": max(abs(c["reading_full"] - c["reading_surrogate"]) for c in checks),
            "sd_surrogate": float(np.std(res.reading[: len(checks)])),
            "sd_full": float(np.std(full)),
            "full_runs": float(len(checks)),
        }
    if run.id == "profile_brute":
        bands, brute = t.profile_band_against_brute_force()
        inside = ~np.array(bands["outside_curve"])
        sd = brute.std(axis=0, ddof=1)[inside]
        err = np.abs(bands["_samples"] - brute)[:, inside]
        lo, hi = np.percentile(brute, [2.5, 97.5], axis=0)
        pct = max(
            np.max(np.abs(np.array(bands["reading_low"])[inside] - lo[inside])),
            np.max(np.abs(np.array(bands["reading_high"])[inside] - hi[inside])),
        )
        return {
            "max_error": float(err.max()),
            "sd_min": float(sd.min()),
            "sd_max": float(sd.max()),
            "sd_rel_diff": float(np.max(np.abs(np.array(bands["reading_sd"])[inside] / sd - 1))),
            "percentile_diff": float(pct),
            "sectors_inside": float(inside.sum()),
        }
    name = run.case
    s = t.profile_band_sensitivity(name, minus_half=bool(run.param("minus_half", False)))
    out: dict[str, Any] = {"sectors": float(len(s["z"]))}
    for k in range(len(s["z"])):
        out[f"z_m_{k}"] = float(s["z"][k])
        out[f"reduced_{k}"] = float(s["a_reduced"][k])
        out[f"calibrated_{k}"] = float(s["a"][k])
        out[f"full_{k}"] = float(s["full"][k])
        out[f"minus_predicted_{k}"] = float(-2 * s["a"][k] + 2 * s["b"][k])
        out[f"minus_full_{k}"] = float(s["minus"][k])
        out[f"plus_full_{k}"] = float(s["calibration"]["full_change"][k])
        if "minus_half" in s:
            out[f"half_predicted_{k}"] = float(s["pred2_half"][k])
            out[f"half_full_{k}"] = float(s["minus_half"][k])
    return out


#: the causes round trip against the full profile model (tests/test_causes.py)
CAUSES_SETS = ("web.width='24 in'", "profile.workers=1")


#: the noise draws of the study (draw 0 is the slow test's problem)
CAUSES_DRAWS = 30
#: shared between the draws measured in one process: the truth's full profile run, and the
#: fit's forward curve and starting Jacobian (draw 0's: tests/test_causes.py)
_CAUSES_CACHE: dict[str, Any] = {}


def _causes_runs() -> list[Any]:
    Run = _records().Run
    return [Run(f"draw{k}", "pet2-53.4N", CAUSES_SETS, (("draw", k),)) for k in range(CAUSES_DRAWS)]


def _causes_measure(run: Any) -> dict[str, Any]:
    """test_round_trip_against_the_full_profile_model on noise draw ``draw``: its fit, the
    level's path through the three full-model corrections, the band amplitudes, the
    thickness error and the posterior's coverage of it (raw and Birge-scaled), and (draw 0
    only) the contact check."""
    import math
    import tempfile

    import numpy as np

    k = int(run.param("draw"))
    cache = _CAUSES_CACHE
    cached = "curve" in cache or k != 0  # the start comes from the cache (draw 0's)
    with tempfile.TemporaryDirectory() as tmp:
        fit, m, c = _causes_tests().full_profile_round_trip(
            Path(tmp), seed=k, cache=cache, verify=k == 0
        )
    zz, hf, hsd = fit.thickness_profile()
    ht = m.thickness(c, zz)
    h0 = m.base_thickness[0]
    err = np.abs(hf - ht)
    level = fit.verification["full_level"]
    npar = len(fit.theta)
    start = 0 if cached else len(fit.model.curve.points) + 1 + npar
    reduced = fit.forward_runs - level["full_runs"] - (3 if k == 0 else 0) - start
    bands = fit.theta[1:]
    out: dict[str, Any] = {
        f"level_{j}": 100 * math.exp(v) for j, v in enumerate(level["ln_s_levels"])
    }
    out |= {
        "levels": float(len(level["ln_s_levels"])),
        "thickness_error": 100 * float(err.max() / h0),
        "thickness_cover": float(np.mean(err < 1.96 * hsd)),
        "thickness_cover_raw": float(np.mean(err < 1.96 * hsd / fit.sd_scale)),
        "thickness_error_sds": float(np.mean(err / hsd)),
        "band_mean_removed": [100 * float(b - bands.mean()) for b in bands],
        "truth_mean_removed": [100 * float(b - c.mean()) for b in c],
        "sd_scale": float(fit.sd_scale),
        "level_sd": 100 * float(fit.sd[0]),
        "relinearised": reduced > 3,  # a first pass takes <= 3 runs, a second 7 + <= 3
        "causes": [cz["cause"] for cz in fit.causes],
        "cause_0": fit.causes[0]["sentence"],
        "cause_1": fit.causes[1]["sentence"],
        "_reduced_runs": float(reduced),
    }
    if k == 0:
        out["contact_check"] = float(fit.verification["max_abs_error"])
    return out


def _reduced_runs() -> list[Any]:
    return [_records().Run("table3", "pet3-2.3MPa", ("profile.sectors=31",))]


def _reduced_measure(run: Any) -> dict[str, Any]:
    """The reduced profile model's near-surface pressures (uncoupled sectors) against the
    coupled (r, z) winding's on the bundled Table 3 profile, and their wall times."""
    import time

    import numpy as np

    from woundroll.assess.uncertainty import reduced_profile
    from woundroll.case import load_case
    from woundroll.inverse.diagnosis import RollModel

    case = load_case(run.case, list(run.overrides))
    model = RollModel.from_case(case)
    n = case.profile.sectors
    t0 = time.perf_counter()
    _, red = reduced_profile(case, model, None, {}, {}, n, pressure=True)
    t1 = time.perf_counter()
    _, cpl = reduced_profile(case, model, None, {}, {}, n, pressure=True, coupled=True)
    t2 = time.perf_counter()
    k = int(np.argmax(red))
    return {
        "sectors": float(n),
        "correlation": float(np.corrcoef(red, cpl)[0, 1]),
        "rms_rel": float(np.sqrt(np.mean((red - cpl) ** 2)) / np.mean(cpl)),
        "min_kPa": float(min(red.min(), cpl.min()) / 1e3),
        "max_kPa": float(max(red.max(), cpl.max()) / 1e3),
        "peak_reduced_kPa": float(red[k] / 1e3),
        "peak_coupled_kPa": float(cpl[k] / 1e3),
        "_wall_ratio": (t2 - t1) / (t1 - t0),
    }


def reduced_check() -> str:
    """The reduced model against the coupled winding on Table 3 (record reduced_model)."""
    r = _records().results("diagnosis.reduced_model")["table3"]
    return (
        f"the sector-to-sector pattern of `P_s` correlates at {r['correlation']:.3f} with the "
        f"coupled (r, z) model's, the RMS difference is {100 * r['rms_rel']:.0f} % of the mean "
        f"over a profile that runs from {max(r['min_kPa'], 0.0):.0f} to {r['max_kPa']:.0f} kPa "
        f"(at the reduced model's highest sector {r['peak_reduced_kPa']:.0f} kPa against "
        f"{r['peak_coupled_kPa']:.0f} kPa coupled); the coupled winding took "
        f"{r['_wall_ratio']:.0f} times as long in the same run "
        f"({_measured('diagnosis.reduced_model')})"
    )


def _nip_runs() -> list[Any]:
    return [_records().Run("pet2_nip", "pet2-53.4N", tuple(_causes_tests().NIP_SETS))]


def _nip_measure(run: Any) -> dict[str, Any]:
    """test_nip_deflection_on_a_soft_web_is_reported_not_identifiable's fit."""
    import numpy as np

    fit, roll, truth = _causes_tests().nip_deflection_fit()
    _, h, _ = fit.thickness_profile()
    bands = [k for k, n in enumerate(fit.names) if n.startswith("band")]
    z = [abs(fit.theta[k]) / fit.sd[k] for k in bands]
    k = bands[int(np.argmax(z))]
    return {
        "reading_change": float(np.ptp(truth)),
        "deflection_sd": float(fit.sd[1]),
        "deflection_prior_sd": float(fit.prior_sd[1]),
        "deflection_identifiable": bool(fit.identifiable[1]),
        "band_max": 100 * float(np.max(np.abs(h / roll.web.thickness - 1))),
        "band_most_sds": float(max(z)),
        "band_most_value": 100 * float(fit.theta[k]),
    }


def nip_check() -> str:
    """The nip-deflection paragraph's numbers (record nip_deflection)."""
    r = _records().results("diagnosis.nip_deflection")["pet2_nip"]
    said = "not identifiable" if not r["deflection_identifiable"] else "IDENTIFIABLE"
    return (
        f"changes the readings by only {r['reading_change']:.2f} Rho in the uncoupled-sector "
        "model: the lanes with more nip-induced tension compress more, build a smaller radius "
        "and are allocated less web tension by the relaxation-radius rule. The fit reports the "
        f"deflection as {said} (posterior SD {r['deflection_sd']:.3f} against the prior "
        f"{r['deflection_prior_sd']:g}) and the bands fitted to 0.3 Rho noise stay below "
        f"{r['band_max']:.2f} % caliper; the one furthest from zero "
        f"({r['band_most_value']:+.2f} %) sits at {r['band_most_sds']:.1f} posterior SDs "
        f"({_measured('diagnosis.nip_deflection')})"
    )


def _measured(name: str) -> str:
    """'measured DATE by `docs/scripts/records.py NAME` (load L on 2 cores)' of a record."""
    rec = _records().load(name)
    return (
        f"measured {rec['measured']} by `docs/scripts/records.py {name}`, load average "
        f"{rec['load_1min']:g}"
    )


def _design_text(r: dict[str, Any], cpu: float | None, nip: bool) -> str:
    """One design's result as the table's cell."""
    from woundroll.inverse.design import _LABELS

    out = "feasible" if r["feasible"] else "infeasible"
    if r["binding"]:
        out += f", binding: {_LABELS.get(r['binding'], r['binding'])} (slack {r['slack']:+.2g})"
    n = int(r["knots"])
    if n:
        pli = " / ".join(f"{r[f'table_pli_{k}']:.2f}" for k in range(n))
        dia = " / ".join(f"{r[f'table_diameter_cm_{k}']:.1f}" for k in range(n))
        out += f": core {r['tension_pli']:.2f} pli, table {pli} pli at {dia} cm diameter"
    else:
        taper = (
            f"{r['taper_kind']} {100 * r['taper_fraction']:.0f} %"
            if r["taper_fraction"] > 0
            else "no taper"
        )
        out += f": {r['tension_pli']:.3g} pli ({r['tension_MPa']:.3g} MPa), {taper}"
    if nip:
        out += f", nip {r['nip_pli']:.2g} pli"
    out += (
        f", {r['reading']:.1f} Rho, {r['pressure_min_kPa']:.0f}-{r['pressure_max_kPa']:.0f} kPa, "
        f"smallest hoop stress {r['hoop_min_kPa']:+.3g} kPa"
    )
    if not r["feasible"] and r["relaxation"]:
        out += f"; to make it feasible: {r['relaxation']}"
    out += f". {r['full_runs']:.0f} full forward runs"
    if cpu is not None:
        out += f", {cpu:.0f} s CPU"
    return out


def design_table() -> str:
    """The design table from the record diagnosis.design."""
    rec = _records().load("diagnosis.design")
    res, cpu = rec["runs"], rec.get("cpu_s", {})

    def cell(rid: str, nip: bool = False) -> str:
        return _design_text(res[rid], cpu.get(rid), nip)

    hyp, tab = res["pet1_hyperbolic"], res["pet1_table"]
    hyp3, tab3 = res["pet3_hyperbolic"], res["pet3_table"]
    pet1_cmp = (
        f"the table's compression is {tab['hoop_min_kPa'] / hyp['hoop_min_kPa']:.2f} of the "
        "hyperbolic taper's within the same window"
    )
    pet3_cmp = (
        f"the table's smallest hoop stress is {tab3['hoop_min_kPa'] / hyp3['hoop_min_kPa']:.2g} "
        "times the hyperbolic design's"
    )
    rows = [
        f"On the bundled cases ({_measured('diagnosis.design')}; CPU times, as the machine is "
        "shared):",
        "",
        "| case | target and limits | result |",
        "|---|---|---|",
        "| `pet1-26.7N` | 55 Rho, 10-200 kPa, 0.5-4 pli, hyperbolic <= 90 % | "
        f"{cell('pet1_hyperbolic')} |",
        "| `pet1-26.7N` | the same, `--taper table --max-taper 0.9` (4 knots) | "
        f"{cell('pet1_table')}: {pet1_cmp} |",
        "| `pet2-53.4N` | 30 Rho, 20-400 kPa, 1-8 pli, linear <= 60 % | "
        f"{cell('pet2_linear')}; with `--allow-negative-hoop` and 10-400 kPa: "
        f"{cell('pet2_negative_hoop')} |",
        "| `pet3-2.3MPa-nip` | 110 Rho, 20-600 kPa, 1-6 pli, nip 0-5 pli, hyperbolic <= 90 % | "
        f"{cell('pet3_hyperbolic', True)} |",
        "| `pet3-2.3MPa-nip` | the same, `--taper table --max-taper 0.9` (4 knots) | "
        f"{cell('pet3_table', True)}: {pet3_cmp} |",
    ]
    return "\n".join(rows)


def causes_level() -> str:
    """The full-model level correction on the first noise draw (record causes_full)."""
    import math

    rec = _records().load("diagnosis.causes_full")
    r = rec["runs"]["draw0"]
    lv = [r[f"level_{k}"] for k in range(int(r["levels"]))]

    def err(x: float) -> str:
        return f"{100 * abs(math.log(x / 110)):.1f} %"

    path = " -> ".join(f"{x:.0f} %" for x in lv[:-1]) + f" -> **{lv[-1]:.1f} %**"
    two = f"; with two runs {lv[2]:.0f} %, {err(lv[2])}" if len(lv) > 3 else ""
    cpu = rec.get("cpu_s", {}).get("draw0")
    cost = (
        f"; the whole round trip, the truth's and three correcting full runs and the fit, "
        f"{cpu:.0f} s CPU"
        if cpu
        else ""
    )
    return (
        f"{path} (truth 110 %: the level error from {err(lv[0])} down to {err(lv[-1])} in "
        f"ln s{two}{cost}; {_measured('diagnosis.causes_full')})"
    )


#: the true tension level of the causes round trip [% of the case's] (tests/test_causes.py)
CAUSES_TRUTH = 110.0


def _study() -> dict[str, Any] | None:
    """The 30-draw study's numbers from the record causes_full (None while incomplete)."""
    import math

    import numpy as np

    rec = _records().load("diagnosis.causes_full")
    draws = [rec["runs"][r.id] for r in _causes_runs() if r.id in rec["runs"]]
    if len(draws) < CAUSES_DRAWS:
        return None
    truth = math.log(CAUSES_TRUTH)

    def level(d: dict[str, Any], last: bool) -> float:
        return d[f"level_{int(d['levels']) - 1}"] if last else d["level_0"]

    out: dict[str, Any] = {"n": len(draws), "rec": rec}
    for key, last in (("reduced", False), ("full", True)):
        ln = np.log([level(d, last) for d in draws])
        sd = np.array([d["level_sd"] / 100 for d in draws])
        raw = sd / np.array([d["sd_scale"] for d in draws])
        out[key] = {
            "mean": float(np.mean(np.exp(ln))),
            "spread": 100 * float(np.std(ln, ddof=1)),
            "bias": 100 * float(np.mean(ln) - truth),
            "sd_raw": 100 * float(np.mean(raw)),
            "sd": 100 * float(np.mean(sd)),
            "cover_raw": 100 * float(np.mean(np.abs(ln - truth) < 1.96 * raw)),
            "cover": 100 * float(np.mean(np.abs(ln - truth) < 1.96 * sd)),
            "own_raw": 100 * float(np.mean(np.abs(ln - ln.mean()) < 1.96 * raw)),
            "own": 100 * float(np.mean(np.abs(ln - ln.mean()) < 1.96 * sd)),
        }
    bands = np.array([d["band_mean_removed"] for d in draws])
    t = draws[0]["truth_mean_removed"]
    k_thick, k_thin = int(np.argmax(t)), int(np.argmin(t))
    for kind, k in (("thick", k_thick), ("thin", k_thin)):
        out[kind] = (t[k], float(bands[:, k].mean()), float(bands[:, k].std(ddof=1)))
    for kind in ("thick", "thin"):
        names: dict[str, int] = {}
        for d in draws:
            for c in d["causes"]:
                if c.startswith(kind + " band"):
                    names[c] = names.get(c, 0) + 1
                    break
            else:
                names["none"] = names.get("none", 0) + 1
        out[f"{kind}_names"] = sorted(names.items(), key=lambda kv: -kv[1])
    err = np.array([d["thickness_error"] for d in draws])
    out["h_err"] = (float(err.mean()), float(err.max()))
    out["h_cover_raw"] = 100 * float(np.mean([d["thickness_cover_raw"] for d in draws]))
    out["h_cover"] = 100 * float(np.mean([d["thickness_cover"] for d in draws]))
    out["h_sds"] = float(np.mean([d["thickness_error_sds"] for d in draws]))
    out["scale"] = float(np.mean([d["sd_scale"] for d in draws]))
    out["scaled"] = sum(d["sd_scale"] > 1 for d in draws)
    out["relin"] = sum(bool(d["relinearised"]) for d in draws)
    cpu = rec.get("cpu_s", {})
    out["cpu_min"] = sum(cpu.values()) / 60
    out["cpu_draw"] = (min(cpu[f"draw{k}"] for k in range(1, len(draws))),
                       max(cpu[f"draw{k}"] for k in range(1, len(draws))))  # fmt: skip
    return out


def _incomplete() -> str:
    rec = _records().load("diagnosis.causes_full")
    return (
        f"(the record diagnosis.causes_full holds {len(rec['runs'])} of {CAUSES_DRAWS} draws: "
        "run `docs/scripts/records.py diagnosis.causes_full` to finish it)"
    )


def _names(pairs: list[tuple[str, int]], n: int) -> str:
    """'always named "thick band 8-12 in"' or the names with their counts."""
    if len(pairs) == 1:
        return f'always named "{pairs[0][0]}"'

    def times(k: int) -> str:
        return "once" if k == 1 else "twice" if k == 2 else f"{k} times"

    return "named " + ", ".join(
        (f'"{name}" {times(k)}' if name != "none" else f"not found {times(k)}") for name, k in pairs
    )


def causes_study_intro() -> str:
    """The study's size and where it comes from (inline)."""
    st = _study()
    if st is None:
        return _incomplete()
    return (
        f"a record of {st['n']} noise draws, {_measured('diagnosis.causes_full')}, "
        f"{st['cpu_min']:.0f} CPU min: the truth's full profile run once, then "
        f"{st['cpu_draw'][0]:.0f}-{st['cpu_draw'][1]:.0f} CPU s a draw"
    )


def causes_study_table() -> str:
    """The recovered bands and level over the noise draws (record causes_full)."""
    st = _study()
    if st is None:
        return _incomplete()
    (tk, mk, sk), (tn, mn, sn) = st["thick"], st["thin"]
    red, full = st["reduced"], st["full"]
    return "\n".join(
        [
            f"| quantity | truth | recovered (mean +- SD over {st['n']} draws) |",
            "|---|---|---|",
            f"| thick band at 10 in | {tk:+.2f} % | {mk:+.2f} +- {sk:.2f} %, "
            f"{_names(st['thick_names'], st['n'])} |",
            f"| thin band at 18 in | {tn:+.2f} % | {mn:+.2f} +- {sn:.2f} %, "
            f"{_names(st['thin_names'], st['n'])} |",
            f"| fitted thickness, largest error | 0 | {st['h_err'][0]:.2f} % of h on average, "
            f"worst {st['h_err'][1]:.2f} % |",
            f"| tension level of the reduced model's fit (`full_level=0`) | {CAUSES_TRUTH:.0f} % "
            f"| {red['mean']:.1f} % +- {red['spread']:.1f} % (posterior SD {red['sd']:.1f} %) |",
            f"| tension level corrected by 3 full runs (`full_level=3`, the default) | "
            f"{CAUSES_TRUTH:.0f} % | **{full['mean']:.1f} % +- {full['spread']:.1f} %** |",
        ]
    )


def causes_study_level() -> str:
    """What the study says of the level (inline, after the table)."""
    st = _study()
    if st is None:
        return _incomplete()
    red, full = st["reduced"], st["full"]
    return (
        f"On average the reduced model's fit reads the level {red['bias']:+.1f} % off the "
        "truth in ln s: its own error against the full model, which the level absorbs; after "
        f"three full runs {full['bias']:+.1f} %, against a spread of {full['spread']:.1f} % "
        "over the draws"
    )


def causes_study_coverage() -> str:
    """The coverage table of the 95 % intervals over the draws (record causes_full)."""
    st = _study()
    if st is None:
        return _incomplete()
    red, full = st["reduced"], st["full"]

    def level(d: dict[str, Any], raw: bool) -> str:
        c, o, sd = (d["cover_raw"], d["own_raw"], d["sd_raw"]) if raw else (
            d["cover"], d["own"], d["sd"])  # fmt: skip
        return f"{c:.0f} %; about its mean {o:.0f} % (SD {sd:.2f} %)"

    return "\n".join(
        [
            f"| {st['n']} draws | tension level, the reduced fit's | the level after 3 full runs "
            "| thickness (121 points across) |",
            "|---|---|---|---|",
            f"| raw posterior | {level(red, True)} | {level(full, True)} | "
            f"{st['h_cover_raw']:.0f} % |",
            f"| Birge-scaled (mean scale {st['scale']:.2f}, above 1 in {st['scaled']} draws): "
            f"**the default** | {level(red, False)} | {level(full, False)} | "
            f"{st['h_cover']:.0f} % |",
        ]
    )


def causes_study_sds() -> str:
    """What the coverage table says (inline, after it)."""
    st = _study()
    if st is None:
        return _incomplete()
    red, full = st["reduced"], st["full"]
    import math

    def size(band: tuple[float, float, float]) -> str:
        """larger / smaller than the truth, or 'as large' within 2 standard errors."""
        t, m, sd = band
        if abs(m - t) < 2 * sd / math.sqrt(st["n"]):
            return "as large (within twice the mean's standard error)"
        return "larger" if abs(m) > abs(t) else "smaller"

    (tk, mk, _), (tn, mn, _) = st["thick"], st["thin"]
    thick, thin = size(st["thick"]), size(st["thin"])
    if thick == thin:
        bands = f"both bands {thick.split(' (')[0]} as the coupled model's".replace(
            "larger as", "larger than"
        ).replace("smaller as", "smaller than")
    else:
        bands = f"the thick band {thick}, the thin one {thin}"
    return (
        f"The level's posterior SD is {red['sd']:.2f} % on average (Birge-scaled) against a "
        f"spread over the draws of {red['spread']:.2f} % (the reduced fit) and "
        f"{full['spread']:.2f} % (after the correction); its interval holds the truth in "
        f"{red['cover']:.0f} % of the draws before the correction and {full['cover']:.0f} % "
        f"after it, the difference the reduced model's level bias ({red['bias']:+.1f} %), a "
        "model error no SD of the fit can hold. The thickness band covers "
        f"{st['h_cover']:.0f} % instead of 95 %: its errors are {st['h_sds']:.2f} times the "
        f"posterior SD on average; the band amplitudes average {mk:+.2f} % and {mn:+.2f} % "
        f"against {tk:+.2f} % and {tn:+.2f} % (the reduced model's uncoupled sectors fit "
        f"{bands} to make the coupled model's readings)"
        + (
            ""
            if thick == thin and thick.startswith("as")
            else ", a bias no rescaling of the noise covariance catches"
        )
        + ". The level moved by more than `RELINEARISE` and the Jacobian was "
        f"recomputed at the fit in {st['relin']} of {st['n']} draws"
    )


def causes_check() -> str:
    """The contact check at three sectors in the full-model round trip (record)."""
    r = _records().results("diagnosis.causes_full")["draw0"]
    return f"{r['contact_check']:.2f} Rho"


def stack_covariance() -> str:
    """tests/materials/test_stack_fit.py's covariance check: reported against observed."""
    import numpy as np

    u, k = _test_module("materials/test_stack_fit").covariance_against_refits()
    sd1, sd2 = np.std(k[:, 0], ddof=1), np.std(k[:, 1], ddof=1)
    return (
        f"reported SDs {u['K1_sd_Pa']:.0f} Pa and {u['K2_sd']:.2g} against {sd1:.0f} Pa and "
        f"{sd2:.2g} observed (the first-order covariance of a single fit is "
        f"{100 * (1 - u['K1_sd_Pa'] / sd1):.0f} and {100 * (1 - u['K2_sd'] / sd2):.0f} % low "
        f"here; the test allows 20 %), correlation {u['K1_K2_correlation']:.2f} against "
        f"{np.corrcoef(k.T)[0, 1]:.2f}"
    )


def surrogate_check() -> str:
    """The 1D reading surrogate against full runs (record diagnosis.uncertainty)."""
    r = _records().results("diagnosis.uncertainty")["surrogate"]
    return (
        f"largest error {r['max_error']:.2f} Rho, SD of the reading {r['sd_surrogate']:.2f} Rho "
        f"(surrogate) against {r['sd_full']:.2f} Rho (full runs) over the same "
        f"{r['full_runs']:.0f} samples; {_measured('diagnosis.uncertainty')}"
    )


def profile_brute() -> str:
    """The profile band's surrogate against the reduced model's brute force (record)."""
    r = _records().results("diagnosis.uncertainty")["profile_brute"]
    return (
        f"largest error per sample {r['max_error']:.2f} Rho against sector SDs of "
        f"{r['sd_min']:.1f}-{r['sd_max']:.1f} Rho (the reading is piecewise linear in `ln P_s` "
        "between the curve's points, which a quadratic smooths; the tension x caliper cross "
        f"term is dropped); the SDs agree to {100 * r['sd_rel_diff']:.1g} %, the 2.5 / 97.5 "
        f"percentiles to {r['percentile_diff']:.2f} Rho (test: 15 % of the SD, 3 %, 0.3 Rho)"
    )


def _loaded(r: dict[str, Any]) -> list[int]:
    """The sectors the sensitivity test checks: a full central sensitivity above 0.5 Rho/SD."""
    return [k for k in range(int(r["sectors"])) if abs(r[f"full_{k}"]) > 0.5]


def sensitivity_table() -> str:
    """The profile band's tension term: reduced, calibrated, full (record)."""
    import numpy as np

    res = _records().results("diagnosis.uncertainty")
    p3, nip = res["sensitivity_pet3"], res["sensitivity_pet3_nip"]
    ks = _loaded(p3)

    def row(r: dict[str, Any], key: str, fmt: str = ".2f") -> str:
        return " | ".join(f"{r[f'{key}_{k}']:{fmt}}" for k in ks)

    def pair(r: dict[str, Any], a: str, b: str, fmt: str = ".1f") -> str:
        return " | ".join(f"{r[f'{a}_{k}']:{fmt}} / {r[f'{b}_{k}']:{fmt}}" for k in ks)

    head = " | ".join(f"{p3[f'z_m_{k}']:.3f}" for k in ks)
    lines = [
        f"| case | sector z [m] | {head} |",
        "|---|---|" + "---|" * len(ks),
        f"| `pet3-2.3MPa` | reduced model, Rho per SD | {row(p3, 'reduced')} |",
        f"| | calibrated (1 run) | {row(p3, 'calibrated')} |",
        f"| | full model, central (+-10 %) | {row(p3, 'full')} |",
        f"| | change at -10 %: calibrated / full | {pair(p3, 'minus_predicted', 'minus_full')} |",
        "| | 2 runs: change at -5 %, predicted / full | "
        f"{pair(p3, 'half_predicted', 'half_full', '.2f')} |",
        f"| `pet3-2.3MPa-nip` (nip roller beam) | reduced model | {row(nip, 'reduced')} |",
        f"| | calibrated (1 run) | {row(nip, 'calibrated')} |",
        f"| | full model, central | {row(nip, 'full')} |",
        f"| | change at -10 %: calibrated / full | {pair(nip, 'minus_predicted', 'minus_full')} |",
    ]
    cal = [p3[f"calibrated_{k}"] / p3[f"full_{k}"] for k in ks]
    cal += [nip[f"calibrated_{k}"] / nip[f"full_{k}"] for k in _loaded(nip)]
    red = [p3[f"reduced_{k}"] / p3[f"full_{k}"] for k in ks]
    red += [nip[f"reduced_{k}"] / nip[f"full_{k}"] for k in _loaded(nip)]

    def rms(r: dict[str, Any], key: str) -> float:
        return float(np.sqrt(np.mean([r[f"{key}_{k}"] ** 2 for k in _loaded(r)])))

    half = max(abs(p3[f"half_predicted_{k}"] - p3[f"half_full_{k}"]) for k in ks)
    nip_c = max(abs(nip[f"calibrated_{k}"] / nip[f"full_{k}"] - 1) for k in _loaded(nip))
    nip_m = max(abs(nip[f"minus_predicted_{k}"] / nip[f"minus_full_{k}"] - 1) for k in _loaded(nip))
    edge = ks[0]
    text = (
        f"The calibrated central sensitivity is within {min(cal):.2f}-{max(cal):.2f} of the full "
        f"model's (the reduced model alone: {min(red):.2f}-{max(red):.2f}); RMS over the loaded "
        f"sectors {rms(p3, 'calibrated'):.2f} against {rms(p3, 'full'):.2f} Rho per SD on "
        f"pet3-2.3MPa (reduced alone {rms(p3, 'reduced'):.2f}). The test allows 25 % per sector, "
        "15 % on the RMS and 40 % on the change at -2 SD. The remaining error of one run is the "
        f"edge sector's skew (the full model's change is {p3[f'plus_full_{edge}']:+.1f} / "
        f"{p3[f'minus_full_{edge}']:+.1f} Rho at +-10 %, which the reduced model's curvature "
        f"does not follow); with two runs (`calibrate=2`) the prediction at -5 % is within "
        f"{half:.2f} Rho of an independent full run in every sector. **A case with a nip**: "
        "the reduced model adds the uniform "
        "`mu N / h` to every sector, the full model distributes the nip load by the roller's "
        "beam (`[winding.nip_roller]`); the calibration run includes the beam, so the tension "
        f"term is right for it (pet3-2.3MPa-nip above: within {100 * nip_c:.0f} % centrally, "
        f"{100 * nip_m:.0f} % at -10 %). {_measured('diagnosis.uncertainty')}."
    )
    return "\n".join(lines) + "\n\n" + text


MEASUREMENTS: dict[str, Any] = {
    "design": _records().Measurement(
        models=_records().PLANE,
        about="the setpoint designs of docs/diagnosis.md's table (woundroll design)",
        runs=_design_runs,
        measure=_design_measure,
        spot=("pet2_negative_hoop",),
        rtol=5e-3,
        reason=(
            "deterministic on one machine; T0 is solved by Brent and secant steps to about "
            "1e-3 in the reading, so platform rounding may move the setpoints by a few 1e-4"
        ),
        cost="6 designs, about 13 CPU min (measured 750 s)",
    ),
    "uncertainty": _records().Measurement(
        models=_records().PLANE,
        about="docs/diagnosis.md's uncertainty checks (tests/test_uncertainty.py's problems)",
        runs=_uncertainty_runs,
        measure=_uncertainty_measure,
        spot=("surrogate",),
        rtol=0.02,
        reason=(
            "deterministic on one machine; the surrogate's error and the SDs are differences "
            "of readings (~0.1-3 Rho) in which platform rounding of the contact and impact "
            "solves (~1e-3 Rho) is a larger relative part: 2 %"
        ),
        cost="a 1D Monte Carlo check, 60 reduced profile runs, 6 full profile runs at 5 "
        "sectors: about 1.5 CPU min",
    ),
    "reduced_model": _records().Measurement(
        models=_records().PLANE,
        about="the reduced profile model's near-surface pressures against the coupled "
        "winding's on the Table 3 profile (docs/diagnosis.md)",
        runs=_reduced_runs,
        measure=_reduced_measure,
        spot=("table3",),
        rtol=1e-3,
        reason="deterministic windings; 1e-3 covers platform rounding of their iterations",
        cost="two 31-sector axisymmetric windings, under a CPU minute",
    ),
    "nip_deflection": _records().Measurement(
        models=_records().PLANE,
        about="the causes fit on a soft web with a nip deflection (tests/test_causes.py)",
        runs=_nip_runs,
        measure=_nip_measure,
        spot=("pet2_nip",),
        rtol=0.01,
        reason=(
            "deterministic; the fit's Gauss-Newton steps and posterior SDs of a "
            "nearly unidentifiable parameter amplify platform rounding of the windings: 1 %"
        ),
        cost="a causes fit with the reduced model, about 1.5 CPU min",
    ),
    "causes_full": _records().Measurement(
        models=_records().PLANE,
        about="the causes fit against readings of the full profile model, with the level "
        "corrected by full runs (tests/test_causes.py)",
        runs=_causes_runs,
        measure=_causes_measure,
        spot=("draw0",),
        rtol=0.01,
        reason=(
            "deterministic on one machine; the fit's Gauss-Newton steps and the secants of "
            "the level correction amplify platform rounding of the windings and contact "
            "solves (~1e-3 Rho) a few times: 1 % (a coverage fraction of 121 points moves by "
            "0.8 % per point). The spot run is draw 0 (the truth's run, the fit, three "
            "correcting full runs and the contact check: about 1.5 CPU min)"
        ),
        cost="30 noise draws: the truth's 31-sector full profile run once, then per draw a "
        "causes fit and three correcting full runs, about 1 CPU min each: ~35 CPU min",
    ),
}


BLOCKS: dict[str, Callable[[], str]] = {
    "sentence": sentence,
    "softer_message": softer_message,
    "midpoints": midpoints,
    "smoothness": smoothness,
    "round_trips": round_trips,
    "coverage": coverage,
    "causes_round_trip": causes_round_trip,
    "stack_covariance": stack_covariance,
    "negative_hoop": negative_hoop,
    "parotester_readout": parotester_readout,
    "buckling": buckling,
    # rendered from the measured records (MEASUREMENTS; docs/scripts/records.py)
    "design_table": design_table,
    "surrogate_check": surrogate_check,
    "profile_brute": profile_brute,
    "sensitivity_table": sensitivity_table,
    "causes_level": causes_level,
    "causes_study_intro": causes_study_intro,
    "causes_study_table": causes_study_table,
    "causes_study_level": causes_study_level,
    "causes_study_coverage": causes_study_coverage,
    "causes_study_sds": causes_study_sds,
    "causes_check": causes_check,
    "reduced_check": reduced_check,
    "nip_check": nip_check,
}
