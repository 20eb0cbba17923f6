"""NumPy twin of the compiled winding kernels (:mod:`woundroll.winding._kernels`).

Same algorithm, same arguments and state, same order of operations per element (results
agree with the compiled kernels to rounding, ~1e-12): the element coefficients, the
predicted moduli and the flushes of the deep levels are vectorised; the Riccati recursion
(a serial division chain) runs as a Python loop over floats.

Why it exists: numba's import and cache load cost 0.5-2 s per process (measured in
``docs/winding.md``), while a roll of a few thousand layers takes a few milliseconds
compiled and ~0.1-0.5 s here. :func:`woundroll.winding.hakiel.wind` uses this module for
rolls up to ``_NUMPY_MAX_NODES`` nodes and imports numba only above that.
"""

from __future__ import annotations

import numpy as np


def _moduli(P: np.ndarray, kp: np.ndarray, ke: np.ndarray, floor: float, slope: float):
    """Vectorised :func:`woundroll.winding._kernels.modulus`."""
    if kp.shape[0] == 2:
        E = ke[0] + slope * (np.maximum(P, kp[0]) - kp[0])
    else:
        E = np.interp(P, kp, ke)
        beyond = P >= kp[-1]
        if beyond.any():
            E = np.where(beyond, ke[-1] + slope * (P - kp[-1]), E)
    return np.maximum(E, floor)


# Horner coefficients of the k d < 0.1 series of p d and q d (rows), highest power first
_SERIES = np.array(
    [[2.0 / 945.0, -1.0 / 45.0, 1.0 / 3.0], [-31.0 / 15120.0, 7.0 / 360.0, -1.0 / 6.0]]
)


def _pq(g: np.ndarray, d: np.ndarray, inv_d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised :func:`woundroll.winding._kernels.element_pq` (series for k d < 0.1).

    The series of p and q are evaluated together (one (2, n) Horner chain, the same
    operations per element as two separate ones: equal bit for bit, half the NumPy calls).
    """
    x2 = g * d * d
    big = x2 >= 0.01
    n_big = np.count_nonzero(big)
    if n_big < big.shape[0]:
        s = _SERIES[:, 0:1] * x2
        s += _SERIES[:, 1:2]
        s *= x2
        s += _SERIES[:, 2:3]
        s *= x2
        s += 1.0
        s *= inv_d
        p = s[0]
        q = s[1]
        if n_big == 0:
            return p, q
        g = g[big]
        d = d[big]
    k = np.sqrt(g)
    em = np.exp(-k * d)
    e2 = em * em
    den = 1.0 - e2
    pb = k * (1.0 + e2) / den
    qb = 2.0 * k * em / den
    if n_big == big.shape[0]:
        return pb, qb
    p[big] = pb
    q[big] = qb
    return p, q


def _riccati(p: np.ndarray, q: np.ndarray, b: float, alpha, beta, e0: int) -> None:
    """``alpha_e = q/(p + beta_{e-1})``, ``beta_e = p - q alpha_e`` from ``beta_{e0-1} = b``."""
    al: list[float] = []
    bl: list[float] = []
    put_a = al.append
    put_b = bl.append
    for pp, qq in zip(p.tolist(), q.tolist(), strict=True):
        a = qq / (pp + b)
        b = pp - qq * a
        put_a(a)
        put_b(b)
    alpha[e0 : e0 + len(al)] = al
    beta[e0 : e0 + len(bl)] = bl


def _below(beta: np.ndarray, c: float, lo: int, hi: int) -> np.ndarray:
    """``beta[i - 1]`` for nodes lo..hi-1 (``c``, the core condition, for node 0)."""
    out = np.empty(hi - lo)
    out[0] = beta[lo - 1] if lo > 0 else c
    out[1:] = beta[lo : hi - 1]
    return out


def _flush_band(hi, lo, S, r, F, st, alpha, beta, c) -> float:
    """Vectorised :func:`woundroll.winding._kernels._flush_band`."""
    if hi <= lo:
        return S
    d = np.cumprod(alpha[lo:hi][::-1])[::-1] * S
    F[lo:hi] += d
    st[lo:hi] += _below(beta, c, lo, hi) * d / r[lo:hi]
    return float(d[0])


def flush_all(nlev, B, S, r, F, st, alpha, beta, c) -> None:
    """Apply every level's pending increment, top down (end of the roll)."""
    for lev in range(1, nlev):
        if B[lev - 1] <= 0:
            break
        d = _flush_band(int(B[lev - 1]), int(B[lev]), S[lev], r, F, st, alpha, beta, c)
        S[lev] = 0.0
        if B[lev] > 0:
            S[lev + 1] += d


def _push(P, t, e0, e1, hist, thist) -> None:
    """Record the pressures P of elements e0..e1-1 at time t (last two distinct times)."""
    h = hist[e0:e1]
    th = thist[e0:e1]
    new = th[:, 0] != t
    np.copyto(h[:, 1], h[:, 0], where=new)
    np.copyto(th[:, 1], th[:, 0], where=new)
    th[:, 0] = t
    h[:, 0] = P


def _refresh(
    t, k, top, wnodes, flush_every, B, S, r, invr, dlog, invd, F, st, hist, thist, w_deep,
    kp, ke, slope, Et, floor, alpha, beta, c, state_i,
):  # fmt: skip
    """Vectorised :func:`woundroll.winding._kernels._refresh` (see there)."""
    nlev = B.shape[0] - 1
    L = 1
    kk = k
    while kk % 2 == 0 and L < nlev - 1:
        kk //= 2
        L += 1
    for lev in range(1, L + 1):
        hi = int(B[lev - 1])
        lo = int(B[lev])
        d = _flush_band(hi, lo, S[lev], r, F, st, alpha, beta, c)
        S[lev] = 0.0
        if lo > 0:
            S[lev + 1] += d
    lo = int(B[L])
    span = wnodes
    for lev in range(L):
        B[lev] = max(top - span, lo)
        if span < top:
            span *= 2
    b0 = int(B[0])
    state_i[4] += b0 - lo
    if b0 > lo:
        period = np.empty(b0 - lo)
        for lev in range(L, 0, -1):
            period[max(int(B[lev]), lo) - lo : int(B[lev - 1]) - lo] = flush_every * (
                1 << (lev - 1)
            )
        Fs = F[lo : b0 + 1] * invr[lo : b0 + 1]
        P = -0.5 * (Fs[:-1] + Fs[1:])
        t1 = thist[lo:b0, 0].astype(float)
        t2 = thist[lo:b0, 1].astype(float)
        P1 = hist[lo:b0, 0].copy()
        P2 = hist[lo:b0, 1]
        ts = t + 0.5 * (period - 1) + w_deep
        x = ts - t
        none = (t1 < 0) | (t1 >= t)
        one = ~none & ((t2 < 0) | (t2 >= t1))
        if not (none.any() or one.any()):  # the usual case: two past refreshes everywhere
            y = x * (ts - t1) / (t - t2)
            c1 = x / (t - t1) + y / (t - t1)
            c2 = y / (t1 - t2)
        else:
            two = ~none & ~one
            c1 = np.zeros_like(P)
            c2 = np.zeros_like(P)
            c1[one] = x[one] / (t - t1[one])
            if two.any():
                y = x[two] * (ts[two] - t1[two]) / (t - t2[two])
                c1[two] = x[two] / (t - t1[two]) + y / (t - t1[two])
                c2[two] = y / (t1[two] - t2[two])
        E = _moduli(P + c1 * (P - P1) - c2 * (P1 - P2), kp, ke, floor, slope)
        _push(P, t, lo, b0, hist, thist)
        p, q = _pq(Et / E, dlog[lo:b0], invd[lo:b0])
        _riccati(p, q, beta[lo - 1] if lo > 0 else c, alpha, beta, lo)
    if top > b0:
        Fs = F[b0 : top + 1] * invr[b0 : top + 1]
        _push(-0.5 * (Fs[:-1] + Fs[1:]), t, b0, top, hist, thist)


def _increment(
    n, J, dsub, nsub, r, invr, dlog, invd, F, st, alpha, beta, dF, kp, ke, slope, Et, c, floor,
    w, iterate, rtol, maxit, S, state_i,
):  # fmt: skip
    """NumPy version of :func:`woundroll.winding._kernels._increment` (same contract)."""
    b = beta[J - 1] if J > 0 else c
    for _sub in range(nsub):
        Fs = F[J : n + 1] * invr[J : n + 1]
        P0 = -0.5 * (Fs[:-1] + Fs[1:])
        d_old = None
        # warm start: the previous increment's shape at the same depth below the
        # load, scaled to this one (as the compiled kernel)
        warm = iterate and w != 0.0 and state_i[5] >= 0
        if warm:
            n_prev = int(state_i[5])
            shift = n - n_prev
            lo_g = max(J, int(state_i[6]) + shift)
            guess = np.zeros(n + 1 - J)
            if lo_g <= n:
                guess[lo_g - J :] = dF[lo_g - shift : n_prev + 1] * (dsub / dF[n_prev])
            dF[J : n + 1] = guess
        err_prev = 0.0
        for it in range(maxit + 1):
            state_i[3] += n - J
            if (it > 0 or warm) and w != 0.0:
                ds = dF[J : n + 1] * invr[J : n + 1]
                P = P0 - w * 0.5 * (ds[:-1] + ds[1:])
            else:
                P = P0
            p, q = _pq(Et / _moduli(P, kp, ke, floor, slope), dlog[J:n], invd[J:n])
            _riccati(p, q, b, alpha, beta, J)
            dF[n] = dsub
            dF[J:n] = np.cumprod(alpha[J:n][::-1])[::-1] * dsub
            if not iterate:
                break
            if d_old is not None:
                err = float(np.max(np.abs(dF[J:n] - d_old)))
                tol = rtol * abs(dsub)  # change, or the contraction's bound on it
                if err <= tol or (
                    it > 1 and err <= 0.5 * err_prev and err * err <= tol * (err_prev - err)
                ):
                    state_i[2] = max(int(state_i[2]), it)
                    break
                if it == maxit:
                    return False
                err_prev = err
            d_old = dF[J:n].copy()
        state_i[5] = n
        state_i[6] = J
        F[J:n] += dF[J:n]
        st[J:n] += _below(beta, c, J, n) * dF[J:n] / r[J:n]
        if J > 0:
            S[1] += dF[J]
        F[n] += dsub
    return True


def run_groups(
    g0, g1, gnode, r, invr, dlog, invd, F, st, Fself, stself, alpha, beta, hist, thist, dF,
    dFold, kp, ke, Et, c, floor, w, iterate, w_deep, rtol, maxit, wnodes, flush_every, nsub,
    body, B, S, state_i,
):  # fmt: skip
    """NumPy version of :func:`woundroll.winding._kernels.run_groups` (same contract)."""
    slope = (ke[-1] - ke[-2]) / (kp[-1] - kp[-2])
    count = int(state_i[0])
    k = int(state_i[1])
    for g in range(g0, g1):
        m = int(gnode[g])
        top = int(gnode[g + 1])
        dtop = float(Fself[m])
        n = top if body else m
        if n > 0 and dtop != 0.0:
            J = min(int(B[0]), m)
            if not _increment(
                n, J, dtop / nsub, nsub, r, invr, dlog, invd, F, st, alpha, beta, dF, kp, ke,
                slope, Et, c, floor, w, iterate, rtol, maxit, S, state_i,
            ):  # fmt: skip
                state_i[0] = count
                state_i[1] = k
                return g
        if not body:
            F[m : top + 1] = Fself[m : top + 1]
        st[m : top + 1] = stself[m : top + 1]
        Fs = F[m : top + 1] * invr[m : top + 1]
        hist[m:top, 0] = -0.5 * (Fs[:-1] + Fs[1:])
        thist[m:top, 0] = g
        thist[m:top, 1] = -1
        count += 1
        if wnodes >= 0 and count >= flush_every:
            k += 1
            _refresh(
                g, k, top, wnodes, flush_every, B, S, r, invr, dlog, invd, F, st, hist, thist,
                w_deep, kp, ke, slope, Et, floor, alpha, beta, c, state_i,
            )  # fmt: skip
            count = 0
    state_i[0] = count
    state_i[1] = k
    return -1
