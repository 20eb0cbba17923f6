"""Radial-modulus laws: E_r = dP/deps of their stack curves, and clear errors."""

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.materials import Constant, Pfeiffer, Polynomial, Tabulated, law_from_spec


def numerical_modulus(law, eps):
    """E_r = dP/deps by central differences, paired with P(eps)."""
    d = 1e-7
    return law.pressure(eps), (law.pressure(eps + d) - law.pressure(eps - d)) / (2 * d)


@pytest.mark.parametrize(
    "law",
    [
        Pfeiffer(K1=4620.0, K2=123.88),
        Pfeiffer(K1=0.0, K2=246.5),
        Constant(E_r=2e6),
        Polynomial(C1=2e5, C2=3e6, C3=4e8, strain_max=0.1),
    ],
)
def test_modulus_is_slope_of_stack_curve(law):
    eps = np.linspace(0.001, 0.05, 20)
    p, slope = numerical_modulus(law, eps)
    # central differences with step 1e-7 are accurate to ~1e-6 relative on these smooth curves;
    # the polynomial law inverts a 2001-point table, so allow 1e-3 there
    tol = 1e-3 if isinstance(law, Polynomial) else 1e-5
    np.testing.assert_allclose(law.modulus(-p), slope, rtol=tol)


def test_pfeiffer_is_equation_2():
    law = Pfeiffer(K1=4620.0, K2=123.88)
    assert law.modulus(np.array([-1e5]))[0] == pytest.approx(123.88 * (4620 + 1e5), rel=1e-14)
    # K1 = 0 (Table 3): zero modulus at zero pressure, no error
    assert Pfeiffer(K1=0.0, K2=246.5).modulus(np.array([0.0]))[0] == 0.0


def test_tension_uses_zero_pressure_modulus():
    law = Pfeiffer(K1=4620.0, K2=123.88)
    assert law.modulus(np.array([+1e4]))[0] == law.modulus(np.array([0.0]))[0]


def test_tabulated_recovers_pfeiffer_curve():
    ref = Pfeiffer(K1=5000.0, K2=100.0)
    eps = np.linspace(0.0, 0.05, 60)
    tab = Tabulated(strain=tuple(eps[1:]), stack_pressure=tuple(ref.pressure(eps[1:])))
    p = np.array([1e3, 1e4, 5e4])
    # PCHIP on 60 points of an exponential: derivative error below 1 %
    np.testing.assert_allclose(tab.modulus_at_pressure(p), ref.modulus_at_pressure(p), rtol=1e-2)


def test_tabulate_is_exact_for_linear_laws():
    law = Pfeiffer(K1=4620.0, K2=123.88)
    p, e = law.tabulate(1e6)
    assert np.allclose(e, law.modulus_at_pressure(p), rtol=1e-14)


@pytest.mark.parametrize(
    ("spec", "field"),
    [
        ({"law": "pfeiffer", "K1": "5 kPa"}, "web.radial_modulus.K2"),
        ({"law": "pfeiffer", "K1": "5 kPa", "K2": 0}, "web.radial_modulus.K2"),
        ({"law": "pfeiffer", "K1": "5 m", "K2": 3}, "web.radial_modulus.K1"),
        ({"law": "constant", "E_r": "-1 MPa"}, "web.radial_modulus.E_r"),
        ({"law": "constant", "E_r": "1 MPa", "K9": 1}, "web.radial_modulus"),
        ({"law": "polynomial", "C1": "-1 MPa"}, "web.radial_modulus.C1"),
        (
            {"law": "tabulated", "strain": [0.01, 0.005, 0.02], "pressure": [1, 2, 3]},
            "web.radial_modulus.strain",
        ),
        ({"law": "nope"}, "web.radial_modulus.law"),
    ],
)
def test_bad_law_specs(spec, field):
    with pytest.raises(InputError) as info:
        law_from_spec(spec)
    assert info.value.field == field, str(info.value)


def test_tabulated_from_csv(tmp_path):
    f = tmp_path / "stack.csv"
    f.write_text("strain [%],pressure [kPa]\n1,1\n2,5\n5,100\n", encoding="utf-8")
    law = law_from_spec({"law": "tabulated", "file": "stack.csv"}, base_dir=tmp_path)
    assert law.pressure(np.array([0.02]))[0] == pytest.approx(5000.0)
