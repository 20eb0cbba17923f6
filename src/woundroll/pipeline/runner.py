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

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from woundroll.case import Case, load_case
from woundroll.errors import InputError
from woundroll.pipeline.results import NoUpdate, RunResult, result_flags

if TYPE_CHECKING:
    from woundroll.contact import RollStiffness
    from woundroll.instruments import HardnessResult, TesterSetup
    from woundroll.materials.web import Core, Web

#: ``progress(stage, fraction)``; stages "winding", "contact", "impact", "foundation",
#: "dynamic".
Progress = Callable[[str, float], None]


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


def _calibration_notes(instrument: Any, model: str) -> list[str]:
    """A note when the head was calibrated on its block in another model than the one that
    reads this roll (docs/instruments.md, "The head calibrated in the reading's model")."""
    cal = instrument.calibration_model
    if not cal or cal == model:
        return []
    return [
        f"the head was calibrated on its block in the {cal!r} model, this roll is read in "
        f"{model!r}: `woundroll calibrate-head --model {model}` gives a head calibrated in it "
        "(on the Table 2 rolls the head radius moves the reading by about 0.4 %)"
    ]


def _restitution_given(case: Case) -> bool:
    t = case.tester or {}
    rs = t.get("roll_spring")
    return "restitution" in t or (isinstance(rs, dict) and "restitution" in rs)


def _with_unloading(setup: TesterSetup, web: Web, pressure: float, notes: list[str]) -> TesterSetup:
    """The setup with the roll spring's restitution from the web's unloading law
    (:func:`woundroll.materials.unloading.restitution_at_pressure` at ``pressure``)."""
    from woundroll.materials.unloading import restitution_at_pressure

    e = restitution_at_pressure(web, pressure)
    notes.append(
        f"roll unloading: web.radial_unloading gives e = {e:.3f} for a stack cycle to "
        f"{pressure / 1e6:.3g} MPa (the pressure under the head), used by the FD model"
    )
    rs = setup.roll_spring
    return replace(
        setup, restitution=e, roll_spring=None if rs is None else replace(rs, restitution=e)
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
    setup = case.tester_setup
    if case.winding.thickness_profile is not None:
        if case.storage is not None:
            raise InputError(
                "a storage change is not modelled with winding.thickness_profile yet", "storage"
            )
        if case.winding.speed > 0:
            raise InputError(
                "entrained air is not modelled with winding.thickness_profile yet",
                "winding.speed",
            )
        return _run_profile(case, web, core, r_out, schedule, options, setup, report)
    # winding: the stresses in the roll
    winding = wind(
        web, core, r_out, schedule, options=options, progress=lambda f: report("winding", f)
    )
    after = after_winding(case, winding, web, core, r_out, schedule, options)
    winding, air_notes, air_warnings = after.winding, after.air_notes, after.air_warnings
    loose, storage_warnings = after.air_loose, after.storage_warnings
    max_p = float(-np.min(winding.sigma_r))
    if setup is None:
        flags, warns = result_flags(None, None, [], case.warnings, max_p)
        result = RunResult(case=case, winding=winding, warnings=tuple(warns), flags=flags)
    elif setup.roll_spring is not None:
        result = _run_given_spring(case, winding, setup, web, core, r_out, max_p, report)
    else:
        result = _run_contact(case, winding, setup, web, core, r_out, max_p, report)
    if winding.air is not None:
        result = replace(
            result,
            notes=(*result.notes, *air_notes),
            warnings=result.warnings + air_warnings,
            flags={**result.flags, "air_loose": loose},
        )
    result = _with_mode_notes(result, schedule, web, core, r_out)
    if case.storage is None:
        return result
    st = winding.storage
    note = (
        f"storage: temperature change {st['temperature_change_K']:g} K, moisture change "
        f"{st['moisture_change']:g}"
        + (
            f", {st['storage_time_s'] / 86400:.4g} d of radial creep"
            if "storage_time_s" in st
            else ""
        )
        + f": core pressure {st['core_pressure_before_Pa'] / 1e3:.4g} -> "
        f"{st['core_pressure_Pa'] / 1e3:.4g} kPa; stresses and reading are after storage"
    )
    return replace(
        result,
        notes=(*result.notes, note),
        warnings=result.warnings + storage_warnings,
        flags={**result.flags, "storage_overstress": bool(storage_warnings)},
    )


def _with_mode_notes(
    result: RunResult, schedule: Any, web: Web, core: Any, r_out: float
) -> RunResult:
    """Surface and centre-surface winding (``winding.mode``): a note with the nip-induced
    tension against centre winding's ``mu N``, a warning where the web slips on the drum
    (:mod:`woundroll.winding.tension`). Centre winding: the result as is."""
    if schedule.mode == "center":
        return result
    nit = schedule.nip_induced_line()
    notes = [
        f"winding.mode = {schedule.mode}: nip-induced tension {nit:.4g} N/m (centre winding's "
        f"mu N would be {schedule.friction * schedule.nip_load:.4g} N/m; it levels off at "
        f"{min(schedule.friction, schedule.drum_friction) * schedule.nip_saturation:.4g} N/m)"
    ]
    warnings: tuple[str, ...] = ()
    r = result.winding.radius
    if schedule.drum_slips(r, core.outer_radius, r_out, web.thickness):
        hold = float(schedule.drum_limit(schedule.web_stress * web.thickness))
        warnings = (
            f"winding: the tension differential {schedule.tension_differential:.4g} N/m exceeds "
            f"what the drum holds ({hold:.4g} N/m at the core's web tension): the web slips on "
            "the drum and the wound-on tension takes the drum's limit",
        )
    return replace(
        result,
        notes=(*result.notes, *notes),
        warnings=result.warnings + warnings,
        flags={**result.flags, "drum_slip": bool(warnings)},
    )


@dataclass(frozen=True)
class AfterWinding:
    """The roll the rest of the chain reads (:func:`after_winding`), with what the steps
    after winding have to say."""

    winding: Any  # WindingResult: after the air has left and after storage
    air_notes: tuple[str, ...] = ()
    air_warnings: tuple[str, ...] = ()
    air_loose: bool = False
    storage_warnings: tuple[str, ...] = ()


def after_winding(
    case: Case, winding: Any, web: Web, core: Any, r_out: float, schedule: Any, options: Any
) -> AfterWinding:
    """The wound roll as the contact model and the reading see it: after the entrained air
    has left (``winding.speed`` > 0) and after storage (``[storage]``: temperature,
    moisture, creep), in that order. The one place every road through the chain takes
    these steps: :func:`run`, and the reverse road's forward model
    (:meth:`woundroll.inverse.diagnosis.RollModel.wound`: diagnose, causes, design,
    uncertainty). A case with neither gets ``winding`` back untouched."""
    winding, air_notes, air_warnings, loose = _after_air(
        case, winding, web, core, r_out, schedule, options
    )
    winding, storage_warnings = _after_storage(case, winding, web, core)
    return AfterWinding(winding, air_notes, air_warnings, loose, storage_warnings)


def _after_air(
    case: Case, winding: Any, web: Web, core: Any, r_out: float, schedule: Any, options: Any
) -> tuple[Any, tuple[str, ...], tuple[str, ...], bool]:
    """``winding.speed`` > 0: the roll wound with entrained air
    (:func:`woundroll.winding.air.wind_with_air`); everything downstream (storage, contact,
    reading) sees the roll after the air has left (the contact model knows the stack's law,
    not the air layer). Speed 0 (the default): the roll as wound, untouched."""
    if not case.winding.speed > 0:
        return winding, (), (), False
    from woundroll.case.schema import AirSpec
    from woundroll.winding.air import wind_with_air

    spec = case.air if case.air is not None else AirSpec()
    roller = case.winding.nip_roller
    settings = spec.build(
        case.winding.speed, case.web.roughness, roller.outer_radius if roller else None
    )
    res = wind_with_air(web, core, r_out, schedule, settings, options=options, no_air=winding)
    when = (
        "after the air has left"
        if math.isinf(settings.time)
        else f"{settings.time:g} s after winding (air.time)"
    )
    notes = (
        res.summary(),
        f"air: the roll downstream (storage, contact, reading) is the roll {when}; 'air' in "
        "result.json holds the roll at winding and the diameters",
    )
    return replace(res.after, air=res.to_dict()), notes, res.warnings, res.loose


def _after_storage(case: Case, winding: Any, web: Web, core: Any) -> tuple[Any, tuple[str, ...]]:
    """``[storage]``: the roll after its temperature and moisture change
    (:func:`woundroll.winding.storage.apply_storage`); everything downstream (contact,
    reading) sees the roll after the change. No ``[storage]``: the wound-in roll as is."""
    if case.storage is None:
        return winding, ()
    from woundroll.winding.storage import apply_storage

    spec = case.storage
    res = apply_storage(winding, web, core, spec.build())
    record = res.to_dict()
    after = res.winding
    law = spec.creep_law()
    if law is not None and spec.time > 0.0:
        # storage time: the stack creeps under the pressure after the temperature change
        from woundroll.winding.creep import apply_creep

        steps = {} if spec.time_steps is None else {"steps": spec.time_steps}
        crept = apply_creep(after, web, core, law, spec.time, **steps)
        after = crept.winding
        record = {
            **record,
            **crept.to_dict(),
            "core_pressure_Pa": float(after.core_pressure),
            "max_pressure_Pa": float(np.max(-after.sigma_r)),
            "max_sigma_theta_Pa": float(np.max(after.sigma_theta)),
            "min_sigma_theta_Pa": float(np.min(after.sigma_theta)),
            "pressure_wound_in_Pa": (-winding.sigma_r).tolist(),
        }
    return replace(after, storage=record), res.warnings


def _run_given_spring(
    case: Case,
    winding: Any,
    setup: TesterSetup,
    web: Web,
    core: Core,
    r_out: float,
    max_p: float,
    report: Callable[[str, float], None],
) -> RunResult:
    """The impact on an explicit ``[tester.roll_spring]``: no contact model."""
    from woundroll.instruments import hardness_from_spring

    report("impact", 0.0)
    hardness = hardness_from_spring(
        setup, pile_height=r_out - core.outer_radius, density=web.density
    )
    notes = ["roll spring given explicitly: contact model bypassed"]
    if web.radial_unloading is not None and not _restitution_given(case):
        # the web's unloading law at the mean pressure under the head, F / contact area
        a = setup.semi_contact_width
        L = setup.instrument.head_length
        area = 2.0 * a * L if L else math.pi * a * a
        setup = _with_unloading(setup, web, hardness.energy.peak_force / area, notes)
        hardness = hardness_from_spring(
            setup, pile_height=r_out - core.outer_radius, density=web.density
        )
    report("impact", 1.0)
    flags, warns = result_flags(setup.instrument, hardness.reading, [], case.warnings, max_p)
    return RunResult(
        case=case,
        winding=winding,
        hardness=hardness,
        notes=tuple(notes),
        warnings=tuple(warns),
        flags=flags,
    )


def _contact_args(case: Case, setup: TesterSetup) -> tuple[dict[str, Any], bool]:
    """The contact model's arguments; ``plane``: the FE impact runs on the plane-strain
    roll, and the 1.5D models beside it take the same roll's spring, without the
    CMD-spreading correction."""
    spec = case.contact
    model = spec.roll_model(setup.instrument.head_shape).name
    plane = spec.dynamic and model == "2d+cmd-spread"
    args = {
        "depth_max": spec.depth_max,
        "friction": spec.friction,
        "options": spec.model_options(),
        "model": "2d" if plane else model,
        "options3d": spec.contact3d_options(),
    }
    return args, plane


def _run_contact(
    case: Case,
    winding: Any,
    setup: TesterSetup,
    web: Web,
    core: Core,
    r_out: float,
    max_p: float,
    report: Callable[[str, float], None],
) -> RunResult:
    """Contact: the roll's spring under the striker -> impact: the reading (and, as the
    case asks, the frozen-modulus reading and the FE impact)."""
    from woundroll.contact import roll_stiffness

    H = r_out - core.outer_radius
    a_given = "semi_contact_width" in (case.tester or {})
    args, plane = _contact_args(case, setup)
    report("contact", 0.0)
    with _user_fields(case, H):
        stiff = roll_stiffness(web, core, winding.radius, winding.sigma_r, setup.instrument, **args)
    unloading_notes: list[str] = _calibration_notes(setup.instrument, stiff.model)
    if web.radial_unloading is not None and not _restitution_given(case):
        p_peak = float(np.max(-stiff.at_impact.sigma_r))
        setup = _with_unloading(setup, web, p_peak, unloading_notes)
    with _thin_roll(case, H, setup.instrument.head_radius):
        hardness = hardness_on_roll(setup, stiff, H, web.density, semi_contact_width_given=a_given)
    no_update = None
    if case.contact.no_update:
        report("contact", 0.5)
        no_update = _frozen_modulus(case, winding, setup, web, core, stiff, args, a_given, H)
    report("contact", 1.0)
    springs = [("contact", stiff), ("no update", no_update and no_update.stiffness)]
    flags, warns = result_flags(setup.instrument, hardness.reading, springs, case.warnings, max_p)
    dynamic = None
    if case.contact.dynamic:
        report("dynamic", 0.0)
        dynamic = _fe_impact(case, winding, setup, web, core, stiff, hardness)
        report("dynamic", 1.0)
        if plane:
            unloading_notes.append(
                "dynamic: the FE impact runs on the plane-strain roll, so the 1.5D models use "
                "the plane-strain spring too (contact.model '2d' instead of '2d+cmd-spread')"
            )
    return RunResult(
        case=case,
        winding=winding,
        contact=stiff,
        hardness=hardness,
        no_update=no_update,
        notes=tuple(unloading_notes),
        warnings=tuple(warns),
        flags=flags,
        dynamic=dynamic,
    )


def _frozen_modulus(
    case: Case,
    winding: Any,
    setup: TesterSetup,
    web: Web,
    core: Core,
    stiff: RollStiffness,
    args: dict[str, Any],
    a_given: bool,
    H: float,
) -> NoUpdate:
    """The reading with E_r frozen at its pre-impact value (contact.no_update)."""
    from woundroll.contact import roll_stiffness

    # E_r frozen is softer: the striker goes at least as deep, start where that ended
    with _user_fields(case, H):
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
    return NoUpdate(
        frozen,
        _thin_roll_call(
            case,
            H,
            setup.instrument.head_radius,
            lambda: hardness_on_roll(
                setup, frozen, H, web.density, semi_contact_width_given=a_given
            ),
        ),
    )


def _fe_impact(
    case: Case,
    winding: Any,
    setup: TesterSetup,
    web: Web,
    core: Core,
    stiff: RollStiffness,
    hardness: HardnessResult,
) -> Any:
    """The FE impact (contact.dynamic) on the same roll model as the spring's."""
    from woundroll.contact.dynamic.plane_strain import impact_dynamic
    from woundroll.contact.solid3d.solver import Contact3DResult

    spec = case.contact
    dyn_args = (web, core, winding.radius, winding.sigma_r, setup.instrument)
    dyn_kw = {
        "contact_time": hardness.fd.contact_time,
        "depth_scale": float(stiff.contact.delta[-1]),
    }
    if isinstance(stiff.contact, Contact3DResult):  # the same model as the spring's
        from woundroll.contact.dynamic.solid3d import Dynamic3DOptions, impact_dynamic3d

        opts3 = Dynamic3DOptions.from_2d(spec.dynamic_settings(), spec.contact3d_options())
        return impact_dynamic3d(*dyn_args, **dyn_kw, options=opts3)
    return impact_dynamic(*dyn_args, **dyn_kw, options=spec.dynamic_settings())


@contextmanager
def _user_fields(case: Case, wound: float) -> Iterator[None]:
    """Errors of the contact model that name an option the user did not set (its defaults
    follow the roll: ``surface_size`` is the web thickness) are about the roll being too thin
    for the model: say so, naming the case's field."""
    try:
        yield
    except InputError as exc:
        fld = exc.field or ""
        name = fld.removeprefix("contact.options.")
        user_set = fld.startswith("contact.options.") and name in case.contact.options
        if user_set or not (fld.startswith("contact.options.") or fld == "contact.radius"):
            raise
        raise InputError(
            f"the roll is too thin for the contact model under the head: {wound * 1e3:.3g} mm "
            f"wound ({exc.message}); wind a larger roll",
            "winding.outer_radius" if case.winding.outer_radius is not None else "winding.length",
        ) from None


@contextmanager
def _thin_roll(case: Case, wound: float, head_radius: float) -> Iterator[None]:
    """On a roll wound thinner than the head radius, an impact that does not end is the
    striker going through the few layers (the contact model's spring is extrapolated far
    beyond them): an input limit naming the roll's size, not a solver failure."""
    from woundroll.errors import ConvergenceError

    try:
        yield
    except ConvergenceError as exc:
        if wound >= head_radius:
            raise
        raise InputError(
            f"the roll is too thin for a hardness reading: {wound * 1e3:.3g} mm wound, less "
            f"than the head radius ({head_radius * 1e3:.3g} mm), and the impact did not end "
            f"({exc}); wind a larger roll",
            "winding.outer_radius" if case.winding.outer_radius is not None else "winding.length",
        ) from None


def _thin_roll_call(case: Case, wound: float, head_radius: float, fn: Callable[[], Any]) -> Any:
    with _thin_roll(case, wound, head_radius):
        return fn()


def _profile_nip(case: Case, schedule: Any, notes: list[str]) -> tuple[Any, Any]:
    """The nip of a profile run: a roller beam on the sectors' foundation (its load then
    leaves the schedule), or a uniform nip-induced tension."""
    from woundroll.profile.hardness import NipSpec

    nip = None
    if case.winding.nip_roller is not None:
        roller = case.winding.nip_roller.build(case.winding.nip_load, case.winding.friction)
        nip = NipSpec(roller, foundation_stride=case.profile.foundation_stride)
        schedule = replace(schedule, nip_load=0.0)
    elif case.winding.nip_load > 0:
        notes.append(
            "nip: uniform nip-induced tension mu N / h across the CMD "
            "(give [winding.nip_roller] for the beam-on-foundation distribution)"
        )
    return nip, schedule


def _profile_contact(case: Case, web: Web, core: Core, instrument: Any, notes: list[str]) -> Any:
    """The contact model solved once per CMD sector (a roll model fast enough for it)."""
    from woundroll.contact.heads import head_length_of
    from woundroll.contact.models import ROLL_MODELS
    from woundroll.profile.hardness import ContactModel

    spec = case.profile
    entry = case.contact.roll_model(instrument.head_shape)
    if not entry.per_sector and spec.contact != "anchored":
        fast = " or ".join(repr(m.name) for m in ROLL_MODELS.values() if m.per_sector)
        raise InputError(
            f"the {entry.name!r} roll model is too slow to solve once per CMD sector "
            f"({spec.sectors} sectors): use {fast}, or [profile] contact = "
            '"anchored" (plane strain on every sector, this model on a few)',
            "contact.model",
        )
    notes += _calibration_notes(instrument, entry.name)
    return ContactModel(
        web,
        core,
        instrument.head_radius,
        head_length_of(instrument),
        spec.depth_max,
        instrument=instrument,
        options=case.contact.contact_options(),
        model=entry.name,
        options3d=case.contact.contact3d_options() if entry.name == "3d" else None,
    )


def _run_profile(
    case: Case,
    web: Web,
    core: Core,
    r_out: float,
    schedule: Any,
    options: Any,
    setup: TesterSetup | None,
    report: Callable[[str, float], None],
) -> RunResult:
    """The CMD hardness profile: axisymmetric winding -> per-sector contact -> reading.

    The 1D winding at the nominal thickness (the result's reference ``winding``) runs on
    a sector worker while this process winds the (r, z) model, on the core the serial
    winding leaves free (inline when there are no workers)."""
    from woundroll.instruments import get_instrument, tester_from_spec
    from woundroll.profile.hardness import early_pool, predict_profile
    from woundroll.winding.hakiel import wind

    if setup is not None and setup.roll_spring is not None:
        raise InputError(
            "a CMD profile computes each sector's roll spring with the contact model; "
            "remove [tester.roll_spring] or winding.thickness_profile",
            "tester.roll_spring",
        )
    instrument = setup.instrument if setup is not None else get_instrument("rho-meter")
    spec = case.profile
    reference = (web, core, r_out, schedule)  # the 1D roll: the schedule with its nip load
    notes = [
        "winding: the 1D model at the nominal web thickness, for reference; "
        "profile: the axisymmetric model with the thickness profile",
    ]
    nip, schedule = _profile_nip(case, schedule, notes)
    contact = _profile_contact(case, web, core, instrument, notes)
    if spec.contact == "interpolated":
        notes.append(
            "profile contact: solved fully on a few sectors, the roll spring interpolated "
            "between them and checked by full solves until no checked reading moved by "
            f'more than {spec.contact_tolerance:g} ([profile] contact = "every-sector" '
            "solves every sector)"
        )

    def progress(stage: str, done: int, total: int) -> None:
        report(stage, done / max(total, 1))

    with early_pool(contact, spec.workers) as pool:
        # the nominal 1D roll on a worker
        job = pool.submit(wind, *reference, options=options) if pool is not None else None
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
            pool=pool,
            setup=setup if setup is not None else tester_from_spec({"instrument": "rho-meter"}),
            contact_stage=spec.contact,
            contact_tolerance=spec.contact_tolerance,
            semi_contact_width_given="semi_contact_width" in (case.tester or {}),
        )
        winding = job.result() if job is not None else wind(*reference, options=options)
    measured = case.measured_profile
    if measured is not None:
        profile = profile.compare(measured)
    p_max = float(np.max(-np.asarray(profile.sigma_r_core)))
    flags, warns = result_flags(instrument, profile.rho, [], case.warnings, p_max)
    return RunResult(
        case=case,
        winding=winding,
        profile=profile,
        notes=tuple(notes),
        warnings=tuple(warns),
        flags=flags,
    )
