"""Clean stops: a CMD-profile run killed while its worker pool is busy ends within seconds,
leaves no process behind (workers, resource tracker) and no file in ``--out``.

A real process is started (``python -m woundroll.app.cli run``), we wait until it has spawned its
pool (two workers and the resource tracker, seen as its children in /proc), send the signal
and watch. The case is the bundled PET3 profile cut to 12 sectors and an 11 cm roll so the
pool starts within about 10 s; its contact solutions then run for tens of seconds, far longer
than the stop we allow.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")

#: Seconds allowed from the signal to the end of the parent (the issue's "a few seconds").
STOP_SECONDS = 8.0
#: Seconds allowed for the orphaned workers of a SIGKILLed parent (they poll every 0.5 s).
ORPHAN_SECONDS = 5.0


def _children(pid: int) -> list[int]:
    out = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            continue
        if ppid == pid:
            out.append(int(d.name))
    return out


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state != "Z"


def _run_and_signal(out: Path, sig: int) -> tuple[subprocess.Popen, set[int], float]:
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "woundroll.app.cli",
            "run",
            "pet3-2.3MPa",
            "-q",
            "--set",
            'winding.outer_radius="11 cm"',
            "--set",
            "profile.sectors=12",
            "--out",
            str(out),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    t0 = time.monotonic()
    kids: list[int] = []
    while time.monotonic() - t0 < 120 and proc.poll() is None:
        kids = _children(proc.pid)
        if len(kids) >= 3:  # two workers and the resource tracker
            break
        time.sleep(0.1)
    if proc.poll() is not None or len(kids) < 3:
        proc.kill()
        proc.communicate()
        pytest.fail(f"the run did not reach its worker pool (children: {kids})")
    time.sleep(1.0)  # the workers are inside contact solutions now
    tree = set(kids) | {g for k in kids for g in _children(k)}
    t1 = time.monotonic()
    proc.send_signal(sig)
    return proc, tree, t1


@pytest.mark.parametrize(
    "sig",
    [signal.SIGTERM, pytest.param(signal.SIGINT, marks=pytest.mark.slow)],
)
def test_signal_stops_run_and_workers(tmp_path, sig):
    out = tmp_path / "out"
    proc, tree, t1 = _run_and_signal(out, sig)
    try:
        _, err = proc.communicate(timeout=STOP_SECONDS)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail(f"the run did not stop within {STOP_SECONDS} s of {sig.name}")
    stopped = time.monotonic() - t1
    assert proc.returncode == 128 + sig, err
    assert "Traceback" not in err
    assert "no output written" in err
    deadline = time.monotonic() + 3.0
    while any(_alive(p) for p in tree) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not [p for p in tree if _alive(p)], f"left running after {sig.name}"
    assert stopped < STOP_SECONDS
    # nothing published, no staging directory left
    assert not out.exists() or os.listdir(out) == []


@pytest.mark.slow
def test_killed_parent_leaves_no_orphans(tmp_path):
    out = tmp_path / "out"
    proc, tree, t1 = _run_and_signal(out, signal.SIGKILL)
    proc.wait(timeout=10)
    deadline = t1 + ORPHAN_SECONDS
    while any(_alive(p) for p in tree) and time.monotonic() < deadline:
        time.sleep(0.1)
    proc.communicate()
    assert not [p for p in tree if _alive(p)], "workers outlived their killed parent"
    assert not (out / "result.json").exists()
