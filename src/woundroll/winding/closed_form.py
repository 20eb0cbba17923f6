"""Linear orthotropic winding in closed form (constant E_r and E_theta; Altmann-type).

An independent reference for :mod:`woundroll.winding.hakiel`. With uniform moduli the
increment of each layer solves ``r^2 s'' + 3 r s' + (1 - E_theta/E_r) s = 0`` (Hakiel's
equation with constant coefficients), whose solutions are ``r^(-1 +- k)`` with
``k = sqrt(E_theta/E_r)``. In terms of ``F = r sigma_r`` the increment of layer ``j``
(wound at radius ``s_j`` with wound-on tension ``T_j``, thickness ``h``) is

    dF_j(r) = -T_j h phi(r) / phi(s_j),    phi(r) = r^k + gamma r_c^(2k) r^-k,
    gamma = (k - c) / (k + c),             c = E_theta / E_c + nu_theta_r,

which satisfies ``F(s_j) = -T_j h`` (the layer's pressure T_j h / s_j) and the core
condition ``r F'(r) = c F`` at ``r_c`` (u(r_c) = r_c sigma_r / E_c). Summing the increments
of all layers wound above a radius gives the stresses there (Altmann, Tappi 51(4), 1968,
integrated the same solution continuously; here the sum runs over the discrete layers).

With ``new_layer="elastic"`` (the other way a new layer can enter its own increment,
``WindingOptions.new_layer``) layer ``j`` is part of the elastic body and its load acts on
its outer face: ``dF_j(r) = -T_j h phi(r) / phi(s_j + h)`` for ``r <= s_j + h``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError

FloatArray = NDArray[np.float64]


def linear_orthotropic(
    core_radius: float,
    thickness: float,
    wot: ArrayLike,
    E_r: float,
    E_theta: float,
    core_stiffness: float = math.inf,
    nu_theta_r: float = 0.0,
    new_layer: str = "laid_on",
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Stresses of a roll of constant moduli wound layer by layer, in closed form.

    Parameters
    ----------
    core_radius : float [m]
    thickness : float [m]
        Web thickness h; layer ``j`` is wound at radius ``r_c + j h``.
    wot : array_like [Pa]
        Wound-on tension of each layer, core outward (its length is the number of layers).
    E_r, E_theta : float [Pa]
        Radial and hoop moduli.
    core_stiffness : float [Pa]
        E_c of the core condition u(r_c) = r_c sigma_r / E_c (inf: rigid).
    nu_theta_r : float [-]
    new_layer : {"laid_on", "elastic"}
        Load of layer j on its inner face (default; the surface is then free) or on its
        outer face with the layer in the elastic body (the surface keeps ``-T h / R``).

    Returns
    -------
    radius, sigma_r, sigma_theta : ndarray
        At the layer interfaces (n + 1 radii, core to surface) [m], [Pa], [Pa]. The hoop
        stress at an interface is that of the layer above it (the last: of the last layer).
    """
    T = np.asarray(wot, dtype=float)
    for name, v in (
        ("core_radius", core_radius),
        ("thickness", thickness),
        ("E_r", E_r),
        ("E_theta", E_theta),
    ):
        if not (math.isfinite(v) and v > 0):
            raise InputError(f"must be positive and finite, got {v}", name)
    if not (core_stiffness > 0) or math.isnan(core_stiffness):
        raise InputError(f"must be positive, got {core_stiffness}", "core_stiffness")
    if T.ndim != 1 or T.size < 1 or not np.all(np.isfinite(T)):
        raise InputError("needs one finite tension per layer", "wot")
    if new_layer not in ("laid_on", "elastic"):
        raise InputError(f"choose laid_on or elastic, got {new_layer!r}", "new_layer")
    shift = 1 if new_layer == "elastic" else 0
    n = T.size
    r = core_radius + thickness * np.arange(n + 1)
    k = math.sqrt(E_theta / E_r)
    c = (0.0 if math.isinf(core_stiffness) else E_theta / core_stiffness) + nu_theta_r
    gamma = (k - c) / (k + c)
    rc = core_radius
    F = np.zeros(n + 1)
    Fx = np.zeros(n + 1)  # r * sigma_theta from the increments
    for j in range(n):
        s = r[j + shift]  # where the load acts
        rr = r[: j + 1 + shift]
        # phi(r)/phi(s) and r phi'(r)/phi(s), written with ratios <= 1 (no overflow)
        a = (rr / s) ** k
        b = gamma * (rc / s) ** k * (rc / rr) ** k
        den = 1.0 + gamma * (rc / s) ** (2 * k)
        F[: j + 1 + shift] += -T[j] * thickness * (a + b) / den
        # the layer's own increment does not load the layer itself (node j is its inner face)
        Fx[:j] += -T[j] * thickness * k * (a[:j] - b[:j]) / den
    st = Fx / r
    st[:n] += T
    st[n] = T[-1]
    sr = F / r
    if not shift:
        sr[n] = 0.0
    return r, sr, st
