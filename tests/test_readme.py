"""The README's example case file is a plausible roll that runs in seconds.

The TOML block of README.md is read from the file itself (so the test follows the README),
loaded, and run through the whole pipeline (winding -> contact -> reading).
"""

import re
from pathlib import Path

import numpy as np

import woundroll
from woundroll.case import load_case

README = Path(__file__).resolve().parents[1] / "README.md"


def _readme_case(tmp_path: Path) -> Path:
    blocks = re.findall(r"```toml\n(.*?)```", README.read_text(encoding="utf-8"), re.S)
    assert len(blocks) == 1, "the README has one TOML case block"
    path = tmp_path / "readme.toml"
    path.write_text(blocks[0], encoding="utf-8")
    return path


def test_readme_case_is_plausible_and_runs(tmp_path):
    case = load_case(_readme_case(tmp_path))
    # plausible: no value outside its usual range (woundroll.limits), no long-run warning
    assert case.warnings == ()
    result = woundroll.run(case)
    assert not any(result.flags.values()), result.warnings
    w = result.winding
    # the numbers the README quotes, to their printed precision
    assert w.n_layers == 1500
    assert 0.3e6 < w.core_pressure < 0.45e6  # README: "about 0.38 MPa"
    assert 70.0 < result.hardness.reading < 95.0  # README: "about 83 Rho"
    assert np.isfinite(result.hardness.to_dict()["rho_energy"])
