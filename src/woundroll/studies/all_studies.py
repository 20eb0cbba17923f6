"""``woundroll study all``: the tension, pile-height and slip studies in one result."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from woundroll.studies import pile_height, slip, tension
from woundroll.studies._common import Progress, SummaryTable, _write


@dataclass(frozen=True)
class AllStudies:
    """The three studies together (``woundroll study all``)."""

    parts: tuple[Any, ...]
    name: str = "all"

    def to_dict(self) -> dict[str, Any]:
        return {"study": self.name, **{p.name: p.to_dict() for p in self.parts}}

    def summary(self) -> list[SummaryTable]:
        return [t for p in self.parts for t in p.summary()]

    def notes(self) -> list[str]:
        return [n for p in self.parts for n in p.notes()]

    def plot(self, prefix: str | Path) -> list[Path]:
        return [q for p in self.parts for q in p.plot(prefix)]

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write one ``study.json`` (a key per study) and every study's PNGs."""
        return _write(self, out_dir)


def _all(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> AllStudies:
    steps = (
        (0.0, 0.55, lambda p: tension.run(p, workers=workers, model=model)),
        (
            0.55,
            0.35,
            lambda p: pile_height.pile_height_study(progress=p, workers=workers, model=model),
        ),
        (0.90, 0.10, lambda p: slip.slip_factor_study(progress=p, model=model)),
    )
    parts = []
    for lo, span, fn in steps:
        sub = (
            None
            if progress is None
            else (lambda stage, f, lo=lo, span=span: progress(stage, lo + span * f))
        )
        parts.append(fn(sub))
    return AllStudies(tuple(parts))


def run(
    progress: Progress | None = None, *, workers: int = 1, model: str | None = None
) -> AllStudies:
    """The registry's entry: the three studies, progress split 55/35/10 %, read with the
    roll ``model`` (None: the registry's default)."""
    return _all(progress, workers=workers, model=model)
