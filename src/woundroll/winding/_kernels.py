"""Compiled kernels of the layer-by-layer winding solve (:mod:`woundroll.winding.hakiel`).

numba is used here because a profile of the NumPy/SciPy per-increment solve showed the
per-increment Python and LAPACK call overhead, and the O(N) refresh of every element's
modulus, dominating a 10,000-layer roll (``benchmarks/bench_winding.py``).

Notation (see ``docs/winding.md``): ``F = r sigma_r`` [N/m] at the nodes, ``x = ln r``;
in each element the radial modulus is uniform, the increment obeys ``F_xx = g F`` with
``g = E_theta / E_r``, and the element relation between the end values of ``F`` and the
flux ``F_x = r sigma_theta`` is exact:

    F_x(left)  = p F_left - q F_right        (sign as seen from the element)
    p = k coth(k d),   q = k csch(k d),      k = sqrt(g), d = ln(r_right / r_left).

Eliminating from the core outward gives ``dF_e = alpha_e dF_{e+1}`` and the flux
``F_x(node e+1) = beta_e dF_{e+1}`` (a Riccati recursion), with ``beta_{-1} = c`` the core
condition ``F_x = c F`` at ``r_c``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def element_pq(g: float, d: float, inv_d: float) -> tuple[float, float]:
    """``(k coth(k d), k csch(k d))`` for ``k = sqrt(g)``, stable for small and large k d."""
    x2 = g * d * d
    if x2 < 0.01:
        # x coth x and x csch x as series in x = k d < 0.1; next terms O(x^8) ~ 1e-12
        p = (1.0 + x2 * (1.0 / 3.0 + x2 * (-1.0 / 45.0 + x2 * (2.0 / 945.0)))) * inv_d
        q = (1.0 + x2 * (-1.0 / 6.0 + x2 * (7.0 / 360.0 + x2 * (-31.0 / 15120.0)))) * inv_d
        return p, q
    k = math.sqrt(g)
    em = math.exp(-k * d)
    e2 = em * em
    den = 1.0 - e2
    return k * (1.0 + e2) / den, 2.0 * k * em / den


@njit(cache=True)
def modulus(P: float, kp: np.ndarray, ke: np.ndarray, floor: float, slope: float) -> float:
    """Piecewise-linear E_r(P) through knots (kp, ke); E_r(0) below 0, last slope beyond.

    ``slope`` is the last segment's slope (:func:`last_slope`, computed once per solve, not per
    element). Two knots (Pfeiffer, constant: exact) take a branch-light fast path.
    """
    n = kp.shape[0]
    if n == 2:
        E = ke[0] + slope * (max(P, kp[0]) - kp[0])
    elif P >= kp[n - 1]:
        E = ke[n - 1] + slope * (P - kp[n - 1])
    elif P <= kp[0]:
        E = ke[0]
    else:
        lo = 0
        hi = n - 1
        while hi - lo > 1:
            mid = (lo + hi) >> 1
            if kp[mid] <= P:
                lo = mid
            else:
                hi = mid
        t = (P - kp[lo]) / (kp[hi] - kp[lo])
        E = ke[lo] + t * (ke[hi] - ke[lo])
    return max(E, floor)


@njit(cache=True)
def last_slope(kp: np.ndarray, ke: np.ndarray) -> float:
    """Slope of the last segment of the knot table (the law's continuation beyond it)."""
    n = kp.shape[0]
    return (ke[n - 1] - ke[n - 2]) / (kp[n - 1] - kp[n - 2])


@njit(cache=True)
def _sweep(e0, e1, b, invr, dlog, invd, F, dF, w, kp, ke, slope, Et, floor, alpha, beta):
    """Element coefficients and the Riccati recursion for elements e0..e1-1, in one pass.

    Element e's modulus is taken at its pressure ``start + w * increment``; then
    ``alpha_e = q/(p + beta_{e-1})``, ``beta_e = p - q alpha_e`` with ``beta_{e0-1} = b``.
    The coefficient work does not depend on the recursion, so in one loop it overlaps with
    the recursion's serial division chain (two separate loops were 1.8x slower).
    """
    for e in range(e0, e1):
        P = -0.5 * (F[e] * invr[e] + F[e + 1] * invr[e + 1])
        if w != 0.0:
            P -= w * 0.5 * (dF[e] * invr[e] + dF[e + 1] * invr[e + 1])
        E = modulus(P, kp, ke, floor, slope)
        p, q = element_pq(Et / E, dlog[e], invd[e])
        a = q / (p + b)
        b = p - q * a
        alpha[e] = a
        beta[e] = b


@njit(cache=True)
def _deep_sweep(e1, c, invr, dlog, invd, F, Pflush, w_deep, kp, ke, slope, Et, floor, alpha, beta):
    """Freeze the deep elements 0..e1-1 and run the Riccati recursion over them from the core.

    Each modulus is taken at ``P + w_deep * (P - Pflush)``: ``P - Pflush`` is the change since
    the last flush, so with ``w_deep = 1/2`` the modulus is the one of the middle of the next
    period (if it is as long). Sets ``Pflush = P``.
    """
    b = c
    for e in range(e1):
        P = -0.5 * (F[e] * invr[e] + F[e + 1] * invr[e + 1])
        E = modulus(P + w_deep * (P - Pflush[e]), kp, ke, floor, slope)
        Pflush[e] = P
        p, q = element_pq(Et / E, dlog[e], invd[e])
        a = q / (p + b)
        b = p - q * a
        alpha[e] = a
        beta[e] = b


@njit(cache=True)
def flush(J, S, r, F, st, alpha, beta, c):
    """Apply the accumulated deep increment ``S`` (at node J) to nodes 0..J-1."""
    phi = 1.0
    for i in range(J - 1, -1, -1):
        phi *= alpha[i]
        d = phi * S
        F[i] += d
        bl = beta[i - 1] if i > 0 else c
        st[i] += bl * d / r[i]


@njit(cache=True)
def run_groups(
    g0,
    g1,
    gnode,
    r,
    invr,
    dlog,
    invd,
    F,
    st,
    Fself,
    stself,
    alpha,
    beta,
    Pflush,
    dF,
    dFold,
    kp,
    ke,
    Et,
    c,
    floor,
    w,
    iterate,
    w_deep,
    rtol,
    maxit,
    wnodes,
    flush_every,
    nsub,
    state_i,
    state_f,
):
    """Wind groups g0..g1-1 (one increment each). Returns -1, or the group that failed.

    ``state_i = [J, increments since flush, max iterations used]``, ``state_f = [S]``
    carry the lazy deep part between calls. ``wnodes < 0``: no lazy part (J = 0).
    """
    slope = last_slope(kp, ke)
    J = state_i[0]
    count = state_i[1]
    S = state_f[0]
    for g in range(g0, g1):
        m = gnode[g]
        top = gnode[g + 1]
        dtop = Fself[m]
        if m > 0 and dtop != 0.0:
            if J > m:
                J = m
            dsub = dtop / nsub
            for _sub in range(nsub):
                for it in range(maxit + 1):
                    _sweep(
                        J,
                        m,
                        beta[J - 1] if J > 0 else c,
                        invr,
                        dlog,
                        invd,
                        F,
                        dF,
                        w if it > 0 else 0.0,
                        kp,
                        ke,
                        slope,
                        Et,
                        floor,
                        alpha,
                        beta,
                    )
                    dF[m] = dsub
                    for e in range(m - 1, J - 1, -1):
                        dF[e] = alpha[e] * dF[e + 1]
                    if not iterate:
                        break
                    if it > 0:
                        err = 0.0
                        for e in range(J, m):
                            d = abs(dF[e] - dFold[e])
                            if d > err:
                                err = d
                        if err <= rtol * abs(dsub):
                            if it > state_i[2]:
                                state_i[2] = it
                            break
                        if it == maxit:
                            state_i[0] = J
                            state_i[1] = count
                            state_f[0] = S
                            return g
                    for e in range(J, m):
                        dFold[e] = dF[e]
                for i in range(J, m):
                    F[i] += dF[i]
                    bl = beta[i - 1] if i > 0 else c
                    st[i] += bl * dF[i] / r[i]
                if J > 0:
                    S += dF[J]
                F[m] += dsub
        # the new group's own state (for g = 0 its pressure acts on the core alone)
        for i in range(m, top + 1):
            F[i] = Fself[i]
            st[i] = stself[i]
        for e in range(m, top):
            Pflush[e] = -0.5 * (F[e] / r[e] + F[e + 1] / r[e + 1])
        count += 1
        if wnodes >= 0 and count >= flush_every:
            if J > 0:
                flush(J, S, r, F, st, alpha, beta, c)
            S = 0.0
            newJ = top - wnodes
            if newJ < 0:
                newJ = 0
            # freeze the deep elements at the pressure predicted for the middle of the
            # next period: P + w_deep * (change over the last period)
            _deep_sweep(
                newJ, c, invr, dlog, invd, F, Pflush, w_deep, kp, ke, slope, Et, floor, alpha, beta
            )
            for e in range(newJ, top):
                Pflush[e] = -0.5 * (F[e] / r[e] + F[e + 1] / r[e + 1])
            J = newJ
            count = 0
    state_i[0] = J
    state_i[1] = count
    state_f[0] = S
    return -1
