"""Anderson acceleration of a fixed-point iteration ``z -> F(z)`` (type II).

The next iterate mixes the last ``m`` images with the weights that minimise the mixed
residual ``F(z) - z`` in the least-squares sense (for a linear map, the iterates of GMRES);
the memory is cleared when the residual grows tenfold over the best one seen (a safeguard for
maps that are only piecewise linear, such as a contact set that changes) or when the caller
says the map itself changed (:meth:`Anderson.reset`). ``m = 0`` is the plain iteration.
Used by the layered 3D roll's interface passes and the 3D dynamic impact's modified-Newton
passes.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


class Anderson:
    """Anderson mixing with memory ``m`` (module docstring)."""

    def __init__(self, m: int) -> None:
        self.m = m
        self.F: list[FloatArray] = []
        self.R: list[FloatArray] = []
        self.best = math.inf

    def reset(self) -> None:
        """Forget the history (the map changed, e.g. a new preconditioner)."""
        self.F, self.R = [], []
        self.best = math.inf

    def step(self, z: FloatArray, fz: FloatArray) -> FloatArray:
        """The next iterate after ``z`` whose image is ``fz``."""
        if self.m == 0:
            return fz
        r = fz - z
        nr = float(np.linalg.norm(r))
        if nr > 10.0 * self.best:
            self.F, self.R = [], []
        self.best = min(self.best, nr)
        self.F.append(fz)
        self.R.append(r)
        if len(self.F) > self.m + 1:
            self.F.pop(0)
            self.R.pop(0)
        if len(self.F) == 1:
            return fz
        dR = np.stack([self.R[i + 1] - self.R[i] for i in range(len(self.R) - 1)], axis=1)
        dF = np.stack([self.F[i + 1] - self.F[i] for i in range(len(self.F) - 1)], axis=1)
        gamma, *_ = np.linalg.lstsq(dR, r, rcond=None)
        return fz - dF @ gamma
