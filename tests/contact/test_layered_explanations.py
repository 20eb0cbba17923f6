"""The other explanations of the readings beside interlayer friction (issue 25, item 4):
G_r_theta frozen at its pre-impact value (``shear_frozen``) and another G/E_r
(``shear_ratio``), in the plane-strain models (docs/contact.md "Other explanations").

Every assertion states its tolerance and why.
"""

from __future__ import annotations

import numpy as np
import pytest

from woundroll.contact import ContactOptions, indent
from woundroll.contact.layered.solver import LayeredOptions, indent_layered
from woundroll.contact.models import ROLL_MODELS
from woundroll.errors import InputError
from woundroll.materials import Core, Pfeiffer, Web
from woundroll.materials.radial_modulus import Constant

R_CORE, R_OUT, H = 0.0445, 0.1334, 1e-4
PET1 = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Pfeiffer(4.62e3, 123.88))
RIGID = Core(outer_radius=R_CORE)
HEAD = {"head_radius": 0.01, "head_length": 0.02, "depth_max": 0.5e-3}
R = np.linspace(R_CORE, R_OUT, 200)
S = -(30e3 + 1e6 * (R_OUT - R) / (R_OUT - R_CORE))


def force(web: Web = PET1, **opts: object) -> np.ndarray:
    res = indent(web, RIGID, R, S, options=ContactOptions(n_steps=6, **opts), **HEAD)  # type: ignore[arg-type]
    return np.asarray(res.force)


@pytest.fixture(scope="module")
def default() -> np.ndarray:
    return force()


def test_unset_options_leave_the_2d_model_bit_for_bit(default: np.ndarray) -> None:
    # the web's own rule is G = 2 E_r (Table 2): shear_ratio = 2 computes the same numbers
    # in the same order, so the curve must be identical to the last bit (exact equality);
    # and a roll whose E_r does not change (a constant law) is the same frozen or not, to
    # rounding (1e-12: the step's secant modulus dP / (dP / E_r) is E_r to the last bit
    # or two, the frozen G is 2 E_r exactly)
    assert np.array_equal(force(shear_ratio=2.0), default)
    flat = Web(thickness=H, width=0.1524, E_theta=5681e6, radial_modulus=Constant(2e6))
    np.testing.assert_allclose(force(flat, shear_frozen=True), force(flat), rtol=1e-12)


def test_frozen_and_lower_shear_soften_the_roll(default: np.ndarray) -> None:
    # E_r stiffens under the head (Pfeiffer {2}), so G frozen at the pre-impact E_r is
    # smaller there than 2 E_r: a softer roll; a lower ratio softens every element. Bounds
    # from the physics only (strict order), no fitted number
    frozen = force(shear_frozen=True)[-1]
    half = force(shear_ratio=1.0)[-1]
    assert frozen < default[-1]
    assert half < default[-1]
    assert force(shear_ratio=0.25)[-1] < half


def test_layered_model_takes_the_options() -> None:
    # the layered model builds on the 2D roll: frozen shear softens it too (strict)
    base = ContactOptions(newton=False, n_steps=4)
    kw = {"friction": 0.3, **HEAD}

    def run(**o: object) -> float:
        opts = LayeredOptions(base=ContactOptions(**{**base.__dict__, **o}), layered_depth=5 * H)
        return float(indent_layered(PET1, RIGID, R, S, options=opts, **kw).force[-1])  # type: ignore[arg-type]

    assert run(shear_frozen=True) < run()


@pytest.mark.parametrize(
    ("opts", "field"),
    [
        ({"shear_ratio": 0.0}, "options.shear_ratio"),
        ({"shear_ratio": float("nan")}, "options.shear_ratio"),
        ({"shear_frozen": "yes"}, "options.shear_frozen"),
    ],
)
def test_bad_shear_options_name_the_field(opts: dict[str, object], field: str) -> None:
    with pytest.raises(InputError) as err:
        ContactOptions(**opts)  # type: ignore[arg-type]
    assert err.value.field == field


def test_the_3d_model_refuses_the_shear_options() -> None:
    # not taken silently: the 3D model has G_r_z too and no such option yet
    from woundroll.instruments import get_instrument

    with pytest.raises(InputError) as err:
        ROLL_MODELS["3d"].solve(
            PET1,
            RIGID,
            R,
            S,
            get_instrument("rho-meter"),
            depth_max=1e-3,
            friction=0.3,
            update_modulus=True,
            options=ContactOptions(shear_frozen=True),
            options3d=None,
        )
    assert err.value.field == "shear_frozen"
