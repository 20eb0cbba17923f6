"""Verification of the layered roll against closed forms: separate sheets bend as separate
plates, and friction begins to slip where the stuck stack's shear reaches mu P.

The setting (derived here, not taken from the paper): N = 9 web sheets of h = 0.1 mm
(8 in the layered zone, the ninth the continuum under it) wound on a soft core of radius
R = 20 m that acts as a Winkler foundation: the 2D model's core is a radial spring of
``E_c / R`` per unit area (:class:`woundroll.materials.Core`, Hakiel's condition) and holds
the tangential displacement of the innermost nodes. A stiff near-isotropic web (E_r =
E_theta = 5 GPa, G = E_theta / 2.6, nu_theta_z = 0.3) makes the sheets Euler-Bernoulli
plates: shear deformation costs E h^2 / (G L^2) ~ 1e-3 at the bending length L = 5 mm.

Closed form: an infinite beam of bending stiffness EI on a foundation k under a line load
P deflects ``w0 = P beta / (2 k)``, ``beta = (k / (4 EI))^(1/4)`` (Hetenyi), so the roll's
stiffness is ``P / w0 = 2 k / beta``. The stack's EI per unit CMD length, with the
plane-strain modulus ``E' = E_theta / (1 - nu^2)``:

* stuck (one plate 9 h thick whose bottom face the core holds tangentially, so it bends
  about that face): ``EI = E' (9 h)^3 / 3``;
* frictionless (eight free sheets ``E' h^3 / 12`` each, and the bottom sheet on the core
  ``E' h^3 / 3``): ``EI = 12 E' h^3 / 12``;

so the stiffness ratio stuck / frictionless is ``(2916 / 12)^(1/4) = 243^(1/4) = 3.948``,
where one plate nine sheets thick would give 1. (With a free bottom face the ratio is
``(N^2)^(1/4) = 3``; the core's tangential hold is part of this setting.)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from woundroll.contact.layered.solver import (
    ContactOptions,
    LayeredOptions,
    LayeredState,
    indent_layered,
)
from woundroll.materials import Core, Web
from woundroll.materials.radial_modulus import Constant

H = 1e-4
N = 9
R_CORE = 20.0
E_T = 5e9
NU = 0.3
E_P = E_T / (1 - NU**2)
STIFF = Web(
    thickness=H,
    width=0.1,
    E_theta=E_T,
    radial_modulus=Constant(E_T),
    G_r_theta=E_T / 2.6,
    nu_theta_z=NU,
)
EI_SLIP = (N - 1) * E_P * H**3 / 12 + E_P * H**3 / 3
EI_STICK = E_P * (N * H) ** 3 / 3
#: Winkler modulus [N/m^3]: the frictionless stack's bending length 1/beta = 5 mm
K_W = 4 * EI_SLIP / 5e-3**4
CORE = Core(outer_radius=R_CORE, stiffness=K_W * R_CORE)
DEPTH = 2e-5  # 0.2 h: small against the bending length and the sheet


def beam_stiffness(EI: float) -> float:
    """``P / w0 = 2 k / beta`` [N/m per m] of a beam on the Winkler foundation."""
    return 2 * K_W / (K_W / (4 * EI)) ** 0.25


def stack(
    mu: float, *, interfaces: bool = True, sheets: int = N, state: list[LayeredState] | None = None
) -> float:
    """Secant stiffness F/(L d) [N/m^2] of the stack pressed DEPTH deep by a 1 mm head."""
    r = np.linspace(R_CORE, R_CORE + sheets * H, 50)
    s = np.full(r.size, -1e3)  # 1 kPa wound-in: the interfaces closed
    base = ContactOptions(newton=False, n_steps=4, tangential_growth=1.05, tangential_size=5e-5)
    opts = LayeredOptions(base=base, layered_depth=(sheets - 1) * H, interfaces=interfaces)
    res = indent_layered(
        STIFF,
        CORE,
        r,
        s,
        head_radius=1e-3,
        head_length=0.1,
        depth_max=DEPTH,
        friction=mu,
        options=opts,
        state=state,
    )
    return float(res.force_per_length[-1] / res.delta[-1])


@pytest.fixture(scope="module")
def stiffness() -> tuple[float, float]:
    """(stuck, frictionless) stiffness of the nine-sheet stack."""
    return stack(1.0, interfaces=False), stack(1e-6)


def test_frictionless_sheets_bend_as_separate_plates(stiffness: tuple[float, float]) -> None:
    # mu = 1e-6 (the model refuses mu <= 0): bound 1e-6 P, the sheets slide freely.
    # Measured 2.839e5 against 2.834e5 N/m^2 (+0.2 %); the stuck stack 1.126e6 against
    # 1.119e6 (+0.6 %); the ratio 3.966 against 3.948. Tolerance 2 %: the ring's own hoop
    # stiffness (R beta = 4000) and the head's finite contact, each well under 1 % here
    # (at R = 5 m the stuck stack read +3.9 %)
    stuck, free = stiffness
    assert free == pytest.approx(beam_stiffness(EI_SLIP), rel=0.02)
    assert stuck == pytest.approx(beam_stiffness(EI_STICK), rel=0.02)
    ratio = (EI_STICK / EI_SLIP) ** 0.25
    assert ratio == pytest.approx(243**0.25)
    assert stuck / free == pytest.approx(ratio, rel=0.02)
    # and not one plate nine sheets thick (ratio 1), nor a free-bottom stack's 3
    assert stuck / free > 3.5


def slip_onset() -> dict[str, Any]:
    """The three-sheet strip stuck (mu 1e4), at mu = 1.5 q and at q / 3, q the stuck
    solution's largest |tau| / P: the forces and the states (docs/scripts/contact_checks.py
    shows them)."""
    st: list[LayeredState] = []
    stuck = stack(1e4, sheets=3, state=st)
    q = float(np.max(np.abs(st[0].shear) / st[0].pressure))
    high: list[LayeredState] = []
    low: list[LayeredState] = []
    return {
        "q": q,
        "stuck": (stuck, st[0]),
        "high": (stack(1.5 * q, sheets=3, state=high), high[0]),
        "low": (stack(q / 3, sheets=3, state=low), low[0]),
    }


def test_slip_starts_where_the_stuck_shear_reaches_mu_p() -> None:
    # a derived limit of the partial-slip solution (onset, as Cattaneo-Mindlin's): a
    # three-sheet strip (two interfaces) under the head. The stuck solution gives the
    # largest ratio q = |tau| / P over the interfaces; with mu = 1.5 q nothing may slip
    # and the force is the stuck one (to the stick passes' tolerance, 1e-4 relative); with
    # mu = q / 3 the strip must slip somewhere and be softer than stuck
    r = slip_onset()
    stuck, st = r["stuck"]
    assert np.all(st.slip == 0)
    q = r["q"]
    assert math.isfinite(q) and q > 0
    f_high, high = r["high"]
    assert f_high == pytest.approx(stuck, rel=1e-4)
    assert np.all(high.slip == 0)
    f_low, low = r["low"]
    assert f_low < stuck * (1 - 1e-3)
    assert np.any(low.slip > 0)
