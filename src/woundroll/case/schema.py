"""Case files: winder settings, web, core and tester as a validated object with SI values.

A case is a TOML file (or the same structure as Python objects, for notebooks). Every
quantity may carry a unit (``"4.62 kPa"``, ``"2 pli"``, ``"3 mil"``); a bare number is SI.
See docs/case-files.md for every key.

Errors: anything wrong raises :class:`woundroll.errors.InputError` whose ``field`` is the
dotted key (``web.thickness``); unknown keys are errors too, so a typo cannot pass silently.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property, partial
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    PrivateAttr,
    model_validator,
)

from woundroll.errors import InputError
from woundroll.materials.presets import material_preset
from woundroll.materials.radial_modulus import RadialModulusLaw, law_from_spec
from woundroll.materials.web import INTERLAYER_FRICTION, SLIP_SHEAR_FRACTION, Core, Web
from woundroll.profile.interpolated import CONTACT_STAGES, DEFAULT_CONTACT_STAGE, DEFAULT_TOLERANCE
from woundroll.units import quantity_kind, to_si
from woundroll.winding.tension import Taper, TensionSchedule


def _quantity(kind: str, sign: str, value: Any) -> float:
    v = to_si(value, kind)
    if sign == "positive" and not v > 0:
        raise ValueError(f"must be positive, got {value!r}")
    if sign == "nonnegative" and v < 0:
        raise ValueError(f"must be zero or positive, got {value!r}")
    return v


def Q(kind: str, sign: str = "positive") -> Any:  # noqa: N802 - reads like a type
    """An annotated float field parsed from a quantity of dimension ``kind`` into SI."""
    return Annotated[float, BeforeValidator(partial(_quantity, kind, sign))]


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, arbitrary_types_allowed=True)


class WebSpec(_Section):
    """``[web]``: the web as wound; ``preset`` fills keys not given (``woundroll materials``)."""

    preset: str | None = None
    thickness: Q("length")
    width: Q("length")
    E_theta: Q("pressure")
    radial_modulus: RadialModulusLaw
    E_z: Q("pressure") | None = None
    density: Q("density") = 1400.0
    nu_theta_r: Q("dimensionless", "nonnegative") = 0.0
    nu_z_r: Q("dimensionless", "nonnegative") = 0.0
    nu_theta_z: Q("dimensionless", "nonnegative") = 0.3
    G_r_theta: Q("pressure") | None = None
    G_r_z: Q("pressure") | None = None
    G_theta_z: Q("pressure") | None = None
    radial_unloading: Any = None
    alpha_r: float = 0.0  # 1/K, thermal expansion (woundroll.winding.storage)
    alpha_theta: float = 0.0
    beta_r: float = 0.0  # hygroscopic: strain per unit moisture content
    beta_theta: float = 0.0
    tensile_strength: Q("pressure") | None = None
    # -- speed and entrained air (woundroll.winding.air) --
    roughness: Q("length", "nonnegative") | None = None  # combined Rq of both faces [m]

    @model_validator(mode="after")
    def _roughness_below_thickness(self) -> WebSpec:
        if self.roughness is not None and self.roughness >= self.thickness:
            raise InputError(
                f"must be smaller than the web thickness ({self.thickness * 1e6:.3g} um), "
                f"got {self.roughness * 1e6:.3g} um",
                "web.roughness",
            )
        return self

    # -- end speed and entrained air --

    @model_validator(mode="before")
    @classmethod
    def _apply_preset(cls, data: Any) -> Any:
        if isinstance(data, dict) and data.get("preset"):
            data = _merge(material_preset(data["preset"]), data)
        if isinstance(data, dict) and data.get("radial_unloading") is not None:
            from woundroll.materials.unloading import unloading_from_spec

            data = dict(data)
            un = data["radial_unloading"]
            # "elastic": no unloading law (unloading follows E_r), over a preset's law
            elastic = isinstance(un, str) and un.strip().lower() == "elastic"
            data["radial_unloading"] = None if elastic else unloading_from_spec(un)
        if isinstance(data, dict) and isinstance(data.get("radial_modulus"), dict):
            _check_tabulated_types(data["radial_modulus"])
            data = dict(data)
            data["radial_modulus"] = law_from_spec(
                data["radial_modulus"], "web.radial_modulus", _BASE_DIR.get()
            )
        return data

    def build(self) -> Web:
        """The SI :class:`~woundroll.materials.web.Web` of this section."""
        return Web(
            **{
                name: getattr(self, name)
                for name in type(self).model_fields
                if name not in ("preset", "roughness")
            }
        )


def _check_tabulated_types(spec: dict[str, Any]) -> None:
    """Types of a tabulated law's keys, before the law reads them (a clear message, no
    TypeError from deep inside)."""
    f = "web.radial_modulus"
    if "law" in spec and not isinstance(spec["law"], str):
        raise InputError(f"must be the name of a law (text), got {spec['law']!r}", f"{f}.law")
    if "file" in spec and not isinstance(spec["file"], str):
        raise InputError(f"must be a file name (text), got {spec['file']!r}", f"{f}.file")
    for key in ("strain", "pressure"):
        if key in spec and not isinstance(spec[key], list):
            raise InputError(f"must be a list of values, got {spec[key]!r}", f"{f}.{key}")


class CoreSpec(_Section):
    """``[core]``: outer radius and either ``stiffness`` (E_c), ``rigid = true``, or a tube."""

    outer_radius: Q("length")
    stiffness: Q("pressure") | None = None
    rigid: bool = False
    inner_radius: Q("length", "nonnegative") | None = None
    E: Q("pressure") | None = None
    nu: Q("dimensionless", "nonnegative") | None = None
    thermal_expansion: float = 0.0  # 1/K (woundroll.winding.storage)

    @model_validator(mode="after")
    def _one_way(self) -> CoreSpec:
        tube = (self.inner_radius, self.E, self.nu)
        ways = sum([self.stiffness is not None, self.rigid, any(v is not None for v in tube)])
        if ways != 1:
            raise InputError(
                "give exactly one of: stiffness = E_c, rigid = true, or a tube "
                "(inner_radius, E, nu)",
                "core",
            )
        if any(v is not None for v in tube) and any(v is None for v in tube):
            missing = [
                n for n, v in zip(("inner_radius", "E", "nu"), tube, strict=True) if v is None
            ]
            raise InputError(
                f"a tube core needs inner_radius, E and nu (missing {', '.join(missing)})",
                "core." + missing[0],
            )
        return self

    def build(self) -> Core:
        """The :class:`~woundroll.materials.web.Core` of this section."""
        if self.rigid:
            core = Core(self.outer_radius, math.inf)
        elif self.stiffness is not None:
            core = Core(self.outer_radius, self.stiffness)
        else:
            core = Core.tube(self.outer_radius, self.inner_radius, self.E, self.nu)
        return dataclasses.replace(core, thermal_expansion=self.thermal_expansion)


class TaperSpec(_Section):
    """``winding.taper``: ``kind`` none/linear/hyperbolic/table, ``fraction`` (0.2 or "20 %")."""

    kind: Literal["none", "linear", "hyperbolic", "table"] = "none"
    fraction: Q("dimensionless", "nonnegative") = 0.0
    radius: list[Q("length")] = Field(default_factory=list)
    factor: list[Q("dimensionless", "nonnegative")] = Field(default_factory=list)

    def build(self) -> Taper:
        return Taper(self.kind, self.fraction, tuple(self.radius), tuple(self.factor))


def _tension(value: Any) -> tuple[str, float]:
    """Classify the tension by its dimension: force, force per width, or stress."""
    kind, v = quantity_kind(value, ("force", "force_per_length", "pressure"))
    if kind is None:
        raise ValueError(
            f"{value!r} is neither a force ('26.7 N'), a force per width ('2 pli') nor a "
            "stress ('1.75 MPa')"
        )
    if not kind:
        raise ValueError(
            "needs a unit: a force over the whole width ('26.7 N'), a force per "
            "width ('2 pli', '175 N/m') or a stress ('1.75 MPa')"
        )
    if not (v >= 0):
        raise ValueError(f"must be zero or positive, got {value!r}")
    return kind, v


class NipRollerSpec(_Section):
    """``[winding.nip_roller]``: the nip roller as a beam on the roll (thickness-profile runs).

    Give either ``EI`` (bending stiffness) or a tube: ``E``, ``outer_radius`` and
    ``inner_radius`` (0 for a solid roller). ``outer_radius`` is also the roller radius of
    its contact with the roll (default 5 cm with ``EI``). ``overhang``: distance of each
    bearing beyond the web edge. The load per width and mu are ``winding.nip_load`` and
    ``winding.friction``.
    """

    EI: Q("bending_stiffness") | None = None
    E: Q("pressure") | None = None
    outer_radius: Q("length") | None = None
    inner_radius: Q("length", "nonnegative") | None = None
    overhang: Q("length", "nonnegative") = 0.0

    @model_validator(mode="after")
    def _one_way(self) -> NipRollerSpec:
        tube = self.E is not None or self.inner_radius is not None
        if (self.EI is not None) == tube:
            raise InputError(
                "give either EI, or a tube: E, outer_radius and inner_radius",
                "winding.nip_roller",
            )
        if tube:
            for name in ("E", "outer_radius", "inner_radius"):
                if getattr(self, name) is None:
                    raise InputError(
                        "missing (a tube roller needs E, outer_radius, inner_radius)",
                        f"winding.nip_roller.{name}",
                    )
        return self

    def build(self, line_load: float, friction: float) -> Any:
        """The :class:`~woundroll.profile.nip.NipRoller` with the winder's load and mu."""
        from woundroll.profile.nip import NipRoller

        try:
            if self.EI is not None:
                return NipRoller(
                    EI=self.EI,
                    line_load=line_load,
                    overhang=self.overhang,
                    radius=self.outer_radius or 0.05,
                    friction=friction,
                )
            return NipRoller.tube(
                self.E,
                self.outer_radius,
                self.inner_radius,
                line_load,
                overhang=self.overhang,
                friction=friction,
            )
        except InputError as exc:
            name = (exc.field or "").rsplit(".", 1)[-1]
            raise InputError(exc.message, f"winding.nip_roller.{name}") from None


class WindingSpec(_Section):
    """``[winding]``: final size, web tension (+ taper), nip load and friction, numerics."""

    outer_radius: Q("length") | None = None
    length: Q("length") | None = None
    tension: Annotated[tuple[str, float], BeforeValidator(_tension)]
    taper: TaperSpec = TaperSpec()
    nip_load: Q("force_per_length", "nonnegative") = 0.0
    friction: Q("dimensionless", "nonnegative") = 0.0
    thickness_profile: str | None = None
    nip_roller: NipRollerSpec | None = None
    options: dict[str, Any] = Field(default_factory=dict)
    # --- winder type (woundroll.winding.tension; docs/winding.md "Surface and centre-surface
    # winding"). ``friction`` above is the kinetic friction between web layers. ---
    mode: Literal["center", "surface", "center-surface"] = "center"
    drum_friction: Q("dimensionless", "nonnegative") | None = None
    nip_saturation: Q("force_per_length") | None = None
    #: wrap of the web on the drum; None: the schedule's default (TensionSchedule.drum_wrap)
    drum_wrap: Q("dimensionless", "nonnegative") | None = None
    tension_differential: Annotated[tuple[str, float], BeforeValidator(_tension)] | None = None
    drum_torque: Q("energy", "any") | None = None
    drum_radius: Q("length") | None = None
    # -- speed and entrained air (woundroll.winding.air): 0 = no air, today's model --
    speed: Q("velocity", "nonnegative") = 0.0
    # -- end speed and entrained air --

    @model_validator(mode="after")
    def _size(self) -> WindingSpec:
        if (self.outer_radius is None) == (self.length is None):
            raise InputError("give exactly one of outer_radius or length", "winding.outer_radius")
        return self

    @model_validator(mode="after")
    def _mode(self) -> WindingSpec:
        surface_keys = (
            "drum_friction",
            "nip_saturation",
            "tension_differential",
            "drum_torque",
            "drum_radius",
            "drum_wrap",
        )
        if self.mode == "center":
            for name in surface_keys:
                if getattr(self, name) is not None:
                    raise InputError(
                        "only with winding.mode = 'surface' or 'center-surface'", f"winding.{name}"
                    )
            return self
        if self.thickness_profile is not None:
            raise InputError(
                "surface winding is not modelled with winding.thickness_profile yet", "winding.mode"
            )
        if self.nip_saturation is None:
            raise InputError(
                "needed for surface winding: the nip load where the nip-induced tension levels "
                "off, from wound-in-tension measurements (docs/winding.md)",
                "winding.nip_saturation",
            )
        given = [n for n in ("tension_differential", "drum_torque") if getattr(self, n) is not None]
        if self.mode == "surface" and given:
            raise InputError("only with winding.mode = 'center-surface'", f"winding.{given[0]}")
        if self.mode == "center-surface":
            if len(given) != 1:
                raise InputError(
                    "give exactly one of tension_differential or drum_torque (with drum_radius)",
                    "winding.tension_differential",
                )
            if self.drum_torque is not None and self.drum_radius is None:
                raise InputError("needed with winding.drum_torque", "winding.drum_radius")
        return self

    def _differential(self, web: Web) -> float:
        """The centre-surface tension differential as a force per width [N/m]."""
        if self.drum_torque is not None and self.drum_radius is not None:
            return self.drum_torque / (web.width * self.drum_radius)
        if self.tension_differential is None:
            return 0.0
        kind, v = self.tension_differential
        return {"force": v / web.width, "force_per_length": v, "pressure": v * web.thickness}[kind]

    def final_radius(self, web: Web, core: Core) -> float:
        """Outer radius [m]: as given, or from the wound length (no compaction assumed)."""
        if self.outer_radius is not None:
            r = self.outer_radius
        else:
            r = math.sqrt(core.outer_radius**2 + self.length * web.thickness / math.pi)
        if r < core.outer_radius + web.thickness * (1 - 1e-9):
            field = "winding.outer_radius" if self.outer_radius is not None else "winding.length"
            raise InputError(
                f"outer radius {r:g} m must exceed the core radius {core.outer_radius:g} m "
                f"by at least one layer (web.thickness = {web.thickness:g} m)",
                field,
            )
        return r

    def schedule(self, web: Web) -> TensionSchedule:
        """The SI :class:`TensionSchedule`; tension converted to a stress in the web."""
        kind, v = self.tension
        stress = {
            "force": v / (web.width * web.thickness),
            "force_per_length": v / web.thickness,
            "pressure": v,
        }[kind]
        if self.mode == "center":
            return TensionSchedule(
                web_stress=stress,
                taper=self.taper.build(),
                nip_load=self.nip_load,
                friction=self.friction,
            )
        return TensionSchedule(
            web_stress=stress,
            taper=self.taper.build(),
            nip_load=self.nip_load,
            friction=self.friction,
            mode=self.mode,
            drum_friction=self.drum_friction,
            nip_saturation=self.nip_saturation,
            tension_differential=self._differential(web),
            **({} if self.drum_wrap is None else {"drum_wrap": self.drum_wrap}),
        )


def _roll_model_name(name: Any) -> str | None:
    """``contact.model``: a registered roll model's name (or unset: the default)."""
    from woundroll.contact.models import check_model_name

    return check_model_name(name, "contact.model")


class ContactSpec(_Section):
    """``[contact]``: the roll model that gives the roll spring under the striker.

    ``model``: its name in the registry :data:`woundroll.contact.models.ROLL_MODELS`; unset,
    the registry's default for the instrument's head (plane strain ``"2d"`` for a cylinder,
    docs/contact.md "Which model reads a roll").

    ``depth_max``: largest indentation [length]; by default it follows the impact (the
    contact is solved to 1.25 x the impact's maximum depth, see
    :func:`woundroll.pipeline.roll_stiffness`). ``friction``: interlayer mu of the slip
    factor {23}. ``no_update``: also solve with E_r frozen at its pre-impact value (the
    paper's Figure 8 comparison; off by default, it costs a second contact solve).
    ``options``: :class:`woundroll.contact.ContactOptions`.
    ``dynamic``: also solve the impact in time on the FE roll (the paper's dynamic reference,
    :func:`woundroll.contact.dynamic.plane_strain.impact_dynamic`); ``dynamic_options``:
    :class:`woundroll.contact.dynamic.plane_strain.DynamicOptions` (time step, mass matrix,
    damping).
    """

    depth_max: Q("length") | None = None
    friction: Q("dimensionless", "nonnegative") = INTERLAYER_FRICTION
    no_update: bool = False
    options: dict[str, Any] = Field(default_factory=dict)
    #: the roll model by its registry name (:data:`woundroll.contact.models.ROLL_MODELS`:
    #: "2d" plane strain, "2d+cmd-spread", "3d"); unset: the registry's default for the head
    model: Annotated[str | None, BeforeValidator(_roll_model_name)] = None
    options3d: dict[str, Any] = Field(default_factory=dict)
    #: slip emulation (Figure 19) in the 2D and 3D models: G_r_theta (and G_r_z) of the
    #: elements where SF {23} reaches 1 (mu = ``friction``) drop to ``slip_shear_fraction``
    slip: Literal["none", "reduced-shear"] = "none"
    slip_shear_fraction: Q("dimensionless") = SLIP_SHEAR_FRACTION

    # -- other explanations of the readings (issue 25; docs/contact.md "Other
    # explanations"), in the plane-strain models "2d" and "layered" --
    #: G_r_theta = shear_ratio x E_r (unset: the web's rule, G_r_theta or 2 E_r)
    shear_ratio: Q("dimensionless") | None = None
    #: G_r_theta kept at its pre-impact value while E_r stiffens under the head
    shear_frozen: bool = False
    # -- the layered roll (contact.model = "layered" or "layered-3d"; docs/contact.md "The
    # layered roll", "The layered roll in 3D") --
    #: depth of the layered zone under the surface (unset: 1.0 a_geo)
    layered_depth: Q("length") | None = None
    #: web layers per element shell in the layered zone (unset: the model's default,
    #: LayeredOptions' 1 in 2D, LAYERS_PER_SHELL_3D in 3D)
    layers_per_shell: int | None = None

    def model_options(self) -> Any:
        """The options of the roll model this section names: :meth:`layered_options` for
        ``"layered"``, else :meth:`contact_options`."""
        if self.model == "layered-3d":
            return self.layered3d_options()
        return self.layered_options() if self.model == "layered" else self.contact_options()

    def layered3d_options(self) -> Any:
        """The :class:`~woundroll.contact.layered.roll3d.Layered3DOptions` of this section:
        the 3D options (``options3d``) and the zone's keys."""
        from woundroll.contact.layered.roll3d import Layered3DOptions

        for key, unset in (("shear_ratio", None), ("shear_frozen", False)):
            if getattr(self, key) != unset:
                raise InputError("is taken by the '2d' and 'layered' models only", f"contact.{key}")
        base = self.contact3d_options()
        try:
            return Layered3DOptions(
                base=base,
                layered_depth=self.layered_depth,
                **(
                    {}
                    if self.layers_per_shell is None
                    else {"layers_per_shell": self.layers_per_shell}
                ),
            )
        except InputError as exc:
            raise exc.at("contact") from None

    def layered_options(self) -> Any:
        """The :class:`~woundroll.contact.layered.solver.LayeredOptions` of this section:
        the 2D options (without the modified Newton step, the layered model factorises
        every increment) and the zone's keys."""
        from dataclasses import replace

        from woundroll.contact.layered.solver import LayeredOptions

        base = replace(self.contact_options(layered=True), newton=False)
        try:
            return LayeredOptions(
                base=base,
                layered_depth=self.layered_depth,
                **(
                    {}
                    if self.layers_per_shell is None
                    else {"layers_per_shell": self.layers_per_shell}
                ),
            )
        except InputError as exc:
            raise exc.at("contact") from None

    def _shear_options(self, table: dict[str, Any]) -> dict[str, Any]:
        """``table`` with the section's shear keys (set as contact.<key> only)."""
        for key in ("shear_ratio", "shear_frozen"):
            if key in table:
                raise InputError(
                    f"set contact.{key}, not contact.options.{key}", f"contact.options.{key}"
                )
        return {**table, "shear_ratio": self.shear_ratio, "shear_frozen": self.shear_frozen}

    def roll_model(self, head_shape: str = "cylinder") -> Any:
        """The registry entry of the roll model that reads this case's roll
        (:func:`woundroll.contact.models.resolve_model`: ``model``, or the default for the
        head)."""
        from woundroll.contact.models import resolve_model

        return resolve_model(self.model, head_shape, "contact.model")

    def _slip_options(self, table: dict[str, Any], name: str) -> dict[str, Any]:
        """``table`` with the section's slip keys (one spelling for 2D and 3D)."""
        for key in ("slip", "slip_shear_fraction"):
            if key in table:
                raise InputError(
                    f"set contact.{key}, not contact.{name}.{key}", f"contact.{name}.{key}"
                )
        if not self.slip_shear_fraction <= 1.0:
            raise InputError(
                f"must lie in (0, 1], got {self.slip_shear_fraction:g}",
                "contact.slip_shear_fraction",
            )
        return {**table, "slip": self.slip, "slip_shear_fraction": self.slip_shear_fraction}

    def contact3d_options(self) -> Any:
        """The :class:`~woundroll.contact.solid3d.options.Contact3DOptions` of ``options3d``."""
        from woundroll.contact.solid3d.options import Contact3DOptions

        known = set(Contact3DOptions.__dataclass_fields__)
        unknown = sorted(set(self.options3d) - known)
        if unknown:
            raise InputError(
                f"unknown option(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}",
                f"contact.options3d.{unknown[0]}",
            )
        table = self._slip_options(self.options3d, "options3d")
        try:
            return Contact3DOptions(**table)
        except InputError as exc:
            raise InputError(exc.message, f"contact.options3d.{exc.field.split('.')[-1]}") from None
        except (TypeError, ValueError) as exc:  # a string where a number belongs
            raise InputError(f"bad value ({exc}); give SI numbers", "contact.options3d") from None

    dynamic: bool = False
    dynamic_options: dict[str, Any] = Field(default_factory=dict)

    def dynamic_settings(self) -> Any:
        """The :class:`~woundroll.contact.dynamic.plane_strain.DynamicOptions` of this section."""
        from woundroll.contact.dynamic.plane_strain import DynamicOptions

        if self.dynamic:  # the FE impact builds its own moduli: not taken silently
            for key, unset in (("shear_ratio", None), ("shear_frozen", False)):
                if getattr(self, key) != unset:
                    raise InputError(
                        "is taken by the quasi-static '2d' and 'layered' models only, not by "
                        "the FE impact (contact.dynamic)",
                        f"contact.{key}",
                    )
        known = set(DynamicOptions.__dataclass_fields__) - {"mesh"}
        unknown = sorted(set(self.dynamic_options) - known)
        if unknown:
            raise InputError(
                f"unknown option(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}",
                f"contact.dynamic_options.{unknown[0]}",
            )
        opts = dict(self.dynamic_options)
        if "time_step" in opts:
            opts["time_step"] = to_si(
                opts["time_step"], "time", "contact.dynamic_options.time_step"
            )
        mesh = self.contact_options()
        if "tangential_growth" not in self.options:  # the dynamic model's own far field
            from dataclasses import replace

            from woundroll.contact.dynamic.plane_strain import GROWTH

            mesh = replace(mesh, tangential_growth=GROWTH)
        return DynamicOptions(mesh=mesh, **opts)

    def contact_options(self, layered: bool = False) -> Any:
        """The :class:`~woundroll.contact.ContactOptions` of this section (validated);
        ``layered``: for the layered model (its zone keys are refused otherwise)."""
        from woundroll.contact import ContactOptions

        if not layered and self.model not in ("layered", "layered-3d"):
            for key, unset in (("layered_depth", None), ("layers_per_shell", None)):
                if getattr(self, key) != unset:
                    raise InputError(
                        "is used by contact.model = 'layered' or 'layered-3d' only",
                        f"contact.{key}",
                    )

        known = set(ContactOptions.__dataclass_fields__)
        unknown = sorted(set(self.options) - known)
        if unknown:
            raise InputError(
                f"unknown option(s) {', '.join(unknown)}; known: {', '.join(sorted(known))}",
                f"contact.options.{unknown[0]}",
            )
        table = self._shear_options(self._slip_options(self.options, "options"))
        try:
            return ContactOptions(**table)
        except InputError as exc:
            raise exc.at("contact") from None
        except (TypeError, ValueError) as exc:
            raise InputError(
                f"bad value ({exc}): {', '.join(f'{k} = {v!r}' for k, v in self.options.items())}",
                "contact.options",
            ) from None


class ProfileSpec(_Section):
    """``[profile]``: the CMD hardness profile (runs with ``winding.thickness_profile``).

    ``sectors``: CMD sectors (default 61, the paper's count); ``groups``: winding increments
    of the axisymmetric model (default: the model's); ``workers``: parallel contact
    solutions (default 2); ``foundation_stride``: nip foundation evaluated at every k-th
    sector; ``depth_max``: depth of each sector's contact solution (default 1 mm, deepened
    where the striker goes further); ``measured``: a measured profile (CSV, path relative to
    the case file, ``position [in],rho``) to compare with the prediction. ``contact``:
    ``"every-sector"`` (default: one full contact solve per sector) or ``"interpolated"``
    (the contact solved on a few sectors, the springs interpolated between them and checked
    by full solves until no checked reading moves by more than ``contact_tolerance``, in
    the instrument's units, default 0.2) or ``"anchored"`` (for a roll model too slow for
    every sector, such as ``contact.model = "layered-3d"``, or to read a few sectors with
    ``"3d"``: plane strain on every sector, the model on a few, its correction to plane
    strain interpolated and checked the same way).
    """

    sectors: int = Field(default=61, ge=1, le=2000)
    measured: str | None = None
    groups: int | None = Field(default=None, ge=1)
    workers: int = Field(default=2, ge=1, le=64)
    foundation_stride: int = Field(default=4, ge=1)
    depth_max: Q("length") = 1e-3
    # the contact stage (woundroll.profile.interpolated: one default in one place)
    contact: Literal[CONTACT_STAGES] = DEFAULT_CONTACT_STAGE  # type: ignore[valid-type]
    contact_tolerance: float = Field(default=DEFAULT_TOLERANCE, ge=0.0, allow_inf_nan=False)


class ReadingsSpec(_Section):
    """``[readings]``: hardness readings taken on the roll (:mod:`woundroll.io.readings`).

    ``file``: the readings CSV (path relative to the case file); ``lane_width``: width of one
    lane when the file gives lane numbers (TAPPI T 834: ``"6 in"``); ``repeatability``: the
    instrument's repeatability, one SD in its scale (used where the file has no repeated
    readings to estimate the scatter from).
    """

    file: str
    lane_width: Q("length") | None = None
    repeatability: Q("dimensionless", "nonnegative") | None = None


def _tolerance(value: Any) -> tuple[str, float]:
    """A tolerance (1 SD): relative (``"2 %"``, ``0.02``) or absolute (``"1.5 um"``)."""
    from woundroll.units import parse_quantity

    q = parse_quantity(value)
    for kind, tag in (("dimensionless", "relative"), ("length", "absolute")):
        try:
            v = to_si(q, kind)
        except InputError:
            continue
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"must be zero or positive, got {value!r}")
        return tag, v
    raise ValueError(f"{value!r} is neither relative ('2 %') nor a length ('1.5 um')")


class UncertaintySpec(_Section):
    """``[uncertainty]``: one standard deviation of the inputs the predictions depend on.

    ``K1`` [pressure], ``K2`` [-] and ``K1_K2_correlation`` of the Pfeiffer law {2} (from
    ``woundroll fit-stack``'s covariance); ``thickness`` (relative ``"2 %"`` or a length
    ``"1.5 um"``); ``tension`` (relative, of the winder's tension setting). Used by
    ``woundroll diagnose`` and ``--uncertainty N`` (docs/diagnosis.md).
    """

    K1: Q("pressure", "nonnegative") | None = None
    K2: Q("dimensionless", "nonnegative") | None = None
    K1_K2_correlation: float = Field(default=0.0, ge=-1.0, le=1.0)
    thickness: Annotated[tuple[str, float], BeforeValidator(_tolerance)] | None = None
    tension: Q("dimensionless", "nonnegative") | None = None

    def thickness_sd(self, thickness: float) -> float:
        """SD of the web thickness [m] for a nominal ``thickness`` [m] (0 when not given)."""
        if self.thickness is None:
            return 0.0
        kind, v = self.thickness
        return v * thickness if kind == "relative" else v


class DefectsSpec(_Section):
    """``[defects]``: limits for the defect-risk criteria (docs/diagnosis.md, "Defect risk").

    ``core_strength`` (radial pressure the core carries), ``blocking_pressure`` (layers
    stick above it), ``friction`` (interlayer mu; default ``contact.friction``),
    ``axial_acceleration_g`` (axial handling load, in g) and ``torque`` (through the roll)
    for slip and telescoping, ``slack_pressure`` (default 1 kPa) and ``slack_fraction``
    (default 0.7 of the lanes' median wound-on tension).
    """

    core_strength: Q("pressure") | None = None
    blocking_pressure: Q("pressure") | None = None
    friction: Q("dimensionless") | None = None
    axial_acceleration_g: Q("dimensionless", "nonnegative") | None = None
    torque: Q("energy", "nonnegative") | None = None
    slack_pressure: Q("pressure") = 1e3
    slack_fraction: float = Field(default=0.7, gt=0.0, lt=1.0)


def _kelvin(value: Any) -> Any:
    """A temperature change: a number [K] or text with ``K`` / ``degC`` / ``°C`` (a change
    of one degree Celsius is one kelvin) or ``degF`` / ``°F`` (a change of one degree
    Fahrenheit is 5/9 K)."""
    if isinstance(value, str):
        text = value.strip()
        factor = 1.0
        for unit, f in (("degC", 1.0), ("°C", 1.0), ("degF", 5 / 9), ("°F", 5 / 9), ("K", 1.0)):
            if text.endswith(unit):
                text, factor = text[: -len(unit)].strip(), f
                break
        try:
            return float(text) * factor
        except ValueError:
            raise ValueError(
                f"must be a number of kelvin such as '-20 K' (or degC, degF), got {value!r}"
            ) from None
    return value


class StorageSpec(_Section):
    """``[storage]``: temperature and moisture after winding
    (:mod:`woundroll.winding.storage`): ``temperature_change`` [K], roll and core in storage
    minus at winding; ``moisture_change`` [-], the web's moisture content change (mass
    fraction, ``"1 %"`` accepted). The web's and core's expansion coefficients are
    ``web.alpha_r``, ``web.alpha_theta``, ``web.beta_r``, ``web.beta_theta`` and
    ``core.thermal_expansion``."""

    temperature_change: Annotated[float, BeforeValidator(_kelvin)] = 0.0
    moisture_change: Q("dimensionless", "any") = 0.0
    # --- storage time (creep; woundroll.winding.creep, docs/winding.md "Storage time") ---
    #: time in storage (``"30 d"``); > 0 needs ``radial_creep``
    time: Q("time", "nonnegative") = 0.0
    #: the stack's creep law, e.g. ``{ law = "power", n = 0.2, tau = "40 d" }``
    #: (:func:`woundroll.materials.creep.creep_from_spec`; ``woundroll fit-stack --creep``)
    radial_creep: dict[str, Any] | None = None
    #: time steps through the storage time; None: :data:`woundroll.winding.creep.TIME_STEPS`
    time_steps: int | None = Field(default=None, ge=1, le=10_000)

    @model_validator(mode="after")
    def _creep_law(self) -> StorageSpec:
        if self.radial_creep is not None:
            self.creep_law()  # its errors name storage.radial_creep.<key>
        elif self.time > 0.0:
            raise InputError(
                "a storage time needs the stack's creep law, e.g. radial_creep = "
                '{ law = "power", n = 0.2, tau = "40 d" } (woundroll fit-stack CSV --creep)',
                "storage.radial_creep",
            )
        return self

    def creep_law(self) -> Any:
        """The creep law (:mod:`woundroll.materials.creep`), or None."""
        if self.radial_creep is None:
            return None
        from woundroll.materials.creep import creep_from_spec

        return creep_from_spec(self.radial_creep, "storage.radial_creep")

    def build(self) -> Any:
        """The :class:`~woundroll.winding.storage.StorageChange` of this section."""
        from woundroll.winding.storage import StorageChange

        return StorageChange(self.temperature_change, self.moisture_change)


# -- speed and entrained air (woundroll.winding.air) --
def _air_default(name: str) -> float:
    from woundroll.winding import air

    return float(getattr(air, name))


class AirSpec(_Section):
    """``[air]``: the air a fast web entrains (:mod:`woundroll.winding.air`; used when
    ``winding.speed`` > 0): ``viscosity`` [Pa s] (bare number, default 1.8e-5, air at
    20 C), ``pressure`` (ambient, default 101.325 kPa), ``nip_modulus`` (contact modulus E*
    of the lay-on roller's cover against the roll, default 10 MPa) and ``nip_radius``
    (default ``winding.nip_roller.outer_radius``, else 5 cm); ``time`` after winding of the
    roll downstream (default: all the air that can leave has left)."""

    viscosity: float = Field(default_factory=lambda: _air_default("VISCOSITY"))
    pressure: Q("pressure") = Field(default_factory=lambda: _air_default("PRESSURE"))
    nip_modulus: Q("pressure") = Field(default_factory=lambda: _air_default("NIP_MODULUS"))
    nip_radius: Q("length") | None = None
    time: Q("time", "nonnegative") | None = None

    def build(self, speed: float, roughness: float | None, nip_radius: float | None) -> Any:
        """The :class:`~woundroll.winding.air.AirSettings` of the case."""
        from woundroll.winding.air import NIP_RADIUS, AirSettings

        return AirSettings(
            speed=speed,
            roughness=roughness or 0.0,
            viscosity=self.viscosity,
            pressure=self.pressure,
            nip_modulus=self.nip_modulus,
            nip_radius=self.nip_radius or nip_radius or NIP_RADIUS,
            time=math.inf if self.time is None else self.time,
        )


# -- end speed and entrained air --


class Case(_Section):
    """A whole case: ``title``, ``[web]``, ``[core]``, ``[winding]``, optional ``[tester]``,
    ``[contact]``, ``[profile]`` (their tables are passed to the models that own them)."""

    title: str = ""
    web: WebSpec
    core: CoreSpec
    winding: WindingSpec
    tester: dict[str, Any] | None = None
    contact: ContactSpec = ContactSpec()
    profile: ProfileSpec = ProfileSpec()
    readings: ReadingsSpec | None = None
    uncertainty: UncertaintySpec | None = None
    defects: DefectsSpec | None = None
    storage: StorageSpec | None = None
    air: AirSpec | None = None  # speed and entrained air
    _base_dir: Path | None = PrivateAttr(default=None)
    _warnings: tuple[str, ...] = PrivateAttr(default=())
    _given: dict[str, Any] = PrivateAttr(default_factory=dict)
    _sources: dict[str, str] = PrivateAttr(default_factory=dict)
    _overrides: tuple[tuple[str, Any, str], ...] = PrivateAttr(default=())

    @property
    def overrides(self) -> tuple[tuple[str, Any, str], ...]:
        """``(key, value as given, source)`` of each value set over the case
        (``--set``, the web form), in the order given."""
        return self._overrides

    @property
    def display_title(self) -> str:
        """The title with the values set over the case: ``PET1 wound at 26.7 N
        (winding.tension = 40 N by --set)``; a title never claims a value that was
        overridden without saying so."""
        if not self._overrides:
            return self.title
        by: dict[str, list[str]] = {}
        for key, value, source in self._overrides:
            by.setdefault(source, []).append(f"{key} = {_given_text(value)}")
        note = "; ".join(f"{', '.join(items)} by {src}" for src, items in by.items())
        return f"{self.title} ({note})" if self.title else f"({note})"

    def record(self) -> dict[str, Any]:
        """The case part of result.json: ``title`` (:attr:`display_title`), the title as
        written (``case_title``), ``overrides`` (key, given, source) and ``inputs``
        (:attr:`inputs`, each ``{"key", "value", "unit", "given", "source"}``, SI values)."""
        return {
            "title": self.display_title,
            "case_title": self.title,
            "overrides": [{"key": k, "given": v, "source": src} for k, v, src in self._overrides],
            "inputs": [v.to_dict() for v in self.inputs],
        }

    def source_of(self, key: str) -> str:
        """Where the value of dotted ``key`` came from: ``case file``, ``preset NAME``,
        ``--set``, ``web form`` or ``default``. A table (``web.radial_modulus``) takes the
        source of an override inside it, else of its first given entry."""
        for k, _, source in reversed(self._overrides):
            if k == key or k.startswith(key + ".") or key.startswith(k + "."):
                return source
        if key in self._sources:
            return self._sources[key]
        inside = [src for k, src in self._sources.items() if k.startswith(key + ".")]
        return inside[0] if inside else FROM_DEFAULT

    @property
    def inputs(self) -> list[InputValue]:
        """Every input value the run uses: each value given (case file, preset, ``--set``,
        web form) as written and in SI, and the defaults of the web, core, winding and (with a
        tester) contact keys not given. result.json writes them as ``inputs``."""
        out = [
            _input_value(key, value, self._sources.get(key, FROM_CASE_FILE))
            for key, value in self._given.items()
            if key != "title"
        ]
        sections: list[tuple[str, BaseModel]] = [
            ("web", self.web),
            ("core", self.core),
            ("winding", self.winding),
        ]
        if self.tester is not None:
            sections.append(("contact", self.contact))
        for name, spec in sections:
            out += _defaults(name, spec, self._given)
        order = {name: i for i, name in enumerate(type(self).model_fields)}
        return sorted(out, key=lambda v: order.get(v.key.split(".")[0], len(order)))

    @property
    def base_dir(self) -> Path | None:
        """Directory of the case file (relative paths inside it), or None."""
        return self._base_dir

    @property
    def warnings(self) -> tuple[str, ...]:
        """Values outside their plausible range and long-run estimates
        (:mod:`woundroll.limits`); the case is valid, the CLI prints them before the run."""
        return self._warnings

    @cached_property
    def thickness_profile(self) -> Any:
        """The CMD :class:`~woundroll.profile.ThicknessProfile` of
        ``winding.thickness_profile`` (path relative to the case file), or None."""
        if self.winding.thickness_profile is None:
            return None
        from woundroll.materials.thickness_profile import load_thickness

        return load_thickness(self._path(self.winding.thickness_profile), width=self.web.width)

    @cached_property
    def measured_profile(self) -> Any:
        """The measured :class:`~woundroll.profile.compare.MeasuredProfile`, or None."""
        if self.profile.measured is None:
            return None
        from woundroll.profile.compare import read_measured_profile

        return read_measured_profile(self._path(self.profile.measured))

    @cached_property
    def measured_readings(self) -> Any:
        """The :class:`~woundroll.io.readings.Readings` of ``[readings]``, or None."""
        if self.readings is None:
            return None
        from woundroll.io.readings import read_readings

        return read_readings(
            self._path(self.readings.file),
            width=self.web.width,
            lane_width=self.readings.lane_width,
            field="readings.file",
        )

    def _path(self, name: str) -> Path:
        path = Path(name).expanduser()
        if not path.is_absolute() and self.base_dir is not None:
            path = self.base_dir / path
        return path

    @cached_property
    def tester_setup(self) -> Any:
        """The :class:`~woundroll.instruments.TesterSetup` of ``[tester]``, or None."""
        if self.tester is None:
            return None
        from woundroll.instruments import tester_from_spec

        return tester_from_spec(self.tester, "tester")


#: Sources of input values (:attr:`Case.inputs`, result.json, the report): the value came
#: from the case file (or a bundled case), a material preset (``"preset PET1"``), an
#: override on the command line, the web page's form, or the model's default.
FROM_CASE_FILE = "case file"
FROM_SET = "--set"
FROM_WEB_FORM = "web form"
FROM_DEFAULT = "default"


@dataclass(frozen=True)
class InputValue:
    """One input of a run: dotted ``key``, the value as ``given`` (None for a default),
    its ``value`` in SI (a number; text or a flag as given) with ``unit`` (SI, ``""`` for a
    pure number or text), and its ``source`` (:data:`FROM_CASE_FILE` ...)."""

    key: str
    given: Any
    value: Any
    unit: str
    source: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``{"key", "value", "unit", "given", "source"}``."""
        return {
            "key": self.key,
            "value": self.value,
            "unit": self.unit,
            "given": self.given,
            "source": self.source,
        }


def _given_text(value: Any) -> str:
    """A value as the user wrote it (TOML-like: text bare, tables inline)."""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_given_text(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_given_text(v) for v in value) + "]"
    return str(value)


def _leaves(data: Any, prefix: str = "") -> dict[str, Any]:
    """``{"web.thickness": "50 um", ...}``: the leaf values of nested tables (lists are
    leaves)."""
    if not isinstance(data, dict):
        return {prefix: data} if prefix else {}
    out: dict[str, Any] = {}
    for k, v in data.items():
        key = f"{prefix}.{k}" if prefix else str(k)
        if isinstance(v, dict) and v:
            out.update(_leaves(v, key))
        else:
            out[key] = v
    return out


def _field_kind(annotation: Any) -> str | None:
    """The quantity kind of a field made by :func:`Q` (also inside ``X | None``, lists)."""
    import typing

    for meta in getattr(annotation, "__metadata__", ()):
        func = getattr(meta, "func", None)
        if isinstance(func, partial) and func.func is _quantity:
            return str(func.args[0])
    for arg in typing.get_args(annotation):
        kind = _field_kind(arg)
        if kind is not None:
            return kind
    return None


def _kind_of_field(f: Any) -> str | None:
    """The quantity kind of a pydantic field (its metadata, or inside its annotation)."""
    for meta in f.metadata:
        func = getattr(meta, "func", None)
        if isinstance(func, partial) and func.func is _quantity:
            return str(func.args[0])
    return _field_kind(f.annotation)


def _kind_of(key: str) -> str | None:
    """The quantity kind of the case key ``key`` when its section declares one."""
    model: Any = Case
    parts = key.split(".")
    for i, part in enumerate(parts):
        fields = getattr(model, "model_fields", None)
        if not fields or part not in fields:
            return None
        ann = fields[part].annotation
        if i == len(parts) - 1:
            return _kind_of_field(fields[part])
        import typing

        nested = [a for a in (ann, *typing.get_args(ann)) if hasattr(a, "model_fields")]
        if not nested:
            return None
        model = nested[0]
    return None


def _input_value(key: str, given: Any, source: str) -> InputValue:
    from woundroll.units import si_value

    si = si_value(given, _kind_of(key))
    if si is None:
        return InputValue(key, given, given, "", source)
    return InputValue(key, given, si[0], si[1], source)


def _defaults(prefix: str, spec: BaseModel, given: dict[str, Any]) -> list[InputValue]:
    """The scalar values of ``spec`` that nobody gave (its defaults), nested sections too."""
    from woundroll.units import SI_UNITS

    out = []
    for name, f in type(spec).model_fields.items():
        key = f"{prefix}.{name}"
        if key in given or any(k.startswith(key + ".") for k in given):
            continue
        value = getattr(spec, name)
        if isinstance(value, BaseModel):
            out += _defaults(key, value, given)
        elif isinstance(value, bool | str) or (
            isinstance(value, int | float) and math.isfinite(value)
        ):
            kind = _kind_of_field(f)
            unit = SI_UNITS.get(kind, "") if kind and not isinstance(value, bool | str) else ""
            out.append(InputValue(key, None, value, unit, FROM_DEFAULT))
    return out


def _sources_of(
    data: dict[str, Any], overrides: list[tuple[str, Any, str]], file_source: str
) -> tuple[dict[str, Any], dict[str, str]]:
    """The given leaves of a case (``data`` with the overrides already set, the web preset
    merged in) and the source of each."""
    leaves = _leaves(data)
    sources = {}
    for key in leaves:
        src = file_source
        for k, _, source in overrides:
            if key == k or key.startswith(k + "."):
                src = source
        sources[key] = src
    web = data.get("web")
    if isinstance(web, dict) and isinstance(web.get("preset"), str):
        try:
            preset = material_preset(web["preset"])
        except InputError:
            preset = None
        if preset is not None:
            label = f"preset {web['preset'].upper()}"
            for key, v in _leaves(_merge(preset, web), "web").items():
                if key not in leaves:
                    leaves[key] = v
                    sources[key] = label
    return leaves, sources


class _BaseDir:
    """Directory of the case file being read, for relative paths inside it."""

    value: Path | None = None

    def get(self) -> Path | None:
        return self.value


_BASE_DIR = _BaseDir()


def _merge(base: dict[str, Any], top: dict[str, Any]) -> dict[str, Any]:
    """``top`` over ``base``, recursively for tables (a preset under the case's own keys)."""
    out = dict(base)
    for k, v in top.items():
        old = out.get(k)
        same_law = (
            isinstance(old, dict)
            and isinstance(v, dict)
            and v.get("law", old.get("law")) == old.get("law")
        )
        out[k] = _merge(old, v) if same_law else v
    return out


def _deepcopy(data: Any) -> Any:
    if isinstance(data, dict):
        return {k: _deepcopy(v) for k, v in data.items()}
    if isinstance(data, list):
        return [_deepcopy(v) for v in data]
    return data
