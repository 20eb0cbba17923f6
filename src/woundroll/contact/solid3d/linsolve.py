"""Sparse symmetric positive definite solvers for the 3D contact model, behind one interface.

``make_solver(name, pattern_upper)`` returns an object with ``factor(values)`` (numeric
factorisation of a matrix with the fixed upper-triangle CSR pattern ``pattern_upper``) and
``solve(b)``. The symbolic analysis (ordering, elimination tree) is done once per pattern and
reused for every load step and contact iteration.

* ``"pardiso"``: Intel MKL PARDISO through :mod:`pypardiso` (real SPD, phase 11 once, then
  phase 22 numeric factorisation and phase 33 solves). The default: fastest measured
  (docs/contact.md, 3D section).
* ``"splu"``: SciPy's SuperLU on the full matrix (no symbolic reuse in SciPy's interface);
  always available.
* ``"amg"``: conjugate gradients preconditioned by a smoothed-aggregation AMG hierarchy
  (:mod:`pyamg`) built once per ``factor`` call; kept for the measurement.
"""

from __future__ import annotations

import functools
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from woundroll.contact.solid3d.options import SOLVERS
from woundroll.errors import ConvergenceError, InputError

FloatArray = NDArray[np.float64]


def _full(upper: sp.csr_matrix) -> sp.csr_matrix:
    d = sp.diags(upper.diagonal())
    return (upper + upper.T - d).tocsr()


@functools.cache
def _mkl_rt() -> str | None:
    """The MKL runtime library the ``mkl`` wheel put under ``sys.prefix/lib``, for
    pypardiso's ``PYPARDISO_MKL_RT``: without it every ``PyPardisoSolver()`` runs
    ``ctypes.util.find_library`` and then globs the whole environment recursively (0.4-0.8 s
    a solver, measured on this project's venv; pypardiso builds one solver when imported).
    None: let pypardiso search."""
    for pattern in ("libmkl_rt.so*", "libmkl_rt*.dylib", "mkl_rt*.dll"):
        for base in (Path(sys.prefix) / "lib", Path(sys.prefix) / "Library" / "bin"):
            found = sorted(base.glob(pattern), key=lambda p: len(p.name))
            if found:
                return str(found[0])
    return None


def _pypardiso() -> Any:
    """pypardiso, imported with :func:`_mkl_rt`'s path in ``PYPARDISO_MKL_RT`` (unless the
    user set one)."""
    if "PYPARDISO_MKL_RT" not in os.environ and (path := _mkl_rt()) is not None:
        os.environ["PYPARDISO_MKL_RT"] = path
    import pypardiso

    return pypardiso


class _Pardiso:
    def __init__(self, pattern: sp.csr_matrix) -> None:
        PyPardisoSolver = _pypardiso().PyPardisoSolver

        self.A = pattern.copy().astype(np.float64)
        self.A.sort_indices()
        self.ps = PyPardisoSolver(mtype=2)
        self.ps.set_statistical_info_off()
        # Our own settings instead of PARDISO's defaults (iparm[0] = 0 lets PARDISO choose
        # them, and it chose two steps of iterative refinement per solve, tripling every
        # solve's cost): nested-dissection ordering (METIS), no refinement. K is symmetric
        # positive definite, so the factorisation has no perturbed pivots to refine after;
        # the solves' relative residual is ~1e-12 either way (docs/history.md, 2026-11-26).
        iparm = self.ps.iparm
        iparm[:] = 0
        iparm[0] = 1  # the settings below, not the defaults
        iparm[1] = 2  # METIS nested dissection
        iparm[7] = 0  # no iterative refinement (SPD: nothing to refine)
        iparm[9] = 13  # pivot perturbation 1e-13 (unused for SPD; PARDISO's value)
        iparm[34] = 0  # one-based indices (pypardiso passes them so)
        self._analysed = False

    def factor(self, values: FloatArray) -> None:
        self.A.data[:] = values
        b = np.zeros((self.A.shape[0], 1))
        if not self._analysed:
            self.ps.set_phase(11)
            self.ps._check_A(self.A)
            self.ps._call_pardiso(self.A, b)
            self._analysed = True
        self.ps.set_phase(22)
        self.ps._call_pardiso(self.A, b)

    def solve(self, b: FloatArray) -> FloatArray:
        self.ps.set_phase(33)
        b2 = np.asfortranarray(b.reshape(b.shape[0], -1), dtype=np.float64)
        x = self.ps._call_pardiso(self.A, b2)
        return x.reshape(b.shape)

    def __del__(self) -> None:
        try:
            self.ps.free_memory(everything=True)
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass


class _SuperLU:
    def __init__(self, pattern: sp.csr_matrix) -> None:
        self.A = pattern.copy().astype(np.float64)
        self.lu: Any = None

    def factor(self, values: FloatArray) -> None:
        self.A.data[:] = values
        try:
            self.lu = spla.splu(
                _full(self.A).tocsc(),
                permc_spec="MMD_AT_PLUS_A",  # symmetric ordering, no pivoting: SPD
                diag_pivot_thresh=0.0,
                options={"SymmetricMode": True},
            )
        except RuntimeError as exc:
            raise ConvergenceError(f"stiffness matrix is singular ({exc})") from None

    def solve(self, b: FloatArray) -> FloatArray:
        return self.lu.solve(b)


class _AMG:
    def __init__(self, pattern: sp.csr_matrix, tol: float = 1e-10) -> None:
        self.A = pattern.copy().astype(np.float64)
        self.tol = tol
        self.iterations: list[int] = []

    def factor(self, values: FloatArray) -> None:
        import pyamg

        self.A.data[:] = values
        self.K = _full(self.A)
        self.ml = pyamg.smoothed_aggregation_solver(self.K, max_coarse=2000)
        self.M = self.ml.aspreconditioner(cycle="V")

    def solve(self, b: FloatArray) -> FloatArray:
        cols = b.reshape(b.shape[0], -1)
        out = np.empty_like(cols)
        n_it = [0]

        def count(_: Any) -> None:
            n_it[0] += 1

        for c in range(cols.shape[1]):
            n_it[0] = 0
            x, info = spla.cg(
                self.K, cols[:, c], rtol=self.tol, maxiter=2000, M=self.M, callback=count
            )
            if info != 0:
                raise ConvergenceError(f"AMG-preconditioned CG did not converge ({info})")
            self.iterations.append(n_it[0])
            out[:, c] = x
        return out.reshape(b.shape)


def pardiso_available() -> bool:
    try:
        _pypardiso()
    except Exception:  # noqa: BLE001 - any import failure means "not usable"
        return False
    return True


def make_solver(name: str, pattern_upper: sp.csr_matrix) -> Any:
    """A solver for matrices with the upper-triangle CSR pattern ``pattern_upper``."""
    if name not in SOLVERS:
        raise InputError(f"must be one of {', '.join(SOLVERS)}, got {name!r}", "options.solver")
    if name == "auto":
        name = "pardiso" if pardiso_available() else "splu"
    if name == "pardiso":
        return _Pardiso(pattern_upper)
    if name == "splu":
        return _SuperLU(pattern_upper)
    return _AMG(pattern_upper)
