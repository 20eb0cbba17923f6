"""The headline numbers of the whole chain against stored references
(tests/reference/pipeline.json): a change of any model that moves a user's number fails here,
naming the roll and the key.

Tolerance: relative 1e-6. On one machine the chain is deterministic (run to run equal to
1e-12); 1e-6 leaves room for another BLAS's summation order and is far below any change worth
noticing (a Rho reading of 50 moves by 5e-5). After a deliberate model change, regenerate with
``python tests/reference/regenerate.py pipeline`` and say why in the commit.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

import woundroll

REFERENCE = Path(__file__).resolve().parent / "reference" / "pipeline.json"

#: the rolls (bundled case, overrides) and the keys of result.json stored for each
ROLLS: dict[str, tuple[str, list[str]]] = {
    "pet1-26.7N": ("pet1-26.7N", ["contact.no_update=true"]),
    "pet2-53.4N": ("pet2-53.4N", []),
    "pet2-53.4N-H2cm": ("pet2-53.4N", ["winding.outer_radius='6.45 cm'"]),
    "pet1-26.7N-cmd-spread": ("pet1-26.7N", ["contact.model='2d+cmd-spread'"]),
}
KEYS: dict[str, tuple[str, ...]] = {
    "winding": ("core_pressure_Pa", "max_pressure_Pa", "outer_radius_m"),
    "contact": (
        "alpha_N_per_m2",
        "beta_N_per_m",
        "semi_contact_width_m",
        "impact_depth_m",
        "max_force_N",
    ),
    "hardness": (
        "reading",
        "rho_fd",
        "rho_energy",
        "impulse_N_s",
        "impact_depth_m",
        "peak_force_N",
        "contact_time_s",
        "effective_mass_kg",
    ),
    "no_update": ("rho_fd", "rho_energy", "impulse_N_s"),
}
RTOL = 1e-6


def headline(case: str, overrides: list[str]) -> dict[str, float]:
    """``{"section.key": value}`` of a run's result.json, for the keys in :data:`KEYS`."""
    d: dict[str, Any] = json.loads(woundroll.run(woundroll.load_case(case, overrides)).to_json())
    return {f"{s}.{k}": d[s][k] for s, keys in KEYS.items() if s in d for k in keys}


@pytest.mark.parametrize("roll", sorted(ROLLS))
def test_headline_numbers_match_the_stored_reference(roll: str) -> None:
    got = headline(*ROLLS[roll])
    want = json.loads(REFERENCE.read_text())[roll]
    assert sorted(got) == sorted(want)
    off = {k: (got[k], w) for k, w in want.items() if got[k] != pytest.approx(w, rel=RTOL)}
    assert off == {}


def test_the_reference_comparison_can_fail() -> None:
    # a reading moved by 1e-5 of itself is caught
    want = json.loads(REFERENCE.read_text())["pet1-26.7N"]["hardness.reading"]
    assert want * (1 + 1e-5) != pytest.approx(want, rel=RTOL)
