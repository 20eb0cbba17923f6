"""The layered roll's diagnostics behind docs/contact.md "Zone depth" (the private
``_Diagnostics`` options): a slip region (interfaces outside a depth and an angle from the
head stick) and a cohesion (the interface limit ``(cohesion + mu P) A``).

Every assertion states its tolerance and why.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

# the PET1 test roll of test_layered.py (Table 2's PET1, 30 kPa at the surface rising to
# ~1 MPa at the core, head R = 10 mm, L = 20 mm)
from test_layered import DEPTH, HEAD, PET1, R_OUT, RIGID, H, pet_profile

from woundroll.contact.layered.solver import (
    ContactOptions,
    LayeredOptions,
    LayeredState,
    _Diagnostics,
    indent_layered,
)
from woundroll.errors import InputError


def options(**kw: object) -> LayeredOptions:
    """5 sheets, 4 depth steps (cheap), with the diagnostics ``kw``."""
    base = LayeredOptions(base=ContactOptions(newton=False, n_steps=4), layered_depth=5 * H)
    return _Diagnostics.of(base, **kw) if kw else base


def run(opts: LayeredOptions, mu: float = 0.3) -> tuple[float, LayeredState]:
    r, s = pet_profile()
    state: list[LayeredState] = []
    res = indent_layered(
        PET1, RIGID, r, s, depth_max=DEPTH, friction=mu, options=opts, state=state, **HEAD
    )
    return float(res.force[-1]), state[0]


@pytest.fixture(scope="module")
def free() -> tuple[float, LayeredState]:
    """Every interface of the zone may slip (the model's default)."""
    return run(options())


def test_the_diagnostics_leave_the_public_options_alone() -> None:
    # the docs records hash LayeredOptions' defaults: the diagnostics live on a subclass
    import dataclasses

    names = {f.name for f in dataclasses.fields(LayeredOptions)}
    assert not names & {"slip_region", "cohesion"}
    assert _Diagnostics.of(options(), cohesion=1.0).layered_depth == 5 * H


def test_a_region_holding_the_whole_zone_is_the_default(free: tuple[float, LayeredState]) -> None:
    # every pair inside the region: the same bounds, the same passes, the same force (to
    # rounding, 1e-12 relative)
    f, st = run(options(slip_region=(1.0, math.pi)))
    assert f == pytest.approx(free[0], rel=1e-12)
    assert np.array_equal(st.slip, free[1].slip)


def test_outside_the_region_the_interfaces_stick(free: tuple[float, LayeredState]) -> None:
    # slip allowed in the top 2 sheets' interfaces within 2 degrees of the head: no pair
    # outside slips (exactly zero: they never leave the stick set); fewer interfaces that
    # can slip make the roll stiffer than the free zone and softer than the stuck one
    # (strict; measured on this roll)
    f_stuck, _ = run(options(), mu=1e4)
    region = (2.5 * H, math.radians(2.0))
    f, st = run(options(slip_region=region))
    theta = st.s / R_OUT
    outside = (st.depth > region[0]) | (theta > region[1])
    assert np.any(outside) and np.any(~outside)
    assert np.all(st.slip[outside] == 0.0)
    assert np.any(st.slip[~outside] > 0.0)
    assert free[0] < f < f_stuck


def test_an_empty_region_is_the_stuck_roll() -> None:
    # no pair inside (shallower than the first interface): every interface sticks, the
    # continuum on the layered mesh to the stick passes' tolerance (1e-4 relative, as
    # test_layered.py's mu = 1e4 check)
    f, st = run(options(slip_region=(0.5 * H, math.pi)))
    f_stuck, _ = run(options(), mu=1e4)
    assert np.all(st.slip == 0.0)
    assert f == pytest.approx(f_stuck, rel=1e-4)


@pytest.mark.parametrize("region", [(0.0, 1.0), (1e-3, -1.0), (1e-3,), "deep", (1e-3, math.nan)])
def test_bad_region_names_the_field(region: object) -> None:
    with pytest.raises(InputError) as err:
        options(slip_region=region)
    assert err.value.field == "options.slip_region"


def test_cohesion_zero_is_coulomb_and_large_cohesion_sticks(
    free: tuple[float, LayeredState],
) -> None:
    # the limit (cohesion + mu P) A: cohesion 0 is the default law (same force to rounding,
    # 1e-12); a cohesion far above any interface shear (1 GPa against the MPa under the
    # head) sticks every pair: the stuck roll to the stick passes' tolerance (1e-4)
    f0, _ = run(options(cohesion=0.0))
    assert f0 == pytest.approx(free[0], rel=1e-12)
    f_big, st = run(options(cohesion=1e9))
    f_stuck, _ = run(options(), mu=1e4)
    assert np.all(st.slip == 0.0)
    assert f_big == pytest.approx(f_stuck, rel=1e-4)
    # a moderate cohesion (the wound-in pressure's order, 30 kPa) lies between (strict)
    f_mid, _ = run(options(cohesion=30e3))
    assert free[0] < f_mid < f_stuck


@pytest.mark.parametrize("cohesion", [-1.0, math.inf, "1 kPa"])
def test_bad_cohesion_names_the_field(cohesion: object) -> None:
    with pytest.raises(InputError) as err:
        options(cohesion=cohesion)
    assert err.value.field == "options.cohesion"
