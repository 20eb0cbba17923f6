"""One BLAS thread for the models (woundroll.util.blas): the command sets it for its process
before NumPy loads, keeps a value the user set, and the library limits its solves where the
process runs more; each case in a fresh interpreter (the thread count is fixed when NumPy
loads OpenBLAS)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

#: prints OpenBLAS's thread count outside and inside the library's limit
PROBE = """
import json, threadpoolctl
from woundroll.util.blas import one_blas_thread
def n():
    return [i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"]
out = {"outside": n()}
with one_blas_thread():
    out["inside"] = n()
out["after"] = n()
print(json.dumps(out))
"""


def _probe(prelude: str, env_value: str | None) -> dict[str, list[int]]:
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS",)}
    if env_value is not None:
        env["OPENBLAS_NUM_THREADS"] = env_value
    code = prelude + "\nimport numpy, scipy.linalg\n" + PROBE
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def _threads_available() -> int:
    out = _probe("", "2")
    return out["outside"][0] if out["outside"] else 0


def test_the_command_runs_one_blas_thread() -> None:
    # importing the command's entry module (what `woundroll` and `python -m woundroll` do
    # first) sets one thread before NumPy loads; inside the library's limit: still one
    got = _probe("import woundroll.app.cli.entry", None)
    assert got["outside"] and set(got["outside"]) == {1}
    assert set(got["inside"]) == {1} and set(got["after"]) == {1}


def test_a_thread_count_the_user_set_is_kept() -> None:
    if _threads_available() < 2:
        pytest.skip("OpenBLAS here runs one thread at most")
    got = _probe("import woundroll.app.cli.entry", "2")
    assert set(got["outside"]) == {2}
    # ... and the models' solves still run on one
    assert set(got["inside"]) == {1} and set(got["after"]) == {2}


def test_the_library_limits_its_solves_and_restores() -> None:
    if _threads_available() < 2:
        pytest.skip("OpenBLAS here runs one thread at most")
    # a user's process with NumPy on two threads (no command): the limit holds inside only
    got = _probe("", "2")
    assert set(got["outside"]) == {2} and set(got["inside"]) == {1} and set(got["after"]) == {2}


def test_after_numpy_the_command_sets_nothing() -> None:
    # NumPy loaded first (an embedding program): the environment is left alone
    code = (
        "import os, numpy\nimport woundroll.app.cli.entry\n"
        "print(os.environ.get('OPENBLAS_NUM_THREADS'))"
    )
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    )
    assert out.stdout.strip() == "None"
