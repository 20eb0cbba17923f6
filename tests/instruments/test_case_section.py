"""The case file's [tester] table and hardness_from_spring."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.instruments import (
    RollSpring,
    get_instrument,
    impact_energy,
    impact_fd,
    roll_effective_mass,
)
from woundroll.instruments.case_section import hardness_from_spring, tester_from_spec

SPEC = {
    "instrument": "rho-meter",
    "head_radius": "1 cm",
    "collision": "keep-velocity",
    "time_step": "0.5 us",
    "pile_height": "8.89 cm",
    "semi_contact_width": "0.6 cm",
    "restitution": 0.9,
    "roll_spring": {"alpha": "3.7e8 N/m^2", "beta": "5.4 N/um", "effective_mass": "0 kg"},
}


def test_full_spec():
    s = tester_from_spec(SPEC)
    assert s.instrument.head_radius == pytest.approx(0.01, rel=1e-12)
    assert s.collision == "keep-velocity"
    assert s.time_step == pytest.approx(5e-7, rel=1e-12)
    assert s.pile_height == pytest.approx(0.0889, rel=1e-12)
    assert s.roll_spring.law.beta == pytest.approx(5.4e6, rel=1e-12)
    assert s.roll_spring.effective_mass == 0.0
    assert s.roll_spring.restitution == 0.9
    minimal = tester_from_spec({})
    assert minimal.instrument == get_instrument("rho-meter") and minimal.collision == "plastic"


@pytest.mark.parametrize(
    ("spec", "field"),
    [
        ({"instrument": "durometer"}, "tester.instrument"),
        ({"head_radius": "1 kg"}, "tester.head_radius"),
        ({"mass": "-5 g"}, "tester.mass"),
        ({"contact_position": "9 mm"}, "tester.contact_position"),
        ({"colour": "red"}, "tester.colour"),
        ({"collision": "sticky"}, "tester.collision"),
        ({"time_step": "1 m"}, "tester.time_step"),
        ({"pile_height": "-1 cm"}, "tester.pile_height"),
        ({"restitution": 1.5}, "tester.restitution"),
        ({"steps_per_contact": 3}, "tester.steps_per_contact"),
        ({"roll_spring": {"alpha": 1e8}}, "tester.roll_spring.beta"),
        ({"roll_spring": {"alpha": -1e8, "beta": 1e5}}, "tester.roll_spring.alpha"),
        ({"roll_spring": {"alpha": 1e8, "beta": "1 N"}}, "tester.roll_spring.beta"),
        ({"roll_spring": {"alpha": 1e8, "beta": 1e5, "gamma": 1}}, "tester.roll_spring.gamma"),
        (
            {"roll_spring": {"alpha": 1e8, "beta": 1e5, "effective_mass": "-1 g"}},
            "tester.roll_spring.effective_mass",
        ),
        ({"roll_spring": 3}, "tester.roll_spring"),
    ],
)
def test_bad_specs_name_the_field(spec, field):
    with pytest.raises(InputError) as exc:
        tester_from_spec(spec)
    assert exc.value.field == field


def test_hardness_from_spring_dict_and_models():
    s = tester_from_spec({"instrument": "rho-meter"})
    r = hardness_from_spring(s, 3.7e8, 5.4e5, 0.0)
    d = r.to_dict()
    for key in (
        "rho_energy",
        "rho_fd",
        "impulse_N_s",
        "impact_depth_m",
        "peak_force_N",
        "contact_time_s",
        "time_s",
        "force_N",
        "deceleration_m_per_s2",
    ):
        assert key in d
    text = json.dumps(d, allow_nan=False)  # JSON-ready and no NaN anywhere
    assert len(text) > 1000
    # the dictionary carries the models' own numbers
    assert d["rho_fd"] == impact_fd(s.instrument, (3.7e8, 5.4e5)).rho
    assert d["rho_energy"] == impact_energy(s.instrument, (3.7e8, 5.4e5)).rho
    assert d["reading"] == d["rho_fd"]
    assert len(d["time_s"]) == len(d["force_N"]) == len(d["deceleration_m_per_s2"])
    assert d["force_N"][-1] == 0.0 and max(d["force_N"]) <= d["peak_force_N"] * (1 + 1e-12)
    # explicit [tester.roll_spring] is used when alpha/beta are not given
    s2 = tester_from_spec({"roll_spring": {"alpha": 3.7e8, "beta": 5.4e5, "effective_mass": 0}})
    assert hardness_from_spring(s2).to_dict()["rho_fd"] == d["rho_fd"]
    with pytest.raises(InputError) as exc:
        hardness_from_spring(s)
    assert exc.value.field == "tester.roll_spring"


def test_schmidt_reading_is_rebound_number():
    s = tester_from_spec({"instrument": "schmidt-n", "restitution": 0.8})
    r = hardness_from_spring(s, 3.7e8, 5.4e5, 0.0)
    assert r.reading == r.fd.rebound_r and 0 < r.reading < 100


def test_effective_mass_from_the_tapered_column():
    s = tester_from_spec({"pile_height": "8.89 cm", "density": "1.4 g/cm^3"})
    L = s.instrument.head_length
    assert s.effective_mass() == pytest.approx(
        roll_effective_mass(0.006, 0.0889, 1400.0, L), rel=1e-12
    )
    with pytest.raises(InputError) as exc:
        tester_from_spec({}).effective_mass()
    assert exc.value.field == "tester.pile_height"


# PET rolls of Table 2 under the Rho-meter head: H = 8.89 cm, 1.4 g/cm^3, a = 0.6 cm
# (NOTES.md: kappa = 0.0601), L = 2.54 cm -> m_r = 19.1 g.
H_PET, RHO_PET = 0.0889, 1400.0
M_PET = roll_effective_mass(0.006, H_PET, RHO_PET, 0.0254)


def test_tapered_column_mass_of_the_pet_rolls():
    # 0.0601 x 1400 x (1.2 + 8.89) cm x 8.89 cm x 2.54 cm = 19.1 g (docs/instruments.md);
    # 0.1 g tolerance: the hand calculation uses kappa rounded to 3 figures
    assert M_PET == pytest.approx(0.0191, abs=1e-4)


def test_omitted_effective_mass_means_the_tapered_column():
    """[tester.roll_spring] without effective_mass: m_r of {14}-{18}, not 0 (issue 3)."""
    s = tester_from_spec({"roll_spring": {"alpha": 3.7e8, "beta": 5.4e5}})
    assert s.roll_mass_from_column
    # the pipeline's call: H and density supplied as fallbacks
    r = hardness_from_spring(s, pile_height=H_PET, density=RHO_PET)
    assert r.effective_mass == pytest.approx(M_PET, rel=1e-12)
    expected = impact_fd(s.instrument, RollSpring.quadratic(3.7e8, 5.4e5, M_PET))
    assert r.fd.rho == pytest.approx(expected.rho, rel=1e-12)
    # the mass matters: a massless roll reads ~25 % higher (77.5 vs 62 Rho, docs section 3)
    r0 = hardness_from_spring(s, effective_mass=0.0)
    assert r0.fd.rho > 1.2 * r.fd.rho
    # [tester] pile_height / density win over the caller's fallbacks
    s_own = tester_from_spec(
        {
            "pile_height": "4 cm",
            "density": "1 g/cm^3",
            "roll_spring": {"alpha": 3.7e8, "beta": 5.4e5},
        }
    )
    m_own = hardness_from_spring(s_own, pile_height=H_PET, density=RHO_PET).effective_mass
    assert m_own == pytest.approx(roll_effective_mass(0.006, 0.04, 1000.0, 0.0254), rel=1e-12)
    assert hardness_from_spring(s_own).effective_mass == m_own  # no fallbacks needed
    # no pile height / density anywhere: a clear error, not a silent 0 kg
    with pytest.raises(InputError) as exc:
        hardness_from_spring(s)
    assert exc.value.field == "tester.pile_height"
    with pytest.raises(InputError) as exc:
        hardness_from_spring(s, pile_height=H_PET)
    assert exc.value.field == "tester.density"


def test_explicit_effective_mass_is_kept_zero_included():
    for m in (0.0, 0.05):
        s = tester_from_spec({"roll_spring": {"alpha": 3.7e8, "beta": 5.4e5, "effective_mass": m}})
        assert not s.roll_mass_from_column
        # explicit value replaces the tapered column even when H and density are known
        r = hardness_from_spring(s, pile_height=H_PET, density=RHO_PET)
        assert r.effective_mass == m
        assert hardness_from_spring(s).effective_mass == m


def test_contact_model_call_form():
    """The pipeline's call after the contact model: (setup, alpha, beta, m_r) positionally."""
    s = tester_from_spec({})
    r = hardness_from_spring(s, 3.7e8, 5.4e5, M_PET)
    assert r.effective_mass == M_PET
    # or leave the mass to the tapered column with the pipeline's H and density
    r2 = hardness_from_spring(s, 3.7e8, 5.4e5, pile_height=H_PET, density=RHO_PET)
    assert r2.effective_mass == pytest.approx(M_PET, rel=1e-12)
    assert r2.fd.rho == pytest.approx(r.fd.rho, rel=1e-9)


def test_plot(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = tester_from_spec({})
    r = hardness_from_spring(s, 3.7e8, 5.4e5, 0.019)
    path = tmp_path / "impact.png"
    fig = r.plot(str(path))
    assert path.stat().st_size > 5000
    # stacked panels (issue 3: twin auto-scaled axes drew force and deceleration on top of
    # each other): force on top, deceleration [Rho] below with its striker-spring part
    force_ax, decel_ax = fig.axes[:2]
    assert force_ax.get_position().y0 > decel_ax.get_position().y1
    assert math.isclose(max(force_ax.lines[0].get_ydata()), max(r.fd.contact_force))
    total, contact, spring = (line.get_ydata() for line in decel_ax.lines[:3])
    rho = r.instrument.rho_unit
    np.testing.assert_allclose(total, r.fd.deceleration / rho, rtol=1e-12)
    np.testing.assert_allclose(total - contact, spring, rtol=1e-9, atol=1e-9)
    assert 0.01 < max(spring) / max(total) < 0.1  # the spring part: a few per cent, drawn
    plt.close(fig)
