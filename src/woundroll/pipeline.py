"""The pipeline: a case -> stresses in the roll -> roll stiffness under the striker ->
striker motion -> instrument reading (and, with a thickness profile, across the CMD).

Each step lives in its own package; this module only chains them and collects the
typed results into :class:`RunResult`:

1. winder settings -> stresses in the roll: :func:`woundroll.winding.hakiel.wind` (1D), or
   with ``winding.thickness_profile`` :func:`woundroll.profile.predict_profile` (axisymmetric
   winding, per-sector contact and reading across the CMD);
2. roll stiffness under the striker: :func:`roll_stiffness` (the 2D contact model
   :func:`woundroll.contact.indent`, and the spring {3} fitted over the depths the striker
   reaches, :func:`woundroll.instruments.roll_side.fit_roll_spring`);
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

from woundroll.case import Case, ContactSpec, load_case
from woundroll.errors import ConvergenceError, InputError

if TYPE_CHECKING:
    from woundroll.contact import ContactResult
    from woundroll.contact.result import ContactState
    from woundroll.instruments import HardnessResult, Instrument, TesterSetup
    from woundroll.instruments.roll_side import SpringFit
    from woundroll.materials.web import Core, Web
    from woundroll.profile.hardness import ProfileResult
    from woundroll.winding.result import WindingResult

#: ``progress(stage, fraction)``; stages "winding", "contact", "impact", "foundation".
Progress = Callable[[str, float], None]

#: Depth of the first contact solution [m]; deepened when the striker goes further.
FIRST_DEPTH = 1e-3


@dataclass(frozen=True, eq=False)
class RollStiffness:
    """Roll stiffness under the striker: the contact solution and the spring {3} used.

    Attributes
    ----------
    contact : ContactResult
        The 2D contact model's F(d), a(d) and fields (at its largest depth).
    spring : SpringFit
        ``alpha``, ``beta`` fitted over the depths the striker reaches, with the impact's
        maximum depth by the energy model {21}.
    """

    contact: ContactResult
    spring: SpringFit

    @property
    def alpha(self) -> float:
        return self.spring.alpha

    @property
    def beta(self) -> float:
        return self.spring.beta

    @property
    def impact_depth(self) -> float:
        """Maximum depth of the impact by the energy model {21} [m]."""
        return float(self.spring.max_depth)  # type: ignore[arg-type]

    @property
    def at_impact(self) -> ContactState:
        """Fields, slip factor {23} and a at the impact's maximum depth (interpolated)."""
        return self.contact.at_depth(min(self.impact_depth, float(self.contact.delta[-1])))

    @property
    def semi_contact_width(self) -> float:
        """Semi-contact width a at the impact's maximum depth [m]."""
        return self.at_impact.semi_contact_width

    def to_dict(self) -> dict[str, Any]:
        """The contact model's JSON (arrays over depth), with the spring actually used.

        ``alpha_N_per_m2`` / ``beta_N_per_m`` are the fit over the striker's reach;
        ``full_range_fit`` is the unconstrained fit over the whole computed curve.
        """
        out = self.contact.to_dict()
        out["full_range_fit"] = {
            "alpha_N_per_m2": out.pop("alpha_N_per_m2"),
            "beta_N_per_m": out.pop("beta_N_per_m"),
            "fit_r2": out.pop("fit_r2"),
            "fit_max_rel_residual": out.pop("fit_max_rel_residual"),
        }
        out.update(self.spring.to_dict())
        at = self.at_impact
        out["semi_contact_width_m"] = at.semi_contact_width
        out["depth_max_m"] = float(self.contact.delta[-1])
        out["at_impact_depth"] = at.to_dict()
        return out

    def plot(self, path: str | Path | None = None) -> list[Any]:
        """F(d) with the fit and a(d), and the slip-factor map {23} at the impact's depth.

        With ``path`` (``contact.png``) the second figure goes to ``contact_slip.png``.
        """
        from woundroll.contact import plot_slip_factor

        slip_path = None if path is None else str(path).removesuffix(".png") + "_slip.png"
        return [self.contact.plot(path), plot_slip_factor(self.at_impact, slip_path)]


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


def _check_head(instrument: Instrument) -> float:
    """The head length of a cylindrical head [m]; other heads are not in the 2D model."""
    if instrument.head_shape != "cylinder":
        raise InputError(
            f"the {instrument.name} has a {instrument.head_shape} head, but the 2D "
            "(plane-strain) contact model takes a cylindrical head with its axis along the "
            "CMD: give [tester.roll_spring] for this instrument",
            "tester.instrument",
        )
    # a cylinder without a length: the paper's plane-strain model per unit length would
    # need one; 2 R is the assumption (docs/contact.md)
    return instrument.head_length or 2.0 * instrument.head_radius


def roll_stiffness(
    web: Web,
    core: Core,
    radius: np.ndarray,
    sigma_r: np.ndarray,
    instrument: Instrument,
    spec: ContactSpec,
    *,
    update_modulus: bool = True,
) -> RollStiffness:
    """The 2D contact solve that gives the roll spring {3} under the instrument's head.

    The contact is solved to ``[contact] depth_max`` (default 1 mm) and the spring fitted
    over the depths the striker reaches (:func:`~woundroll.instruments.roll_side.fit_roll_spring`).
    Without an explicit ``depth_max``, a striker that goes deeper than the computed curve
    (extrapolation) makes the contact be solved again to 1.25 times its depth (at most
    three times); with one, that is an error.

    Parameters
    ----------
    radius, sigma_r : array [m], [Pa]
        The roll's pre-impact radial stress profile (core to surface).
    """
    from woundroll.contact import indent
    from woundroll.instruments.roll_side import fit_roll_spring

    head_length = _check_head(instrument)
    options = spec.contact_options()
    depth = spec.depth_max if spec.depth_max is not None else FIRST_DEPTH
    for _ in range(4):
        contact = indent(
            web,
            core,
            radius,
            sigma_r,
            head_radius=instrument.head_radius,
            head_length=head_length,
            depth_max=depth,
            friction=spec.friction,
            update_modulus=update_modulus,
            options=options,
        )
        spring = fit_roll_spring(contact.delta, contact.force, instrument)
        if not spring.extrapolated:
            return RollStiffness(contact, spring)
        if spec.depth_max is not None:
            raise InputError(
                f"the striker reaches {spring.max_depth * 1e3:.3g} mm, deeper than the "
                f"contact solution ({depth * 1e3:.3g} mm): raise it or leave it unset",
                "contact.depth_max",
            )
        depth = 1.25 * float(spring.max_depth)  # type: ignore[arg-type]
    raise ConvergenceError(
        f"the striker's depth kept growing past the contact solution ({depth * 1e3:.3g} mm) "
        "after 4 solutions"
    )


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
    setup = case.tester_setup()
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

    H = r_out - core.outer_radius
    a_given = "semi_contact_width" in (case.tester or {})
    report("contact", 0.0)
    stiff = roll_stiffness(
        web, core, winding.radius, winding.sigma_r, setup.instrument, case.contact
    )
    hardness = hardness_on_roll(setup, stiff, H, web.density, semi_contact_width_given=a_given)
    no_update = None
    if case.contact.no_update:
        report("contact", 0.5)
        frozen = roll_stiffness(
            web,
            core,
            winding.radius,
            winding.sigma_r,
            setup.instrument,
            case.contact,
            update_modulus=False,
        )
        no_update = NoUpdate(
            frozen,
            hardness_on_roll(setup, frozen, H, web.density, semi_contact_width_given=a_given),
        )
    report("contact", 1.0)
    return RunResult(
        case=case, winding=winding, contact=stiff, hardness=hardness, no_update=no_update
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
        _check_head(instrument),
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
        case.thickness_profile(),
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
    measured = case.measured_profile()
    if measured is not None:
        profile = profile.compare(measured)
    return RunResult(case=case, winding=winding, profile=profile, notes=tuple(notes))
