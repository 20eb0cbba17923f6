"""``woundroll study slip``: Figure 18 and the slip emulation of Figure 19 (issue 9 item 6).

One roll in the default suite (the Figure 18 roll read with and without reduced shear); the
seven Table 2 rolls are what ``woundroll study slip`` runs (docs/studies.md has the table).
"""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.errors import InputError
from woundroll.studies.slip import slip_factor_study


@pytest.fixture(scope="module")
def study():
    return slip_factor_study("pet2-53.4N", emulation_cases=("pet2-53.4N",))


# slow: with the next test it runs the slip study (~30 s of the default suite);
# tests/contact/test_slip2d.py keeps the emulation in the default suite
@pytest.mark.slow
def test_emulation_rows_read_lower_with_slip(study) -> None:
    """Reduced shear where SF >= 1 softens the roll: lower reading, deeper striker (2D:
    measured 24.0 -> 13.4 Rho FD, 1.43 -> 2.01 mm); the no-slip row is the study's own
    Figure 18 roll read the same way (same case, same overrides but the slip key: equal to
    round-off)."""
    (row,) = study.emulation
    assert row["case"] == "pet2-53.4N"
    assert row["rho_fd_slip"] < 0.8 * row["rho_fd"]
    assert row["rho_energy_slip"] < 0.8 * row["rho_energy"]
    assert row["impact_depth_slip_m"] > row["impact_depth_m"]
    assert row["slipped_elements"] > 0
    assert row["rho_fd"] == pytest.approx(study.row["rho_fd"], rel=1e-9)


# slow: the slip study (see above)
@pytest.mark.slow
def test_emulation_in_tables_json_and_plot(study, tmp_path) -> None:
    titles = [t.title for t in study.summary()]
    assert len(titles) == 2 and "Figure 19" in titles[1]
    d = study.to_dict()
    assert d["emulation"]["contact_model"] == "2d"
    assert d["emulation"]["rolls"][0]["rho_fd_slip"] == study.emulation[0]["rho_fd_slip"]
    json.dumps(d, allow_nan=False)
    names = {p.name for p in study.write(tmp_path)}
    assert {"study.json", "slip_factor.png", "slip_emulation.png"} <= names


def test_bad_contact_model_is_rejected() -> None:
    with pytest.raises(InputError) as e:
        slip_factor_study(model="4d", emulation_cases=("pet2-53.4N",))
    assert e.value.field == "study.model"


def test_cli_model_option_names_the_studies() -> None:
    # the dynamic study fixes its models (2D and 3D rows side by side)
    res = CliRunner().invoke(app, ["study", "dynamic", "--model", "3d", "-q"])
    assert res.exit_code == 2
    assert "--model" in res.output and "slip" in res.output
    res = CliRunner().invoke(app, ["study", "tension", "--model", "4d", "-q"])
    assert res.exit_code == 2 and "unknown roll model" in res.output
