"""What an instrument shows: Rho, g, Schmidt R, Parotester L.

Rho (Beloit Rho-meter)
    ``Rho = a_max / (3.76 g)`` with ``g = 9.81 m/s^2`` (the paper's {22}: 1 Rho = 3.76 g).
g (tapper-style testers)
    Peak deceleration divided by ``g``.
Schmidt R
    ``R = 100 x (rebound distance) / stroke``. The stroke is the travel from release to first
    contact, ``x_in + x_gap``; the rebound distance is the travel from the contact position back
    to the turning point of the rebound, ``x_gap + x_back`` (``x_back`` = distance of that
    turning point behind equilibrium). On the Schmidt hammer the spring is unstressed at impact
    (``x_gap = 0``), so ``R = 100 x_back / x_in``, the rider's position on its scale.
Parotester L
    ``L = 1000 x v_rebound / v_impact``, both speeds taken where the striker passes the contact
    position (on the way in and on the way out). This is woundroll's reading of "L is related to
    the ratio of the velocities" (reference paper, Introduction); the factor 1000 is a stated
    assumption, not a manufacturer's calibration.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "G_STANDARD",
    "READOUTS",
    "RHO_PER_G",
    "deceleration_from_rho",
    "g_from_deceleration",
    "parotester_l",
    "rho_from_deceleration",
    "schmidt_r",
]

#: Standard gravity as the paper uses it [m/s^2] ({22}).
G_STANDARD = 9.81
#: g per Rho: 1 Rho = 3.76 g ({22}).
RHO_PER_G = 3.76
#: Readout kinds an :class:`~woundroll.instruments.Instrument` may declare.
READOUTS = {
    "rho": "Rho (peak deceleration / 3.76 g)",
    "g": "peak deceleration in g",
    "schmidt-r": "Schmidt rebound number R = 100 rebound distance / stroke",
    "parotester-l": "Parotester L = 1000 v_rebound / v_impact",
}


def rho_from_deceleration(
    a: ArrayLike, rho_per_g: float = RHO_PER_G, g: float = G_STANDARD
) -> NDArray[np.float64]:
    """Rho from a peak deceleration ``a`` [m/s^2]: ``a / (3.76 g)`` {22}."""
    return np.asarray(a, dtype=float) / (rho_per_g * g)


def deceleration_from_rho(
    rho: ArrayLike, rho_per_g: float = RHO_PER_G, g: float = G_STANDARD
) -> NDArray[np.float64]:
    """Peak deceleration [m/s^2] for a Rho reading: ``Rho x 3.76 g`` {22}.

    The inverse of :func:`rho_from_deceleration`.
    """
    return np.asarray(rho, dtype=float) * (rho_per_g * g)


def g_from_deceleration(a: ArrayLike, g: float = G_STANDARD) -> NDArray[np.float64]:
    """Peak deceleration ``a`` [m/s^2] in units of g [-]."""
    return np.asarray(a, dtype=float) / g


def schmidt_r(
    back_position: ArrayLike, release_position: float, contact_position: float
) -> NDArray[np.float64]:
    """Schmidt rebound number ``R = 100 (x_gap + x_back) / (x_in + x_gap)`` [-].

    Parameters
    ----------
    back_position : float or array [m]
        Distance of the rebound's turning point behind equilibrium (x_back > 0 on the
        release side).
    release_position : float [m]
        x_in.
    contact_position : float [m]
        x_gap (0 for the Schmidt hammer).
    """
    xb = np.asarray(back_position, dtype=float)
    return 100.0 * (contact_position + xb) / (release_position + contact_position)


def parotester_l(v_impact: ArrayLike, v_rebound: ArrayLike) -> NDArray[np.float64]:
    """Parotester-style ``L = 1000 v_rebound / v_impact`` [-] (speeds [m/s], both > 0)."""
    return 1000.0 * np.asarray(v_rebound, dtype=float) / np.asarray(v_impact, dtype=float)
