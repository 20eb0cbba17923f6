"""Slip emulation in the 2D contact model (the paper's Figure 19, issue 9 item 6).

Where the interlayer shear reaches Coulomb's limit (the slip factor {23} reaching 1) the
element keeps ``slip_shear_fraction`` of G_r_theta for the rest of the loading; within an
increment the slipping share of each element is iterated until it stops growing
(docs/contact.md, "Slip emulation"). Roll: PET2 53.4 N (Hakiel profile), Rho-meter head, the
depth the pipeline's striker reaches there (1.5 mm).
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.contact import ContactOptions, indent
from woundroll.errors import ConvergenceError, InputError

DEPTH = 1.5e-3
FAST = {"n_steps": 8}  # the properties below hold at any step count


@cache
def real_roll(name: str) -> tuple:
    """Web, core and the Hakiel pre-impact profile (radius, sigma_r) of a bundled case."""
    from woundroll.winding.hakiel import wind

    case = load_case(name)
    web, core = case.web.build(), case.core.build()
    w = wind(web, core, case.winding.final_radius(web, core), case.winding.schedule(web))
    return web, core, np.asarray(w.radius), np.asarray(w.sigma_r)


@cache
def rho_meter_head() -> dict[str, float]:
    from woundroll.instruments import get_instrument

    ins = get_instrument("rho-meter")
    return {"head_radius": ins.head_radius, "head_length": ins.head_length}


def solve(options: ContactOptions, friction: float = 0.3, **kw: object):
    web, core, radius, sigma_r = real_roll("pet2-53.4N")
    return indent(
        web,
        core,
        radius,
        sigma_r,
        depth_max=DEPTH,
        friction=friction,
        **rho_meter_head(),
        options=options,
        **kw,
    )


def test_slip_off_and_its_limits_leave_the_curve_unchanged() -> None:
    """slip = "none" is the model without slip (no mask, no extra pass); a fraction of 1
    (slipped elements keep all their shear stiffness) and a friction no shear reaches give
    the same curve and fields bit for bit: the matrices are the same, only the passes
    differ."""
    plain = solve(ContactOptions(**FAST))
    assert plain.slipped is None and plain.slip_passes == 0
    one = solve(ContactOptions(**FAST, slip="reduced-shear", slip_shear_fraction=1.0))
    sticky = solve(ContactOptions(**FAST, slip="reduced-shear"), friction=1e12)
    assert one.slipped.sum() > 100  # the zone is found, its moduli just do not change
    assert sticky.slipped.sum() == 0
    for res in (one, sticky):
        np.testing.assert_array_equal(res.force, plain.force)
        np.testing.assert_array_equal(res.sigma_r, plain.sigma_r)
        np.testing.assert_array_equal(res.tau_r_theta, plain.tau_r_theta)


# slow: a contact solve with the slip iteration at every depth (~16 s);
# test_pipeline_reading_with_slip_is_lower keeps slip in the default suite
@pytest.mark.slow
def test_slip_softens_the_roll_at_every_depth_and_is_consistent() -> None:
    """Monotone: the reduced shear makes the roll softer at every depth (F with slip <=
    F without; measured 0.36-0.74 of it); the more shear is left, the stiffer (fractions
    0.01 < 0.1). Consistency of the converged zone: no element outside it reaches
    SF >= 1 (measured max 0.998; the tolerance 1.02 is the iteration's stopping rule, a
    share of the increment of 0.05)."""
    plain = solve(ContactOptions(**FAST))
    forces = {}
    for f in (0.01, 0.1):
        res = solve(ContactOptions(**FAST, slip="reduced-shear", slip_shear_fraction=f))
        assert np.all(res.force[1:] < plain.force[1:])
        forces[f] = res.force[-1]
        sf = np.asarray(res.slip_factor)
        assert np.max(sf[~np.asarray(res.slipped)]) < 1.02
    assert forces[0.01] < forces[0.1] < plain.force[-1]
    # mu: a larger friction lets fewer layers slip
    more = solve(ContactOptions(**FAST, slip="reduced-shear"), friction=0.6)
    assert forces[0.01] < more.force[-1] < plain.force[-1]


def test_slip_without_the_modulus_update() -> None:
    """With E_r frozen the slip zone changes the one factorisation: refactorised per new
    zone, still softer than without slip."""
    plain = solve(ContactOptions(**FAST), update_modulus=False)
    res = solve(ContactOptions(**FAST, slip="reduced-shear"), update_modulus=False)
    assert res.slipped.sum() > 0
    assert np.all(res.force[1:] < plain.force[1:])


def test_slip_zone_that_does_not_settle_says_so() -> None:
    """One pass per increment cannot confirm the zone (the first pass always finds new
    slip): ConvergenceError naming the option, not a silently unconverged curve."""
    with pytest.raises(ConvergenceError, match="slip_max_passes"):
        solve(ContactOptions(**FAST, slip="reduced-shear", slip_max_passes=1))


def test_slip_zone_iteration_converges_in_a_few_passes() -> None:
    """The default settles every increment (measured: 6.6 passes per increment on average
    at the default 16 increments, 8.9 at 24; the largest well under the 50 allowed)."""
    res = solve(ContactOptions(slip="reduced-shear"))
    assert res.slip_passes < 20 * (res.delta.size - 1)


@pytest.mark.slow
def test_slip_curve_converges_with_steps_and_mesh() -> None:
    """Step refinement: with the slipping share of each increment (not the end-of-step zone
    for the whole increment, which was first order: 24 -> 48 steps moved F by 5 %) 24 -> 48
    steps moves F(d) by 1.0 % (measured), 48 -> 96 by 0.6 %; the surface ring halved by
    0.4 %. Bar: 2 % (the project's discretisation bar)."""
    base = solve(ContactOptions(slip="reduced-shear"))
    for change in ({"n_steps": 48}, {"surface_size": real_roll("pet2-53.4N")[0].thickness / 4}):
        fine = solve(ContactOptions(slip="reduced-shear", **change))
        d = np.linspace(0.2, 1.0, 9) * DEPTH
        rel = np.abs(
            np.interp(d, fine.delta, fine.force) / np.interp(d, base.delta, base.force) - 1
        )
        assert rel.max() < 0.02, change


def test_slip_options_are_checked() -> None:
    for bad, field in (
        ({"slip": "coulomb"}, "options.slip"),
        ({"slip_shear_fraction": 0.0}, "options.slip_shear_fraction"),
        ({"slip_shear_fraction": 1.5}, "options.slip_shear_fraction"),
        ({"slip_max_passes": 0}, "options.slip_max_passes"),
    ):
        with pytest.raises(InputError) as e:
            ContactOptions(**bad)
        assert e.value.field == field


def test_case_keys_one_spelling_for_2d_and_3d() -> None:
    """``[contact] slip`` and ``slip_shear_fraction`` set both models' options; the same
    keys inside ``options`` / ``options3d`` are refused with a pointer to the one place."""
    case = load_case(
        "pet2-53.4N", ["contact.slip='reduced-shear'", "contact.slip_shear_fraction=0.05"]
    )
    o2, o3 = case.contact.contact_options(), case.contact.contact3d_options()
    assert (o2.slip, o2.slip_shear_fraction) == ("reduced-shear", 0.05)
    assert (o3.slip, o3.slip_shear_fraction) == ("reduced-shear", 0.05)
    assert load_case("pet2-53.4N").contact.contact_options().slip == "none"
    for key, field in (
        ("contact.options.slip='reduced-shear'", "contact.options.slip"),
        ("contact.options3d.slip='reduced-shear'", "contact.options3d.slip"),
        ("contact.slip_shear_fraction=2", "contact.slip_shear_fraction"),
    ):
        with pytest.raises(InputError) as e:
            load_case("pet2-53.4N", [key]).contact.contact_options()
            load_case("pet2-53.4N", [key]).contact.contact3d_options()
        assert e.value.field == field
    with pytest.raises(InputError) as e:
        load_case("pet2-53.4N", ["contact.slip='coulomb'"])
    assert e.value.field == "contact.slip"
    # a quantity string where the 3D options take SI numbers: a one-line error, no traceback
    with pytest.raises(InputError) as e:
        load_case(
            "pet2-53.4N", ["contact.options3d.axial_size='0.5 mm'"]
        ).contact.contact3d_options()
    assert e.value.field == "contact.options3d"


def test_pipeline_reading_with_slip_is_lower() -> None:
    """Through the pipeline (winding -> 2D contact with slip -> impact): the reading with
    slip is below the one without (measured PET2 53.4 N: 24.0 -> 13.4 Rho FD)."""
    from woundroll.pipeline import run

    plain = run(load_case("pet2-53.4N"))
    slip = run(load_case("pet2-53.4N", ["contact.slip='reduced-shear'"]))
    assert slip.hardness.fd.rho < 0.8 * plain.hardness.fd.rho
    assert slip.contact.contact.to_dict()["slipped_elements"] > 0
