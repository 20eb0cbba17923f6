"""The test process runs BLAS on one thread, as the ``woundroll`` command does
(:func:`woundroll.util.blas.single_thread_process`, before NumPy is imported): OpenBLAS's
threads only wait on each other in the models' small solves on a loaded 2-core machine.
The library's own limit (:func:`woundroll.util.blas.one_blas_thread`) is tested in
tests/util/test_blas.py in a fresh interpreter."""

from woundroll.util.blas import single_thread_process

single_thread_process()
