"""The pipeline: a case -> stresses in the roll -> roll stiffness under the striker ->
striker motion -> instrument reading (and, with a thickness profile, across the CMD).

Each step lives in its own package; this module only chains them and collects the
typed results into :class:`RunResult`:

1. winder settings -> stresses in the roll: :func:`woundroll.winding.hakiel.wind` (1D), or
   with ``winding.thickness_profile`` :func:`woundroll.profile.predict_profile` (axisymmetric
   winding, per-sector contact and reading across the CMD);
2. roll stiffness under the striker: :func:`woundroll.contact.roll_stiffness` (the 2D
   contact model, and the spring {3} fitted over the depths the striker reaches);
3. striker motion and reading: :func:`woundroll.instruments.hardness_from_spring` (FD
   {4}-{13} and energy {19}-{22} models).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from woundroll.case import Case, load_case
from woundroll.errors import InputError

if TYPE_CHECKING:
    from woundroll.contact import RollStiffness
    from woundroll.instruments import HardnessResult, TesterSetup
    from woundroll.materials.web import Core, Web
    from woundroll.profile.hardness import ProfileResult
    from woundroll.winding.result import WindingResult

#: ``progress(stage, fraction)``; stages "winding", "contact", "impact", "foundation".
Progress = Callable[[str, float], None]


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
            "impulse_Ns": h["impulse_Ns"],
            "delta_max_m": h["delta_max_m"],
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
    notes : tuple of str
    """

    case: Case
    winding: WindingResult | None = None
    contact: RollStiffness | None = None
    hardness: HardnessResult | None = None
    no_update: NoUpdate | None = None
    profile: ProfileResult | None = None
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
        """Write ``result.json`` and a PNG for every profile into ``out_dir``; return the paths.

        Raises
        ------
        InputError
            ``out_dir`` cannot be created or written (field ``--out``).
        """
        out = Path(out_dir)
        try:
            out.mkdir(parents=True, exist_ok=True)
            written = [out / "result.json"]
            written[0].write_text(self.to_json(indent=1), encoding="utf-8")
        except OSError as exc:
            raise InputError(f"cannot write to {out}: {exc.strerror or exc}", "--out") from None
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
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def hardness_on_roll(
    setup: TesterSetup,
    stiffness: RollStiffness,
    pile_height: float,
    density: float,
    *,
    semi_contact_width_given: bool = False,
) -> HardnessResult:
    """Impact models {4}-{22} with the contact model's spring and the roll's active mass.

    Active mass {14}-{18}: pile height H (``tester.pile_height``, else ``pile_height``: the
    wound thickness), density (``tester.density``, else the web's), and the semi-contact
    width a of the contact
    model at the impact's maximum depth (the paper takes a from its contact algorithm),
    unless ``tester.semi_contact_width`` is given.
    """
    from woundroll.instruments import hardness_from_spring

    if not semi_contact_width_given:
        setup = replace(setup, semi_contact_width=stiffness.semi_contact_width)
    return hardness_from_spring(
        setup, stiffness.alpha, stiffness.beta, pile_height=pile_height, density=density
    )


def run(case: Case | str | Path, *, progress: Progress | None = None) -> RunResult:
    """Run every model the case asks for.

    winder settings -> stresses in the roll (:mod:`woundroll.winding`) -> with ``[tester]``:
    roll stiffness under the striker (:mod:`woundroll.contact`, unless an explicit
    ``[tester.roll_spring]`` is given) -> striker motion and reading
    (:mod:`woundroll.instruments`). With ``winding.thickness_profile``: the CMD profile
    (:mod:`woundroll.profile`) instead of a single reading.

    Parameters
    ----------
    case : Case, or a path / bundled case name
    progress : callable, optional
        ``progress(stage, fraction)``.
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
    winding = wind(
        web, core, r_out, schedule, options=options, progress=lambda f: report("winding", f)
    )
    setup = case.tester_setup
    if case.winding.thickness_profile is not None:
        return _run_profile(case, web, core, r_out, schedule, winding, setup, report)
    if setup is None:
        return RunResult(case=case, winding=winding)

    from woundroll.instruments import hardness_from_spring

    if setup.roll_spring is not None:
        report("impact", 0.0)
        hardness = hardness_from_spring(
            setup, pile_height=r_out - core.outer_radius, density=web.density
        )
        report("impact", 1.0)
        return RunResult(
            case=case,
            winding=winding,
            hardness=hardness,
            notes=("roll spring given explicitly: contact model bypassed",),
        )

    from woundroll.contact import roll_stiffness

    H = r_out - core.outer_radius
    a_given = "semi_contact_width" in (case.tester or {})
    spec = case.contact
    args = {
        "depth_max": spec.depth_max,
        "friction": spec.friction,
        "options": spec.contact_options(),
        "model": spec.model,
        "options3d": spec.contact3d_options(),
    }
    report("contact", 0.0)
    stiff = roll_stiffness(web, core, winding.radius, winding.sigma_r, setup.instrument, **args)
    hardness = hardness_on_roll(setup, stiff, H, web.density, semi_contact_width_given=a_given)
    no_update = None
    if spec.no_update:
        report("contact", 0.5)
        # E_r frozen is softer: the striker goes at least as deep, start where that ended
        frozen = roll_stiffness(
            web,
            core,
            winding.radius,
            winding.sigma_r,
            setup.instrument,
            update_modulus=False,
            start_depth=float(stiff.contact.delta[-1]),
            **args,
        )
        no_update = NoUpdate(
            frozen,
            hardness_on_roll(setup, frozen, H, web.density, semi_contact_width_given=a_given),
        )
    report("contact", 1.0)
    notes = tuple(
        f"{label}: the striker reaches {rs.impact_depth * 1e3:.3g} mm, beyond the contact "
        f"model's range ({rs.contact.delta[-1] * 1e3:.3g} mm): its spring is extrapolated"
        for label, rs in (("contact", stiff), ("no update", no_update and no_update.stiffness))
        if rs is not None and rs.extrapolated
    )
    return RunResult(
        case=case,
        winding=winding,
        contact=stiff,
        hardness=hardness,
        no_update=no_update,
        notes=notes,
    )


def _run_profile(
    case: Case,
    web: Web,
    core: Core,
    r_out: float,
    schedule: Any,
    winding: WindingResult,
    setup: TesterSetup | None,
    report: Callable[[str, float], None],
) -> RunResult:
    """The CMD hardness profile: axisymmetric winding -> per-sector contact -> reading."""
    from woundroll.contact.spring import head_length_of
    from woundroll.instruments import get_instrument, tester_from_spec
    from woundroll.profile.hardness import ContactModel, FdReadout, NipSpec, predict_profile

    if setup is not None and setup.roll_spring is not None:
        raise InputError(
            "a CMD profile computes each sector's roll spring with the contact model; "
            "remove [tester.roll_spring] or winding.thickness_profile",
            "tester.roll_spring",
        )
    instrument = setup.instrument if setup is not None else get_instrument("rho-meter")
    spec = case.profile
    notes = [
        "winding: the 1D model at the nominal web thickness, for reference; "
        "profile: the axisymmetric model with the thickness profile",
    ]
    nip = None
    if case.winding.nip_roller is not None:
        roller = case.winding.nip_roller.build(case.winding.nip_load, case.winding.friction)
        nip = NipSpec(roller, foundation_stride=spec.foundation_stride)
        schedule = replace(schedule, nip_load=0.0)
    elif case.winding.nip_load > 0:
        notes.append(
            "nip: uniform nip-induced tension mu N / h across the CMD "
            "(give [winding.nip_roller] for the beam-on-foundation distribution)"
        )
    contact = ContactModel(
        web,
        core,
        instrument.head_radius,
        head_length_of(instrument),
        spec.depth_max,
        instrument=instrument,
        options=case.contact.contact_options(),
    )

    def progress(stage: str, done: int, total: int) -> None:
        report(stage, done / max(total, 1))

    profile = predict_profile(
        web,
        core,
        schedule,
        case.thickness_profile,
        outer_radius=r_out,
        contact=contact,
        instrument=instrument,
        n_sectors=spec.sectors,
        n_groups=spec.groups,
        nip=nip,
        depth_max=spec.depth_max,
        workers=spec.workers,
        progress=progress,
    )
    # the FD model per sector (the paper's "FD optional"), a few ms for the whole profile
    fd_setup = setup if setup is not None else tester_from_spec({"instrument": "rho-meter"})
    w = profile.winding
    fd = FdReadout(fd_setup, w.build_radius - w.core_radius, web.density)
    profile = replace(profile, rho_fd=fd(profile.alpha, profile.beta))
    measured = case.measured_profile
    if measured is not None:
        profile = profile.compare(measured)
    return RunResult(case=case, winding=winding, profile=profile, notes=tuple(notes))
