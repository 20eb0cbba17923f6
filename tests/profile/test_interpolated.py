"""The interpolated contact stage of a profile (woundroll.profile.interpolated): nodes,
interpolation, the check, and the option from the case file to the CLI."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.materials.radial_modulus import Pfeiffer
from woundroll.materials.web import Core, Web
from woundroll.profile.hardness import predict_profile
from woundroll.profile.interpolated import (
    DEFAULT_TOLERANCE,
    check_stage,
    descriptors,
    interpolated_springs,
)
from woundroll.winding.tension import TensionSchedule

H = 0.1  # pile height of the synthetic sectors [m]


def sector(p0: float, shape: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """A synthetic sector: pressure rising from 0 at the surface to ``p0`` deep down;
    ``shape`` > 1 shifts it deeper."""
    r = np.linspace(0.1, 0.1 + H, 200)
    depth = r[-1] - r
    return r, -p0 * (1 - np.exp(-((depth / (0.02 * shape)) ** 1)))


def spring(radius: np.ndarray, sigma_r: np.ndarray) -> tuple[float, float]:
    """A stand-in spring that depends on the pressure profile, mostly near the surface."""
    depth = radius[-1] - radius
    p = -np.interp(0.005, depth[::-1], sigma_r[::-1])
    q = -np.interp(0.05, depth[::-1], sigma_r[::-1])
    return 1e9 * (p / 1e4) ** 0.8 + 1e7 * q / 1e4, 1e4


def reading(alpha: np.ndarray, beta: np.ndarray) -> np.ndarray:
    return 20.0 * np.log(np.asarray(alpha) / 1e8)


def run(profiles: list, tol: float = DEFAULT_TOLERANCE, batch: int = 2):
    fns = [spring] * len(profiles)
    calls: list[int] = []

    def solve(f, p):
        calls.append(len(p))
        ab = np.array([fi(*pi) for fi, pi in zip(f, p, strict=True)])
        return ab[:, 0], ab[:, 1]

    res = interpolated_springs(
        fns, profiles, solve, lambda a, b, w, sel: reading(a, b), tolerance=tol, batch=batch
    )
    exact = reading(*np.array([spring(*p) for p in profiles]).T)
    return res, reading(res.alpha, res.beta), exact, sum(calls)


def test_uniform_web_gives_a_flat_profile_exactly() -> None:
    # every sector with one descriptor: one full solve, copied (bit for bit)
    res, r, exact, n = run([sector(2e4) for _ in range(31)])
    assert n == 1 and res.solved.sum() == 1
    assert np.all(r == r[0]) and r[0] == exact[0]


def test_uniform_web_through_predict_profile_is_flat_with_one_solve() -> None:
    # the (r, z) model of a uniform web without axial coupling: every sector is the same
    # roll (to 1e-7, docs/profile.md section 6), so one contact solve serves all
    web = Web(
        thickness=76e-6, width=0.61, E_theta=4999e6, radial_modulus=Pfeiffer(0.0, 246.5),
        nu_theta_r=0.01, nu_z_r=0.0, nu_theta_z=0.0,
    )  # fmt: skip
    calls: list[int] = []

    def contact(r: np.ndarray, s: np.ndarray) -> tuple[float, float]:
        calls.append(1)
        return spring(r, s)

    res = predict_profile(
        web, Core.tube(0.1016, 0.095, 69e9, 0.33), TensionSchedule(web_stress=2.3e6),
        outer_radius=0.13, contact=contact, instrument=reading, n_sectors=9, n_groups=40,
        workers=1, contact_stage="interpolated",
    )  # fmt: skip
    assert len(calls) == 1
    assert np.all(res.rho == res.rho[0])
    d = res.to_dict()["contact_stage"]
    assert d["stage"] == "interpolated" and d["n_solved"] == 1


def test_interpolated_equals_exact_within_the_tolerance_with_fewer_solves() -> None:
    # a smooth family: the check stops once no checked reading moves by more than 0.2
    profiles = [sector(p) for p in np.geomspace(2e3, 2e5, 41)]
    res, r, exact, n = run(profiles)
    assert np.max(np.abs(r - exact)) <= DEFAULT_TOLERANCE
    assert n == res.solved.sum() <= 30  # (measured: 25 of 41)
    assert res.largest_check <= DEFAULT_TOLERANCE
    assert np.all(r[res.solved] == exact[res.solved])  # solved sectors are exact
    # tolerance 0: every sector ends up solved
    res0, r0, exact0, n0 = run(profiles, tol=0.0)
    assert n0 == 41 and np.array_equal(r0, exact0)


def test_the_semi_contact_width_is_interpolated_with_the_springs_and_checked() -> None:
    """A contact that gives (alpha, beta, a) and a reading that depends on a (the FD
    reading's active mass): the width is carried like the springs (the solved sectors'
    own, linear in x between the nodes) and the check judges the reading of both, so every
    reading ends within the tolerance of the exact one; a contact that gives no width
    leaves it NaN."""
    profiles = [sector(p) for p in np.geomspace(2e3, 2e5, 41)]

    def width(r: np.ndarray, s: np.ndarray) -> float:  # a wider contact on a softer sector
        return 1e-3 * (1 + 1e4 / (1e3 + spring(r, s)[0] / 1e5))

    def read(a: np.ndarray, b: np.ndarray, w: np.ndarray) -> np.ndarray:
        return reading(a, b) - 5.0 * np.asarray(w) / 1e-3

    exact_w = np.array([width(*p) for p in profiles])
    exact = read(*np.array([spring(*p) for p in profiles]).T, exact_w)

    def solve(f, p):
        return (*np.array([fi(*pi) for fi, pi in zip(f, p, strict=True)]).T,
                np.array([width(*pi) for pi in p]))  # fmt: skip

    res = interpolated_springs(
        [spring] * len(profiles), profiles, solve, lambda a, b, w, sel: read(a, b, w)
    )
    got = read(res.alpha, res.beta, res.width)
    assert np.max(np.abs(got - exact)) <= DEFAULT_TOLERANCE
    assert np.array_equal(res.width[res.solved], exact_w[res.solved])
    rest = ~res.solved
    lo, hi = exact_w.min(), exact_w.max()  # linear between the nodes: within their range
    assert rest.any() and np.all((lo <= res.width[rest]) & (res.width[rest] <= hi))
    assert np.all(np.isnan(run(profiles)[0].width))  # (alpha, beta) only: no width


def test_an_outlier_sector_is_caught_by_the_check_and_solved_fully() -> None:
    # sector 20 has the geometric-mean pressure of its neighbours (its x) but its pressure
    # lies deeper: its spring (near-surface pressure) is far softer. The pressure profile's
    # mismatch against the interpolated one makes its estimate the largest: it is checked,
    # found off by far more than the tolerance, and solved
    profiles = [sector(p) for p in np.geomspace(2e3, 2e5, 41)]
    x = descriptors(profiles).mean(1)
    lo, hi = 0.3, 3.0
    for _ in range(60):  # the deeper-lying profile with the same x
        mid = 0.5 * (lo + hi)
        p0 = sector(np.geomspace(2e3, 2e5, 41)[20], 3.0)
        trial = (p0[0], p0[1] * mid)
        xt = descriptors([*profiles[:20], trial, *profiles[21:]]).mean(1)[20]
        lo, hi = (mid, hi) if xt < x[20] else (lo, mid)
    profiles[20] = trial
    res, r, exact, n = run(profiles)
    assert abs(exact[20] - r[20]) == 0 and res.solved[20]
    assert res.largest_change > 10 * DEFAULT_TOLERANCE  # the check found it
    assert np.max(np.abs(r - exact)) <= DEFAULT_TOLERANCE


def test_bad_stage_and_tolerance_name_their_field() -> None:
    with pytest.raises(InputError) as e:
        check_stage("some-sectors", 0.2)
    assert e.value.field == "profile.contact"
    for bad in (-1.0, float("nan"), "0.2", True):
        with pytest.raises(InputError) as e:
            check_stage("interpolated", bad)
        assert e.value.field == "profile.contact_tolerance"


# ------------------------------------------------------------------------- anchored stage
def _anchored(profiles: list, factor, tol: float = DEFAULT_TOLERANCE):
    """The anchored stage on synthetic sectors: the cheap spring is :func:`spring`, the
    expensive one ``factor(x_sector) *`` it (alpha and beta alike); returns the record,
    its readings, the exact readings and the expensive solves made."""
    x = descriptors(profiles).mean(axis=1)
    cheap = np.array([spring(*p) for p in profiles])
    dear = cheap * np.asarray([factor(v) for v in x])[:, None]
    index = {id(p): j for j, p in enumerate(profiles)}
    calls: list[int] = []

    def solve(f, p):
        calls.append(len(p))
        ab = np.array([dear[index[id(pi)]] for pi in p])
        return ab[:, 0], ab[:, 1]

    res = interpolated_springs(
        [spring] * len(profiles), profiles, solve, lambda a, b, w, sel: reading(a, b),
        tolerance=tol, base=(cheap[:, 0], cheap[:, 1]),
    )  # fmt: skip
    return res, reading(res.alpha, res.beta), reading(*dear.T), sum(calls)


def test_anchored_stage_is_exact_when_the_correction_is_linear_in_the_descriptor() -> None:
    """A correction (expensive over cheap spring) linear in x is interpolated exactly: the
    readings equal the expensive model's on every sector to rounding (1e-9 Rho: log and
    products of O(1e9) numbers). The error estimates act on the reading's correction, here
    20 ln f(x), whose curvature they see: two check rounds of two sectors find no change
    and stop (5 first nodes + 4 checks of 12 sectors)."""
    profiles = [sector(p0, shape) for p0 in (5e3, 1e4, 2e4, 4e4) for shape in (0.7, 1.0, 1.6)]
    res, got, exact, solves = _anchored(profiles, lambda v: 1.5 + 0.05 * v)
    assert np.max(np.abs(got - exact)) < 1e-9
    assert solves <= 5 + 2 * 2


def test_anchored_stage_carries_what_the_plain_interpolation_cannot() -> None:
    """Sectors whose spring is not a function of x alone (pressure shifted deeper: the
    plain interpolation needs many full solves) but whose correction is constant: the
    anchored stage reads every sector exactly with the first nodes only, the plain one
    needs more full solves for the same tolerance."""
    profiles = [sector(p0, shape) for p0 in np.geomspace(4e3, 5e4, 8) for shape in (0.5, 2.0)]
    res, got, exact, solves = _anchored(profiles, lambda v: 2.0)
    assert np.max(np.abs(got - exact)) < 1e-9
    _, plain_got, plain_exact, plain_solves = run(profiles)
    assert solves < plain_solves
    assert np.max(np.abs(plain_got - plain_exact)) <= DEFAULT_TOLERANCE + 1e-9


def test_anchored_stage_checks_a_correction_that_is_not_smooth() -> None:
    """A correction with a step in x (the interpolation cannot carry it): the checks find
    the sectors it moves by more than the tolerance and solve them; every reading ends
    within the tolerance of the expensive model's."""
    profiles = [sector(p0) for p0 in np.geomspace(3e3, 6e4, 21)]
    x_mid = float(np.median(descriptors(profiles).mean(axis=1)))
    res, got, exact, solves = _anchored(profiles, lambda v: 1.5 if v < x_mid else 1.8)
    assert np.max(np.abs(got - exact)) <= DEFAULT_TOLERANCE
    assert 5 < solves < 21


def _case(tmp_path: Path, extra: str) -> Path:
    import woundroll.data

    csv = Path(woundroll.data.__file__).parent / "profiles" / "table3_synthetic_pet.csv"
    path = tmp_path / "case.toml"
    path.write_text(
        f"""title = "small profile"
[web]
preset = "PET3"
[core]
outer_radius = "10.16 cm"
inner_radius = "9.5 cm"
E = "69 GPa"
nu = 0.33
[winding]
outer_radius = "11 cm"
tension = "2.3 MPa"
thickness_profile = "{csv}"
[tester]
instrument = "rho-meter"
[profile]
sectors = 3
groups = 30
workers = 1
{extra}
"""
    )
    return path


def test_cli_bad_contact_stage_is_a_one_line_error(tmp_path: Path) -> None:
    res = CliRunner().invoke(app, ["run", str(_case(tmp_path, 'contact = "fast"')), "--json"])
    assert res.exit_code == 2
    assert "profile.contact" in res.output and "Traceback" not in res.output


def test_cli_runs_each_contact_stage(tmp_path: Path) -> None:
    out = {}
    for stage in ("every-sector", "interpolated"):
        path = _case(tmp_path, f'contact = "{stage}"\ncontact_tolerance = 0.2')
        res = CliRunner().invoke(app, ["run", str(path), "--json"])
        assert res.exit_code == 0, res.output
        prof = json.loads(res.stdout)["profile"]
        assert prof["contact_stage"]["stage"] == stage
        out[stage] = prof
    # three sectors: each is a node of the interpolation (extremes and median), so the two
    # stages give the same readings
    assert out["interpolated"]["contact_stage"]["n_solved"] == 3
    assert out["interpolated"]["reading"] == out["every-sector"]["reading"]


@pytest.mark.slow
def test_interpolated_profile_equals_every_sector_on_table3() -> None:
    # pet3-2.3MPa (61 sectors, 14 saturated, 23 slack): what the instrument shows moves by
    # at most the tolerance (measured 0.123 Rho, sector 29; 50 of 61 sectors solved in 10
    # rounds), the saturated and slack sectors are the same, mean and CoV of the on-scale
    # readings move by < 0.01 Rho and < 1e-4 (measured 0.0008, 4.4e-5; the semi-contact
    # width a of the FD reading interpolated with the springs in the descriptor x and
    # checked with them: interpolated along the CMD and not checked it gave 3.7e-4). The
    # model's value beyond the scale is interpolated there: what the device shows is not.
    from woundroll.case import load_case
    from woundroll.pipeline.runner import run as run_case

    out = {}
    for stage in ("every-sector", "interpolated"):
        case = load_case("pet3-2.3MPa")
        spec = case.profile.model_copy(update={"contact": stage})
        out[stage] = run_case(case.model_copy(update={"profile": spec})).profile
    a, b = out["every-sector"], out["interpolated"]
    assert np.max(np.abs(a.shown - b.shown)) <= DEFAULT_TOLERANCE
    assert np.array_equal(a.saturated, b.saturated) and np.array_equal(a.slack, b.slack)
    assert abs(a.rho_stats.mean - b.rho_stats.mean) < 0.01
    assert abs(a.rho_stats.cov - b.rho_stats.cov) < 1e-4
    solved = b.contact_stage.solved
    assert solved.sum() < a.rho.size and np.array_equal(a.rho[solved], b.rho[solved])


def test_cli_reads_a_profile_with_the_3d_model(tmp_path: Path) -> None:
    """`woundroll run CASE --set contact.model=3d`: a profile read with the 3D model on
    every sector, and with `--set profile.contact=anchored` (plane strain on every sector,
    3D on the nodes). Three sectors are all nodes, so both read each sector with the 3D
    model: equal (1e-9 relative, the same solves) to the API's profile with the 3D model on
    every sector. A coarse 3D mesh keeps the test short."""
    coarse = {"n_fine": 4, "n_steps": 8, "radial_growth": 2.0, "tangential_growth": 2.0,
              "axial_growth": 2.0}  # fmt: skip
    sets = [x for k, v in coarse.items() for x in ("--set", f"contact.options3d.{k}={v}")]
    path = _case(tmp_path, "")
    read = {}
    for stage in ("every-sector", "anchored"):
        args = ["run", str(path), "--set", "contact.model=3d", "--set", f"profile.contact={stage}"]
        res = CliRunner().invoke(app, [*args, *sets, "--json"])
        assert res.exit_code == 0, res.output
        prof = json.loads(res.stdout)["profile"]
        assert prof["contact_stage"]["stage"] == stage
        assert prof["roll_model"] == "3d"
        read[stage] = prof["reading_model"]
    assert prof["contact_stage"]["n_solved"] == 3

    from woundroll.case import load_case
    from woundroll.contact.solid3d.options import Contact3DOptions
    from woundroll.profile.hardness import ContactModel

    c = load_case(str(path))
    web, core, ins = c.web.build(), c.core.build(), c.tester_setup.instrument
    every = predict_profile(
        web, core, c.winding.schedule(web), c.thickness_profile,
        outer_radius=c.winding.final_radius(web, core), instrument=ins, n_sectors=3,
        n_groups=30, workers=1,
        contact=ContactModel(web, core, ins.head_radius, ins.head_length, 1e-3,
                             instrument=ins, model="3d", options3d=Contact3DOptions(**coarse)),
    )  # fmt: skip
    for stage in read:
        np.testing.assert_allclose(read[stage], every.rho, rtol=1e-9, err_msg=stage)
