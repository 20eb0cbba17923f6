"""The pipeline: a case -> stresses in the roll -> roll stiffness under the striker ->
striker motion -> instrument reading (and, with a thickness profile, across the CMD).

Each step lives in its own package; this module only chains them and collects the
typed results into :class:`RunResult`.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from woundroll.case import Case, load_case

Progress = Callable[[str, float], None]


@dataclass(frozen=True)
class RunResult:
    """Everything one run produced; parts that did not run are None."""

    case: Case
    winding: Any = None
    contact: Any = None
    hardness: Any = None
    profile: Any = None
    notes: tuple[str, ...] = field(default_factory=tuple)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``{"case": ..., "winding": {...}, "contact": ..., "hardness": ...}``."""
        out: dict[str, Any] = {"case": {"title": self.case.title}}
        for name in ("winding", "contact", "hardness", "profile"):
            part = getattr(self, name)
            if part is not None:
                out[name] = part.to_dict()
        if self.notes:
            out["notes"] = list(self.notes)
        return out

    def to_json(self, **kw: Any) -> str:
        return json.dumps(self.to_dict(), default=_json_default, **kw)

    def write(self, out_dir: str | Path) -> list[Path]:
        """Write ``result.json`` and a PNG for every profile into ``out_dir``; return the paths."""
        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        written = [out / "result.json"]
        written[0].write_text(self.to_json(indent=1), encoding="utf-8")
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        for name in ("winding", "contact", "hardness", "profile"):
            part = getattr(self, name)
            if part is None or not hasattr(part, "plot"):
                continue
            figs = part.plot(out / f"{name}.png")
            for fig in figs if isinstance(figs, list | tuple) else [figs]:
                plt.close(fig)
            written.extend(sorted(out.glob(f"{name}*.png")))
        return written


def _json_default(obj: Any) -> Any:
    import numpy as np

    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def run(case: Case | str | Path, *, progress: Progress | None = None) -> RunResult:
    """Run every model the case asks for.

    Parameters
    ----------
    case : Case, or a path / bundled case name
    progress : callable(stage, fraction), optional
        Called as the long steps advance (the CLI draws a progress bar from it).
    """
    if not isinstance(case, Case):
        case = load_case(case)
    from woundroll.winding.hakiel import WindingOptions, wind

    web = case.web.build()
    core = case.core.build()
    r_out = case.winding.final_radius(web, core)
    schedule = case.winding.schedule(web)
    options = WindingOptions.from_dict(case.winding.options, "winding.options")
    cb = (lambda f: progress("winding", f)) if progress else None
    winding = wind(web, core, r_out, schedule, options=options, progress=cb)
    return RunResult(case=case, winding=winding)
