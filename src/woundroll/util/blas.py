"""One BLAS thread for the models' many small dense and banded solves.

The models factorise and solve many small systems (banded Cholesky of a plane-strain contact
mesh, bandwidth 60; the axisymmetric winding's windows; the layered roll's active-set
passes; the 3D assembly's per-ring products). OpenBLAS splits even these over its threads,
and on a 2-core machine with other work running its threads wait on each other: measured
on this project's machine at load 7, one ``Y.T @ Y`` of a 1055 x 20 matrix in the 2D contact
solve took 80 ms with OpenBLAS's threads against 0.04 ms with one; a Table 2 roll's contact
solve 0.44 s CPU against 0.28 s; the axisymmetric winding's window 20.5 against 3.0 ms; a
5-sheet layered test roll 72 s against 2.3 s. The models gain nothing from the threads (the
matrices are small; the profile's sectors and a sweep's rolls use the cores as processes).

Two ways, one policy:

* the command line calls :func:`single_thread_process` before NumPy is imported: the
  ``OPENBLAS_NUM_THREADS=1`` it sets holds for the whole process and for the worker
  processes it starts (they inherit the environment), at no cost; a value the user set is
  kept;
* the library wraps its solvers in :func:`one_blas_thread` (threadpoolctl's limit, ~1.5 ms
  a call after a first ~25 ms to find the loaded BLAS), which does nothing where the process
  already runs one thread.
"""

from __future__ import annotations

import os
import sys
from contextlib import AbstractContextManager, nullcontext
from typing import Any

#: The environment variable that sets OpenBLAS's threads (read once, when NumPy loads it).
ENV = "OPENBLAS_NUM_THREADS"
_process_single = False


def single_thread_process() -> None:
    """One OpenBLAS thread for this process and the processes it starts, if NumPy is not
    loaded yet (else nothing: the library's :func:`one_blas_thread` limits each solve) and
    the user has not set ``OPENBLAS_NUM_THREADS`` (their value is kept)."""
    global _process_single
    if "numpy" in sys.modules:
        return
    os.environ.setdefault(ENV, "1")
    _process_single = os.environ[ENV] == "1"


def one_blas_thread() -> AbstractContextManager[Any]:
    """A context in which BLAS runs one thread (module docstring)."""
    if _process_single:
        return nullcontext()
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1, user_api="blas")
