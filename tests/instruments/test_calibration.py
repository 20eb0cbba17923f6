"""Hertz line contact on the calibration block and the head calibration (77 Rho)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from woundroll.errors import ConvergenceError
from woundroll.instruments import get_instrument, impact_energy, impact_fd
from woundroll.instruments.calibration import CalibrationBlock, HertzLineContact, calibrate_head

RM = get_instrument("rho-meter")
BLOCK = CalibrationBlock.from_preset("rho-meter")


def test_block_is_table_1():
    assert BLOCK.youngs_modulus == pytest.approx(44.614e6, rel=1e-12)
    assert BLOCK.poisson_ratio == 0.458
    assert BLOCK.density == pytest.approx(1400.0, rel=1e-12)
    assert BLOCK.target_rho == 77


def test_hertz_half_width_and_asymptotic_approach():
    # NOTES: a = sqrt(4 P R / (pi E*)). For a << h the approach tends to
    # 2P(1-nu^2)/(pi E) (ln(2h/a) - nu/(2(1-nu))); at a/h ~ 1e-4 the difference is O((a/h)^2) ~ 1e-8
    c = HertzLineContact(0.01, 0.0254, BLOCK)
    F = 1e-3
    P = F / 0.0254
    a = float(c.half_width(F))
    assert a == pytest.approx(
        math.sqrt(4 * P * 0.01 / (math.pi * BLOCK.plane_strain_modulus)), rel=1e-14
    )
    assert a / BLOCK.thickness < 2e-4
    nu, E = BLOCK.poisson_ratio, BLOCK.youngs_modulus
    asym = (
        2
        * P
        * (1 - nu**2)
        / (math.pi * E)
        * (math.log(2 * BLOCK.thickness / a) - nu / (2 * (1 - nu)))
    )
    assert float(c.approach(F)) == pytest.approx(asym, rel=1e-7)


def test_hertz_approach_equals_integrated_axis_strain():
    # independent check of the closed form: integrate the plane-strain strain
    # eps_z = ((1 - nu^2) s_z - nu (1 + nu) s_x)/E along the axis from 0 to h numerically
    c = HertzLineContact(0.0066, 0.0254, BLOCK)
    nu, E, h = BLOCK.poisson_ratio, BLOCK.youngs_modulus, BLOCK.thickness
    for F in (10.0, 350.0, 2000.0):
        a = float(c.half_width(F))
        p0 = 2 * F / 0.0254 / (math.pi * a)

        def eps(z, a=a, p0=p0):
            r = math.sqrt(a * a + z * z)
            sz = -p0 * a / r
            sx = -p0 * ((a * a + 2 * z * z) / r - 2 * z) / a
            return ((1 - nu**2) * sz - nu * (1 + nu) * sx) / E

        val, _ = quad(eps, 0, h, epsabs=0, epsrel=1e-12, limit=200)
        assert float(c.approach(F)) == pytest.approx(-val, rel=1e-9)


#: The head radius Hertz line contact calibrates (docs/instruments.md, section 6): the
#: bundled file's head is calibrated through the default roll model instead (7.820 mm,
#: tests/contact/test_block.py), so the Hertz value is stated here.
HERTZ_HEAD = RM.with_overrides(head_radius=6.565e-3)


def test_hertz_head_reads_77_rho_on_the_block():
    # the Hertz-calibrated head reads 77 +- 0.5 Rho (FD = accelerometer) through Hertz
    law = HertzLineContact(HERTZ_HEAD.head_radius, RM.head_length, BLOCK).law(
        0.5 * RM.spring_stiffness * RM.release_position**2
    )
    fd = impact_fd(HERTZ_HEAD, law)
    assert fd.rho == pytest.approx(77.0, abs=0.5)
    # the energy model {22} reads lower by the striker spring's share (a few per cent)
    en = impact_energy(HERTZ_HEAD, law)
    assert fd.rho - en.rho == pytest.approx(
        RM.spring_stiffness * (RM.contact_position + en.max_depth) / (RM.rho_unit * RM.mass),
        abs=1e-3,
    )


def test_calibration_reproduces_the_hertz_radius():
    cal = calibrate_head(RM)
    assert cal.rho_fd == pytest.approx(77.0, abs=1e-6)
    # the documented Hertz radius to 4 figures (6.565 mm)
    assert cal.head_radius == pytest.approx(HERTZ_HEAD.head_radius, rel=2e-4)
    # Hertz stays a small-contact problem: half-width well below radius and block thickness
    assert cal.half_width < 0.3 * cal.head_radius and cal.half_width < 0.1 * BLOCK.thickness
    # the quadratic fit {3} over the impact's depth range reads within 1 Rho of the exact curve
    assert cal.rho_fd_fit == pytest.approx(cal.rho_fd, abs=1.0)
    e_cal = calibrate_head(RM, model="energy")
    assert e_cal.rho_energy == pytest.approx(77.0, abs=1e-6)
    assert e_cal.head_radius > cal.head_radius  # {22} omits the spring: needs a stiffer head


def test_calibration_accepts_any_roll_source():
    # a linear contact beta = c R from a callable: closed-form target for the energy model.
    # beta d = F_t and k(x_gap + d)^2 + F_t d = k x_in^2 give d, then beta, then R = beta/c.
    c = 5e7  # N/m per m of radius
    k, xi, xg = RM.spring_stiffness, RM.release_position, RM.contact_position
    F_t = 60.0 * RM.rho_unit * RM.mass
    # k d^2 + (2 k xg + F_t) d + k (xg^2 - xi^2) = 0
    A, B, C = k, 2 * k * xg + F_t, k * (xg**2 - xi**2)
    d = (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)
    R_exact = F_t / d / c
    cal = calibrate_head(
        RM, BLOCK, 60.0, contact=lambda inst: (0.0, c * inst.head_radius), model="energy"
    )
    assert cal.head_radius == pytest.approx(R_exact, rel=1e-8)
    # a callable F(d) is tabulated and works as well
    cal2 = calibrate_head(
        RM,
        BLOCK,
        60.0,
        model="energy",
        contact=lambda inst: lambda x: c * inst.head_radius * np.asarray(x),
    )
    assert cal2.head_radius == pytest.approx(R_exact, rel=1e-6)


def test_unreachable_target():
    with pytest.raises(ConvergenceError):
        calibrate_head(RM, BLOCK, 5000.0)
