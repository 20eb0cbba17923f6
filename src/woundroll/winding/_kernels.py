"""Compiled kernels of the layer-by-layer winding solve (:mod:`woundroll.winding.hakiel`).

numba is used here because a profile of the NumPy/SciPy per-increment solve showed the
per-increment Python and LAPACK call overhead dominating a 10,000-layer roll
(``benchmarks/bench_winding.py``). Small rolls use the NumPy twin
(:mod:`woundroll.winding._kernels_numpy`) instead: numba's import and cache load cost more
than their whole solve. The lazy deep part (levels of doubling depth, :func:`_refresh`) is
described in :mod:`woundroll.winding.hakiel`.

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
def _flush_band(hi, lo, S, r, F, st, alpha, beta, c):
    """Apply the pending increment ``S`` at node ``hi`` to nodes hi-1 .. lo (frozen shape).

    Returns the increment given to node ``lo`` (``S`` itself for an empty band), which is
    the pending increment at the top of the band below.
    """
    phi = 1.0
    for i in range(hi - 1, lo - 1, -1):
        phi *= alpha[i]
        d = phi * S
        F[i] += d
        bl = beta[i - 1] if i > 0 else c
        st[i] += bl * d / r[i]
    return phi * S


@njit(cache=True)
def flush_all(nlev, B, S, r, F, st, alpha, beta, c):
    """Apply every level's pending increment, top down (end of the roll)."""
    for lev in range(1, nlev):
        if B[lev - 1] <= 0:
            break
        d = _flush_band(B[lev - 1], B[lev], S[lev], r, F, st, alpha, beta, c)
        S[lev] = 0.0
        if B[lev] > 0:
            S[lev + 1] += d


@njit(cache=True)
def _push(P, t, e, hist, thist):
    """Record element e's pressure P at time t (keeps the last two distinct times)."""
    if thist[e, 0] == t:
        hist[e, 0] = P
        return
    hist[e, 1] = hist[e, 0]
    thist[e, 1] = thist[e, 0]
    hist[e, 0] = P
    thist[e, 0] = t


@njit(cache=True)
def _flush_levels(k, B, S, r, F, st, alpha, beta, c):
    """Step 1 of :func:`_refresh`: the levels L = 1 + (trailing zero bits of k) apply their
    pending increments with their frozen shapes, top down. Returns L."""
    nlev = B.shape[0] - 1
    L = 1
    kk = k
    while kk % 2 == 0 and L < nlev - 1:
        kk //= 2
        L += 1
    for lev in range(1, L + 1):
        hi = B[lev - 1]
        lo = B[lev]
        if hi > lo:
            d = _flush_band(hi, lo, S[lev], r, F, st, alpha, beta, c)
        else:
            d = S[lev]
        S[lev] = 0.0
        if lo > 0:
            S[lev + 1] += d
    return L


@njit(cache=True)
def _place_levels(L, top, wnodes, B):
    """Step 2 of :func:`_refresh`: boundaries B[0..L-1] at wnodes 2^l below the surface
    (not below B[L])."""
    lo = B[L]
    span = wnodes
    for lev in range(L):
        b_new = top - span
        if b_new < lo:
            b_new = lo
        B[lev] = b_new
        if span < top:
            span *= 2


@njit(cache=True)
def _refresh(
    t, k, top, wnodes, flush_every, B, S, r, invr, dlog, invd, F, st, hist, thist, w_deep, kp,
    ke, slope, Et, floor, alpha, beta, c, state_i,
):  # fmt: skip
    """Refresh number ``k`` (at increment ``t``, surface node ``top``): levels 1..L, L = 1 +
    (trailing zero bits of k).

    Level l >= 1 is the band of elements B[l] <= e < B[l-1]; level 0 (e >= B[0]) is the
    window re-solved every increment. Band l is refreshed every 2^(l-1) refreshes and, once
    placed, starts wnodes 2^(l-1) nodes below the surface, so the period over which its
    moduli stay frozen is a fixed fraction (flush_every / window) of its depth at every
    level: O(log N) work per increment, amortised.

    1. The pending increments of levels 1..L are applied with their frozen shapes, top down.
    2. The boundaries B[0..L-1] are placed at wnodes 2^l below the surface (not below B[L]).
    3. Elements B[L] .. B[0]-1 get moduli at the pressure predicted for the middle of their
       next frozen period (rate of change since their last refresh x half the period), and
       the Riccati recursion is re-run over them from beta[B[L]-1].
    """
    L = _flush_levels(k, B, S, r, F, st, alpha, beta, c)
    lo = B[L]
    _place_levels(L, top, wnodes, B)
    state_i[4] += B[0] - lo
    b = beta[lo - 1] if lo > 0 else c
    lev = L
    period = flush_every * (1 << (L - 1))
    # pressure predicted at time ts from now (t, P) and the last two refreshes (t1, P1),
    # (t2, P2), Newton form: P + c1 (P - P1) - c2 (P1 - P2) (quadratic; linear with one
    # earlier value, P with none). c1, c2 depend on the times only: shared by a band.
    key1 = -2
    key2 = -2
    key_ts = -1.0
    c1 = 0.0
    c2 = 0.0
    for e in range(lo, B[0]):
        while lev > 1 and e >= B[lev - 1]:
            lev -= 1
            period //= 2
        P = -0.5 * (F[e] * invr[e] + F[e + 1] * invr[e + 1])
        t1 = thist[e, 0]
        t2 = thist[e, 1]
        ts = t + 0.5 * (period - 1) + w_deep
        if t1 != key1 or t2 != key2 or ts != key_ts:
            key1 = t1
            key2 = t2
            key_ts = ts
            x = ts - t
            if t1 < 0 or t1 >= t:
                c1 = 0.0
                c2 = 0.0
            elif t2 < 0 or t2 >= t1:
                c1 = x / (t - t1)
                c2 = 0.0
            else:
                y = x * (ts - t1) / (t - t2)
                c1 = x / (t - t1) + y / (t - t1)
                c2 = y / (t1 - t2)
        P1 = hist[e, 0]
        E = modulus(P + c1 * (P - P1) - c2 * (P1 - hist[e, 1]), kp, ke, floor, slope)
        if t1 != t:
            hist[e, 1] = P1
            thist[e, 1] = t1
            thist[e, 0] = t
        hist[e, 0] = P
        p, q = element_pq(Et / E, dlog[e], invd[e])
        a = q / (p + b)
        b = p - q * a
        alpha[e] = a
        beta[e] = b
    for e in range(B[0], top):
        _push(-0.5 * (F[e] * invr[e] + F[e + 1] * invr[e + 1]), t, e, hist, thist)


@njit(cache=True, inline="always")
def _increment(
    n_inc, J, dsub, nsub, r, invr, dlog, invd, F, st, alpha, beta, dF, dFold, kp, ke, slope, Et,
    c, floor, w, iterate, rtol, maxit, S, state_i,
):  # fmt: skip
    """One increment: the load ``dsub`` at node ``n_inc`` applied in ``nsub`` substeps on the
    window ``J..n_inc`` (warm start, fixed-point iteration of E_r, then the update of F,
    sigma_theta and the pending increment ``S[1]`` of the first frozen level). Returns
    False when the iteration did not converge in ``maxit`` iterations."""
    for _sub in range(nsub):
        # warm start: the previous increment's shape at the same depth below the
        # load, scaled to this one (midpoint/end rules; docs/winding.md)
        warm = iterate and w != 0.0 and state_i[5] >= 0
        if warm:
            n_prev = state_i[5]
            shift = n_inc - n_prev
            lo_g = state_i[6] + shift
            if lo_g < J:
                lo_g = J
            scale = dsub / dF[n_prev]
            for e in range(n_inc, J - 1, -1):  # top down: reads below, shift >= 0
                dF[e] = dF[e - shift] * scale if e >= lo_g else 0.0
        err_prev = 0.0
        for it in range(maxit + 1):
            state_i[3] += n_inc - J
            _sweep(
                J,
                n_inc,
                beta[J - 1] if J > 0 else c,
                invr,
                dlog,
                invd,
                F,
                dF,
                w if (it > 0 or warm) else 0.0,
                kp,
                ke,
                slope,
                Et,
                floor,
                alpha,
                beta,
            )
            dF[n_inc] = dsub
            for e in range(n_inc - 1, J - 1, -1):
                dF[e] = alpha[e] * dF[e + 1]
            if not iterate:
                break
            if it > 0:
                err = 0.0
                for e in range(J, n_inc):
                    d = abs(dF[e] - dFold[e])
                    if d > err:
                        err = d
                # converged: the change, or the contraction's a-posteriori bound
                # on the remaining error, err * rho / (1 - rho) with
                # rho = err / err_prev (docs/winding.md), is within rtol
                tol = rtol * abs(dsub)
                if err <= tol or (
                    it > 1 and err <= 0.5 * err_prev and err * err <= tol * (err_prev - err)
                ):
                    if it > state_i[2]:
                        state_i[2] = it
                    break
                if it == maxit:
                    return False
                err_prev = err
            for e in range(J, n_inc):
                dFold[e] = dF[e]
        state_i[5] = n_inc
        state_i[6] = J
        for i in range(J, n_inc):
            F[i] += dF[i]
            bl = beta[i - 1] if i > 0 else c
            st[i] += bl * dF[i] / r[i]
        if J > 0:
            S[1] += dF[J]
        F[n_inc] += dsub
    return True


@njit(cache=True)
def run_groups(
    g0, g1, gnode, r, invr, dlog, invd, F, st, Fself, stself, alpha, beta, hist, thist, dF,
    dFold, kp, ke, Et, c, floor, w, iterate, w_deep, rtol, maxit, wnodes, flush_every, nsub,
    body, B, S, state_i,
):  # fmt: skip
    """Wind groups g0..g1-1 (one increment each). Returns -1, or the group that failed.

    ``state_i = [increments since the last refresh, refreshes so far, max iterations used,
    element evaluations in the window, in refreshes, top node and lowest window node of the
    last iterated increment (-1: none; the warm start's shape)]``
    and the level boundaries ``B`` and pending increments ``S`` carry the lazy deep part
    between calls (:func:`_refresh`). ``wnodes < 0``: no lazy part (the window reaches the
    core). ``body``: the new group is part of the elastic body and its load acts on its
    outer face (node ``top``) instead of its inner face (node ``m``, the default).
    """
    slope = last_slope(kp, ke)
    count = state_i[0]
    k = state_i[1]
    for g in range(g0, g1):
        m = gnode[g]
        top = gnode[g + 1]
        dtop = Fself[m]
        n_inc = top if body else m
        if n_inc > 0 and dtop != 0.0:
            J = B[0]
            if J > m:
                J = m
            if not _increment(
                n_inc, J, dtop / nsub, nsub, r, invr, dlog, invd, F, st, alpha, beta, dF, dFold,
                kp, ke, slope, Et, c, floor, w, iterate, rtol, maxit, S, state_i,
            ):  # fmt: skip
                state_i[0] = count
                state_i[1] = k
                return g
        # the new group's own state (for g = 0 its pressure acts on the core alone)
        if body:
            for i in range(m, top + 1):
                st[i] = stself[i]
        else:
            for i in range(m, top + 1):
                F[i] = Fself[i]
                st[i] = stself[i]
        for e in range(m, top):
            hist[e, 0] = -0.5 * (F[e] * invr[e] + F[e + 1] * invr[e + 1])
            thist[e, 0] = g
            thist[e, 1] = -1
        count += 1
        if wnodes >= 0 and count >= flush_every:
            k += 1
            _refresh(
                g, k, top, wnodes, flush_every, B, S, r, invr, dlog, invd, F, st,
                hist, thist, w_deep, kp, ke, slope, Et, floor, alpha, beta, c,
                state_i,
            )  # fmt: skip
            count = 0
    state_i[0] = count
    state_i[1] = k
    return -1
