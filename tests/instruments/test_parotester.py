"""The Parotester preset and the impact of a free-flying striker on a beta = 0 roll spring.

The Parotester's own data are not published; the preset is the Leeb type-D impact device
(11 mJ, 5.5 g, 3 mm sphere), docs/instruments.md. Its striker flies free at impact
(contact_position 0), and the 3D contact model's spring for a small sphere often fits with
beta = 0 (F = alpha d^2 stiffens faster than d): the FD impact must then still end.
"""

from __future__ import annotations

import math

import pytest

from woundroll.instruments import get_instrument, list_instruments
from woundroll.instruments.impact import impact_energy, impact_fd
from woundroll.instruments.roll_side import RollSpring

ALPHA = 3.4e7  # N/m^2: the 3D model's fit for this head on PET2 53.4 N (coarse mesh)


def test_preset_carries_the_stand_in_striker() -> None:
    p = get_instrument("parotester")
    assert "parotester" in list_instruments()
    assert p.readout == "parotester-l" and p.head_shape == "sphere" and not p.calibrated
    assert p.impact_energy == pytest.approx(0.011, rel=1e-12)  # 11 mJ: k x_in^2 / 2
    assert p.impact_speed == pytest.approx(math.sqrt(2 * 0.011 / 0.0055), rel=1e-12)  # 2 m/s
    assert p.head_radius == pytest.approx(1.5e-3) and p.contact_position == 0.0
    for key in ("mass", "spring_stiffness", "head_radius", "readout"):
        assert key in p.sources


@pytest.mark.parametrize("beta", [0.0, 1e3])
def test_elastic_massless_roll_returns_the_impact_speed(beta: float) -> None:
    """Closed-form limit: an elastic roll without mass gives the energy back, so the
    striker passes the contact position at its impact speed, L = 1000. beta = 0 ran into
    ConvergenceError before (F = alpha d^2 >= 0 for d < 0: the contact force never
    crossed zero). Tolerance 1e-6: the FD end point's interpolation (measured 2e-10)."""
    p = get_instrument("parotester")
    r = impact_fd(p, RollSpring.quadratic(ALPHA, beta))
    assert r.rebound_l == pytest.approx(1000.0, rel=1e-6)
    # the same depth as the energy balance {19}-{21} (no mass, no loss): 1e-3, FD steps
    assert r.max_depth == pytest.approx(
        impact_energy(p, RollSpring.quadratic(ALPHA, beta)).max_depth, rel=1e-3
    )


def test_restitution_and_plastic_collision_limits_with_beta_zero() -> None:
    """e = 0.7: the roll returns e^2 of the energy, L = 1000 e (+0.13 % from the striker's
    weak spring over the residual depth; tolerance 0.5 %). Plastic first contact with the
    roll mass m_r, then an elastic roll: L = 1000 m_s / (m_s + m_r) exactly (momentum)."""
    p = get_instrument("parotester")
    r = impact_fd(p, RollSpring.quadratic(ALPHA, 0.0, restitution=0.7))
    assert r.rebound_l == pytest.approx(700.0, rel=5e-3)
    m_r = 0.5e-3
    r = impact_fd(p, RollSpring.quadratic(ALPHA, 0.0, effective_mass=m_r))
    assert r.rebound_l == pytest.approx(1000.0 * p.mass / (p.mass + m_r), rel=1e-6)
