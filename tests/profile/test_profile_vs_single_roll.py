"""A uniform web read across the CMD is the single roll: the profile's sector reading of a
roll with a flat thickness profile must equal what `woundroll run` reads on the same roll
(the same contact model, impact model and instrument), up to the (r, z) winding's own
difference from the 1D winding.

PET2 53.4 N, 24 in wide, at 110 % of its tension (the causes round trip's roll), 3 sectors:
the single roll reads 16.68 Rho (FD) with the contact model's semi-contact width a = 1.45 mm
in the roll's active mass {14}-{18}; the profile's sectors take their own contact widths the
same way (until 2026-11-26 they took the tester's default 0.6 cm and read 14.67, 12 % low).
Tolerance 1.5 %: the profile reads 16.62 (-0.37 %, measured 2026-11-26); the (r, z)
winding's core pressure is 22.3 against the 1D's 20.5 kPa and its stresses within 3 % of the
1D's over the outer 20 mm.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from woundroll.case import load_case
from woundroll.pipeline import run


@pytest.fixture(scope="module")
def single_and_flat(tmp_path_factory: pytest.TempPathFactory) -> tuple:
    from woundroll.inverse.diagnosis import RollModel

    base = ["web.width='24 in'"]
    tension = 1.1 * RollModel.from_case(load_case("pet2-53.4N", base)).tension
    base.append(f"winding.tension='{tension} Pa'")
    single = run(load_case("pet2-53.4N", base))
    flat: Path = tmp_path_factory.mktemp("flat") / "flat.csv"
    pos = np.linspace(0.0, 609.6, 25)
    np.savetxt(flat, np.column_stack([pos, np.full(pos.size, 100.0)]), delimiter=",",
               header="position [mm],thickness [um]", comments="")  # fmt: skip
    sets = [*base, "profile.workers=1", "profile.sectors=3", f"winding.thickness_profile='{flat}'"]
    return single, sets


def test_with_the_single_rolls_a_the_profile_reads_the_single_roll(single_and_flat) -> None:
    single, sets = single_and_flat
    a = single.contact.semi_contact_width
    prof = run(load_case("pet2-53.4N", [*sets, f"tester.semi_contact_width='{a} m'"])).profile
    np.testing.assert_allclose(prof.rho, single.hardness.reading, rtol=0.015)


def test_the_profile_reads_the_single_roll(single_and_flat) -> None:
    single, sets = single_and_flat
    prof = run(load_case("pet2-53.4N", sets)).profile
    np.testing.assert_allclose(prof.rho, single.hardness.reading, rtol=0.015)
