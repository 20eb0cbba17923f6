"""The impact in time on the 2D finite-element roll: the paper's dynamic reference model.

The reference paper checks its 1.5D models against a dynamic finite-element impact
(ABAQUS/Explicit with a VUMAT that updates E_r with the dynamic pressure; Figures 6-10).
This module is that model on woundroll's 2D plane-strain roll, so it lives beside the
quasi-static contact model it shares everything with (:mod:`woundroll.contact.plane_strain.solver`):
the same mesh (:func:`~woundroll.contact.plane_strain.mesh.build_mesh`, same defaults), the same
element and assembly (:mod:`woundroll.contact.plane_strain.fem`), the same cylindrically
orthotropic material with the hypoelastic radial modulus at the element's current total radial
stress (the VUMAT's role), the same frictionless contact with a rigid cylindrical head (exact linear
complementarity on the surface nodes). What is added:

* **Inertia of the roll**: mass matrix ``M = rho int N^T N r dr dtheta`` of the curved
  element (u_r, u_theta interpolated bilinearly in (r, theta), as in the stiffness), density
  ``web.density``; lumped (row sums, default) or consistent.
* **The striker {1}** as a rigid head on one degree of freedom: mass m_s, spring k_s, released
  at rest at ``x = -x_in`` {10}-{11}. Free flight up to first contact at ``x = x_gap`` is the
  exact harmonic motion (as in :func:`woundroll.instruments.impact_fd`), so the time
  integration starts at contact with ``v_c = omega sqrt(x_in^2 - x_gap^2)`` and the roll at
  rest in its wound state. Nothing is switched at contact: the roll's mass takes part
  through the contact forces (no active-mass formula {14}-{18}, no collision model).
* **Time integration (choice)**: implicit Newmark with ``gamma = 0.6``,
  ``beta = (gamma + 1/2)^2 / 4 = 0.3025`` by default: unconditionally stable, with numerical
  damping of the highest modes. Average acceleration (gamma = 1/2, no damping) was tried
  first and is available, but on the wound rolls it gains energy and blows up at small time
  steps (PET1 26.7 N, E_r frozen or updated: 400 steps per contact end with joules of
  spurious energy), the known lack of energy conservation of the trapezoidal rule with
  displacement-level contact constraints: nodes of the stiff, light surface layer chatter
  against the head. With gamma = 0.6 the loss is first order in dt and measured (the energy
  budget below), a few 1e-3 of the impact energy at the default step; the striker-on-roll
  mode (omega dt ~ 0.01) is not damped visibly. The roll's internal force is integrated
  incrementally like the quasi-static model:
  ``f_int,n+1 = f_int,n + K_t(E_r) du`` with the tangent stiffness at the element moduli of
  the step; the modulus is taken at the mid-step stress predicted by extrapolating the last
  increment (``modulus_update="extrapolated"``, one solve per step, default), at a trial
  increment's mid-step stress (``"midpoint"``, two solves) or at the start (``"euler"``).
* **Contact in time**: at each step, the effective stiffness ``K_eff = K_t + c0 M`` (plus
  damping) of the roll and ``k_s + c0 m_s`` of the striker are factorised; the free step is
  solved; the gaps of the candidate surface nodes to the head at its new position are linear
  in the contact forces with the flexibility ``W = N^T K_eff^-1 N + n_x n_x^T / (k_s + c0 m_s)``
  (the head moves back under the reaction), and the complementarity problem
  ``lam >= 0, g = g_free + W lam >= 0, lam g = 0`` is solved exactly (NNLS on the Cholesky
  factor of W). Penetration outside the candidates enlarges the set and repeats the step.
* **Rayleigh damping** ``C = a0 M + a1 K_t`` (off by default).

The half model (0 <= theta <= pi, symmetry) carries half the load per unit CMD length; the
striker's mass and spring are divided by ``2 L`` (L the head length) so that the per-length
equations hold, and every force and energy reported is multiplied back by ``2 L``.

Outputs: the striker's position, velocity, deceleration (spring plus contact force over m_s:
what the accelerometer feels, as in the FD model) and contact force against time; Rho (peak
deceleration / 3.76 g {22}), impulse ``int f dt``, contact time, maximum depth; the energy
budget (striker kinetic and spring energy, roll kinetic energy, work of the roll's internal
forces, damping); the radial pressure along the contact axis against depth at the peak
deceleration (Figure 10) and the contact pressure there; the rebound speed and the
coefficient of restitution ``e = v_rebound / v_impact``. An elastic roll (no unloading law)
gives back everything but what is still in the roll when the striker leaves (its motion and
its not yet recovered indentation), so e < 1 measures that; the readout says the material
is elastic.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.linalg as la
from numpy.typing import NDArray
from scipy.linalg.blas import dsbmv
from scipy.linalg.lapack import dtbtrs

from woundroll.contact.dynamic import timeloop
from woundroll.contact.dynamic.timeloop import ImpactState, Increment, Newmark, Striker
from woundroll.contact.plane_strain.fem import Assembler, plane_strain_moduli
from woundroll.contact.plane_strain.mesh import RollMesh
from woundroll.contact.plane_strain.solver import ContactOptions, _Roll, contact_mesh
from woundroll.errors import ConvergenceError, InputError
from woundroll.util.blas import one_blas_thread

if TYPE_CHECKING:
    from woundroll.instruments import Instrument
    from woundroll.materials.web import Core, Web

FloatArray = NDArray[np.float64]

MASS_MATRICES = ("lumped", "consistent")
MODULUS_UPDATES = ("extrapolated", "midpoint", "euler")


#: Far-field tangential grading of the dynamic model's mesh unless the options set one
#: (the case file's ``[contact.options] tangential_growth``): 1.1, the quasi-static default
#: until session 12 (now 1.15). The far field carries the waves here: Rho moved by 0.62 %
#: between 200 and 400 steps per contact on PET1 at 1.15, 0.30 % at 1.1 (the time-step
#: test of `tests/contact/test_dynamic.py` allows 0.5 %).
GROWTH = 1.1


@dataclass(frozen=True)
class DynamicOptions:
    """Numerical settings of :func:`impact_dynamic`.

    Attributes
    ----------
    time_step : float or None [s]
        Fixed time step; None: the estimated contact duration / ``steps_per_contact``.
    steps_per_contact : int
        Resolution of the automatic time step (default 400; docs/dynamic.md has the study).
    mass : {"lumped", "consistent"}
        Mass matrix. Lumped (row sums, default): the usual choice for impact (what an
        explicit code such as the paper's ABAQUS/Explicit uses), no coupling of the contact
        nodes' inertia; consistent: the variationally consistent matrix (same band as K).
    newmark_gamma : float
        Newmark gamma in [0.5, 1]; beta = (gamma + 1/2)^2 / 4. 0.5: average acceleration.
    rayleigh_mass, rayleigh_stiffness : float [1/s], [s]
        Rayleigh damping ``C = a0 M + a1 K_t`` (default 0, 0: undamped).
    modulus_update : {"extrapolated", "midpoint", "euler"}
        Where in the step the hypoelastic E_r is taken (module docstring).
    update_modulus : bool
        False freezes E_r at its pre-impact value (the paper's "no update").
    max_contact_times : float
        Give up (ConvergenceError) if the striker has not left after this many estimated
        contact durations.
    mesh : ContactOptions or None
        Mesh and material settings shared with the quasi-static model (its ``n_steps``,
        ``step_exponent`` and ``midpoint`` do not apply here). None: the quasi-static
        defaults with the far field graded at :data:`GROWTH`.
    """

    time_step: float | None = None
    steps_per_contact: int = 400
    mass: str = "lumped"
    newmark_gamma: float = 0.6
    rayleigh_mass: float = 0.0
    rayleigh_stiffness: float = 0.0
    modulus_update: str = "extrapolated"
    update_modulus: bool = True
    max_contact_times: float = 8.0
    mesh: ContactOptions | None = None

    def __post_init__(self) -> None:
        f = "contact.dynamic_options"
        if self.time_step is not None and not (
            isinstance(self.time_step, int | float)
            and math.isfinite(self.time_step)
            and self.time_step > 0
        ):
            raise InputError(f"must be a positive time, got {self.time_step!r}", f"{f}.time_step")
        if (
            isinstance(self.steps_per_contact, bool)
            or not isinstance(self.steps_per_contact, int | np.integer)
            or self.steps_per_contact < 20
        ):
            raise InputError(
                f"must be an integer >= 20, got {self.steps_per_contact!r}",
                f"{f}.steps_per_contact",
            )
        if self.mass not in MASS_MATRICES:
            raise InputError(f"must be one of {', '.join(MASS_MATRICES)}", f"{f}.mass")
        if self.modulus_update not in MODULUS_UPDATES:
            raise InputError(f"must be one of {', '.join(MODULUS_UPDATES)}", f"{f}.modulus_update")
        if not (math.isfinite(self.newmark_gamma) and 0.5 <= self.newmark_gamma <= 1.0):
            raise InputError(
                f"must lie in [0.5, 1], got {self.newmark_gamma!r}", f"{f}.newmark_gamma"
            )
        for name in ("rayleigh_mass", "rayleigh_stiffness"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InputError(f"must be zero or positive, got {v!r}", f"{f}.{name}")
        if not (math.isfinite(self.max_contact_times) and self.max_contact_times >= 2):
            raise InputError("must be >= 2", f"{f}.max_contact_times")
        if self.mesh is not None and not isinstance(self.mesh, ContactOptions):
            raise InputError("must be a ContactOptions", f"{f}.mesh")

    @property
    def newmark_beta(self) -> float:
        return 0.25 * (self.newmark_gamma + 0.5) ** 2


def element_mass(mesh: RollMesh) -> FloatArray:
    """Consistent mass matrices ``(n_el, 8, 8)`` of the curved element per unit density and
    unit CMD length [m^2]: ``int N_a N_b r dr dtheta`` on the u_r and on the u_theta DOFs
    (2x2 Gauss points: exact, the integrand is cubic in r and quadratic in theta).

    Element geometry as in :func:`woundroll.contact.plane_strain.fem.element_basis` (curved element:
    the exact annular sector; the same matrices serve the flat element, whose area differs
    by the chord's, O(element angle^2)).
    """
    conn = mesh.connectivity()
    r_node = np.tile(mesh.r, mesh.n_theta)
    th = mesh.node_angle()[conn]
    r0, r1 = r_node[conn[:, 0]], r_node[conn[:, 1]]
    t0, t1 = th[:, 0], th[:, 3]
    if mesh.periodic:
        t1 = np.where(t1 < t0, t1 + 2.0 * np.pi, t1)
    dr, dt = r1 - r0, t1 - t0
    g = 1.0 / math.sqrt(3.0)
    pts = (0.5 - 0.5 * g, 0.5 + 0.5 * g)
    m4 = np.zeros((conn.shape[0], 4, 4))
    for a in pts:
        for b in pts:
            N = np.array([(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b])
            w = 0.25 * (r0 + a * dr) * dr * dt
            m4 += w[:, None, None] * np.outer(N, N)[None, :, :]
    M = np.zeros((conn.shape[0], 8, 8))
    M[:, 0::2, 0::2] = m4
    M[:, 1::2, 1::2] = m4
    return M


class _FeRoll(_Roll):
    """The quasi-static model's roll section (:class:`woundroll.contact.plane_strain.solver._Roll`:
    mesh, element data, boundary conditions, pre-impact state) with its mass matrix."""

    def __init__(
        self,
        web: Web,
        core: Core,
        radius: FloatArray,
        sigma_r: FloatArray,
        mesh: RollMesh,
        opts: ContactOptions,
        density: float,
        consistent: bool,
    ) -> None:
        super().__init__(web, core, radius, sigma_r, mesh, opts)
        self.asm = self.assembler
        self.fi = self.asm.free_index
        self.n = self.asm.n_free
        n_dof = 2 * mesh.n_nodes
        free = self.free
        # mass on the free DOFs: lumped diagonal or banded consistent (same band as K)
        Me = element_mass(mesh) * density
        self.m_lumped = np.bincount(
            self.basis.dofs.ravel(), weights=Me.sum(axis=2).ravel(), minlength=n_dof
        )[free]
        self.M_band: FloatArray | None = None
        if consistent:
            z = np.zeros(mesh.n_elements)
            masm = Assembler(replace(self.basis, A=np.stack([Me, 0 * Me, 0 * Me, 0 * Me])), free)
            band = masm.banded(masm.values_lower(np.ones_like(z), z, z, z), lower_only=True)
            bw = self.asm.bandwidth
            if band.shape[0] < bw + 1:
                band = np.vstack([band, np.zeros((bw + 1 - band.shape[0], self.n))])
            self.M_band = band[: bw + 1]
        #: elements of the column on the contact axis (theta_0 .. theta_1), core -> surface
        self.axis_elements = mesh.j0 * (mesh.n_r - 1) + np.arange(mesh.n_r - 1)

    def mass_times(self, x: FloatArray) -> FloatArray:
        if self.M_band is None:
            return self.m_lumped * x
        return dsbmv(self.M_band.shape[0] - 1, 1.0, self.M_band, x, lower=1)

    def moduli(
        self, sigma_r_total: FloatArray, p_hist: FloatArray | None = None
    ) -> tuple[FloatArray, ...]:
        """Element moduli at the total radial stress; with the web's unloading law and the
        largest pressure each element has seen (``p_hist``), elements below it take the
        unloading modulus (:mod:`woundroll.materials.unloading`)."""
        E_r = self.web.E_r(sigma_r_total)
        un = self.web.radial_unloading
        if un is not None and p_hist is not None:
            P = -sigma_r_total
            E_r = np.where(P < p_hist * (1.0 - 1e-9), un.modulus_at_pressure(P), E_r)
        E_r = np.clip(E_r, self.E_floor, self.E_cap)
        return plane_strain_moduli(self.web, E_r)

    def k_band(self, mod: tuple[FloatArray, ...]) -> FloatArray:
        return self.asm.banded(self.asm.values_lower(*mod), lower_only=True)

    def full(self, x_free: FloatArray) -> FloatArray:
        out = np.zeros(self.free.size)
        out[self.free] = x_free
        return out


@dataclass(frozen=True, eq=False)
class DynamicImpactResult:
    """One impact of the striker on the FE roll, in time (:func:`impact_dynamic`).

    Scalars are SI; histories run from first contact to separation, ``time`` counted from
    release (as :class:`woundroll.instruments.ImpactResult`).

    Attributes
    ----------
    rho : float [Rho]
        Peak striker deceleration / (3.76 g) {22} (spring plus contact force, accelerometer).
    peak_deceleration : float [m/s^2]
    peak_time : float [s]
        Time of the peak deceleration, from first contact.
    peak_force : float [N]
    max_depth : float [m]
        Largest ``x_s - x_gap``: the head's depth below the undeformed surface.
    impulse : float [N s]
        ``int f dt`` of the contact force on the striker.
    contact_time : float [s]
    contact_start : float [s]
        From release.
    impact_speed, rebound_speed : float [m/s]
        At the contact position, before and after.
    restitution : float [-]
        ``rebound_speed / impact_speed``.
    rebound_r, rebound_l : float
        Schmidt R and Parotester L of the rebound (:mod:`woundroll.instruments.readout`).
    energy_in : float [J]
        Striker kinetic energy at contact.
    energy_roll_left : float [J]
        Energy left in the roll when the striker leaves (kinetic + work of internal forces).
    energy_damped : float [J]
        Work of the Rayleigh damping forces.
    energy_contact_loss : float [J]
        ``energy_in`` minus everything accounted for at separation (the discrete impact loss
        of nodes coming into contact; tends to 0 with the time step).
    elastic_rebound : bool
        True: the roll's material has no unloading law (the rebound is elastic but for the
        energy still in the roll when the striker leaves).
    time, position, velocity, deceleration, contact_force : ndarray
    energy_striker, energy_roll_kinetic, energy_roll_internal : ndarray [J]
    axis_depth : ndarray [m]
        Depth below the outer surface of the element centres on the contact axis.
    axis_pressure : ndarray [Pa]
        Total radial pressure ``-sigma_r`` there at the peak deceleration (Figure 10).
    axis_pressure_pre : ndarray [Pa]
        The pre-impact (wound-in) pressure there.
    contact_s, contact_pressure : ndarray [m], [Pa]
        Contact pressure on the surface nodes (arc length from the axis) at the peak.
    time_step : float [s]
    n_steps : int
    n_dof : int
    density : float [kg/m^3]
    solve_time_s : float
    options : DynamicOptions
    model : str
        Which FE roll (2D plane strain, or the 3D quarter of
        :mod:`woundroll.contact.dynamic.solid3d`).
    stats : dict
        Work counters of the 3D model (factorisations, solves, modified-Newton passes).
    """

    rho: float
    peak_deceleration: float
    peak_time: float
    peak_force: float
    max_depth: float
    impulse: float
    contact_time: float
    contact_start: float
    impact_speed: float
    rebound_speed: float
    restitution: float
    rebound_r: float
    rebound_l: float
    energy_in: float
    energy_roll_left: float
    energy_damped: float
    energy_contact_loss: float
    elastic_rebound: bool
    time: FloatArray = field(repr=False)
    position: FloatArray = field(repr=False)
    velocity: FloatArray = field(repr=False)
    deceleration: FloatArray = field(repr=False)
    contact_force: FloatArray = field(repr=False)
    energy_striker: FloatArray = field(repr=False)
    energy_roll_kinetic: FloatArray = field(repr=False)
    energy_roll_internal: FloatArray = field(repr=False)
    axis_depth: FloatArray = field(repr=False)
    axis_pressure: FloatArray = field(repr=False)
    axis_pressure_pre: FloatArray = field(repr=False)
    contact_s: FloatArray = field(repr=False)
    contact_pressure: FloatArray = field(repr=False)
    time_step: float = 0.0
    n_steps: int = 0
    n_dof: int = 0
    density: float = 0.0
    solve_time_s: float = 0.0
    options: DynamicOptions = field(default_factory=DynamicOptions, repr=False)
    contact_position: float = 0.0
    model: str = "2D plane-strain FE roll, implicit Newmark, frictionless contact"
    stats: dict = field(default_factory=dict, repr=False)

    @property
    def depth(self) -> FloatArray:
        """Head depth below the undeformed surface against time [m]."""
        return self.position - self.contact_position

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the ``hardness.dynamic`` block (SI, unit in each key)."""

        def lst(a: FloatArray) -> list[float]:
            return [float(x) for x in a]

        return {
            "model": self.model,
            "rho_dynamic": self.rho,
            "impulse_N_s": self.impulse,
            "contact_time_s": self.contact_time,
            "impact_depth_m": self.max_depth,
            "peak_deceleration_m_per_s2": self.peak_deceleration,
            "peak_time_s": self.peak_time,
            "peak_force_N": self.peak_force,
            "impact_speed_m_per_s": self.impact_speed,
            "rebound_speed_m_per_s": self.rebound_speed,
            "restitution": self.restitution,
            "rebound_R": self.rebound_r,
            "parotester_L": self.rebound_l,
            "rebound": (
                "elastic material (no unloading law): the striker loses only the energy still "
                "in the roll when it leaves (its motion, its not yet recovered indentation)"
                if self.elastic_rebound
                else "unloading law of the roll"
            ),
            "energy_in_J": self.energy_in,
            "energy_left_in_roll_J": self.energy_roll_left,
            "energy_damped_J": self.energy_damped,
            "energy_contact_loss_J": self.energy_contact_loss,
            "density_kg_per_m3": self.density,
            "time_step_s": self.time_step,
            "n_steps": self.n_steps,
            "n_dof": self.n_dof,
            "mass_matrix": self.options.mass,
            "rayleigh": [self.options.rayleigh_mass, self.options.rayleigh_stiffness],
            "solve_time_s": self.solve_time_s,
            **({"stats": self.stats} if self.stats else {}),
            "time_s": lst(self.time),
            "position_m": lst(self.position),
            "depth_m": lst(self.depth),
            "velocity_m_per_s": lst(self.velocity),
            "contact_force_N": lst(self.contact_force),
            "deceleration_m_per_s2": lst(self.deceleration),
            "at_peak": {
                "depth_below_surface_m": lst(self.axis_depth),
                "radial_pressure_Pa": lst(self.axis_pressure),
                "radial_pressure_pre_impact_Pa": lst(self.axis_pressure_pre),
                "contact_s_m": lst(self.contact_s),
                "contact_pressure_Pa": lst(self.contact_pressure),
            },
        }

    def plot(
        self, path: str | Path | None = None, fd: Any = None, rho_unit: float | None = None
    ) -> Any:
        """Deceleration against time (with the FD model's on the same axes when ``fd``, an
        :class:`~woundroll.instruments.ImpactResult`, is given) and the pressure under the
        head against depth at the peak (Figure 10). Returns the Figure."""
        import matplotlib.pyplot as plt

        unit = rho_unit if rho_unit is not None else self.peak_deceleration / max(self.rho, 1e-300)
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10.0, 4.2))
        t0 = self.contact_start
        ax.plot(
            (self.time - t0) * 1e3,
            self.deceleration / unit,
            color="C0",
            lw=2.0,
            label=f"{self.model[:2]} FE, dynamic: {self.rho:.1f} Rho",
        )
        if fd is not None:
            ax.plot(
                (fd.time - fd.contact_start) * 1e3,
                fd.deceleration / unit,
                color="C1",
                ls="--",
                lw=1.5,
                label=f"1.5D FD: {fd.rho:.1f} Rho",
            )
        ax.set_xlabel("time from contact [ms]")
        ax.set_ylabel("striker deceleration [Rho]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title(
            f"impulse {self.impulse:.3f} N s, contact {self.contact_time * 1e3:.2f} ms, "
            f"e = {self.restitution:.3f}",
            fontsize=9,
        )
        keep = self.axis_depth <= max(20 * self.max_depth, 5e-3)
        ax2.semilogy(
            self.axis_depth[keep] * 1e3,
            np.maximum(self.axis_pressure[keep], 1.0),
            color="C0",
            lw=2.0,
            label="at peak deceleration",
        )
        ax2.semilogy(
            self.axis_depth[keep] * 1e3,
            np.maximum(self.axis_pressure_pre[keep], 1.0),
            color="0.5",
            ls=":",
            label="wound-in (pre-impact)",
        )
        ax2.set_xlabel("depth below the surface on the contact axis [mm]")
        ax2.set_ylabel("radial pressure [Pa]")
        ax2.grid(alpha=0.3, which="both")
        ax2.legend(fontsize=8)
        ax2.set_title("pressure under the head (cf. Figure 10)", fontsize=9)
        fig.tight_layout()
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def _dynamic_mesh(
    web: Web, core: Core, r_out: float, head_radius: float, depth: float, opts: ContactOptions
) -> RollMesh:
    """The quasi-static model's mesh (:func:`~woundroll.contact.plane_strain.solver.contact_mesh`)
    with the surface ring one layer thick and the fine zone the whole a_geo."""
    return contact_mesh(
        web,
        core,
        r_out,
        head_radius,
        depth,
        opts,
        surface_layers=1.0,
        fine_zone=1.0,
        field="contact.options.surface_size",
    )


class _ImpactRoll2D:
    """The 2D roll in the time loop (:class:`woundroll.contact.dynamic.timeloop.FeRoll`): the
    moduli of a step, its solve with the contact (module docstring), the roll's Newmark
    update and its stresses."""

    label = "dynamic impact"
    n_stress = 3

    def __init__(
        self,
        roll: _FeRoll,
        opts: DynamicOptions,
        nm: Newmark,
        striker: Striker,
        head_radius: float,
        depth_scale: float,
    ) -> None:
        self.roll, self.opts, self.nm, self.striker = roll, opts, nm, striker
        self.R_h = self.head_radius = head_radius
        self.r_out = float(roll.mesh.r[-1])
        self.n = roll.n
        self.sigma_pre, self.r_centre = roll.sigma_pre, roll.r_centre
        self.elastic = roll.web.radial_unloading is None
        self.n_contact = roll.surface.size
        self.mass_times = roll.mass_times
        s_surf = self.r_out * roll.mesh.theta
        trib = 0.5 * (np.roll(s_surf, -1) - np.roll(s_surf, 1))
        if not roll.mesh.periodic:  # the half model
            trib[0] = 0.5 * s_surf[1]
            trib[-1] = 0.5 * (s_surf[-1] - s_surf[-2])
        self.surface_s, self.trib = s_surf, trib
        col = roll.axis_elements
        self.axis_depth = self.r_out - roll.r_centre[col]
        #: the contact axis's elements, surface first (as reported)
        self.axis_elements = col[np.argsort(self.axis_depth)]
        self.frozen = roll.moduli(roll.sigma_pre) if not opts.update_modulus else None
        self.tol_gap = 1e-6 * max(float(depth_scale), 1e-9)
        self._factor_cache: list[Any] = []  # (moduli, K band, Cholesky) for E_r frozen

    def contact_pressure(self, lam: FloatArray) -> FloatArray:
        return lam / self.trib

    def _moduli(self, st: ImpactState) -> tuple[FloatArray, ...]:
        """The element moduli of the step (``modulus_update``, module docstring)."""
        roll, sig, p_hist = self.roll, st.sig, st.p_hist
        if self.frozen is not None:
            return self.frozen
        if self.opts.modulus_update == "euler":
            return roll.moduli(roll.sigma_pre + sig[:, 0], p_hist)
        if self.opts.modulus_update == "extrapolated":
            return roll.moduli(roll.sigma_pre + sig[:, 0] + 0.5 * st.dsig_prev_r, p_hist)
        # midpoint: trial step at the start-of-step moduli
        mod0 = roll.moduli(roll.sigma_pre + sig[:, 0], p_hist)
        trial = self._solve(st, mod0)
        dsr = roll.stress_increment(mod0, roll.full(trial[0]))[:, 0]
        return roll.moduli(roll.sigma_pre + sig[:, 0] + 0.5 * dsr, p_hist)

    def _effective_stiffness(self, mod: tuple[FloatArray, ...]) -> tuple[FloatArray, FloatArray]:
        """The stiffness band and the Cholesky factor of ``K_eff = K_t + c0 M`` (+ damping);
        with E_r frozen factorised once."""
        cache = self._factor_cache
        if cache and cache[0] is mod:
            return cache[1], cache[2]
        roll, nm = self.roll, self.nm
        Kb = roll.k_band(mod)
        A = (1.0 + nm.c1 * nm.a1) * Kb
        if roll.M_band is None:
            A[0] += (nm.c0 + nm.c1 * nm.a0) * roll.m_lumped
        else:
            A = A + (nm.c0 + nm.c1 * nm.a0) * roll.M_band
        try:
            cb = la.cholesky_banded(A, lower=True, check_finite=False)
        except la.LinAlgError:
            raise ConvergenceError("effective stiffness is not positive definite") from None
        if mod is self.frozen:
            cache[:] = [mod, Kb, cb]
        return Kb, cb

    def _free_step(
        self, st: ImpactState, Kb: FloatArray, cb: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The roll's step without contact forces: (du, predicted a, predicted v)."""
        nm, m_vec = self.nm, self.mass_times
        a0, a1 = nm.a0, nm.a1
        a_pred = nm.predicted_acceleration(st.v, st.acc)
        v_pred = nm.predicted_velocity(st.v, st.acc, a_pred)
        rhs = -st.f_int + m_vec(a_pred)
        if a0 > 0 or a1 > 0:
            cv = a0 * m_vec(v_pred)
            if a1 > 0:
                cv = cv + a1 * dsbmv(Kb.shape[0] - 1, 1.0, Kb, v_pred, lower=1)
            rhs = rhs - cv
        du_free = la.cho_solve_banded((cb, True), rhs, check_finite=False)
        return du_free, a_pred, v_pred

    def _head_to_surface(
        self, st: ImpactState, du: FloatArray, dx: float
    ) -> tuple[FloatArray, FloatArray]:
        """Distances of the surface nodes from the head's axis at the striker's new
        position, and the vectors from the axis to them."""
        roll = self.roll
        centre = np.array([self.r_out + self.R_h - (st.x + dx - self.striker.xg), 0.0])
        pos = roll.xy[roll.surface] + roll.cartesian(roll.full(st.u + du), roll.surface)
        dpos = pos - centre
        return np.hypot(dpos[:, 0], dpos[:, 1]), dpos

    def _contact(
        self, st: ImpactState, cb: FloatArray, du_free: FloatArray, dx_free: float
    ) -> tuple[FloatArray, float, FloatArray, FloatArray]:
        """The step with the contact forces: the exact complementarity on the candidate
        nodes, the set enlarged where a node outside it penetrates. (du, dx, lam, normal)"""
        roll, n_surf, fi = self.roll, self.n_contact, self.roll.fi
        s_eff = self.striker.stiffness(self.nm)
        dist, dpos = self._head_to_surface(st, du_free, dx_free)
        g_free = dist - self.R_h
        normal = dpos / dist[:, None]
        cand = (g_free < 0) | (st.lam > 0)
        lam_new = np.zeros(n_surf)
        du, dx = du_free, dx_free
        for _ in range(8):
            if not np.any(cand):
                break
            band = np.flatnonzero(cand)
            idx = np.unique(
                np.clip(np.concatenate([band + k for k in (-2, -1, 0, 1, 2)]), 0, n_surf - 1)
            )
            nodes = roll.surface[idx]
            n_r, n_t = roll.polar(normal[idx], nodes)
            rows_r, rows_t = fi[2 * nodes], fi[2 * nodes + 1]
            m = idx.size
            rhs_c = np.zeros((self.n, m))
            cols = np.arange(m)
            ok_r, ok_t = rows_r >= 0, rows_t >= 0
            rhs_c[rows_r[ok_r], cols[ok_r]] = n_r[ok_r]
            rhs_c[rows_t[ok_t], cols[ok_t]] = n_t[ok_t]
            # W = N^T K_eff^-1 N = Y^T Y with Y = L^-1 N (forward substitutions only);
            # the displacement of the contact forces is then one backward solve L^-T (Y lam)
            Y, info = dtbtrs(cb, rhs_c, uplo="L", trans="N", diag="N")
            if info != 0:
                raise ConvergenceError("banded triangular solve failed")
            nx = normal[idx, 0]
            W = Y.T @ Y + np.outer(nx, nx) / s_eff
            lam_c = timeloop.lcp(W, g_free[idx])
            dz, info = dtbtrs(cb, Y @ lam_c, uplo="L", trans="T", diag="N")
            if info != 0:
                raise ConvergenceError("banded triangular solve failed")
            du = du_free + dz
            dx = dx_free + float(nx @ lam_c) / s_eff
            gap = self._head_to_surface(st, du, dx)[0] - self.R_h
            outside = np.ones(n_surf, dtype=bool)
            outside[idx] = False
            bad = outside & (gap < -self.tol_gap)
            lam_new = np.zeros(n_surf)
            lam_new[idx] = lam_c
            if not np.any(bad):
                break
            cand |= bad
        else:
            raise ConvergenceError(
                "dynamic contact: the contact set did not settle in 8 enlargements; "
                "use a smaller time step or a finer mesh"
            )
        return du, dx, lam_new, normal

    def _solve(self, st: ImpactState, mod: tuple[FloatArray, ...]) -> tuple[Any, ...]:
        """The step at the moduli ``mod``: (du, dx, lam, contact forces on the roll's free
        DOFs, contact force on the striker per model, predicted a and v, K band)."""
        roll = self.roll
        Kb, cb = self._effective_stiffness(mod)
        du_free, a_pred, v_pred = self._free_step(st, Kb, cb)
        dx_free = self.striker.free_step(st, self.nm)
        du, dx, lam_new, normal = self._contact(st, cb, du_free, dx_free)
        # contact forces: on the roll nodes lam * normal (polar DOFs), on the striker n_x lam
        fc = np.zeros(roll.free.size)
        fr, ft = roll.polar(normal * lam_new[:, None], roll.surface)
        fc[2 * roll.surface] = fr
        fc[2 * roll.surface + 1] = ft
        f_striker = float(normal[:, 0] @ lam_new)  # + towards the roll
        return du, dx, lam_new, fc[roll.free], f_striker, a_pred, v_pred, Kb

    def _damping_force(self, x: FloatArray, Kb: FloatArray) -> FloatArray:
        nm = self.nm
        return nm.a0 * self.mass_times(x) + (
            nm.a1 * dsbmv(Kb.shape[0] - 1, 1.0, Kb, x, lower=1) if nm.a1 > 0 else 0.0
        )

    def advance(self, st: ImpactState, k_step: int) -> Increment:
        """The step's increment: moduli, solve, the roll's Newmark update, stresses."""
        nm, roll = self.nm, self.roll
        mod = self._moduli(st)
        du, dx, lam_new, fc, f_s, a_pred, v_pred, Kb = self._solve(st, mod)
        acc_new = nm.c0 * du - a_pred
        v_new = v_pred + nm.c1 * du
        f_int_new = fc - self.mass_times(acc_new)
        damping = None
        if nm.damped:
            cv_old, cv_new = self._damping_force(st.v, Kb), self._damping_force(v_new, Kb)
            f_int_new = f_int_new - cv_new
            damping = (cv_old, cv_new)
        dsig = roll.stress_increment(mod, roll.full(du))
        force = -self.striker.scale * f_s  # on the striker, pushing it back [N]
        return Increment(du, dx, lam_new, acc_new, v_new, f_int_new, dsig, force, damping)


def _spring_estimate(
    web: Web,
    core: Core,
    profile: tuple[FloatArray, FloatArray],
    instrument: Instrument,
    opts: DynamicOptions,
    mesh_opts: ContactOptions,
) -> tuple[float, float, float]:
    """The energy model's depth on the quasi-static roll spring (coarse), the spring's
    secant stiffness there and the deepest depth solved
    (:func:`woundroll.contact.dynamic.timeloop.estimates`)."""
    from woundroll.contact.spring import roll_stiffness

    est = roll_stiffness(
        web,
        core,
        *profile,
        instrument,
        update_modulus=opts.update_modulus,
        options=replace(mesh_opts, n_steps=8),
    )
    d_est = est.impact_depth
    return d_est, est.alpha * d_est + est.beta, float(est.contact.delta[-1])


def impact_dynamic(
    web: Web,
    core: Core,
    radius: FloatArray,
    sigma_r: FloatArray,
    instrument: Instrument,
    *,
    contact_time: float | None = None,
    depth_scale: float | None = None,
    density: float | None = None,
    options: DynamicOptions | None = None,
) -> DynamicImpactResult:
    """The striker hits the 2D FE roll: the impact solved in time (module docstring).

    Parameters
    ----------
    web, core : Web, Core
        The roll's material (``web.density`` is the roll density) and core.
    radius, sigma_r : array [m], [Pa]
        Pre-impact radial stress profile (core to surface), e.g. from the winding model.
    instrument : Instrument
        Striker (k_s, m_s, x_in, x_gap) and cylindrical head (radius, length).
    contact_time : float, optional [s]
        Estimated contact duration, sets the default time step. Default: from the
        quasi-static roll spring (:func:`woundroll.contact.roll_stiffness`, coarse),
        ``pi sqrt(m_s / (k_s + F(d)/d))`` at the energy model's depth.
    depth_scale : float, optional [m]
        Expected maximum depth: sets the fine mesh zone as the quasi-static model's
        ``depth_max`` does. Default: from the same quasi-static estimate (x 1.25).
    density : float, optional [kg/m^3]
        Roll density; default ``web.density``. (A tiny density gives the massless-roll limit
        of the 1.5D models.)
    options : DynamicOptions, optional

    Raises
    ------
    InputError
        A non-cylindrical head, bad options.
    ConvergenceError
        The striker does not leave the roll within ``max_contact_times`` estimated contact
        durations, or the contact set does not settle.
    """
    from woundroll.contact.heads import head_length_of

    t_start = time.perf_counter()
    opts = options if options is not None else DynamicOptions()
    if not isinstance(opts, DynamicOptions):
        raise InputError("must be a DynamicOptions", "contact.dynamic_options")
    mesh_opts = opts.mesh if opts.mesh is not None else ContactOptions(tangential_growth=GROWTH)
    L = head_length_of(instrument)
    R_h = float(instrument.head_radius)
    r = np.asarray(radius, dtype=float)
    s = np.asarray(sigma_r, dtype=float)
    rho_roll = timeloop.roll_density(web, density)
    contact_time, depth_scale = timeloop.estimates(
        instrument,
        contact_time,
        depth_scale,
        lambda: _spring_estimate(web, core, (r, s), instrument, opts, mesh_opts),
    )
    dt = timeloop.time_step(opts, contact_time)
    r_out = float(r[-1])
    reach = 0.98 * min(0.5 * R_h, 0.25 * (r_out - core.outer_radius))
    mesh = _dynamic_mesh(web, core, r_out, R_h, min(float(depth_scale), reach), mesh_opts)
    roll = _FeRoll(web, core, r, s, mesh, mesh_opts, rho_roll, opts.mass == "consistent")
    # the half model carries half the load per unit CMD length: per length -> whole head
    striker = Striker.of(instrument, (2.0 if mesh_opts.half_model else 1.0) * L)
    fe = _ImpactRoll2D(roll, opts, Newmark.of(opts, dt), striker, R_h, depth_scale)
    with one_blas_thread():  # woundroll.util.blas
        run = timeloop.run_impact(fe, contact_time, opts.max_contact_times)
    return DynamicImpactResult(
        **timeloop.result_fields(run, fe, instrument),
        n_dof=roll.n + 1,
        density=rho_roll,
        solve_time_s=time.perf_counter() - t_start,
        options=opts,
    )


def matching_active_mass(
    instrument: Instrument,
    spring: Any,
    rho_target: float,
    *,
    collision: str = "plastic",
    m_max: float = 1.0,
) -> float:
    """The active roll mass m_r [kg] with which the 1.5D FD model {4}-{13} reads
    ``rho_target`` on the roll spring ``spring`` (what the FE roll "shows" as active mass).

    The FD reading falls monotonically with m_r (the plastic collision takes
    ``m_r/(m_s + m_r)`` of the impact energy and the deceleration is shared by
    ``m_s + m_r``), so the root is unique; NaN when even ``m_r = 0`` reads lower than the
    target (the FE roll reads harder than any massless spring) or ``m_max`` is not enough.

    Parameters
    ----------
    instrument : Instrument
    spring : force law, (alpha, beta) or RollSpring (its mass is replaced)
    rho_target : float [Rho]
        Typically :attr:`DynamicImpactResult.rho`.
    collision : {"plastic", "keep-velocity"}
    m_max : float [kg]
        Upper end of the search.
    """
    from scipy.optimize import brentq

    from woundroll.instruments import RollSpring, impact_fd
    from woundroll.instruments.roll_side import as_roll_spring

    base = as_roll_spring(spring)

    def f(m: float) -> float:
        rs = RollSpring(base.law, m, base.restitution)
        return impact_fd(instrument, rs, collision=collision).rho - rho_target

    lo, hi = f(0.0), f(m_max)
    if lo < 0 or hi > 0:
        return math.nan
    return float(brentq(f, 0.0, m_max, xtol=1e-7, rtol=1e-6))
