"""The fast 2D path made to agree with the 3D model: load carried past the head's ends.

The plane-strain model (:func:`woundroll.contact.indent`) gives a force per unit CMD length
and multiplies it by the head's length L, as if the head were infinitely long. The 3D model
(:mod:`woundroll.contact.solid3d.solver`) shows that under the Rho-meter's 25 mm head the roll is
1.4-3 times stiffer than that: the outer layers, stiff along the CMD (E_z ~ GPa against
E_r ~ MPa), are pulled down beyond the head's ends and carry load there, like a plate on a
soft foundation. Plane strain has the same mechanism along the hoop: the surface around the
head sinks with it over a basin much wider than the contact (the roll's surface deflection
u(s) falls to 1/e of the head's depth 5-25 mm from the axis).

The correction (docs/contact.md, "Fast path: plane strain + CMD spreading"): the layers
are orthotropic with the same kind of stiffness along the hoop and along the CMD (Table 2:
E_z = E_theta, G_r_z = G_r_theta = 2 E_r), so past each end of the head the surface is
pulled down along the CMD about as far as the plane-strain basin reaches along the hoop.
The head then loads an effective length

    L_eff(d) = L + 2 s(d),   s(d) = c_b lambda(d) + c_a a(d),

F(d) = F_2D(d) L_eff(d) / L, where lambda(d) is the distance from the head's axis at which
the plane-strain surface deflection has fallen to 1/e of its value under the head
(:func:`deflection_decay_length`) and a(d) the 2D semi-contact width, both at the depth d
and read from the 2D solution. The basin term c_b lambda is the layers pulled down past the
end (c_b = 1 would be the exact hoop/CMD analogy); the end term c_a a is the load the head's
sharp ends concentrate over the contact width 2a (the bundled Rho-meter file has sharp
ends, and so had the 3D model the constants were fitted to). c_b, c_a
(:data:`BASIN_FACTOR`, :data:`END_FACTOR`) are fitted to the 3D model on two rolls and
validated on eight more rolls and two longer heads (docs/contact.md). The spread carries
no factor of the web's CMD stiffness: a plate on a foundation would suggest
(E_z/E_theta)^(1/4), but the 3D model with E_z = E_theta / 8 is as much stiffer than
plane strain as with E_z = E_theta, and s(d) without a factor matches it (docs/contact.md).

Limits: s / L -> 0 (a head much longer than the basin) gives plane strain back; the
stresses, the slip factor and the semi-contact width stay those of the 2D solution at the
same depth (only the force is corrected).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.contact.result import ContactResult, fit_spring
from woundroll.errors import InputError

FloatArray = NDArray[np.float64]

#: c_b and c_a of s(d) = c_b lambda(d) + c_a a(d): the two values
#: with which PET1 26.7 N and PET2 53.4 N read the 3D model's Rho (FD) with the 6.565 mm
#: Hertz head (the cached references, tests/contact/data; refitted 2026-11-26 on the 3D
#: mesh with a node on the head's end, and 2026-12-07 on the 3D model's lagged predictor,
#: whose references read 0.1-0.7 % higher: 0.865 / 3.9 -> 0.892 / 3.76, the two rolls
#: within 6e-5 of 3D); validated on the other eight rolls and two longer heads
#: (docs/contact.md, "Fast path: plane strain + CMD spreading").
BASIN_FACTOR = 0.892
END_FACTOR = 3.76

#: Name of the corrected path in results and JSON.
MODEL_NAME = "2d+cmd-spread"


def deflection_decay_length(s: ArrayLike, deflection: ArrayLike) -> float:
    """Distance [m] from the head's axis at which the surface deflection has fallen to 1/e.

    ``s``: arc length of the surface nodes from the axis (increasing, ``s[0] = 0``);
    ``deflection``: inward radial displacement there. Linear interpolation between the
    nodes that bracket ``deflection[0] / e``; 0 if the surface has not moved in; the last
    node's ``s`` if the deflection never falls that far.
    """
    s = np.asarray(s, dtype=float)
    u = np.asarray(deflection, dtype=float)
    u0 = float(u[0])
    if not u0 > 0:
        return 0.0
    target = u0 / math.e
    below = np.flatnonzero(u <= target)
    if below.size == 0:
        return float(s[-1])
    j = int(below[0])
    u1, u2 = float(u[j - 1]), float(u[j])
    t = (u1 - target) / (u1 - u2) if u1 != u2 else 1.0
    return float(s[j - 1] + t * (s[j] - s[j - 1]))


@dataclass(frozen=True)
class CmdSpread:
    """The CMD-spreading correction applied to one 2D solution.

    Attributes
    ----------
    plane_strain : ContactResult
        The 2D solution (force = plane-strain force per length x L).
    corrected : ContactResult
        The same with ``force`` (and the full-range fit {3}) multiplied by L_eff(d) / L.
    decay_length : ndarray [m]
        lambda(d) at every depth of the solution.
    spread : ndarray [m]
        s(d) = c_b lambda(d) + c_a a(d): how far the loaded length
        reaches past each end of the head.
    basin_factor, end_factor : float
        c_b and c_a used.
    head_length : float [m]
    """

    plane_strain: ContactResult
    corrected: ContactResult
    decay_length: FloatArray
    spread: FloatArray
    basin_factor: float
    end_factor: float
    head_length: float

    @property
    def length_ratio(self) -> FloatArray:
        """L_eff(d) / L at every depth (1 at d = 0)."""
        return 1.0 + 2.0 * self.spread / self.head_length

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": MODEL_NAME,
            "formula": "F = F_2D (L + 2 s) / L, s = c_b lambda(d) + c_a a(d)",
            "basin_factor_c_b": self.basin_factor,
            "end_factor_c_a": self.end_factor,
            "decay_length_m": self.decay_length.tolist(),
            "spread_m": self.spread.tolist(),
            "length_ratio": self.length_ratio.tolist(),
            "plane_strain_force_N": np.asarray(self.plane_strain.force).tolist(),
        }


def apply_cmd_spread(
    contact: ContactResult,
    *,
    basin_factor: float = BASIN_FACTOR,
    end_factor: float = END_FACTOR,
) -> CmdSpread:
    """Correct a 2D (plane-strain) solution for the load carried past the head's ends.

    Parameters
    ----------
    contact : ContactResult
        A 2D solution of :func:`woundroll.contact.indent` (it carries the surface
        deflection at every depth).
    basin_factor, end_factor : float
        c_b and c_a of the spread (defaults :data:`BASIN_FACTOR`, :data:`END_FACTOR`,
        fitted to the 3D model).

    Returns
    -------
    CmdSpread
    """
    hist = contact.surface_deflection_history
    if hist is None:
        raise InputError(
            "the CMD-spreading correction needs a 2D solution with its surface deflection",
            "contact.model",
        )
    for name, value in (("basin_factor", basin_factor), ("end_factor", end_factor)):
        if not (math.isfinite(value) and value >= 0):
            raise InputError(f"must be zero or positive, got {value!r}", f"contact.{name}")
    s = np.asarray(contact.contact_s, dtype=float)
    lam = np.array([deflection_decay_length(s, row) for row in np.asarray(hist)])
    a = np.asarray(contact.half_width, dtype=float)
    spread = basin_factor * lam + end_factor * a
    L = float(contact.head_length)
    force = np.asarray(contact.force) * (1.0 + 2.0 * spread / L)
    alpha, beta, r2, max_res = fit_spring(np.asarray(contact.delta), force)
    corrected = replace(
        contact, force=force, alpha=alpha, beta=beta, fit_r2=r2, fit_max_rel_residual=max_res
    )
    return CmdSpread(contact, corrected, lam, spread, float(basin_factor), float(end_factor), L)
