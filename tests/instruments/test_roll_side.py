"""Roll spring, unloading branch and the tapered-column active mass ({3}, {14}-{18}, {20})."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from woundroll.errors import InputError
from woundroll.instruments import (
    QuadraticLaw,
    RollSpring,
    TabulatedLaw,
    as_roll_spring,
    roll_effective_mass,
    tapered_column_factor,
)


def _kappa_printed(a, H):
    """The paper's formula for kappa {18}, transcribed literally."""
    lam = a / (a + H)
    ln = math.log(lam)
    return (2 * lam**2 * (ln - 1) * ln + lam**2 - 1) / (2 * (lam**2 - 1) * ln**2)


def _kappa_by_quadrature(a, H):
    """Independent: kinetic-energy-equivalent mass of the column A(z) = 2(z + a) {16}, loaded
    at the top, fixed at depth H, with the static shape u ~ ln((H + a)/(z + a)), over rho V."""

    def shape(z):
        return math.log((H + a) / (z + a)) / math.log((H + a) / a)

    m, _ = quad(lambda z: 2 * (z + a) * shape(z) ** 2, 0.0, H, epsabs=0, epsrel=1e-13)
    return m / ((2 * a + H) * H)


def test_kappa_pet_rolls_notes_value():
    # NOTES.md: a = 0.6 cm, H = 8.89 cm -> kappa = 0.0601 (given to 3 significant figures)
    assert float(tapered_column_factor(0.006, 0.0889)) == pytest.approx(0.0601, abs=5e-5)


@pytest.mark.parametrize("ratio", [1e-2, 0.3, 1.0, 14.8, 300.0])
def test_kappa_matches_printed_formula_and_quadrature(ratio):
    # the cancellation-free evaluation must equal the printed formula (rel 1e-11 where that
    # one is well conditioned; for shallow columns its numerator cancels to ~u^3, u = H/a,
    # losing ~1e-16/u^3 -> rel 1e-8 at H/a = 0.01) and the independent quadrature (1e-9)
    a = 0.006
    H = ratio * a
    k = float(tapered_column_factor(a, H))
    assert k == pytest.approx(_kappa_printed(a, H), rel=1e-11 if ratio >= 0.3 else 1e-8)
    assert k == pytest.approx(_kappa_by_quadrature(a, H), rel=1e-9)


def test_kappa_uniform_column_limit():
    # H -> 0: lambda -> 1, the column becomes uniform; a uniform bar fixed at its base has
    # the textbook effective tip mass 1/3 of its mass. Series: kappa = 1/3 - u/6 + O(u^2),
    # u = ln(1 + H/a); at H/a = 1e-7 that is 1/3 - 1.7e-8.
    k = float(tapered_column_factor(1.0, 1e-7))
    assert k == pytest.approx(1.0 / 3.0 - 1e-7 / 6.0, abs=1e-12)
    ks = tapered_column_factor(1.0, np.geomspace(1e-9, 1e3, 200))
    assert np.all(np.diff(ks) < 0)  # deeper columns: smaller share of their mass is active


def test_effective_mass_formula():
    a, H, rho, L = 0.006, 0.0889, 1400.0, 0.0254
    m = roll_effective_mass(a, H, rho, L)
    assert m == pytest.approx(
        float(tapered_column_factor(a, H)) * rho * (2 * a + H) * H * L, rel=1e-14
    )
    # order of magnitude used in the docs: ~19 g for the PET rolls under a 1 inch head
    assert m == pytest.approx(0.0191, abs=5e-4)
    with pytest.raises(InputError) as exc:
        roll_effective_mass(a, -1.0, rho, L)
    assert exc.value.field == "tester.pile_height"


def test_quadratic_law_energy_is_integral_of_force():
    law = QuadraticLaw(3.7e8, 5.4e5)
    d = 5e-4
    W, _ = quad(lambda x: float(law.force(x)), 0, d, epsrel=1e-13)
    assert float(law.energy(d)) == pytest.approx(W, rel=1e-12)
    with pytest.raises(InputError) as exc:
        QuadraticLaw(-1.0, 5.4e5)
    assert exc.value.field == "roll_spring.alpha"
    with pytest.raises(InputError):
        QuadraticLaw(0.0, 0.0)


@pytest.mark.parametrize("e", [1.0, 0.9, 0.5, 0.2])
def test_unloading_returns_e_squared_of_stored_energy(e):
    # definition of the energetic restitution: unloading gives back e^2 W (quadrature, 1e-10)
    spring = RollSpring.quadratic(3.7e8, 5.4e5, restitution=e)
    d_max = 4.9e-4
    W = float(spring.law.energy(d_max))
    d_res = spring.residual_depth(d_max)
    back, _ = quad(lambda x: float(spring.unloading_force(x, d_max)), d_res, d_max, epsrel=1e-13)
    assert back == pytest.approx(e * e * W, rel=1e-10)
    assert float(spring.unloading_force(d_max, d_max)) == pytest.approx(
        float(spring.law.force(d_max)), rel=1e-14
    )
    assert float(spring.unloading_force(d_res, d_max)) == pytest.approx(0.0, abs=1e-9)
    if e == 1.0:  # elastic: unloading is the loading curve
        x = np.linspace(0, d_max, 7)
        assert np.allclose(spring.unloading_force(x, d_max), spring.law.force(x), rtol=1e-14)


def test_tabulated_law_is_exact_for_piecewise_linear_curves():
    d = np.array([0.0, 1e-4, 3e-4, 6e-4])
    F = np.array([0.0, 10.0, 50.0, 200.0])
    law = TabulatedLaw(d, F)
    assert float(law.force(2e-4)) == pytest.approx(30.0, rel=1e-14)
    # energy up to 3e-4: triangles/trapezoids 0.5e-3 + 6e-3 = 6.5e-3 J
    assert float(law.energy(3e-4)) == pytest.approx(0.5 * 10 * 1e-4 + 0.5 * 60 * 2e-4, rel=1e-14)
    assert law.force_scalar(4.5e-4) == pytest.approx(float(law.force(4.5e-4)), rel=1e-14)
    with pytest.raises(InputError):
        TabulatedLaw(d, np.array([0.0, 10.0, 5.0, 200.0]))
    with pytest.raises(InputError):
        TabulatedLaw(d[::-1], F)


def test_as_roll_spring_accepts_every_source():
    pair = as_roll_spring((3.7e8, 5.4e5), effective_mass=0.01)
    assert isinstance(pair.law, QuadraticLaw) and pair.effective_mass == 0.01
    tab = as_roll_spring(lambda x: 3.7e8 * x**2 + 5.4e5 * x, max_depth=1e-3)
    assert float(tab.law.force(5e-4)) == pytest.approx(float(pair.law.force(5e-4)), rel=1e-5)
    with pytest.raises(InputError):
        as_roll_spring("hard")
    with pytest.raises(InputError) as exc:
        RollSpring.quadratic(1e8, 1e5, effective_mass=-1.0)
    assert exc.value.field == "roll_spring.effective_mass"
    with pytest.raises(InputError) as exc:
        RollSpring.quadratic(1e8, 1e5, restitution=1.2)
    assert exc.value.field == "roll_spring.restitution"


def test_regularised_gamma3_matches_scipy() -> None:
    # the written-out P(3, x) of the tapered column {18} against SciPy's gammainc, over the
    # range u = ln(1 + H/a) spans (x = 2u from 1e-8 to 100) and across the switch at x = 1:
    # both are accurate to round-off, so 1e-12 relative
    from scipy.special import gammainc

    from woundroll.instruments.roll_side import _regularised_gamma3

    x = np.concatenate([np.logspace(-8, 2, 500), [1 - 1e-9, 1.0, 1 + 1e-9]])
    np.testing.assert_allclose(_regularised_gamma3(x), gammainc(3.0, x), rtol=1e-12)
