"""Radial Poisson ratios on a stack stiffened under the head (issue 13, the contact cliff).

With nu_theta_r fixed, the reciprocal nu_r_theta = nu_theta_r E_r / E_theta grows with the
radial modulus, and past E_r ~ E_theta / nu_theta_r^2 (11 E_theta at 0.3) the orthotropic
compliance is indefinite. Pfeiffer's E_r = K2 (K1 - sigma_r) reaches that under the head of
a hard roll; the contact model holds the couplings nu_ij nu_ji at a bound there
(``woundroll.contact.plane_strain.fem.plane_strain_moduli``) instead of failing.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from woundroll.contact import ContactOptions, indent
from woundroll.contact.plane_strain.fem import MAX_RADIAL_COUPLING, plane_strain_moduli
from woundroll.materials import Core, Pfeiffer, Web

E_T = 5681e6
HARD = Web(
    thickness=1e-4,
    width=0.1524,
    E_theta=E_T,
    nu_theta_r=0.3,
    radial_modulus=Pfeiffer(4.62e3, 2000.0),  # PET1 with a 16x higher K2: a hard roll
)


def reference_moduli(web: Web, E_r: float) -> np.ndarray:
    """C11, C12, C22 by inverting the reduced 3x3 compliance directly (no scaling)."""
    Et, Ez = web.E_theta, web.E_z
    S = np.array(
        [
            [1 / E_r, -web.nu_theta_r / Et, -web.nu_z_r / Ez],
            [-web.nu_theta_r / Et, 1 / Et, -web.nu_theta_z / Et],
            [-web.nu_z_r / Ez, -web.nu_theta_z / Et, 1 / Ez],
        ]
    )
    red = S[:2, :2] - np.outer(S[:2, 2], S[:2, 2]) / S[2, 2]
    C = np.linalg.inv(red)
    return np.array([C[0, 0], C[0, 1], C[1, 1]])


@pytest.mark.parametrize(("nu_tr", "nu_zr"), [(0.3, 0.0), (0.0, 0.3), (0.3, 0.3), (0.49, 0.2)])
def test_moduli_positive_definite_for_any_radial_modulus(nu_tr: float, nu_zr: float) -> None:
    web = dataclasses.replace(HARD, nu_theta_r=nu_tr, nu_z_r=nu_zr)
    E_r = E_T * np.logspace(-4, 4, 81)
    C11, C12, C22, _ = plane_strain_moduli(web, E_r)
    assert np.all(np.isfinite(C11)) and np.all(C11 > 0) and np.all(C22 > 0)
    assert np.all(C11 * C22 - C12 * C12 > 0)
    # below the bound (coupling < 0.9 of its limit) the moduli are the unscaled ones, to
    # rounding (1e-9: the direct 3x3 inverse of the test)
    for e in E_r[E_r <= 0.5 * E_T]:
        got = np.array([m[0] for m in plane_strain_moduli(web, np.array([e]))[:3]])
        np.testing.assert_allclose(got, reference_moduli(web, e), rtol=1e-9, atol=1e-9 * e)
    # at the bound, the scaled couplings sit exactly at MAX_RADIAL_COUPLING of the limit
    C = plane_strain_moduli(web, np.array([1e4 * E_T]))
    det = C[0][0] * C[2][0] - C[1][0] ** 2
    assert np.isfinite(det) and det > 0
    assert MAX_RADIAL_COUPLING < 1


def test_hard_roll_with_poisson_ratios_indents() -> None:
    """The cliff of issue 13: nu_theta_r = 0.3 (or nu_z_r = 0.3) on a hard roll used to stop
    with "stiffness matrix is not positive definite". Now it solves, E_r under the head
    does pass the bound (else this test would not test the cap), and the force grows
    monotonically and continuously with the Poisson ratio (0 -> 0.25 -> 0.3: the cap only
    limits a coupling, it does not switch it off). Measured at 10 um (E_r up to 53 E_theta):
    F = 226, 252, 258 N; 25 % bounds the spread. (The law is exponential in the strain:
    at 30 um the same three differ 4x, so the depth is kept small.)"""
    r = np.linspace(0.0445, 0.06, 60)
    s = -np.linspace(1.0e6, 3.0e4, 60)
    head = {"head_radius": 6.565e-3, "head_length": 0.0254}
    opts = ContactOptions(n_steps=6, tangential_growth=1.25)
    forces = {}
    for nu in (0.0, 0.25, 0.3):
        web = dataclasses.replace(HARD, nu_theta_r=nu)
        res = indent(web, Core(outer_radius=0.0445), r, s, depth_max=1e-5, **head, options=opts)
        forces[nu] = res.force[-1]
        if nu == 0.3:
            assert np.max(web.E_r(res.sigma_r)) > E_T / nu**2  # past the old cliff
    assert forces[0.0] < forces[0.25] < forces[0.3] < 1.25 * forces[0.0]
    web = dataclasses.replace(HARD, nu_z_r=0.3)
    res = indent(web, Core(outer_radius=0.0445), r, s, depth_max=1e-5, **head, options=opts)
    # nu_z_r = 0.3 (plane strain: the CMD constraint couples it to sigma_r): 287 N measured
    assert forces[0.0] < res.force[-1] < 1.4 * forces[0.0]
