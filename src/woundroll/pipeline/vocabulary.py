"""The JSON vocabulary: one description of every key the JSON documents write.

Every key of ``result.json`` (and of ``diagnosis.json``, ``defects.json``, ``design.json``,
``uncertainty.json``, ``study.json``, the ``--json`` output of every command and the web API's
result) is a :class:`Term` of :data:`TERMS`: its name, its SI unit, its symbol and its meaning.
One name means one quantity wherever it appears (``impact_depth_m`` is the striker's deepest
point in the impact, under ``hardness``, ``no_update``, ``hardness.dynamic`` and a study's
rows alike). Three readers share this one description:

* ``docs/nomenclature.md`` (its table is :func:`nomenclature_table`, a test keeps them equal);
* :func:`json_schema`, the JSON Schema (draft 2020-12) of each document
  (``woundroll schema result``);
* the sweep (:mod:`woundroll.app.sweep`), which labels each column with :func:`unit_of`.

The rules (:func:`check_terms` enforces them): a dimensional key ends in the suffix of its SI
unit (:data:`UNIT_SUFFIXES`: ``_m``, ``_Pa``, ``_N_per_m`` ...); a dimensionless key carries no
unit suffix; a reading on an instrument's scale (Rho, g, Schmidt R, Parotester L) is
dimensionless and names its scale (``rho_fd``, ``peak_g``, ``rebound_R``); ``sigma_r < 0`` is
compression and the interlayer pressure is ``P = -sigma_r``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

#: Version of the JSON documents' vocabulary (the ``schema_version`` key of each document).
#: 1: the keys before issue 20 (no ``schema_version`` key); 2: this vocabulary.
SCHEMA_VERSION = 2

#: SI unit -> key suffix (the unit in a key's name; ``_per_`` for a division).
UNIT_SUFFIXES: dict[str, str] = {
    "m": "_m",
    "Pa": "_Pa",
    "N": "_N",
    "s": "_s",
    "J": "_J",
    "kg": "_kg",
    "kg/m^3": "_kg_per_m3",
    "N/m": "_N_per_m",
    "N/m^2": "_N_per_m2",
    "m/s": "_m_per_s",
    "m/s^2": "_m_per_s2",
    "N s": "_N_s",
    "N m": "_N_m",
    "K": "_K",
    "Pa s": "_Pa_s",
    "pli": "_pli",  # lbf/in: the US copy of a tension per width beside its SI key
}

#: Unit of a member of a block whose own name carries the unit (``mean`` of
#: ``stats.thickness_m``, ``p50`` of ``core_pressure_Pa``): the enclosing block's unit.
BLOCK_UNIT = "block"

#: The scales an instrument reads on (dimensionless readings).
SCALES = {"rho": "Rho", "g": "g", "R": "Schmidt R", "L": "Parotester L", "readout": "readout"}

KINDS = ("number", "integer", "boolean", "string", "object", "objects", "map", "any")


@dataclass(frozen=True)
class Term:
    """One JSON key.

    Attributes
    ----------
    name : str
        The key, exactly as the JSON writes it.
    unit : str
        SI unit ("" dimensionless; :data:`BLOCK_UNIT`: the enclosing block's unit).
    meaning : str
        One line: what the value is.
    symbol : str
        Symbol in the docs and the reference paper ("" when none).
    kind : str
        JSON shape (:data:`KINDS`): a number, integer, boolean or string (each also as a list
        of them, one per node, position or sample, and null where undefined); ``object``: a
        block whose keys are terms; ``objects``: a list of such blocks; ``map``: a block keyed
        by names the data choose (parameter names, constraint names).
    scale : str
        For a reading: the scale (key of :data:`SCALES`; "readout": the instrument's).
    """

    name: str
    unit: str
    meaning: str
    symbol: str = ""
    kind: str = "number"
    scale: str = ""


def _t(name: str, unit: str, meaning: str, symbol: str = "", kind: str = "number") -> Term:
    return Term(name, unit, meaning, symbol, kind)


def _r(name: str, scale: str, meaning: str, symbol: str = "") -> Term:
    """A reading on an instrument's scale."""
    return Term(name, "", meaning, symbol, "number", scale)


def _o(name: str, meaning: str, kind: str = "object", unit: str = "") -> Term:
    return Term(name, unit, meaning, "", kind)


def _s(name: str, meaning: str) -> Term:
    return Term(name, "", meaning, "", "string")


def _b(name: str, meaning: str) -> Term:
    return Term(name, "", meaning, "", "boolean")


def _i(name: str, meaning: str) -> Term:
    return Term(name, "", meaning, "", "integer")


# fmt: off
_TERMS: tuple[Term, ...] = (
    # ------------------------------------------------------------------ documents, blocks
    _i("schema_version", "version of this vocabulary the document is written in (2)"),
    _o("case", "the case as run: title and every input with its source (in a row: its name)"),
    _o("winding", "the 1D winding model: stresses per node from the core out"),
    _o("contact", "the roll under the striker: force-depth curve and the roll spring {3}"),
    _o("hardness", "the reading: the striker's impact on the roll spring"),
    _o("no_update", "the same with E_r frozen at its pre-impact value (Figure 8)"),
    _o("dynamic", "the impact in time on the FE roll (contact.dynamic = true)"),
    _o("profile", "the CMD profile (winding.thickness_profile), or a fitted thickness profile"),
    _o("flags", "flags of the run (a reading off the scale, an extrapolated spring ...)"),
    _s("warnings", "what the flags mean, one sentence each"),
    _s("notes", "remarks on the run"),
    _s("files", "the files the run wrote into --out"),
    _s("arrays_omitted", "dotted keys of the arrays a compact result leaves out (in result.npz with --out; --fields full: in the JSON)"),  # noqa: E501
    _o("uncertainty", "Monte Carlo bands of the case's [uncertainty]"),
    _o("readings", "a sheet of measured readings: mean and scatter per position"),
    _o("diagnosis", "readings -> wound-on tension and near-surface pressure per position"),
    _o("defects", "defect risk of the roll: demand against capacity per criterion"),
    _o("design", "setpoint design for a target reading"),
    _o("inputs", "SI echo of the inputs a model used"),
    _o("options", "numerical options a model used"),
    _o("stats", "solver statistics, or statistics of a profile"),
    _o("web", "the web (film): thickness, width, moduli"),
    _o("core", "the core: radius and radial stiffness"),
    _o("tension", "the tension schedule: web stress and taper"),
    _o("radial_modulus", "the radial-modulus law E_r(P) of the stack"),
    _o("full_range_fit", "the roll spring {3} fitted over the whole solved depth"),
    _o("at_impact_depth", "the contact solution at the striker's impact depth"),
    _o("cmd_spread", "the CMD-spread correction of the plane-strain force (2d+cmd-spread)"),
    _o("head_calibration", "the head's dimensions and where they come from"),
    _o("at_peak", "the field under the head at the peak of the impact"),
    _o("nip", "the nip's load across the CMD"),
    _o("timings_s", "wall time of each stage", "map", "s"),
    _o("curve", "the forward curve: reading against web tension"),
    _o("verification", "a full forward run at the diagnosed point, against the curve"),
    _o("material_sensitivity", "d ln(T)/d p of the diagnosed tension for each material parameter", "map"),  # noqa: E501
    _o("raw", "the readings as read: one entry per value"),
    _o("profile_check", "the profiler's check of the readings: CoV, band, faults"),
    _o("faults", "hard and soft bands the check found", "objects"),
    _o("unchecked", "criteria not checked for want of a limit", "objects"),
    _o("roll", "criteria over the whole roll", "objects"),
    _o("lanes", "criteria per lane (position across the CMD)", "objects"),
    _o("criteria", "the criteria of one lane", "objects"),
    _o("limits", "the [defects] limits used (SI; null when not given)"),
    _o("causes", "the causes of the profile, ranked", "objects"),
    _o("cause_fit", "the cause fit: parameters, verification, forward runs"),
    _o("parameters", "fitted parameters with their standard deviations", "objects"),
    _o("parameters_sd", "SD of each uncertain parameter (SI of the parameter)", "map"),
    _o("surrogate", "the surrogate of the reading used by the Monte Carlo"),
    _o("linear", "linear coefficients of the surrogate per parameter", "map"),
    _o("quadratic", "quadratic coefficients of the surrogate per parameter", "map"),
    _o("checks", "full runs checking the surrogate", "objects"),
    _o("setpoints", "the designed setpoints"),
    _o("table", "the table taper: one entry per knot", "objects"),
    _o("target", "what the design aims for"),
    _o("margins", "margins of the designed roll against its constraints"),
    _o("profiles", "the designed roll's stresses per node"),
    _o("candidates", "the setpoints tried", "objects"),
    _o("slacks", "normalised slack per constraint (< 0: violated)", "map"),
    _o("fitted", "each fitted parameter: value, standard error", "map"),
    _o("rolls", "one entry per roll", "objects"),
    _o("overrides", "the --set overrides", "objects"),
    _o("history", "time histories of a study's roll", "any"),
    _o("pfeiffer", "the Pfeiffer law's fit"),
    _o("constant", "the constant-modulus law's fit"),
    _o("polynomial", "the polynomial law's fit"),
    _o("loading", "the loading law"),
    _o("unloading", "the unloading law"),
    # ------------------------------------------------------------------ case record
    _s("title", "title of the case"),
    _s("case_title", "title of the case as the case file gives it"),
    _s("key", "dotted case key (web.thickness)"),
    _t("value", "", "value of an entry (SI for a case input, or as read)", kind="any"),
    _s("unit", "unit of the entry's value or of a criterion's demand and capacity"),
    _t("given", "", "the value as written in the case file or on the command line", kind="any"),
    _s("source", "where a value or a file comes from"),
    _s("label", "label of a row"),
    _t("si", "", "the value in SI", kind="any"),
    _s("si_unit", "the SI unit of si"),
    # ------------------------------------------------------------------ winding
    _t("radius_m", "m", "radius from the roll's axis (per node)", "r"),
    _t("sigma_r_Pa", "Pa", "radial stress; < 0 compression; P = -sigma_r", "σ_r"),
    _t("sigma_theta_Pa", "Pa", "hoop (MD) stress", "σ_θ"),
    _t("E_r_Pa", "Pa", "radial tangent modulus at the final pressure", "E_r"),
    _t("wound_on_tension_Pa", "Pa", "wound-on tension: hoop stress a layer is wound in at", "WOT"),  # noqa: E501
    _t("core_pressure_Pa", "Pa", "interlayer pressure at the core surface, -sigma_r", "P_core"),
    _i("n_layers", "layers wound"),
    _i("n_nodes", "nodes of the radial mesh"),
    _t("outer_radius_m", "m", "outer radius of the roll", "R"),
    _t("max_pressure_Pa", "Pa", "largest interlayer pressure in the roll", "P_max"),
    _t("thickness_m", "m", "web thickness (per CMD position in a profile)", "h"),
    _t("width_m", "m", "web width, or a band's width", "W"),
    _t("E_theta_Pa", "Pa", "in-plane (MD) Young's modulus of the web", "E_θ"),
    _t("nu_theta_r", "", "Poisson ratio theta-r", "ν_θr"),
    _s("law", "name of a law: radial modulus, unloading or creep"),
    _t("K1_Pa", "Pa", "Pfeiffer's K1", "K1"),
    _t("K2", "", "Pfeiffer's K2", "K2"),
    _t("stiffness_Pa", "Pa", "radial stiffness of the core", "E_c"),
    _t("web_stress_Pa", "Pa", "web stress at the winder", "T_w/(W h)"),
    _s("taper", "taper law of the tension"),
    _t("taper_fraction", "", "taper: fraction the tension falls by from core to surface"),
    _t("nip_load_N_per_m", "N/m", "nip load per width", "N"),
    _t("friction", "", "coefficient of friction", "μ"),
    _i("subdivisions", "nodes per layer"),
    _i("layers_per_increment", "layers added per increment"),
    _s("modulus_update", "how E_r follows the pressure"),
    _t("rtol", "", "relative tolerance"),
    _i("max_iterations", "iteration limit"),
    _t("modulus_floor", "", "floor of E_r, as a fraction of E_theta"),
    _i("window_layers", "layers of the active window"),
    _i("flush_interval", "increments between flushes of the window"),
    _i("load_substeps", "load substeps of an increment"),
    _s("new_layer", "how a new layer is added"),
    _i("increments", "increments solved"),
    _i("max_iterations_used", "largest number of iterations in an increment"),
    _i("nodes", "nodes solved"),
    _i("element_evaluations_window", "element evaluations inside the window"),
    _i("element_evaluations_refresh", "element evaluations of the refreshes"),
    # ------------------------------------------------------------------ contact
    _t("depth_m", "m", "depth of the striker below the undeformed surface", "δ"),
    _t("force_N", "N", "force on the striker", "F"),
    _t("force_per_length_N_per_m", "N/m", "plane-strain force per unit head length", "F/L"),
    _t("half_width_m", "m", "half-width of the contact", "a"),
    _t("peak_pressure_Pa", "Pa", "peak contact pressure", "p_max"),
    _t("semi_contact_width_m", "m", "semi-contact width at the deepest depth", "a"),
    _t("max_force_N", "N", "largest force of the force-depth curve", "F_max"),
    _t("slip_region_depth_m", "m", "depth of the region where the layers slip"),
    _t("slip_region_halfwidth_m", "m", "half-width of the region where the layers slip"),
    _t("max_slip_factor_near_contact", "", "largest slip factor {23} near the contact"),
    _i("unbounded_slip_elements_near_contact", "elements near the contact with no slip bound"),
    _t("head_radius_m", "m", "radius of the striker's head", "R_h"),
    _t("head_length_m", "m", "length of the striker's head", "L"),
    _b("update_modulus", "E_r updated with the contact pressure"),
    _i("n_elements", "finite elements"),
    _i("n_dof", "degrees of freedom"),
    _t("solve_time_s", "s", "solver wall time"),
    _i("factorisations", "matrix factorisations"),
    _t("alpha_N_per_m2", "N/m^2", "roll spring {3}: F = alpha d^2 + beta d, quadratic term", "α"),  # noqa: E501
    _t("beta_N_per_m", "N/m", "roll spring {3}: linear term", "β"),
    _t("fit_r2", "", "R^2 of the spring fit"),
    _t("fit_max_rel_residual", "", "largest relative residual of the spring fit"),
    _t("fit_depth_m", "m", "depth range of the spring fit"),
    _i("fit_points", "points of the spring fit"),
    _t("impact_depth_m", "m", "deepest point the striker reaches in the impact", "δ_max"),
    _t("impact_depth_energy_m", "m", "impact_depth_m of the energy model {19}-{22}"),
    _s("model", "name of the model used"),
    _t("depth_max_m", "m", "deepest depth the contact model solved (contact.depth_max)"),
    _t("max_contact_pressure_Pa", "Pa", "largest contact pressure"),
    _t("max_radial_pressure_Pa", "Pa", "largest radial pressure under the head"),
    _s("name", "name of an entry"),
    _s("formula", "the formula used"),
    _t("basin_factor_c_b", "", "CMD spread: basin factor c_b"),
    _t("end_factor_c_a", "", "CMD spread: end factor c_a"),
    _t("decay_length_m", "m", "CMD spread: decay length"),
    _t("spread_m", "m", "CMD spread: spread beyond the head"),
    _t("length_ratio", "", "CMD spread: effective length over head length L_eff/L"),
    _t("plane_strain_force_N", "N", "force of the plane-strain model before the correction"),
    # ------------------------------------------------------------------ hardness
    _s("instrument", "the tester (an instrument preset's name)"),
    _s("readout", "the scale the instrument reads on (rho, g, R, L)"),
    _r("reading", "readout", "what the instrument shows (its scale's end when saturated)"),
    _r("reading_model", "readout", "the model's reading, not clipped to the scale"),
    _b("saturated", "the model's reading is beyond the scale: the instrument shows the end"),
    _t("scale", "", "the scale's range [low, high], or the scale's name", kind="any"),
    _s("calibrated_in", "roll model the head was calibrated in"),
    _s("head_length_source", "where the head length comes from"),
    _r("rho_energy", "rho", "Rho of the energy model {19}-{22}", "ρ"),
    _r("rho_fd", "rho", "Rho of the finite-difference impact {4}-{13}", "ρ"),
    _r("rho_dynamic", "rho", "Rho of the FE impact in time (contact.dynamic)", "ρ"),
    _r("peak_g", "g", "peak deceleration in g (the g readout)"),
    _r("rebound_R", "R", "Schmidt rebound number R"),
    _r("parotester_L", "L", "Parotester reading L"),
    _t("impulse_N_s", "N s", "impulse of the contact force", "I"),
    _t("peak_force_N", "N", "peak contact force"),
    _t("peak_force_energy_N", "N", "peak contact force of the energy model"),
    _t("peak_deceleration_m_per_s2", "m/s^2", "peak deceleration of the striker"),
    _t("contact_time_s", "s", "duration of the contact"),
    _t("impact_speed_m_per_s", "m/s", "striker speed at first contact", "v_0"),
    _t("rebound_speed_m_per_s", "m/s", "striker speed when it leaves the roll"),
    _t("effective_mass_kg", "kg", "effective mass of the striker", "m_s"),
    _t("restitution", "", "coefficient of restitution", "e"),
    _s("rebound", "how the rebound is modelled"),
    _s("collision", "how the collision is modelled"),
    _t("time_step_s", "s", "time step"),
    _t("time_s", "s", "time since first contact"),
    _t("velocity_m_per_s", "m/s", "velocity of the striker"),
    _t("deceleration_m_per_s2", "m/s^2", "deceleration of the striker"),
    _s("roll_model", "the roll model behind the reading"),
    _t("peak_time_s", "s", "time of the peak deceleration"),
    _t("energy_in_J", "J", "kinetic energy of the striker at first contact"),
    _t("energy_left_in_roll_J", "J", "energy still in the roll when the striker leaves"),
    _t("energy_damped_J", "J", "energy dissipated by damping"),
    _t("energy_contact_loss_J", "J", "energy lost in the contact (numerical)"),
    _t("density_kg_per_m3", "kg/m^3", "density of the web", "ρ_w"),
    _i("n_steps", "time steps"),
    _s("mass_matrix", "mass matrix: lumped or consistent"),
    _t("rayleigh", "", "Rayleigh damping coefficients [mass 1/s, stiffness s]"),
    _t("position_m", "m", "CMD position from the drive-side edge (or the striker's position)", "z"),  # noqa: E501
    _t("contact_force_N", "N", "contact force on the striker"),
    _t("depth_below_surface_m", "m", "depth below the roll's surface"),
    _t("radial_pressure_Pa", "Pa", "radial pressure, -sigma_r"),
    _t("radial_pressure_pre_impact_Pa", "Pa", "radial pressure before the impact"),
    _t("contact_s_m", "m", "arc length along the contact"),
    _t("contact_pressure_Pa", "Pa", "contact pressure"),
    # ------------------------------------------------------------------ flags
    _b("reading_outside_range", "a reading beyond the instrument's scale"),
    _b("spring_extrapolated", "the striker goes deeper than the contact model solved"),
    _b("implausible_input", "a case value outside its plausible range"),
    _b("pressure_implausible", "the largest pressure beyond its plausible range"),
    _b("storage_overstress", "after the storage change layers separate or exceed strength"),
    _b("drum_slip", "centre-surface winding: the tension differential exceeds the drum's hold"),
    _b("air_loose", "after the entrained air has left, layers are apart (a loose roll)"),
    # ------------------------------------------------------------------ air (winding speed)
    _o("air", "the roll wound at speed with entrained air, and after the air has left"),
    _t("speed_m_per_s", "m/s", "winding speed (mean surface speed at the lay-on line)", "U"),
    _t("roughness_m", "m", "combined Rq of the two web faces in contact", "σ"),
    _t("viscosity_Pa_s", "Pa s", "dynamic viscosity of the air", "η"),
    _t("ambient_pressure_Pa", "Pa", "ambient (absolute) air pressure", "p_atm"),
    _t("nip_modulus_Pa", "Pa", "contact modulus E* of the lay-on roller's cover against the roll", "E*"),  # noqa: E501
    _t("nip_radius_m", "m", "lay-on (nip) roller radius", "R_nip"),
    _t("film_at_lay_on_m", "m", "air film at the lay-on line at the end of winding", "h_0"),
    _t("entrained_air_m", "m", "air layer per layer wound in, beyond the roughness", "a_0"),
    _t("film_radius_m", "m", "roll radius at which each layer is laid on (per layer)"),
    _t("film_m", "m", "air film at the lay-on line (per layer)", "h_0"),
    _t("outer_diameter_no_air_m", "m", "outer diameter of the roll wound without air, compacted"),  # noqa: E501
    _t("outer_diameter_at_winding_m", "m", "outer diameter of the roll with its air, compacted"),  # noqa: E501
    _t("outer_diameter_after_m", "m", "outer diameter after the air has left"),
    _t("core_pressure_at_winding_Pa", "Pa", "core pressure of the roll with its air"),
    _t("core_pressure_after_Pa", "Pa", "core pressure after the air has left"),
    _t("core_pressure_no_air_Pa", "Pa", "core pressure of the roll wound without air"),
    _t("air_radius_m", "m", "node radii of the roll wound with air (per node)", "r"),
    _t("sigma_r_at_winding_Pa", "Pa", "radial stress of the roll with its air (per node)", "σ_r"),  # noqa: E501
    _t("sigma_theta_at_winding_Pa", "Pa", "wound-in (hoop) stress of the web with the air in (per node)", "σ_θ"),  # noqa: E501
    _t("sigma_r_after_Pa", "Pa", "radial stress after the air has left (per node)", "σ_r"),
    _t("sigma_theta_after_Pa", "Pa", "hoop stress of the web after the air has left (per node)", "σ_θ"),  # noqa: E501
    _t("wound_length_m", "m", "web length wound up to a point of the finished roll"),
    _t("diameter_no_air_m", "m", "diameter where that length sits, roll wound without air"),
    _t("diameter_with_air_m", "m", "diameter where that length sits, roll wound with air"),
    _t("air_leakage_time_s", "s", "initial time constant of the air leaving at the roll's edges (slowest layer)", "τ"),  # noqa: E501
    _t("time_after_winding_s", "s", "time after winding of the roll 'after' (null: all the air that can leave has left)"),  # noqa: E501
    _t("air_gone_fraction", "", "share of the wound-in air gone in the roll 'after'"),
    _t("air_leaves_90_s", "s", "time for 90 % of the air to leave the slowest layer (the gap narrowing)", "t_90"),  # noqa: E501
    # ------------------------------------------------------------------ storage
    _o("storage", "the roll's change after winding: temperature and moisture"),
    _t("temperature_change_K", "K", "temperature in storage minus at winding", "ΔT"),
    _t("moisture_change", "", "change of the web's moisture content (mass fraction)", "ΔM"),
    _t("core_pressure_before_Pa", "Pa", "core pressure before the storage change"),
    _t("max_sigma_theta_Pa", "Pa", "largest hoop stress in the roll"),
    _t("min_sigma_theta_Pa", "Pa", "smallest hoop stress in the roll"),
    _t("delta_sigma_r_Pa", "Pa", "change of the radial stress by the storage change (per node)"),
    _t("delta_sigma_theta_Pa", "Pa", "change of the hoop stress by the storage change (per node)"),
    _i("iterations", "iterations used"),
    _t("storage_time_s", "s", "time in storage (radial creep)", "t_s"),
    _o("radial_creep", "the stack's creep law: phi(t), J(t) = (1 + phi(t)) / E_r"),
    _t("exponent", "", "exponent n of a power creep law phi = (t/tau)^n", "n"),
    _t("tau_s", "s", "time constant(s) of a creep law: power tau, Prony retardation times", "τ"),  # noqa: E501
    _t("weights", "", "Prony weights c_i of a creep law", "c_i"),
    _t("core_pressure_before_creep_Pa", "Pa", "core pressure when the storage time begins"),
    _t("core_pressure_after_creep_Pa", "Pa", "core pressure after the storage time"),
    _t("pressure_wound_in_Pa", "Pa", "interlayer pressure as wound, before storage (per node)"),
    _t("pressure_before_creep_Pa", "Pa", "interlayer pressure when the storage time begins (per node)"),  # noqa: E501
    _t("pressure_after_creep_Pa", "Pa", "interlayer pressure after the storage time (per node)"),
    _t("creep_time_s", "s", "time steps through the storage time"),
    _t("creep_core_pressure_Pa", "Pa", "core pressure at each creep time step"),
    # ------------------------------------------------------------------ profile
    _t("z_m", "m", "CMD position of a sector's centre", "z"),
    _r("reading_energy", "readout", "the energy model's reading"),
    _t("sigma_r_outer_Pa", "Pa", "radial stress near the surface"),
    _t("sigma_r_core_Pa", "Pa", "radial stress at the core"),
    _i("n", "count"),
    _t("mean", BLOCK_UNIT, "mean"),
    _t("sd", BLOCK_UNIT, "standard deviation"),
    _t("cov", "", "coefficient of variation sd/mean", "CoV"),
    _t("min", BLOCK_UNIT, "smallest value"),
    _t("max", BLOCK_UNIT, "largest value"),
    _t("peak_to_peak", BLOCK_UNIT, "max - min"),
    _s("band", "acceptance band of the CoV: very good, acceptable, bad"),
    _i("reading_n_saturated", "sectors whose reading is off the scale"),
    _b("slack", "a sector wound slack"),
    _i("n_groups", "groups of layers"),
    _t("contact_fraction", "", "share of the width the nip touches"),
    _t("peak_to_mean", "", "peak over mean nip load"),
    _t("foundation_depth_m", "m", "depth of the nip's foundation"),
    _o(
        "contact_stage",
        "how the sectors' roll springs were found (every sector, interpolated or anchored)",
    ),
    _s("stage", "the contact stage: every-sector, interpolated or anchored"),
    _r("contact_tolerance", "readout", "largest reading change the interpolation's check accepts"),
    _b("solved", "a sector whose contact was solved fully (not interpolated)"),
    _i("n_solved", "sectors whose contact was solved fully"),
    _i("check_rounds", "rounds of full solves that checked the interpolation"),
    _r("largest_check", "readout", "largest reading change found by the last check round"),
    # ------------------------------------------------------------------ readings
    _i("passes", "passes over the roll"),
    _t("lane_width_m", "m", "lane width, for lane numbers"),
    _t("scatter", BLOCK_UNIT, "scatter of the passes at a position"),
    _i("count", "values at a position"),
    _t("pooled_sd", "", "pooled standard deviation of the passes, in the readings' scale"),
    _i("pass", "pass a value belongs to"),
    _i("line", "line of the file a value was read from"),
    _o("ids", "identifiers of the roll (lot, roll)", "map"),
    _i("n_positions", "positions across the roll"),
    _s("verdict", "the check's verdict, one sentence"),
    _t("fault_band", "", "deviation from the mean that makes a fault, in the readings' scale"),
    _s("kind", "kind of an entry"),
    _t("start_m", "m", "start of a band"),
    _t("end_m", "m", "end of a band"),
    _t("peak_position_m", "m", "position of a band's peak"),
    _t("peak", "", "a band's peak reading"),
    _t("deviation", "", "deviation from the mean reading"),
    _s("chart", "the control chart's kind and limits"),
    _b("provisional", "too few rolls for settled control limits"),
    _o("mean_chart", "X-mR chart of the rolls' mean readings"),
    _o("cov_chart", "X-mR chart of the rolls' CoV"),
    _s("flagged", "rolls outside the control limits, one sentence each"),
    _t("values", "", "the chart's values, one per roll"),
    _t("center", "", "the chart's centre line"),
    _t("mr_bar", "", "mean moving range"),
    _t("ucl", "", "upper control limit"),
    _t("lcl", "", "lower control limit"),
    _t("mr_ucl", "", "upper control limit of the moving range"),
    _i("out_of_control", "indices of the rolls outside the limits"),
    # ------------------------------------------------------------------ diagnosis
    _t("web_tension_Pa", "Pa", "web stress at the winder (tension / (width thickness))", "T_w"),
    _t("web_tension_low_Pa", "Pa", "lower end of web_tension_Pa's interval"),
    _t("web_tension_high_Pa", "Pa", "upper end of web_tension_Pa's interval"),
    _t("wound_on_tension_low_Pa", "Pa", "lower end of wound_on_tension_Pa's interval"),
    _t("wound_on_tension_high_Pa", "Pa", "upper end of wound_on_tension_Pa's interval"),
    _t("surface_pressure_Pa", "Pa", "interlayer pressure near the surface (at pressure_depth_m)"),  # noqa: E501
    _t("surface_pressure_low_Pa", "Pa", "lower end of surface_pressure_Pa's interval"),
    _t("surface_pressure_high_Pa", "Pa", "upper end of surface_pressure_Pa's interval"),
    _s("status", "status of a position: ok, off the curve ..."),
    _t("confidence", "", "two-sided confidence of the intervals"),
    _t("pressure_depth_m", "m", "depth below the surface of the near-surface pressure"),
    _t("case_web_tension_Pa", "Pa", "the case's own web stress"),
    _t("dlnT_dp", "", "d ln(T)/d p: sensitivity of the diagnosed tension"),
    _b("extrapolated_spring", "the roll spring is extrapolated at this point"),
    _r("target_reading", "readout", "the reading the verification aims at"),
    _r("full_forward_reading", "readout", "reading of the full forward run"),
    _t("error", "", "error of the verification, in the readings' scale"),
    _t("surface_pressure_interpolated_Pa", "Pa", "surface pressure from the curve"),
    _t("surface_pressure_full_Pa", "Pa", "surface pressure of the full run"),
    _s("summary", "the diagnosis in one sentence"),
    _i("full_level", "full profile-model runs that corrected the tension level"),
    # ------------------------------------------------------------------ defects
    _s("risk", "risk level: low, watch, high, n/a"),
    _s("needs", "the case key a criterion needs"),
    _t("margin", "", "capacity over demand"),
    _t("demand", "", "demand of a criterion, in its unit"),
    _t("capacity", "", "capacity of a criterion, in its unit"),
    _t("where_radius_m", "m", "radius where the criterion is worst"),
    _s("sentence", "the finding in one sentence"),
    _t("wound_on_tension_over_median", "", "a lane's wound-on tension over the median lane's"),
    _b("slack_lane", "the lane is wound slack"),
    _t("core_strength_Pa", "Pa", "limit: pressure the core withstands"),
    _t("blocking_pressure_Pa", "Pa", "limit: pressure at which layers block"),
    _t("axial_acceleration_m_per_s2", "m/s^2", "limit: axial handling acceleration"),
    _t("torque_N_m", "N m", "limit: torque through the roll"),
    _t("slack_pressure_Pa", "Pa", "pressure below which a layer counts as slack"),
    _t("slack_fraction", "", "share of slack layers that makes a slack lane"),
    _t("watch_margin", "", "margin below which a risk is 'watch'"),
    # ------------------------------------------------------------------ causes
    _t("thickness_low_m", "m", "lower end of the fitted thickness' 95 % band"),
    _t("thickness_high_m", "m", "upper end of the fitted thickness' 95 % band"),
    _r("reading_measured", "readout", "measured mean reading per position"),
    _r("reading_fit", "readout", "reading of the fitted causes"),
    _r("reading_initial", "readout", "reading before the fit"),
    _t("residual_rms", "", "RMS residual of the fit, in the readings' scale"),
    _t("prior_sd", "", "prior standard deviation"),
    _b("identifiable", "the readings determine the parameter"),
    _t("correlation", "", "correlation matrix or coefficient"),
    _i("forward_runs", "forward runs made"),
    _t("posterior_sd_scale", "", "scale of the posterior SD"),
    _t("residual_chi2", "", "chi^2 of the residuals"),
    _i("residual_dof", "degrees of freedom of the residuals"),
    _s("cause", "a cause of the profile (a thickness band, the tension level, the nip)"),
    _t("share", "", "share of the explained CMD variation"),
    _r("mean_shift", "readout", "shift of the mean reading a cause makes"),
    _t("ln_s_levels", "", "ln of the tension-level factor at each correction"),
    _t("offsets", "", "offsets of the full runs"),
    _r("reading_full", "readout", "reading of a full forward run"),
    _r("reading_reduced", "readout", "reading of the reduced model"),
    _r("reading_map", "readout", "reading of the reduced model's pressure-to-reading map"),
    _r("reading_surrogate", "readout", "reading of the surrogate"),
    _t("full_slope", "", "slope of the full runs' level against the reduced model's"),
    _t("ln_s_correction", "", "correction of ln(tension level) by the full runs"),
    _o("sectors", "sectors checked", "objects"),
    # ------------------------------------------------------------------ uncertainty
    _t("percentiles", "", "percentiles of the bands"),
    _t("p2_5", BLOCK_UNIT, "2.5th percentile"),
    _t("p50", BLOCK_UNIT, "median"),
    _t("p97_5", BLOCK_UNIT, "97.5th percentile"),
    _t("surface_pressure_depth_m", "m", "depth of the near-surface pressure"),
    _t("min_hoop_stress_Pa", "Pa", "smallest hoop stress (layer mean)"),
    _t("negative_hoop_share", "", "share of samples with a negative hoop stress"),
    _r("nominal", "readout", "value at the nominal inputs"),
    _t("step_sd", "", "finite-difference step in SDs"),
    _i("full_runs", "full forward runs"),
    _i("sample", "index of a sample"),
    _t("max_abs_error", "", "largest |surrogate - full|"),
    _r("reading_nominal", "readout", "reading at the nominal inputs (band centre)"),
    _r("reading_low", "readout", "lower end of the reading's band or interval"),
    _r("reading_p50", "readout", "median reading of the samples"),
    _r("reading_high", "readout", "upper end of the reading's band or interval"),
    _r("reading_sd", "readout", "standard deviation of the reading over the samples"),
    _s("centre", "what the band is centred on: a full profile run or the reduced model"),
    _r("reduced_nominal", "readout", "reduced model's reading at the nominal inputs"),
    _b("outside_curve", "the sector's pressure lies outside the forward curve"),
    _s("outside_note", "what outside_curve means"),
    _i("curve_runs", "runs of the forward curves"),
    _o("linear_reduced", "the reduced model's linear coefficients per parameter", "map"),
    _o("tension_calibration", "the tension term scaled to full runs per sector"),
    _r("full_change", "readout", "full run's change of the reading at +step"),
    _r("full_change_minus", "readout", "full run's change of the reading at -step"),
    _r("reduced_change", "readout", "reduced model's change of the reading at +step"),
    _t("ratio", "", "full over reduced change"),
    _b("linear_only", "the sector takes the full run's change as a linear term"),
    _t("web_stress_minus_Pa", "Pa", "web stress of the run at -step"),
    # ------------------------------------------------------------------ design
    _t("min_pressure_Pa", "Pa", "smallest interlayer pressure (core to near surface)"),
    _s("violations", "constraints the design violates"),
    _t("score", "", "the candidate's score"),
    _s("taper_kind", "taper law: linear, hyperbolic, table"),
    _t("table_factor", "", "table taper's factors, core to surface"),
    _b("feasible", "every constraint met"),
    _t("web_tension_N_per_m", "N/m", "web tension per width"),
    _t("web_tension_pli", "pli", "web tension per width in pli (a US copy)"),
    _t("web_tension_N", "N", "web tension"),
    _t("nip_load_pli", "pli", "nip load in pli (a US copy)"),
    _t("diameter_m", "m", "diameter"),
    _t("factor", "", "tension factor of a knot"),
    _t("tolerance", "", "accepted |reading - target|, in the target's scale"),
    _t("pressure_min_Pa", "Pa", "smallest accepted interlayer pressure"),
    _t("pressure_max_Pa", "Pa", "largest accepted interlayer pressure"),
    _t("tension_min_Pa", "Pa", "lower end of the winder's tension range"),
    _t("tension_max_Pa", "Pa", "upper end of the winder's tension range"),
    _t("nip_min_N_per_m", "N/m", "lower end of the nip load range"),
    _t("nip_max_N_per_m", "N/m", "upper end of the nip load range"),
    _t("taper_max", "", "largest taper fraction"),
    _b("allow_negative_hoop", "a negative hoop stress is accepted"),
    _t("hoop_min_Pa", "Pa", "smallest accepted layer-mean hoop stress"),
    _i("knots", "knots of the table taper"),
    _b("monotone", "the table taper only falls"),
    _t("pressure_min_margin", "", "smallest pressure over its limit"),
    _t("pressure_max_margin", "", "limit over the largest pressure"),
    _t("lowest_web_tension_Pa", "Pa", "lowest web stress that meets the target"),
    _t("highest_web_tension_Pa", "Pa", "highest web stress that meets the target"),
    _t("reading_error", "", "designed reading minus target"),
    _t("surrogate_reading_error", "", "surrogate's reading error"),
    _t("layer_radius_m", "m", "mid radius of a layer"),
    _t("layer_mean_hoop_stress_Pa", "Pa", "mean hoop stress of a layer"),
    _s("binding_constraint", "the constraint with the least slack"),
    _o("relaxations", "per violated constraint, the limit that admits the design", "objects"),
    _s("constraint", "name of a design constraint"),
    _t("normalised_slack", "", "slack of a constraint over its limit (< 0: violated)"),
    _t("limit_needed_Pa", "Pa", "the constraint's limit that would admit the design"),
    _i("full_forward_runs", "full forward runs made"),
    _s("case_snippet", "the setpoints as case-file TOML"),
    # ------------------------------------------------------------------ calibration
    _s("unknown", "the head dimension solved for"),
    _t("head_radius_before_m", "m", "head radius before the calibration"),
    _t("head_length_before_m", "m", "head length before the calibration"),
    _r("target_rho", "rho", "block reading to match"),
    _r("block_reading", "rho", "reading on the calibration block"),
    _r("block_reading_energy", "rho", "energy model's reading on the block"),
    _r("block_reading_before", "rho", "block reading before the calibration"),
    _t("block_impact_depth_m", "m", "impact_depth_m on the calibration block"),
    _i("evaluations", "model evaluations"),
    _t("value_m", "m", "fitted value"),
    _t("standard_error_m", "m", "standard error of the fitted value"),
    _t("standard_error", "", "standard error of the fitted value"),
    _s("describe", "what the parameter is"),
    _i("n_readings", "readings of the roll"),
    _r("measured_mean", "readout", "measured mean reading"),
    _r("model_before", "readout", "model reading before the fit"),
    _r("model_fitted", "readout", "model reading after the fit"),
    _r("loo_predicted", "readout", "leave-one-out prediction"),
    _t("scatter_fit", "", "scatter of the fit's residuals, in the readings' scale"),
    _t("scatter_repeat", "", "scatter of repeated readings, in the readings' scale"),
    _b("predicts_left_out_rolls", "the calibrated model predicts rolls it was not fitted to"),
    _i("runs", "forward runs made"),
    _t("loo_error", "", "leave-one-out error, in the readings' scale"),
    _t("loo_allowed", "", "allowed leave-one-out error"),
    # ------------------------------------------------------------------ stack tests
    _t("C1_Pa", "Pa", "polynomial law's C1", "C1"),
    _t("C2_Pa", "Pa", "polynomial law's C2", "C2"),
    _t("C3_Pa", "Pa", "polynomial law's C3", "C3"),
    _t("strain", "", "radial strain of the stack (tabulated law)", "ε"),
    _t("strain_max", "", "largest strain of the stack test"),
    _t("K1_sd_Pa", "Pa", "standard error of K1"),
    _t("K2_sd", "", "standard error of K2"),
    _t("K1_K2_correlation", "", "correlation of K1 and K2"),
    _t("covariance", "", "covariance matrix of the fitted parameters (SI)"),
    _t("r2", "", "R^2 of the fit"),
    _t("rms_rel_error", "", "RMS relative error of the fit"),
    _t("max_rel_error", "", "largest relative error of the fit"),
    _i("n_points", "points fitted"),
    _t("energy_ratio_measured", "", "unloading over loading energy of the cycle"),
    _t("restitution_measured", "", "restitution the cycle implies"),
    # ------------------------------------------------------------------ studies
    _s("study", "name of the study"),
    _s("figures", "figures of the reference paper the study reproduces"),
    _s("material", "web material preset"),
    _t("tension_N", "N", "winder tension", "T"),
    _t("pile_height_m", "m", "pile height: outer minus core radius"),
    _s("series", "which series of a study a roll belongs to"),
    _o("model_readings", "per roll model (and friction): the reading it gives", "objects"),
    _o("overrides_3d", "the --set overrides of a study's 3D columns (their mesh)", "objects"),
    _t("elastic_impulse_bound_N_s", "N s", "2 m_s v_0: the elastic bound of the impulse"),
    _t("peak_contact_pressure_Pa", "Pa", "peak contact pressure at impact_depth_m"),
    _r("rho_fd_no_update", "rho", "rho_fd with E_r frozen"),
    _r("rho_energy_no_update", "rho", "rho_energy with E_r frozen"),
    _t("impulse_no_update_N_s", "N s", "impulse with E_r frozen"),
    _t("alpha_no_update_N_per_m2", "N/m^2", "alpha with E_r frozen"),
    _t("beta_no_update_N_per_m", "N/m", "beta with E_r frozen"),
    _t("manual_impulse_N_s", "N s", "impulse the instrument's manual gives"),
    _s("contact_model", "roll model of a study's contact runs"),
    _o("emulation", "the slip emulation's roll"),
    _t("fields_depth_m", "m", "depth at which the slip fields are shown"),
    _s("fields_source", "which model the slip fields come from"),
    _t("impact_depth_slip_m", "m", "impact_depth_m with interlayer slip"),
    _r("rho_energy_slip", "rho", "rho_energy with interlayer slip"),
    _r("rho_fd_slip", "rho", "rho_fd with interlayer slip"),
    _i("elements_near_contact", "elements near the contact"),
    _i("slip_elements_near_contact", "slipping elements near the contact"),
    _t("slip_region_depth_whole_model_m", "m", "depth of the slip region over the whole model"),  # noqa: E501
    _t("slip_shear_fraction", "", "reduced-shear emulation's shear fraction"),
    _t("shear_ratio", "", "G_r_theta / E_r set in place of the web's rule"),
    _b("shear_frozen", "G_r_theta kept at its pre-impact value"),
    _i("slipped_elements", "elements that slipped"),
    _t("active_mass_column_kg", "kg", "active mass of the striker column"),
    _t("active_mass_fe_kg", "kg", "active mass in the FE model"),
    _t("axis_depth_m", "m", "depth below the surface on the head's axis"),
    _t("axis_pressure_Pa", "Pa", "radial pressure on the head's axis"),
    _t("axis_approach_m", "m", "approach of the layers on the head's axis"),
    _r("block_abaqus_rho", "rho", "block reading of the reference paper's Abaqus model"),
    _r("block_manual_rho", "rho", "block reading the manual gives"),
    _t("contact_time_dynamic_s", "s", "contact_time_s of the FE impact in time"),
    _t("contact_time_fd_s", "s", "contact_time_s of the FD impact"),
    _t("energy_loss_numerical_J", "J", "energy lost numerically in the FE impact"),
    _t("fd_deceleration_m_per_s2", "m/s^2", "deceleration of the FD impact"),
    _t("fd_time_from_contact_s", "s", "time since first contact of the FD impact"),
    _t("time_from_contact_s", "s", "time since first contact"),
    _t("impact_depth_dynamic_m", "m", "impact_depth_m of the FE impact in time"),
    _t("impact_depth_fd_m", "m", "impact_depth_m of the FD impact"),
    _t("impulse_dynamic_N_s", "N s", "impulse of the FE impact in time"),
    _t("impulse_dynamic_no_update_N_s", "N s", "impulse_dynamic_N_s with E_r frozen"),
    _t("impulse_fd_N_s", "N s", "impulse of the FD impact"),
    _t("peak_pressure_dynamic_Pa", "Pa", "peak pressure under the head in the FE impact"),
    _t("peak_time_dynamic_s", "s", "peak_time_s of the FE impact"),
    _t("peak_time_fd_s", "s", "peak_time_s of the FD impact"),
    _t("restitution_dynamic", "", "restitution of the FE impact"),
    _t("restitution_dynamic_no_update", "", "restitution_dynamic with E_r frozen"),
    _r("rho_dynamic_no_update", "rho", "rho_dynamic with E_r frozen"),
    _r("rho_fd_hertz", "rho", "rho_fd on a Hertz spring"),
    _t("solve_time_dynamic_s", "s", "solver wall time of the FE impact"),
    _t("approach_share_deeper_1cm", "", "share of the approach deeper than 1 cm"),
    _t("approach_share_deeper_2cm", "", "share of the approach deeper than 2 cm"),
    _t("pre_impact_pressure_Pa", "Pa", "radial pressure before the impact"),
    _t("pressure_Pa", "Pa", "interlayer pressure P = -sigma_r", "P"),
    _o("pressure_profiles", "pressure against radius per pile height", "objects"),
    _t("reference_depth_max_m", "m", "depth_max_m of the reference roll"),
    _t("reference_pile_height_m", "m", "pile height of the reference roll"),
    _o("under_head_at_impact", "pressure under the head at the impact"),
)
# fmt: on

#: Every key, by name.
TERMS: dict[str, Term] = {}
for _term in _TERMS:
    if _term.name in TERMS:
        raise ValueError(f"two descriptions of {_term.name!r}")
    TERMS[_term.name] = _term


def check_term(term: Term) -> list[str]:
    """What is wrong with a term under the rules (empty when nothing): an unknown unit, a
    dimensional key without its unit's suffix, a dimensionless key with a unit suffix."""
    problems = []
    if term.kind not in KINDS:
        problems.append(f"{term.name}: unknown kind {term.kind!r}")
    if term.unit in ("", BLOCK_UNIT):
        for unit, suffix in UNIT_SUFFIXES.items():
            if term.name.endswith(suffix) and term.name != suffix:
                problems.append(
                    f"{term.name}: dimensionless but ends in {suffix!r} (the suffix of {unit})"
                )
    elif term.unit not in UNIT_SUFFIXES:
        problems.append(f"{term.name}: unit {term.unit!r} has no key suffix (UNIT_SUFFIXES)")
    elif not term.name.endswith(UNIT_SUFFIXES[term.unit]):
        problems.append(
            f"{term.name}: in {term.unit} but does not end in {UNIT_SUFFIXES[term.unit]!r}"
        )
    if term.scale and term.scale not in SCALES:
        problems.append(f"{term.name}: unknown scale {term.scale!r}")
    return problems


def check_terms(terms: Any = None) -> list[str]:
    """:func:`check_term` over ``terms`` (default: every term of :data:`TERMS`)."""
    return [p for t in (TERMS.values() if terms is None else terms) for p in check_term(t)]


def unit_of(path: str, readout: str | None = None) -> str | None:
    """The unit label of the value at a dotted JSON path (``hardness.impulse_N_s`` ->
    ``"N s"``, ``hardness.rho_fd`` -> ``"rho"``, ``profile.stats.thickness_m.mean`` ->
    ``"m"``); ``""`` for a dimensionless value, None for a key the vocabulary lacks.
    ``readout``: the instrument's readout, the unit of ``reading`` and its kin."""
    parts = path.split(".")
    parent = TERMS.get(parts[-2]) if len(parts) > 1 else None
    if parent is not None and parent.kind == "map":  # a data name under a map: its unit
        return parent.unit
    if parts[-1] not in TERMS:
        return None
    for name in reversed(parts):  # a block member (mean, p50): the block's unit
        term = TERMS.get(name)
        if term is None:
            return ""
        if term.scale:
            return (readout or "") if term.scale == "readout" else term.scale
        if term.unit != BLOCK_UNIT:
            return term.unit
    return ""


def column_name(path: str, readout: str | None = None) -> str:
    """The sweep's column of a dotted JSON path: the key without its unit suffix and the
    unit in brackets (``winding.core_pressure [Pa]``, ``hardness.rho_fd [rho]``,
    ``contact.friction [-]``)."""
    unit = unit_of(path, readout)
    head, _, last = path.rpartition(".")
    term = TERMS.get(last)
    if term is not None and term.unit in UNIT_SUFFIXES:
        suffix = UNIT_SUFFIXES[term.unit]
        path = f"{head}.{last.removesuffix(suffix)}" if head else last.removesuffix(suffix)
    return f"{path} [{unit or '-'}]"


def undescribed_keys(doc: Any, path: str = "") -> list[str]:
    """Dotted paths of the keys of a JSON document the vocabulary lacks (a ``map`` block's
    keys are the data's own names and are not looked up)."""
    out: list[str] = []
    if isinstance(doc, dict):
        for k, v in doc.items():
            p = f"{path}.{k}" if path else k
            term = TERMS.get(k)
            if term is None:
                out.append(p)
            elif term.kind not in ("map", "any"):
                out += undescribed_keys(v, p)
    elif isinstance(doc, list):
        for v in doc:
            out += undescribed_keys(v, path + "[]")
    return sorted(set(out))


def versioned(doc: dict[str, Any]) -> dict[str, Any]:
    """``doc`` with ``schema_version`` first (the top level of each JSON document)."""
    return {"schema_version": SCHEMA_VERSION, **doc}


# ---------------------------------------------------------------------------- JSON Schema

#: The JSON documents: name -> (title, the top-level keys every one has).
DOCUMENTS: dict[str, tuple[str, tuple[str, ...]]] = {
    "result": (
        "result.json / woundroll run --json: one run of a case",
        ("schema_version", "case", "flags", "warnings"),
    ),
    "diagnosis": (
        "diagnosis.json / woundroll diagnose --json: readings -> tension and pressure",
        ("schema_version", "case", "readings", "diagnosis"),
    ),
    "readings": (
        "readings.json / woundroll readings --json: a sheet of readings and its check",
        ("schema_version", "position_m", "mean"),
    ),
    "defects": ("defects.json / woundroll defects --json", ("schema_version",)),
    "design": ("design.json / woundroll design --json", ("schema_version",)),
    "uncertainty": ("uncertainty.json: Monte Carlo bands", ("schema_version", "n")),
    "calibrate": (
        "woundroll calibrate --json: site calibration",
        ("schema_version", "fitted", "rolls"),
    ),
    "calibrate-head": (
        "woundroll calibrate-head --json: the head on its calibration block",
        ("schema_version", "instrument", "unknown"),
    ),
    "study": ("study.json / woundroll study --json", ("schema_version",)),
    "trend": (
        "trend.json / woundroll readings --trend --json: roll-to-roll control charts",
        ("schema_version", "rolls"),
    ),
    "fit-stack": ("woundroll fit-stack --json: radial-modulus laws fitted", ("schema_version",)),
}

#: Blocks that a row names by a string instead (``rolls[].case``: the case's name).
_ALSO_A_NAME = {"case"}

_SCALAR = {"number": "number", "integer": "integer", "boolean": "boolean", "string": "string"}


def _term_schema(term: Term) -> dict[str, Any]:
    unit = SCALES.get(term.scale, "") if term.scale else term.unit
    desc = term.meaning + (f" [{unit}]" if unit and unit != BLOCK_UNIT else "")
    if term.kind in _SCALAR:
        s: dict[str, Any] = {"$ref": f"#/$defs/list_of_{term.kind}"}
        if term.kind == "number":  # or the quantity's statistics: {"mean": ..., "p50": ...}
            s = {"anyOf": [s, {"$ref": "#/$defs/block"}]}
    elif term.kind in ("object", "objects"):  # a block, or a list of blocks (case.inputs)
        s = {
            "anyOf": [
                {"$ref": "#/$defs/block"},
                {"type": "array", "items": {"$ref": "#/$defs/block"}},
                {"type": "null"},
            ]
        }
        if term.name in _ALSO_A_NAME:
            s["anyOf"].append({"type": "string"})
    elif term.kind == "map":
        s = {"type": ["object", "null"]}
    else:
        s = {}
    if term.name == "schema_version":
        s = {"const": SCHEMA_VERSION}
    if term.unit in UNIT_SUFFIXES:
        s["x-unit"] = term.unit
    if term.scale:
        s["x-scale"] = term.scale
    return {"description": desc, **s}


def json_schema(document: str = "result") -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of a document of :data:`DOCUMENTS`.

    Each key is described once under ``$defs`` (from :data:`TERMS`: description with the
    unit, the type, ``x-unit``); every block, the top level included, admits only those keys.
    """
    if document not in DOCUMENTS:
        raise KeyError(f"unknown document {document!r}; one of {', '.join(DOCUMENTS)}")
    title, required = DOCUMENTS[document]
    defs: dict[str, Any] = {name: _term_schema(t) for name, t in sorted(TERMS.items())}
    for kind in _SCALAR:
        item = {"type": [_SCALAR[kind], "null"]}
        defs[f"list_of_{kind}"] = {
            "anyOf": [item, {"type": "array", "items": {"$ref": f"#/$defs/list_of_{kind}"}}]
        }
    defs["block"] = {
        "type": "object",
        "properties": {name: {"$ref": f"#/$defs/{name}"} for name in sorted(TERMS)},
        "additionalProperties": False,
    }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "$id": f"https://woundroll.invalid/schema/{SCHEMA_VERSION}/{document}.json",
        "title": title,
        "description": (
            f"woundroll JSON vocabulary, schema_version {SCHEMA_VERSION} "
            "(docs/nomenclature.md): one name per quantity, the SI unit in the key's suffix."
        ),
        "type": "object",
        "$ref": "#/$defs/block",
        "required": list(required),
        "$defs": defs,
    }


def nomenclature_table() -> str:
    """The Markdown table of docs/nomenclature.md: one row per key."""
    rows = ["| key | symbol | meaning | unit |", "|---|---|---|---|"]
    for t in sorted(TERMS.values(), key=lambda t: t.name.lower()):
        if t.scale:
            unit = f"{SCALES[t.scale]} (reading)"
        elif t.unit == BLOCK_UNIT:
            unit = "of the block"
        elif t.kind in ("object", "objects", "map") and not t.unit:
            unit = {"object": "(block)", "objects": "(list of blocks)", "map": "(named)"}[t.kind]
        else:
            unit = t.unit or "-"
        rows.append(f"| `{t.name}` | {t.symbol} | {t.meaning.replace('|', '/')} | {unit} |")
    return "\n".join(rows) + "\n"


if __name__ == "__main__":  # print the nomenclature table (docs/nomenclature.md)
    print(nomenclature_table(), end="")
