"""Sparse symmetric positive definite solvers for the 3D contact model, behind one interface.

``make_solver(name, pattern_upper)`` returns an object with ``factor(values)`` (numeric
factorisation of a matrix with the fixed upper-triangle CSR pattern ``pattern_upper``) and
``solve(b)``. The symbolic analysis (ordering, elimination tree) is done once per pattern and
reused for every load step and contact iteration.

* ``"pardiso"``: Intel MKL PARDISO, the library :mod:`pypardiso` loads, called directly with
  index arrays converted once (real SPD, phase 11 once, then phase 22 numeric factorisation
  and phase 33 solves); optionally in single precision. Fastest measured (docs/contact.md,
  3D section).
* ``"pardiso-mixed"``: PARDISO factorising in single precision, each solve refined in double
  against the matrix itself until its relative residual is below :data:`MIXED_RTOL` (one
  step as a rule). The numeric factorisation, most of a 3D reading's time, takes 0.6 of the
  time, a solve with its step 1.7 times; what ``"auto"`` (the default) picks when PARDISO
  is installed (docs/contact.md, "The solver's precision").
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


def upper_times(U: sp.spmatrix, Ut: sp.spmatrix, d: FloatArray, x: FloatArray) -> FloatArray:
    """``K x`` for the symmetric K stored as its upper triangle ``U`` (``Ut`` its transpose,
    ``d`` its diagonal): ``U x + U^T x - diag(U) x``; ``x`` one vector or columns."""
    return U @ x + Ut @ x - (d if x.ndim == 1 else d[:, None]) * x


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


class _Solver:
    """What every solver offers beside ``factor`` and ``solve``: :meth:`flexibility` by
    whole solves (PARDISO does partial ones)."""

    def solve(self, b: FloatArray) -> FloatArray:
        raise NotImplementedError

    def mark(self, dofs: NDArray[np.int64]) -> bool:
        """Unknowns :meth:`flexibility` will be asked for; True if that is then a partial
        solve (PARDISO), False if it would take whole solves (the others)."""
        return False

    def flexibility(self, dofs: NDArray[np.int64]) -> FloatArray:
        """The block ``K^-1[dofs, dofs]``."""
        dofs = np.asarray(dofs, dtype=np.int64)
        return np.asarray(self.solve(_unit_loads(self.n, dofs, np.float64))[dofs])


def _unit_loads(n: int, dofs: NDArray[np.int64], dtype: Any) -> FloatArray:
    """Columns (n, len(dofs)), Fortran order, of unit loads at ``dofs``."""
    B = np.zeros((n, dofs.size), dtype=dtype, order="F")
    B[dofs, np.arange(dofs.size)] = 1.0
    return B


class _Pardiso(_Solver):
    """MKL PARDISO for a real SPD matrix of a fixed pattern, called directly through the
    library pypardiso loaded (its handle ``pt`` and ``iparm``): the 1-based int32 index
    arrays are made once, not on every call as ``PyPardisoSolver._call_pardiso`` does
    (~0.3 ms a call on 18,792 DOF). ``single``: factorise and solve in single precision
    (``iparm[27] = 1``; half the factor's memory traffic, relative residual ~1e-6): only
    for iterations whose residual is computed exactly (the 3D dynamic impact's passes)."""

    def __init__(self, pattern: sp.csr_matrix, single: bool = False) -> None:
        self.ps = _pypardiso().PyPardisoSolver(mtype=2)
        self.ps.set_statistical_info_off()
        self.A = pattern.copy().astype(np.float64)
        self.A.sort_indices()
        self.single = single
        self.dtype = np.float32 if single else np.float64
        self.n = self.A.shape[0]
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
        iparm[27] = 1 if single else 0  # precision of the arrays and the factor
        iparm[34] = 0  # one-based indices
        self.ia = self.A.indptr.astype(np.int32) + 1
        self.ja = self.A.indices.astype(np.int32) + 1
        self.a = self.A.data.astype(self.dtype)
        self._analysed = False
        self.ps.perm = np.zeros(self.n, dtype=np.int32)
        #: the unknowns of :meth:`flexibility`'s partial solves (:meth:`mark`), or None
        self.marked: NDArray[np.int64] | None = None
        self._marked_mask = np.zeros(self.n, dtype=bool)

    def _call(self, phase: int, b: FloatArray) -> FloatArray:
        """One PARDISO call (``b``: Fortran-ordered, of ``self.dtype``); returns x."""
        import ctypes

        ps = self.ps
        x = np.zeros_like(b)
        err = ctypes.c_int32(0)
        i32 = ctypes.POINTER(ctypes.c_int32)
        f64 = ctypes.POINTER(ctypes.c_double)  # the prototype's type; single: float data

        def ref(v: int) -> Any:
            return ctypes.byref(ctypes.c_int32(v))

        ps._mkl_pardiso(
            ps.pt.ctypes.data_as(ctypes.POINTER(ps._pt_type[0])),
            ref(1),  # maxfct
            ref(1),  # mnum
            ref(2),  # mtype: real SPD
            ref(phase),
            ref(self.n),
            ctypes.cast(self.a.ctypes.data, f64),
            self.ia.ctypes.data_as(i32),
            self.ja.ctypes.data_as(i32),
            ps.perm.ctypes.data_as(i32),
            ref(b.shape[1]),  # nrhs
            ps.iparm.ctypes.data_as(i32),
            ref(0),  # msglvl
            ctypes.cast(b.ctypes.data, f64),
            ctypes.cast(x.ctypes.data, f64),
            ctypes.byref(err),
        )
        if err.value != 0:
            raise ConvergenceError(f"PARDISO failed with error {err.value} (phase {phase})")
        return x

    def mark(self, dofs: NDArray[np.int64]) -> bool:
        """Order the unknowns ``dofs`` last in the factorisation (before the first
        :meth:`factor`), so that :meth:`flexibility` among them is a partial solve: PARDISO's
        sparse right-hand sides and selected solution components (``iparm[30] = 1``), which
        touch only the factor's last block (0.7 ms for 52 columns against 54 ms for a
        whole solve on PET2 53.4 N's 17,860 unknowns; the factorisation with 60 / 180 /
        300 such unknowns last takes 1.01 / 1.07 / 1.10 times as long on PET1 26.7 N's)."""
        if self._analysed:
            raise RuntimeError("mark() comes before the first factor()")
        self.marked = np.unique(np.asarray(dofs, dtype=np.int64))
        self._marked_mask[:] = False
        self._marked_mask[self.marked] = True
        return True

    def _markers(self) -> None:
        perm = self.ps.perm
        perm[:] = 0
        perm[self._marked_mask] = 1

    def factor(self, values: FloatArray) -> None:
        self.a[:] = values
        b = np.zeros((self.n, 1), dtype=self.dtype, order="F")
        if not self._analysed:
            self.A.data[:] = values
            self.ps._check_A(self.A)  # square, sorted, no empty rows, CSR
            if self.marked is not None:
                self._markers()
                self.ps.iparm[30] = 1  # the marked unknowns last in the ordering
            try:
                self._call(11, b)
            finally:
                self.ps.iparm[30] = 0
            self._markers()  # phase 11 wrote its permutation there
            self._analysed = True
        self._call(22, b)

    def flexibility(self, dofs: NDArray[np.int64]) -> FloatArray:
        """The block ``K^-1[dofs, dofs]`` (columns: the responses at ``dofs`` to unit loads
        at ``dofs``), by a partial solve where every one of ``dofs`` is marked
        (:meth:`mark`), else by whole solves (in the factorisation's own precision: for
        an iteration whose residual is computed exactly)."""
        dofs = np.asarray(dofs, dtype=np.int64)
        B = _unit_loads(self.n, dofs, self.dtype)
        if self.marked is not None and np.all(self._marked_mask[dofs]):
            self.ps.iparm[30] = 1
            try:
                X = self._call(33, B)
            finally:
                self.ps.iparm[30] = 0
        else:
            X = self._call(33, B)
        return np.asarray(X[dofs], dtype=np.float64)

    def solve(self, b: FloatArray) -> FloatArray:
        b2 = np.asfortranarray(b.reshape(b.shape[0], -1), dtype=self.dtype)
        x = self._call(33, b2)
        return np.ascontiguousarray(x, dtype=np.float64).reshape(b.shape)

    def __del__(self) -> None:
        try:
            self.ps.free_memory(everything=True)
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass


#: Relative residual ``|b - K x| / |b|`` every solve of ``"pardiso-mixed"`` reaches (the
#: double-precision factorisation's is ~1e-12). A single-precision solve of the 3D stiffness
#: leaves ~5e-4 and a refinement step gains about three orders (PET1 26.7 N's last
#: increment: 5.4e-4, 7.6e-7, 1.5e-9; over a whole reading one step leaves at most 1.6e-5):
#: one step a solve as a rule. The 3D reading of PET1 26.7 N moves by 2e-7 of itself (1e-7
#: at 1e-5, which takes 1.4 steps a solve and a third of the time saved; docs/contact.md,
#: "The solver's precision").
MIXED_RTOL = 3e-5
#: Refinement steps after which a solve that has not reached :data:`MIXED_RTOL` is redone
#: with a double-precision factorisation (an ill-conditioned matrix).
MIXED_MAX_STEPS = 4


class _PardisoMixed(_Pardiso):
    """PARDISO factorising in single precision, each solve refined in double precision
    against the matrix (its upper triangle, kept in double) until the relative residual is
    below :data:`MIXED_RTOL`; a matrix whose single-precision factorisation fails or on which
    the refinement stalls is factorised again in double precision, and so is every later
    matrix of this solver (counted in ``double_fallbacks`` and ``double_factorisations``).

    Sticky, because the matrices of one loading share their conditioning (the elements at
    the modulus floor stay there): on a slack sector of Table 3 (pet3-2.3MPa, sector 30) 29
    of 31 factorisations fell back, each after a single-precision factorisation and a
    stalled refinement, and each in a new double-precision solver with its own analysis
    (24.8 CPU s the sector); one fallback and the double-precision solver kept: see
    docs/history.md, 2026-12-07."""

    def __init__(self, pattern: sp.csr_matrix) -> None:
        super().__init__(pattern, single=True)
        self.U = self.A  # double-precision values of the factorised matrix
        #: the double-precision solver, made at the first fallback and from then on used
        #: for every matrix (kept with its analysis), or None
        self.double: _Pardiso | None = None
        self.refinement_steps = 0
        self.double_fallbacks = 0
        self.double_factorisations = 0
        self.largest_residual = 0.0

    def factor(self, values: FloatArray) -> None:
        self.U.data[:] = values
        self._d = self.U.diagonal()
        self._Ut = self.U.T  # a CSC view: K x = U x + U^T x - diag(U) x
        if self.double is not None:  # an earlier matrix needed double precision
            self._factor_double()
            return
        try:
            super().factor(values)
        except ConvergenceError:  # a pivot lost in single precision: this one in double
            self._fall_back()

    def _fall_back(self) -> None:
        self.double_fallbacks += 1
        self._factor_double()

    def _factor_double(self) -> None:
        if self.double is None:
            self.double = _Pardiso(self.U)
            if self.marked is not None:
                self.double.mark(self.marked)
        self.double.factor(self.U.data)
        self.double_factorisations += 1

    def flexibility(self, dofs: NDArray[np.int64]) -> FloatArray:
        """As :meth:`_Pardiso.flexibility`, in single precision (relative error ~1e-6; for
        an iteration whose residual is computed with the refined solves)."""
        if self.double is not None:
            return self.double.flexibility(dofs)
        return super().flexibility(dofs)

    def _residual(self, b: FloatArray, x: FloatArray) -> FloatArray:
        return b - upper_times(self.U, self._Ut, self._d, x)

    def solve(self, b: FloatArray) -> FloatArray:
        if self.double is not None:
            return self.double.solve(b)
        B = np.asarray(b, dtype=np.float64).reshape(b.shape[0], -1)
        scale = np.maximum(np.linalg.norm(B, axis=0), 1e-300)
        x = super().solve(B)
        for step in range(MIXED_MAX_STEPS + 1):
            r = self._residual(B, x)
            rel = float(np.max(np.linalg.norm(r, axis=0) / scale))
            if rel <= MIXED_RTOL:
                self.largest_residual = max(self.largest_residual, rel)
                return x.reshape(b.shape)
            if step == MIXED_MAX_STEPS:
                break
            x += super().solve(r)
            self.refinement_steps += 1
        self._fall_back()  # the refinement stalls on this matrix: factorise it in double
        assert self.double is not None
        return self.double.solve(b)


class _SuperLU(_Solver):
    def __init__(self, pattern: sp.csr_matrix) -> None:
        self.A = pattern.copy().astype(np.float64)
        self.n = self.A.shape[0]
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


class _AMG(_Solver):
    def __init__(self, pattern: sp.csr_matrix, tol: float = 1e-10) -> None:
        self.A = pattern.copy().astype(np.float64)
        self.n = self.A.shape[0]
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


def make_solver(
    name: str, pattern_upper: sp.csr_matrix, single: bool = False, mixed: bool = True
) -> Any:
    """A solver for matrices with the upper-triangle CSR pattern ``pattern_upper``;
    ``single``: ``"pardiso"`` in single precision (ignored by the other solvers); ``mixed``:
    ``"auto"`` may pick the mixed-precision PARDISO (False: double precision, for an
    iteration whose own tolerance is near :data:`MIXED_RTOL`)."""
    if name not in SOLVERS:
        raise InputError(f"must be one of {', '.join(SOLVERS)}, got {name!r}", "options.solver")
    if name == "auto":
        name = ("pardiso-mixed" if mixed else "pardiso") if pardiso_available() else "splu"
    if name == "pardiso":
        return _Pardiso(pattern_upper, single)
    if name == "pardiso-mixed":
        return _PardisoMixed(pattern_upper)
    if name == "splu":
        return _SuperLU(pattern_upper)
    return _AMG(pattern_upper)
