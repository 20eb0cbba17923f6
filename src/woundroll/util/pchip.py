"""Monotone piecewise-cubic Hermite interpolation (PCHIP, Fritsch and Carlson), NumPy only.

The same slopes as SciPy's ``PchipInterpolator`` (weighted harmonic mean of the adjacent
secants inside, the shape-preserving three-point formula at the ends), so the curves agree
to round-off (tested); kept here because the contact spring's fit samples F(d) on every run
and importing ``scipy.interpolate`` costs a one-roll run 0.1 s of its ~1 s.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]


def _edge_slope(h0: float, h1: float, m0: float, m1: float) -> float:
    d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    if np.sign(d) != np.sign(m0):
        return 0.0
    if np.sign(m0) != np.sign(m1) and abs(d) > 3.0 * abs(m0):
        return 3.0 * m0
    return float(d)


def pchip(x: ArrayLike, y: ArrayLike) -> Callable[[ArrayLike], FloatArray]:
    """The PCHIP interpolant through (x, y), x strictly increasing (>= 2 points); outside
    [x0, xn] it extends the end cubics, as SciPy does."""
    xs = np.asarray(x, dtype=float)
    ys = np.asarray(y, dtype=float)
    if xs.ndim != 1 or xs.shape != ys.shape or xs.size < 2 or np.any(np.diff(xs) <= 0):
        raise ValueError("pchip needs >= 2 points with strictly increasing x")
    h = np.diff(xs)
    m = np.diff(ys) / h
    dk = np.empty_like(ys)
    if xs.size == 2:
        dk[:] = m[0]
    else:
        flat = (np.sign(m[1:]) != np.sign(m[:-1])) | (m[1:] == 0) | (m[:-1] == 0)
        w1 = 2.0 * h[1:] + h[:-1]
        w2 = h[1:] + 2.0 * h[:-1]
        with np.errstate(divide="ignore", invalid="ignore"):
            inner = (w1 + w2) / (w1 / m[:-1] + w2 / m[1:])
        dk[1:-1] = np.where(flat, 0.0, inner)
        dk[0] = _edge_slope(h[0], h[1], m[0], m[1])
        dk[-1] = _edge_slope(h[-1], h[-2], m[-1], m[-2])

    def evaluate(t: ArrayLike) -> FloatArray:
        tt = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(xs, tt, side="right") - 1, 0, xs.size - 2)
        hk = h[k]
        s = (tt - xs[k]) / hk
        s2, s3 = s * s, s * s * s
        return (
            (2 * s3 - 3 * s2 + 1) * ys[k]
            + (s3 - 2 * s2 + s) * hk * dk[k]
            + (-2 * s3 + 3 * s2) * ys[k + 1]
            + (s3 - s2) * hk * dk[k + 1]
        )

    return evaluate
