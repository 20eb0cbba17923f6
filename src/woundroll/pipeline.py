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

from woundroll.case import Case, ContactSpec, load_case

Progress = Callable[[str, float], None]


@dataclass(frozen=True)
class RunResult:
    """Everything one run produced; parts that did not run are None."""

    case: Case
    winding: Any = None
    contact: Any = None
    hardness: Any = None
    profile: Any = None
    no_update: Any = None
    notes: tuple[str, ...] = field(default_factory=tuple)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: ``{"case": ..., "winding": {...}, "contact": ..., "hardness": ...}``."""
        out: dict[str, Any] = {"case": {"title": self.case.title}}
        for name in ("winding", "contact", "hardness", "no_update", "profile"):
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


def roll_stiffness(
    web: Any,
    core: Any,
    winding: Any,
    instrument: Any,
    spec: ContactSpec,
    *,
    update_modulus: bool = True,
) -> Any:
    """The 2D contact solve that gives the roll spring {3} under the instrument's head.

    The depth range of the fit matters (F(d) is not exactly quadratic), so by default it
    follows the impact: the contact is solved to ``depth_max``, the energy model {21} gives
    the impact's maximum depth ``d`` with the fitted spring, and the solve is repeated to
    ``1.25 d`` until ``d <= depth_max <= 1.6 d`` (at most four solves; the first guess is
    1 mm). A ``[contact] depth_max`` fixes the range instead. (Assumption: the paper does
    not say over which range its quadratic was fitted.)
    """
    from woundroll.contact import indent
    from woundroll.instruments import energy_max_depth

    def solve(depth: float) -> Any:
        return indent(
            web, core, winding.radius, winding.sigma_r,
            head_radius=instrument.head_radius,
            head_length=instrument.head_length or 2 * instrument.head_radius,
            depth_max=depth, friction=spec.friction, update_modulus=update_modulus,
            options=spec.contact_options(),
        )

    if spec.depth_max is not None:
        return solve(spec.depth_max)
    depth = 1e-3
    for _ in range(4):
        contact = solve(depth)
        d = float(energy_max_depth(contact.alpha, contact.beta, instrument.spring_stiffness,
                                   instrument.release_position, instrument.contact_position))
        if d <= depth <= 1.6 * d:
            break
        depth = 1.25 * d
    return contact


def hardness_on_roll(setup: Any, contact: Any, winding: Any, web: Any, tester_spec: dict) -> Any:
    """Impact models {4}-{22} with the contact model's spring and the roll's active mass.

    Active mass {14}-{18}: pile height H = outer minus core radius (or
    ``tester.pile_height``), density of the web (or ``tester.density``), semi-contact width
    a = the contact model's half-width at the energy model's maximum depth (the paper takes
    a from its contact algorithm), unless ``tester.semi_contact_width`` is given.
    """
    from dataclasses import replace

    import numpy as np

    from woundroll.instruments import energy_max_depth, hardness_from_spring

    ins = setup.instrument
    if "semi_contact_width" not in tester_spec:
        d = float(energy_max_depth(contact.alpha, contact.beta, ins.spring_stiffness,
                                   ins.release_position, ins.contact_position))
        a = float(np.interp(d, contact.delta, contact.half_width))
        setup = replace(setup, semi_contact_width=max(a, web.thickness))
    H = setup.pile_height if setup.pile_height is not None else winding.radius[-1] - winding.radius[0]
    m_r = setup.effective_mass(pile_height=H, density=setup.density or web.density)
    return hardness_from_spring(setup, contact.alpha, contact.beta, m_r)


def run(case: Case | str | Path, *, progress: Progress | None = None) -> RunResult:
    """Run every model the case asks for.

    winder settings -> stresses in the roll (:mod:`woundroll.winding`) -> with ``[tester]``:
    roll stiffness under the striker (:mod:`woundroll.contact`, unless an explicit
    ``[tester.roll_spring]`` is given) -> striker motion and reading
    (:mod:`woundroll.instruments`).

    Parameters
    ----------
    case : Case, or a path / bundled case name
    progress : callable(stage, fraction), optional
        Called as the long steps advance (the CLI draws a progress bar from it).
    """
    if not isinstance(case, Case):
        case = load_case(case)
    from woundroll.winding.hakiel import WindingOptions, wind

    def report(stage: str, fraction: float) -> None:
        if progress is not None:
            progress(stage, fraction)

    web = case.web.build()
    core = case.core.build()
    r_out = case.winding.final_radius(web, core)
    schedule = case.winding.schedule(web)
    options = WindingOptions.from_dict(case.winding.options, "winding.options")
    winding = wind(web, core, r_out, schedule, options=options,
                   progress=lambda f: report("winding", f))
    setup = case.tester_setup()
    if setup is None:
        return RunResult(case=case, winding=winding)

    from woundroll.instruments import hardness_from_spring

    if setup.roll_spring is not None:
        report("impact", 0.0)
        hardness = hardness_from_spring(setup)
        report("impact", 1.0)
        return RunResult(case=case, winding=winding, hardness=hardness,
                         notes=("roll spring given explicitly: contact model bypassed",))

    report("contact", 0.0)
    contact = roll_stiffness(web, core, winding, setup.instrument, case.contact)
    report("contact", 0.5 if case.contact.no_update else 1.0)
    hardness = hardness_on_roll(setup, contact, winding, web, case.tester or {})
    no_update = None
    if case.contact.no_update:
        frozen = roll_stiffness(web, core, winding, setup.instrument, case.contact,
                                update_modulus=False)
        no_update = NoUpdate(frozen, hardness_on_roll(setup, frozen, winding, web,
                                                      case.tester or {}))
        report("contact", 1.0)
    return RunResult(case=case, winding=winding, contact=contact, hardness=hardness,
                     no_update=no_update)


@dataclass(frozen=True)
class NoUpdate:
    """The paper's "no update" comparison (Figure 8): E_r frozen at its pre-impact value."""

    contact: Any
    hardness: Any

    def to_dict(self) -> dict[str, Any]:
        h = self.hardness.to_dict()
        return {"alpha_N_per_m2": self.contact.alpha, "beta_N_per_m": self.contact.beta,
                "rho_fd": h["rho_fd"], "rho_energy": h["rho_energy"],
                "impulse_Ns": h["impulse_Ns"], "delta_max_m": h["delta_max_m"]}
