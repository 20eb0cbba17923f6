"""Regenerate the table of docs/contact.md "Which model reads a roll": Rho (FD) of the Table 2
rolls and the pile heights through each roll model.

The 3D column is read from the cached 3D references (``tests/contact/data/
contact3d_reference.json``, ~1 CPU min a roll to recompute with
``tests/contact/data/make_contact3d_reference.py``), computed with the Hertz-calibrated head
(6.565 mm); the 2D columns are run live with that head, and with the bundled head (the
registry's default model's calibration) in the last column. About a minute::

    .venv/bin/python docs/scripts/model_choice.py
"""

from __future__ import annotations

import json
from pathlib import Path

import woundroll

REF = Path(__file__).resolve().parents[2] / "tests/contact/data/contact3d_reference.json"
REF_HEAD = "tester.head_radius='6.565 mm'"


def reading(case: str, overrides: list[str]) -> float:
    return woundroll.run(woundroll.load_case(case, overrides)).hardness.reading


def main() -> None:
    ref = json.loads(REF.read_text())["cases"]
    print("| roll | 2d | 2d+cmd-spread | 3d (cached) | 2d, bundled head |")
    print("|---|---|---|---|---|")
    for key, entry in ref.items():
        c3 = entry["3d"]
        ov = [*c3["overrides"], REF_HEAD]
        r2 = reading(c3["case"], [*ov, "contact.model='2d'"])
        rs = reading(c3["case"], [*ov, "contact.model='2d+cmd-spread'"])
        rb = reading(c3["case"], c3["overrides"])
        print(f"| {key} | {r2:.1f} | {rs:.1f} | {c3['rho_fd']:.1f} | {rb:.1f} |")


if __name__ == "__main__":
    main()
