"""Generator of the table of docs/contact.md "Which model reads a roll": Rho (FD) of the
Table 2 rolls and the pile heights through each roll model (docs/scripts/regenerate.py).

The 3D column is read from the cached 3D references (``tests/contact/data/
contact3d_reference.json``, ~1 CPU min a roll to recompute with
``tests/contact/data/make_contact3d_reference.py``), computed with the Hertz-calibrated head
(6.565 mm); the 2D columns are run live with that head. About a minute on a quiet machine.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

REF = Path(__file__).resolve().parents[2] / "tests/contact/data/contact3d_reference.json"
REF_HEAD = "tester.head_radius='6.565 mm'"

#: rows of the table: label, the cached roll keys, the paper's measured fact
ROWS = [
    (
        "PET1 26.7 / 33.4 / 40 / 46.7 N",
        ("pet1-26.7N", "pet1-33.4N", "pet1-40N", "pet1-46.7N"),
        "its 1.5D models with the plane-strain spring agree closely with its 3D model and "
        "approach its tests as rolls get harder",
    ),
    (
        "PET2 26.7 / 53.4 / 80 N",
        ("pet2-26.7N", "pet2-53.4N", "pet2-80N"),
        "tests read *below* every model (interlayer slip)",
    ),
    (
        "PET2 53.4 N at H = 2 / 4 / 6 / 8.89 cm",
        ("pet2-53.4N-H2cm", "pet2-53.4N-H4cm", "pet2-53.4N-H6cm", "pet2-53.4N"),
        "tests nearly independent of the pile height",
    ),
]


def _reading(case: str, overrides: list[str]) -> float:
    import woundroll

    return woundroll.run(woundroll.load_case(case, overrides)).hardness.reading


def table() -> str:
    """The model-choice table: 2d and 2d+cmd-spread live, 3d cached."""
    ref = json.loads(REF.read_text())["cases"]
    lines = ["| roll | 2d | 2d+cmd-spread | 3d | measured fact (paper) |", "|---|---|---|---|---|"]
    for label, keys, fact in ROWS:
        cols: dict[str, list[str]] = {"2d": [], "2d+cmd-spread": [], "3d": []}
        for key in keys:
            c3 = ref[key]["3d"]
            ov = [*c3["overrides"], REF_HEAD]
            for model in ("2d", "2d+cmd-spread"):
                rho = _reading(c3["case"], [*ov, f"contact.model='{model}'"])
                cols[model].append(f"{rho:.1f}")
            cols["3d"].append(f"{c3['rho_fd']:.1f}")
        cells = " | ".join(" / ".join(v) for v in cols.values())
        lines.append(f"| {label} | {cells} | {fact} |")
    return "\n".join(lines)


BLOCKS: dict[str, Callable[[], str]] = {"table": table}

if __name__ == "__main__":
    print(table())
