"""The fast path against the 3D model: plane strain corrected for the CMD spreading.

The 3D reference (Rho, F(d)) of the 7 Table 2 rolls and of PET2 53.4 N wound to
H = 2, 4, 6 cm is cached in ``data/contact3d_reference.json`` (computed once by
``data/make_contact3d_reference.py``, ~1 CPU min a roll); the slow tests recompute two of
its 3D curves.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.contact import indent, roll_stiffness
from woundroll.contact.plane_strain.cmd_spread import (
    BASIN_FACTOR,
    END_FACTOR,
    MODEL_NAME,
    apply_cmd_spread,
    deflection_decay_length,
)
from woundroll.errors import InputError
from woundroll.pipeline import run

DATA = Path(__file__).with_name("data")
REF = json.loads((DATA / "contact3d_reference.json").read_text())
CASES = sorted(REF["cases"])
#: the rolls c_b and c_a were fitted on (docs/contact.md); the other eight validate them
FIT_SET = ("pet1-26.7N", "pet2-53.4N")
#: Validation cases the fast path misses (measured on the 3D references recomputed
#: 2026-12-07 with the lagged predictor, after refitting c_b, c_a on FIT_SET; 7.8 / 6.4 %
#: on those of 2026-11-26): strict xfail, so a change that brings them within the bar fails
#: here and the docs and registry get updated.
KNOWN_MISSES = {
    "pet1-26.7N-L50.8mm": "F(d) up to 8.9 % below the 3D model (bar 5 %)",
    "pet2-53.4N-L50.8mm": "F(d) up to 7.0 % below the 3D model (bar 5 %)",
}


def _cases(keys):  # noqa: ANN001, ANN202
    return [
        pytest.param(k, marks=pytest.mark.xfail(strict=True, reason=KNOWN_MISSES[k]))
        if k in KNOWN_MISSES
        else k
        for k in keys
    ]


#: The head the cached 3D curves were computed with (the Hertz-calibrated radius; the
#: bundled file's head is now calibrated through the 2D model, docs/instruments.md).
REF_HEAD = "tester.head_radius='6.565 mm'"


def _overrides(key: str) -> list[str]:
    return [
        *REF["cases"][key]["3d"]["overrides"],
        "contact.no_update=false",
        "contact.model='2d+cmd-spread'",
        REF_HEAD,
    ]


def _case_name(key: str) -> str:
    return REF["cases"][key]["3d"]["case"]


def test_decay_length_of_an_exponential_basin() -> None:
    s = np.linspace(0.0, 0.1, 2001)
    lam = 7e-3
    assert deflection_decay_length(s, 2e-4 * np.exp(-s / lam)) == pytest.approx(lam, rel=1e-4)
    # linear interpolation between nodes: exact for a linear basin
    assert deflection_decay_length([0, 1, 2], [1.0, 0.5, 0.0]) == pytest.approx(
        2 * (1 - 1 / math.e)
    )
    # no deflection: no spreading; a basin that never falls to 1/e: the model's extent
    assert deflection_decay_length(s, np.zeros_like(s)) == 0.0
    assert deflection_decay_length(s, np.ones_like(s)) == pytest.approx(0.1)


@pytest.fixture(scope="module")
def pet2_solution():
    case = load_case("pet2-53.4N", ["contact.no_update=false"])
    res = run(case)
    web, core = case.web.build(), case.core.build()
    ins = case.tester_setup.instrument
    c = indent(
        web,
        core,
        res.winding.radius,
        res.winding.sigma_r,
        head_radius=ins.head_radius,
        head_length=ins.head_length,
        depth_max=1.2e-3,
    )
    return web, c


def test_deflection_basin_is_the_2d_solution(pet2_solution) -> None:
    web, c = pet2_solution
    u = np.asarray(c.surface_deflection_history)
    # the surface under the head moves in with it (the head's axis node is in contact)
    assert u[1:, 0] == pytest.approx(c.delta[1:], rel=1e-3)
    assert np.all(u[0] == 0.0)
    spread = apply_cmd_spread(c)
    lam = spread.decay_length
    # the basin is far wider than the contact and widens with the depth
    assert np.all(lam[2:] > 3 * np.asarray(c.half_width)[2:])
    assert np.all(np.diff(lam[1:]) > 0)


def test_correction_vanishes_for_a_long_head(pet2_solution) -> None:
    """Plane strain is the limit of a head much longer than the basin (lambda ~ 1-3 cm)."""
    web, c = pet2_solution
    from dataclasses import replace

    L = 25.4e-3
    for length, bound in ((10 * L, 0.25), (1000 * L, 0.0025)):
        long = replace(c, head_length=length, force=np.asarray(c.force) * length / L)
        sp = apply_cmd_spread(long)
        extra = float(sp.length_ratio[-1]) - 1.0
        # the spread does not depend on L: the excess falls as 1/L
        assert 0 < extra < bound
        assert sp.spread == pytest.approx(apply_cmd_spread(c).spread, rel=1e-12)
    # without both terms the correction is the identity
    none = apply_cmd_spread(c, basin_factor=0.0, end_factor=0.0)
    assert np.array_equal(none.corrected.force, c.force)
    with pytest.raises(InputError) as exc:
        apply_cmd_spread(c, end_factor=-1.0)
    assert exc.value.field == "contact.end_factor"


@pytest.mark.parametrize("key", _cases(CASES))
def test_fast_path_within_3_percent_of_3d(key: str) -> None:
    """Rho (FD) of the corrected 2D path against the cached 3D model, every case.

    Tolerance 3 % (the issue's bar) on the eight validation rolls: the 3D reference itself
    carries ~1 % (mesh < 1 %, 24 increments ~1 % at the shallow end of the curve,
    docs/contact.md "Refinement"). The two rolls c_b, c_a were fitted on read the 3D Rho to
    0.1 % by construction: 0.5 % there (round-off of the constants, solver changes).
    Raw plane strain misses by 23-37 %: this test cannot pass without the correction.
    """
    ref = REF["cases"][key]["3d"]
    res = run(load_case(_case_name(key), _overrides(key)))
    assert res.contact.model == MODEL_NAME
    rho = res.hardness.to_dict()["rho_fd"]
    assert rho == pytest.approx(ref["rho_fd"], rel=0.005 if key in FIT_SET else 0.03)
    raw = REF["cases"][key]["2d"]["rho_fd"]
    assert abs(raw / ref["rho_fd"] - 1) > 0.15


def test_pipeline_json_names_the_model() -> None:
    auto = json.loads(run(load_case("pet1-26.7N", ["contact.model='2d+cmd-spread'"])).to_json())[
        "contact"
    ]
    assert auto["model"] == MODEL_NAME
    cs = auto["cmd_spread"]
    assert (cs["basin_factor_c_b"], cs["end_factor_c_a"]) == (BASIN_FACTOR, END_FACTOR)
    n = len(auto["depth_m"])
    assert len(cs["decay_length_m"]) == len(cs["length_ratio"]) == n
    # the corrected force is the plane-strain force times L_eff / L
    np.testing.assert_allclose(
        np.asarray(auto["force_N"]),
        np.asarray(cs["plane_strain_force_N"]) * np.asarray(cs["length_ratio"]),
        rtol=1e-12,
    )
    raw = json.loads(run(load_case("pet1-26.7N", ["contact.model='2d'"])).to_json())["contact"]
    assert raw["model"] == "2d" and raw["cmd_spread"] is None
    assert auto["alpha_N_per_m2"] > 2 * raw["alpha_N_per_m2"]


def _extra_curves(key: str):
    """The cached 3D curve of an extra case and the corrected 2D curve at its depths."""
    e = REF["extra"][key]
    overrides = [
        "contact.no_update=false",
        "contact.model='2d'",
        REF_HEAD,
        *e.get("overrides", []),
    ]
    case = load_case(e["case"], overrides)
    res = run(case)
    web, core = case.web.build(), case.core.build()
    ins = case.tester_setup.instrument
    d = np.asarray(e["curve"]["delta_m"])
    c = indent(
        web,
        core,
        res.winding.radius,
        res.winding.sigma_r,
        head_radius=ins.head_radius,
        head_length=e["head_length_m"],
        depth_max=float(d[-1]),
    )
    sp = apply_cmd_spread(c)
    sel = d > 0.25 * d[-1]
    f3 = np.asarray(e["curve"]["force_N"])[sel]
    fc = np.interp(d[sel], sp.corrected.delta, sp.corrected.force)
    f2 = np.interp(d[sel], c.delta, c.force)
    return f3, fc, f2


@pytest.mark.parametrize("key", _cases(["pet1-26.7N-L50.8mm", "pet2-53.4N-L50.8mm"]))
def test_longer_head_against_3d(key: str) -> None:
    """The spread does not depend on the head's length: a 50.8 mm head (twice the
    Rho-meter's; cached 3D curve) against the correction with the same s(d)."""
    f3, fc, f2 = _extra_curves(key)
    # plane strain misses by a third or more; the corrected F(d) is within 5 % over
    # 0.25-1 depth_max (5 % more force at every depth is +1.7 % in Rho, docs/contact.md)
    assert np.min(f3 / f2) > 1.3
    assert np.max(np.abs(fc / f3 - 1)) < 0.05


def test_cmd_stiffness_scaling_against_3d() -> None:
    """E_z = E_theta / 8 (PET1 26.7 N; cached 3D curve): the 3D roll is as much stiffer than
    plane strain as with E_z = E_theta, and the spread without a factor of E_z matches it
    (a plate-on-foundation factor (E_z/E_theta)^(1/4) would read 21-25 % low; 5 % as for
    the longer head)."""
    f3, fc, f2 = _extra_curves("pet1-26.7N-Ez/8")
    assert np.max(np.abs(fc / f3 - 1)) < 0.05


def test_study_model_option() -> None:
    from typer.testing import CliRunner

    from woundroll.app.cli import app

    res = CliRunner().invoke(app, ["study", "tension", "--model", "auto"])
    assert res.exit_code == 2 and "--model" in res.output


@pytest.mark.slow
@pytest.mark.parametrize("key", ["pet1-26.7N", "pet2-53.4N-H2cm"])
def test_3d_reference_recomputed(key: str) -> None:
    """The cached 3D curves are what the 3D model gives now (~1 CPU min each)."""
    ref = REF["cases"][key]["3d"]
    d = np.asarray(ref["curve"]["delta_m"])
    # the pipeline's own path, as make_contact3d_reference.py ran it: one 3D solve, its first
    # depth from the guide (or 1 mm) and the loading stopped past the fit window, so the
    # mesh and increments are the reference's
    case = load_case(_case_name(key), [*_overrides(key)[:-2], REF_HEAD, "contact.model='3d'"])
    res = run(case)
    assert res.contact.model == "3d"
    c = res.contact.contact
    f_now = np.interp(d[1:], c.delta, c.force)
    # the same code, mesh and increments: only the sparse solver's rounding differs
    assert f_now == pytest.approx(np.asarray(ref["curve"]["force_N"])[1:], rel=1e-6)
    # the cached Rho of pet1-26.7N was read with the earlier spring fit (the computed points
    # inside the window rather than 24 samples of the interpolated curve): 0.01 % apart
    assert res.hardness.to_dict()["rho_fd"] == pytest.approx(ref["rho_fd"], rel=1e-3)
    st = roll_stiffness(
        case.web.build(),
        case.core.build(),
        res.winding.radius,
        res.winding.sigma_r,
        case.tester_setup.instrument,
        model="2d+cmd-spread",
    )
    assert st.model == MODEL_NAME
