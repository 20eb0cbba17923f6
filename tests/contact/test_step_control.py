"""Step control of the contact solve (issue 14): one factorisation per load step, Rho kept.

The default contact solve predicts each increment's mid-step stress from the previous
increment and solves once at the modulus there, re-solving only where the achieved mid-step
modulus differs by more than ``step_tol`` (``woundroll.contact.solver._predicted_increment``).
Its reading must stay within 0.5 % of the 48-step explicit-midpoint answer (two
factorisations per step) on every Table 2 roll; measured: 0.23 % at most (PET2 80 N),
0.06 % on the PET1 rolls (docs/contact.md, step control).
"""

from __future__ import annotations

import pytest

from woundroll.case import load_case
from woundroll.pipeline import run

TABLE2 = ["pet1-26.7N", "pet1-33.4N", "pet1-40N", "pet1-46.7N", "pet2-26.7N", "pet2-53.4N"]
TABLE2 += ["pet2-80N"]
TOL = 0.005  # issue 14: Rho within 0.5 % of the 48-step answer


def reading(name: str, *options: str) -> tuple[float, int, int]:
    sets = [f"contact.options.{o}" for o in options]
    res = run(load_case(name, sets))
    assert res.hardness is not None and res.contact is not None
    c = res.contact.contact
    return res.hardness.to_dict()["rho_fd"], c.factorisations, len(c.delta) - 1


def check(name: str) -> None:
    rho, n_fact, n_steps = reading(name)
    ref, ref_fact, ref_steps = reading(name, "n_steps=48", "predictor=false")
    assert ref_steps == 48 and ref_fact == 2 * 48
    assert rho == pytest.approx(ref, rel=TOL), name
    # the predictor's point: well under the explicit midpoint's two factorisations per step
    # (31 of 48 possible on PET1 26.7 N, 27 on PET2 80 N, the first step always takes two)
    assert n_fact <= 1.5 * n_steps, (name, n_fact)


@pytest.mark.parametrize("name", ["pet1-26.7N", "pet2-80N"])
def test_predicted_steps_keep_rho(name: str) -> None:
    check(name)


@pytest.mark.slow
@pytest.mark.parametrize("name", TABLE2)
def test_predicted_steps_keep_rho_on_every_table2_roll(name: str) -> None:
    check(name)


def test_predictor_off_is_the_explicit_midpoint() -> None:
    # predictor=false keeps the earlier scheme: exactly two factorisations per step
    _, n_fact, n_steps = reading("pet1-46.7N", "predictor=false", "n_steps=8")
    assert n_fact == 2 * n_steps
