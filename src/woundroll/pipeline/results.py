"""What a run returns: :class:`RunResult` (the typed results of every step and their JSON)
and :func:`result_flags` (the flags and warnings of a run)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

#: the output's fields: "compact" (the default: every key but arrays longer than
#: :data:`COMPACT_MAX_POINTS`, which go to result.npz with --out) or "full" (every array in
#: the JSON as text); one default for every entry point (CLI --fields, RunResult.write)
FIELDS = ("compact", "full")
DEFAULT_FIELDS = "compact"
#: arrays longer than this are left out of a compact result (a 10,000-layer roll's five
#: per-node arrays are 1.6 MB of JSON text; docs/performance.md). 1,000: a Table 2 roll's
#: per-node fields (1,779 nodes) and impact time series (~2,000 steps) go to result.npz
#: too (its JSON 373 kB -> ~12 kB, ~50 ms of its process: writing the text); kept are the
#: scalars and the short tables (F(d) curves, a profile's sectors, limits).
COMPACT_MAX_POINTS = 1000


def compact(doc: dict[str, Any], max_points: int = COMPACT_MAX_POINTS) -> tuple[
    dict[str, Any], dict[str, np.ndarray]
]:  # fmt: skip
    """``doc`` without its numeric arrays longer than ``max_points`` (at any depth), and
    those arrays by dotted key (``"winding.sigma_r_Pa"``). The compact document lists the
    keys left out under ``"arrays_omitted"`` (absent when none was)."""
    arrays: dict[str, np.ndarray] = {}

    def walk(d: Any, path: str) -> Any:
        if isinstance(d, dict):
            out = {}
            for k, v in d.items():
                key = f"{path}.{k}" if path else str(k)
                a = _long_numeric(v, max_points)
                if a is not None:
                    arrays[key] = a
                else:
                    out[k] = walk(v, key)
            return out
        return d

    small = walk(doc, "")
    if arrays:
        small["arrays_omitted"] = sorted(arrays)
    return small, arrays


def _long_numeric(v: Any, max_points: int) -> np.ndarray | None:
    """``v`` as a float array (None: NaN) if it is a flat list of numbers longer than
    ``max_points``, else None."""
    if not isinstance(v, list) or len(v) <= max_points:
        return None
    try:
        a = np.array(v, dtype=float)  # None -> nan; nested lists give a 2D array
    except (TypeError, ValueError):
        return None
    return a if a.ndim == 1 else None


def _check_fields(fields: str) -> None:
    from woundroll.errors import InputError

    if fields not in FIELDS:
        raise InputError(f"fields must be one of {', '.join(FIELDS)}, got {fields!r}", "--fields")


if TYPE_CHECKING:
    from woundroll.case import Case
    from woundroll.contact import RollStiffness
    from woundroll.contact.dynamic.plane_strain import DynamicImpactResult
    from woundroll.instruments import HardnessResult
    from woundroll.profile.hardness import ProfileResult
    from woundroll.winding.result import WindingResult


@dataclass(frozen=True)
class NoUpdate:
    """The paper's "no update" comparison (Figure 8): E_r frozen at its pre-impact value."""

    stiffness: RollStiffness
    hardness: HardnessResult

    def to_dict(self) -> dict[str, Any]:
        h = self.hardness.to_dict()
        return {
            "alpha_N_per_m2": self.stiffness.alpha,
            "beta_N_per_m": self.stiffness.beta,
            "rho_fd": h["rho_fd"],
            "rho_energy": h["rho_energy"],
            "impulse_N_s": h["impulse_N_s"],
            "impact_depth_m": h["impact_depth_m"],
        }


@dataclass(frozen=True)
class RunResult:
    """Everything one run produced; parts that did not run are None.

    Attributes
    ----------
    case : Case
    winding : WindingResult or None
        1D Hakiel model (with a thickness profile: at the nominal thickness, for reference).
    contact : RollStiffness or None
        Contact model and the roll spring under the striker.
    hardness : HardnessResult or None
        The reading (FD and energy models).
    no_update : NoUpdate or None
        The same with E_r frozen at its pre-impact value.
    profile : ProfileResult or None
        CMD profile (runs with ``winding.thickness_profile``).
    dynamic : DynamicImpactResult or None
        The impact in time on the FE roll (``contact.dynamic = true``); in the JSON under
        ``hardness.dynamic``.
    notes : tuple of str
    """

    case: Case
    winding: WindingResult | None = None
    contact: RollStiffness | None = None
    hardness: HardnessResult | None = None
    no_update: NoUpdate | None = None
    profile: ProfileResult | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)
    warnings: tuple[str, ...] = field(default_factory=tuple)
    flags: dict[str, bool] = field(default_factory=dict)
    dynamic: DynamicImpactResult | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``{"schema_version": 2, "case": ..., "winding": {...}, "contact":
        ..., "hardness": ..., "flags": {...}, "warnings": [...]}`` (``flags``:
        :func:`result_flags`; the keys: :mod:`woundroll.pipeline.vocabulary`)."""
        from woundroll.pipeline.vocabulary import SCHEMA_VERSION

        out: dict[str, Any] = {"schema_version": SCHEMA_VERSION, "case": self.case.record()}
        for name in ("winding", "contact", "hardness", "no_update", "profile"):
            part = getattr(self, name)
            if part is not None:
                out[name] = part.to_dict()
        if "hardness" in out:
            # the roll model behind the reading (the registry's name, or the given spring)
            out["hardness"]["roll_model"] = (
                self.contact.model if self.contact is not None else "tester.roll_spring"
            )
        if self.dynamic is not None and "hardness" in out:
            out["hardness"]["dynamic"] = self.dynamic.to_dict()
        out["flags"] = dict(self.flags)
        out["warnings"] = list(self.warnings)
        if self.notes:
            out["notes"] = list(self.notes)
        return out

    def to_json(self, fields: str = "full", **kw: Any) -> str:
        """Standard JSON: NaN and infinities are written as null. ``fields="full"`` (the
        Python API's default: :meth:`to_dict` as is); ``"compact"`` (the CLI's and
        result.json's default, :data:`DEFAULT_FIELDS`) leaves out the arrays longer than
        :data:`COMPACT_MAX_POINTS` (listed under ``arrays_omitted``)."""
        from woundroll.util.output import strict_json

        _check_fields(fields)
        d = self.to_dict()
        return strict_json(d if fields == "full" else compact(d)[0], **kw)

    def write(self, out_dir: str | Path, fields: str = DEFAULT_FIELDS) -> list[Path]:
        """Write ``result.json`` and the PNG plots into ``out_dir``; return the paths.

        ``fields="compact"`` (the default): the arrays longer than
        :data:`COMPACT_MAX_POINTS` go to ``result.npz`` (NumPy's archive, one array per
        dotted key, ``numpy.load``) instead of the JSON, which lists them under
        ``arrays_omitted``; ``"full"``: every array in ``result.json``, no npz.

        Every file is written to a temporary directory inside ``out_dir`` and moved into
        place atomically, ``result.json`` last; it lists the run's files under ``"files"``.
        Files the previous run's ``result.json`` listed and this run did not write are
        removed; other plot-named PNGs are reported in ``notes`` (:mod:`woundroll.util.output`).

        Raises
        ------
        InputError
            ``out_dir`` cannot be created or written (field ``--out``).
        """
        import matplotlib

        from woundroll.util.output import OutputDir

        _check_fields(fields)
        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        parts = ("winding", "contact", "hardness", "profile")
        with OutputDir(out_dir) as od:
            for name in parts:
                part = getattr(self, name)
                if part is None or not hasattr(part, "plot"):
                    continue
                figs = part.plot(od.tmp / f"{name}.png")
                figs = list(figs) if isinstance(figs, list | tuple) else [figs]
                warning = self._plot_warning(name)
                if warning and figs:
                    # the flag on the plot itself (first figure: the one showing the reading)
                    first = sorted(od.tmp.glob(f"{name}*.png"))[0]
                    figs[0].text(0.01, 0.005, warning, color="red", fontsize=7, va="bottom")
                    figs[0].savefig(first, dpi=120)
                for fig in figs:
                    plt.close(fig)
            if self.dynamic is not None:
                fd = self.hardness.fd if self.hardness is not None else None
                plt.close(self.dynamic.plot(od.tmp / "dynamic.png", fd=fd))
            data = self.to_dict()
            arrays: dict[str, np.ndarray] = {}
            if fields == "compact":
                data, arrays = compact(data)
            if arrays:
                np.savez(od.tmp / "result.npz", **arrays)
            names = sorted(p.name for p in od.tmp.glob("*.png"))
            names += ["result.npz"] * bool(arrays) + ["result.json"]
            data["files"] = names
            from woundroll.util.output import strict_json

            (od.tmp / "result.json").write_text(strict_json(data, indent=1), encoding="utf-8")
            written, stale = od.publish(names, tuple(f"{p}*.png" for p in (*parts, "dynamic")))
        if stale:
            object.__setattr__(self, "notes", self.notes + tuple(stale))
        return written

    def _plot_warning(self, part: str) -> str:
        """The flags shown on the plot of ``part`` (empty when none)."""
        f = self.flags
        out = []
        if part in ("hardness", "profile") and f.get("reading_outside_range"):
            out.append("reading outside the instrument's range")
        if part in ("contact", "hardness", "profile") and f.get("spring_extrapolated"):
            out.append("roll spring extrapolated beyond the contact model's depth")
        if part == "winding" and f.get("implausible_input"):
            out.append("inputs outside their usual range (see warnings in result.json)")
        return ("warning: " + "; ".join(out)) if out else ""


def result_flags(
    instrument: Any,
    readings: Any,
    stiffness: list[Any],
    case_warnings: tuple[str, ...],
    max_pressure: float | None,
) -> tuple[dict[str, bool], list[str]]:
    """Flags of a run and the warnings that explain them.

    ``reading_outside_range``: a reading beyond the instrument's scale
    (:attr:`~woundroll.instruments.Instrument.reading_range`: the instrument would show its
    end stop). ``spring_extrapolated``: the striker goes deeper than the contact model was
    solved, so the spring {3} is extrapolated there. ``implausible_input``: a case value
    outside its plausible range (:mod:`woundroll.limits`). ``pressure_implausible``: the
    largest radial pressure in the roll is beyond the plausible range.
    """
    from woundroll.limits import pressure_warning

    flags = {
        "reading_outside_range": False,
        "spring_extrapolated": False,
        "implausible_input": any(not w.startswith("long run:") for w in case_warnings),
        "pressure_implausible": False,
    }
    warnings: list[str] = list(case_warnings)
    if max_pressure is not None:
        w = pressure_warning(max_pressure)
        if w:
            flags["pressure_implausible"] = True
            warnings.append(w)
    rng = getattr(instrument, "reading_range", None) if instrument is not None else None
    if rng is not None and readings is not None:
        r = np.atleast_1d(np.asarray(readings, dtype=float))
        out = (r < rng[0]) | (r > rng[1]) | ~np.isfinite(r)
        if out.any():
            flags["reading_outside_range"] = True
            bad = r[out & np.isfinite(r)]
            mid = 0.5 * (rng[0] + rng[1])
            far = bad[np.argmax(np.abs(bad - mid))] if bad.size else math.nan
            where = (
                f" in {int(out.sum())} of {r.size} sectors (excluded from the statistics)"
                if r.size > 1
                else ""
            )
            warnings.append(
                f"the model reads {far:.4g}{where}, beyond the {instrument.name}'s scale "
                f"{rng[0]:g}-{rng[1]:g} ({instrument.readout}): the instrument shows the scale's "
                "end there (saturated)"
            )
    for label, rs in stiffness:
        if rs is not None and rs.extrapolated:
            flags["spring_extrapolated"] = True
            ratio = rs.impact_depth / float(rs.contact.delta[-1])
            warnings.append(
                f"{label}: the striker reaches {rs.impact_depth * 1e3:.3g} mm, {ratio:.2g} x the "
                f"contact model's depth ({rs.contact.delta[-1] * 1e3:.3g} mm): the roll spring "
                "is extrapolated (set contact.depth_max deeper)"
            )
    return flags, warnings
