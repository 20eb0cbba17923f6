"""Regenerate the stored references the tests compare with (after a deliberate model change).

``python tests/reference/regenerate.py examples`` runs every example in examples/ and stores
the numbers it prints in tests/reference/examples.json; ``... pipeline`` stores the headline
numbers of the rolls of tests/test_pipeline_reference.py in tests/reference/pipeline.json.
Commit the new file with the reason.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from test_examples import EXAMPLES, REFERENCE, numbers, run_example  # noqa: E402
from test_pipeline_reference import REFERENCE as PIPELINE  # noqa: E402
from test_pipeline_reference import ROLLS, headline  # noqa: E402


def examples() -> None:
    refs = {}
    for script in EXAMPLES:
        with tempfile.TemporaryDirectory() as tmp:
            refs[script.name] = numbers(run_example(script, Path(tmp)))
        print(f"{script.name}: {len(refs[script.name])} numbers")
    REFERENCE.write_text(json.dumps(refs, indent=1) + "\n")


def pipeline() -> None:
    refs = {roll: headline(*ROLLS[roll]) for roll in sorted(ROLLS)}
    PIPELINE.write_text(json.dumps(refs, indent=1) + "\n")
    print(f"{len(refs)} rolls")


if __name__ == "__main__":
    {"examples": examples, "pipeline": pipeline}[sys.argv[1] if len(sys.argv) > 1 else "examples"]()
