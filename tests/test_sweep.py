"""Sweeps: axes and designs, one table whatever runs it (serial, process pool, Dask cluster),
failures of single rolls recorded, columns named by key with their unit."""

import csv
import math

import numpy as np
import pytest
from typer.testing import CliRunner

import woundroll
from woundroll.app.cli import app
from woundroll.app.sweep import design_points, parse_vary, run_sweep
from woundroll.errors import InputError

# an explicit roll spring bypasses the contact model: a roll takes milliseconds, so the tests
# exercise the sweep machinery; the 1D winding still responds to tension and K2
FAST = {
    "title": "fast sweep roll",
    "web": {"preset": "PET1"},
    "core": {"outer_radius": "4.45 cm", "rigid": True},
    "winding": {"outer_radius": "6 cm", "tension": "26.7 N"},
    "tester": {
        "instrument": "rho-meter",
        "roll_spring": {"alpha": "2.6e8 N/m^2", "beta": "1.05e5 N/m"},
    },
}
VARY = ["winding.tension=20 N:80 N:4", "web.radial_modulus.K2=20,60,-1"]


def test_parse_range_and_list():
    a = parse_vary("winding.tension=20 N:80 N:13")
    assert a.column == "winding.tension [N]" and len(a.values) == 13 and a.continuous
    assert a.values[0] == 20 and a.values[-1] == 80 and math.isclose(a.values[1], 25)
    assert a.case_value(a.values[1]) == "25.0 N"
    # stop in another unit of the same dimension: converted to start's (1 pli = 175.127 N/m)
    b = parse_vary("winding.tension=1 pli:350.254 N/m:3")
    assert b.unit == "pli" and math.isclose(b.values[-1], 2.0, rel_tol=1e-5)
    c = parse_vary("web.radial_modulus.K2=20,60,120")
    assert c.column == "web.radial_modulus.K2 [-]" and c.values == (20, 60, 120)
    d = parse_vary("winding.taper.kind=linear,hyperbolic")
    assert d.column == "winding.taper.kind" and d.case_value("linear") == "linear"


@pytest.mark.parametrize(
    "text",
    [
        "winding.tension",
        "=1,2",
        "winding.tension=20 N:80 N",
        "winding.tension=20 N:80 N:0",
        "winding.tension=20 N:80 N:2.5",
        "winding.tension=20 N:3 m:4",
        "winding.tension=20 N,linear",
        "winding.tension=20 N,,3 N",
        "winding.tension=20 furlong:3 N:4",
    ],
)
def test_parse_errors_name_vary(text):
    with pytest.raises(InputError) as exc:
        parse_vary(text)
    assert exc.value.field.startswith("--vary")


def test_designs():
    a = parse_vary("winding.tension=20 N:80 N:5")
    b = parse_vary("web.radial_modulus.K2=20,60,120")
    assert len(design_points([a, b])) == 15
    pts = np.array(design_points([a, b], "lhs", samples=10, seed=3), float)
    # Latin hypercube: each of the 10 strata of the continuous axis holds exactly one roll
    strata = np.floor((pts[:, 0] - 20) / 60 * 10).clip(0, 9)
    assert sorted(strata) == list(range(10))
    assert set(pts[:, 1]) <= {20, 60, 120}
    r1 = design_points([a, b], "random", samples=50, seed=1)
    assert r1 == design_points([a, b], "random", samples=50, seed=1)
    assert all(20 <= p[0] <= 80 for p in r1)
    with pytest.raises(InputError, match="--samples"):
        design_points([a], "lhs")
    with pytest.raises(InputError) as exc:
        design_points([a], "sobol", samples=4)
    assert exc.value.field == "--design"


@pytest.fixture(scope="module")
def serial():
    return run_sweep(FAST, VARY, workers=1)


def test_table_failures_recorded_not_fatal(serial):
    assert serial.columns[:2] == ["winding.tension [N]", "web.radial_modulus.K2 [-]"]
    assert serial.columns[-1] == "error"
    for col in ("winding.core_pressure [Pa]", "hardness.reading [rho]", "hardness.impulse [N s]"):
        assert col in serial.columns
    assert len(serial.rows) == 12 and serial.n_failed == 4
    err = serial.column("error")
    k2 = serial.column("web.radial_modulus.K2 [-]")
    p = serial.column("winding.core_pressure [Pa]")
    for e, k, v in zip(err, k2, p, strict=True):
        assert bool(e) == (k == -1)
        assert (k == -1) == math.isnan(v)
    assert "web.radial_modulus.K2" in err[2]
    assert serial.notes == ["4 of 12 rolls failed: see the error column"]


def test_rows_equal_single_runs(serial):
    # a row is the run of the case with the point's values set: bit-identical results
    t = serial.column("winding.tension [N]")
    k2 = serial.column("web.radial_modulus.K2 [-]")
    i = next(j for j in range(12) if t[j] == 60 and k2[j] == 60)
    data = {**FAST, "web": {"preset": "PET1", "radial_modulus": {"K2": 60}}}
    data["winding"] = {**FAST["winding"], "tension": "60.0 N"}
    direct = woundroll.run(woundroll.load_case(data))
    assert serial.column("winding.core_pressure [Pa]")[i] == direct.winding.core_pressure
    # physics, not just plumbing: core pressure rises with tension at each K2
    for k in (20, 60):
        cp = [serial.rows[j][2] for j in range(12) if k2[j] == k]
        assert all(np.diff(cp) > 0)


def test_dask_local_cluster_equals_serial(serial):
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        by_client = run_sweep(FAST, VARY, scheduler=client)
        by_address = run_sweep(FAST, VARY, scheduler=cluster.scheduler_address)
    for res in (by_client, by_address):
        assert res.columns == serial.columns
        assert _same(res.rows, serial.rows)


def test_process_pool_equals_serial(serial):
    res = run_sweep(FAST, VARY[:1], workers=2)
    ref = run_sweep(FAST, VARY[:1], workers=1)
    assert res.columns == ref.columns and _same(res.rows, ref.rows)


def _same(a, b):
    def eq(x, y):
        return (
            isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y)
        ) or x == y

    return all(eq(x, y) for ra, rb in zip(a, b, strict=True) for x, y in zip(ra, rb, strict=True))


def test_write_parquet_and_csv_agree(serial, tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    written = serial.write(tmp_path)
    assert [p.name for p in written] == ["sweep.parquet", "sweep.csv", "main_effects.png"]
    table = pq.read_table(tmp_path / "sweep.parquet")
    assert table.column_names == serial.columns
    with open(tmp_path / "sweep.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    assert rows[0] == serial.columns
    j = serial.columns.index("winding.core_pressure [Pa]")
    from_csv = [float(r[j]) if r[j] else math.nan for r in rows[1:]]
    from_pq = table.column(j).to_pylist()
    # repr() of a float round-trips exactly through the CSV
    assert _same([from_csv], [from_pq]) and _same([from_pq], [serial.column(serial.columns[j])])


def test_cli(tmp_path):
    case = tmp_path / "fast.toml"
    case.write_text(
        'title = "fast"\n[web]\npreset = "PET1"\n[core]\nouter_radius = "4.45 cm"\n'
        'rigid = true\n[winding]\nouter_radius = "6 cm"\ntension = "26.7 N"\n'
    )
    runner = CliRunner()
    res = runner.invoke(
        app,
        [
            "sweep",
            str(case),
            "--vary",
            "winding.tension=1 pli:3 pli:3",
            "--out",
            str(tmp_path / "o"),
            "--workers",
            "1",
        ],
    )
    assert res.exit_code == 0, res.output
    assert "3 rolls, 3 ran, 0 failed" in res.output
    head = (tmp_path / "o" / "sweep.csv").read_text().splitlines()[0]
    assert head.startswith("winding.tension [pli],winding.core_pressure [Pa]")
    for args, field in [
        (["--vary", "winding.tensio=1 N:2 N:2"], "--vary winding.tensio"),
        (["--vary", "winding.tension=1 N:2 N:2", "--design", "lhs"], "--samples"),
        (["--vary", "winding.tension=1 N:2 N:x"], "--vary winding.tension"),
    ]:
        res = runner.invoke(app, ["sweep", str(case), *args, "--out", str(tmp_path / "e")])
        lines = [ln for ln in res.output.splitlines() if ln.strip()]
        assert res.exit_code == 2 and len(lines) == 1 and f"{field}:" in lines[0], res.output


# --uncertainty: K2 and tension tolerances on the fast roll; the second K2-SD value is zero,
# so that roll's propagation fails ("every tolerance is zero") while its run succeeds
UQ_CASE = {**FAST, "uncertainty": {"K2": 5}}
UQ_VARY = ["winding.tension=20 N:60 N:2", "uncertainty.K2=5,0"]
BANDS = ("winding.core_pressure", "uncertainty.surface_pressure", "uncertainty.min_hoop_stress")


@pytest.fixture(scope="module")
def uq_serial():
    return run_sweep(UQ_CASE, UQ_VARY, workers=1, uncertainty=12)


def test_uncertainty_band_columns_bracket_nominal(uq_serial):
    s = uq_serial
    for b in BANDS:
        assert f"{b}_low [Pa]" in s.columns and f"{b}_high [Pa]" in s.columns
    # an explicit roll spring: the reading does not depend on the stresses, no reading band
    assert not any(
        c.startswith(("hardness.reading_low", "hardness.reading_high")) for c in s.columns
    )
    err = s.column("error")
    k2sd = s.column("uncertainty.K2 [-]")
    p = s.column("winding.core_pressure [Pa]")
    lo, hi = s.column("winding.core_pressure_low [Pa]"), s.column("winding.core_pressure_high [Pa]")
    for e, k, v, a, b in zip(err, k2sd, p, lo, hi, strict=True):
        if k == 0:
            # propagation failed: recorded, the roll's own results kept, no band
            assert e == "uncertainty: every tolerance is zero: nothing to propagate"
            assert math.isfinite(v) and math.isnan(a) and math.isnan(b)
        else:
            # K2 +-5 (1 SD) about 33 moves the core pressure by several %: a band of finite
            # width; the nominal (K2 at its mean) lies inside the 2.5-97.5 % band of 12 samples
            assert not e and a < v < b and (b - a) > 0.01 * v
    assert s.n_failed == 2
    # the same seed for every roll (common random numbers): the band of the roll at 20 N
    # equals that of a single propagation of the case at 20 N
    from woundroll.assess.uncertainty import propagate
    from woundroll.case import load_case

    data = {**UQ_CASE, "winding": {**FAST["winding"], "tension": "20.0 N"}}
    uq = propagate(load_case(data), 12)
    assert lo[0] == np.percentile(uq.core_pressure, 2.5)


def test_uncertainty_dask_equals_serial(uq_serial):
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        res = run_sweep(UQ_CASE, UQ_VARY, scheduler=client, uncertainty=12)
    assert res.columns == uq_serial.columns and _same(res.rows, uq_serial.rows)


def test_uncertainty_process_pool_equals_serial(uq_serial):
    res = run_sweep(UQ_CASE, UQ_VARY, workers=2, uncertainty=12)
    assert res.columns == uq_serial.columns and _same(res.rows, uq_serial.rows)


def contact_model_band_row():  # type: ignore[no-untyped-def]
    """One roll of the sweep with the contact model and ``--uncertainty 10``: its table row
    as a dict (the test below; docs/scripts/misc.py renders the surrogate's check)."""
    data = {**UQ_CASE, "tester": {"instrument": "rho-meter"}}
    s = run_sweep(data, ["winding.tension=26.7 N"], workers=1, uncertainty=10)
    assert s.n_failed == 0
    (row,) = s.rows
    return dict(zip(s.columns, row, strict=True))


def test_uncertainty_reading_band_with_contact_model():
    # the contact model instead of an explicit spring: the reading gets a (surrogate) band,
    # checked against full forward runs; one roll (about 3 s: 1 + 3 + 2 forward runs)
    v = contact_model_band_row()
    # the band is the model's reading's (unclipped): it brackets reading_model; the column
    # hardness.reading is what the dial shows (100 here: this 6 cm roll reads past the scale)
    assert v["hardness.reading_low [rho]"] < v["hardness.reading_model [rho]"]
    assert v["hardness.reading_model [rho]"] < v["hardness.reading_high [rho]"]
    assert v["hardness.reading [rho]"] == min(v["hardness.reading_model [rho]"], 100.0)
    # the surrogate's check against full runs is reported (its size on this roll: docs/sweeps.md)
    assert v["uncertainty.surrogate_error [rho]"] >= 0.0


def test_uncertainty_input_errors():
    with pytest.raises(InputError) as exc:
        run_sweep(UQ_CASE, UQ_VARY, workers=1, uncertainty=5)
    assert exc.value.field == "--uncertainty"
    with pytest.raises(InputError) as exc:
        run_sweep(FAST, UQ_VARY[:1], workers=1, uncertainty=12)  # no [uncertainty] table
    assert exc.value.field == "uncertainty"


def test_cli_uncertainty(tmp_path):
    case = tmp_path / "fast.toml"
    case.write_text(
        'title = "fast"\n[web]\npreset = "PET1"\n[core]\nouter_radius = "4.45 cm"\n'
        'rigid = true\n[winding]\nouter_radius = "6 cm"\ntension = "26.7 N"\n'
        '[uncertainty]\ntension = "5 %"\n'
    )
    runner = CliRunner()
    args = ["sweep", str(case), "--vary", "winding.tension=1 pli:2 pli:2", "--workers", "1"]
    res = runner.invoke(app, [*args, "--uncertainty", "10", "--out", str(tmp_path / "o")])
    assert res.exit_code == 0 and "2 rolls, 2 ran, 0 failed" in res.output, res.output
    head = (tmp_path / "o" / "sweep.csv").read_text().splitlines()[0].split(",")
    assert "winding.core_pressure_low [Pa]" in head and "winding.core_pressure_high [Pa]" in head
    res = runner.invoke(app, [*args, "--uncertainty", "3", "--out", str(tmp_path / "e")])
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert res.exit_code == 2 and len(lines) == 1 and "--uncertainty:" in lines[0], res.output


# the cluster a user starts: its own process, workers in their own processes; the test gives
# its address on the command line exactly as a cluster user does
_CLUSTER = """
import sys, distributed
if __name__ == "__main__":
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0"
    ) as cluster:
        print(cluster.scheduler_address, flush=True)
        sys.stdin.read()  # until the test closes stdin
"""

FAST_TOML = """title = "fast sweep roll"
web = { preset = "PET1" }
core = { outer_radius = "4.45 cm", rigid = true }
winding = { outer_radius = "6 cm", tension = "26.7 N" }
[tester]
instrument = "rho-meter"
roll_spring = { alpha = "2.6e8 N/m^2", beta = "1.05e5 N/m" }
"""


@pytest.fixture(scope="module")
def cluster_address():
    import os
    import subprocess
    import sys
    from pathlib import Path

    pytest.importorskip("distributed")
    src = str(Path(woundroll.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.Popen(
        [sys.executable, "-c", _CLUSTER],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        env=env,
    )
    try:
        address = proc.stdout.readline().strip()  # blocks until the cluster is up
        assert address.startswith("tcp://"), f"cluster did not start: {address!r}"
        yield address, env
    finally:
        proc.stdin.close()  # the cluster's context manager closes scheduler and workers
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:  # pragma: no cover - a stuck cluster
            proc.kill()
            proc.wait()
        proc.stdout.close()


def test_cli_scheduler_address_equals_serial(cluster_address, tmp_path):
    # issue 22.1: `woundroll sweep --scheduler ADDRESS` failed with "No clients found" because
    # the command's client is not the process's default client
    import subprocess
    import sys

    address, env = cluster_address
    case = tmp_path / "fast.toml"
    case.write_text(FAST_TOML, encoding="utf-8")
    vary = ["--vary", VARY[0], "--vary", VARY[1]]
    cmd = [sys.executable, "-m", "woundroll.app.cli", "sweep", str(case), *vary, "--quiet"]
    run = subprocess.run(
        [*cmd, "--scheduler", address, "--out", str(tmp_path / "dask")],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr
    serial = CliRunner().invoke(
        app, ["sweep", str(case), *vary, "--workers", "1", "--quiet", "--out", str(tmp_path / "s")]
    )
    assert serial.exit_code == 0, serial.output
    dask_csv = (tmp_path / "dask" / "sweep.csv").read_text(encoding="utf-8")
    serial_csv = (tmp_path / "s" / "sweep.csv").read_text(encoding="utf-8")
    # the same rolls in the same code: the same table to the last digit (the csv writes
    # floats with repr), failed rolls (K2 = -1) included
    assert dask_csv == serial_csv
    rows = list(csv.DictReader(serial_csv.splitlines()))
    assert len(rows) == 12 and sum(1 for r in rows if r["error"]) == 4
    pq = pytest.importorskip("pyarrow.parquet")
    a = pq.read_table(tmp_path / "dask" / "sweep.parquet").to_pydict()
    b = pq.read_table(tmp_path / "s" / "sweep.parquet").to_pydict()
    assert list(a) == list(b)
    assert _same(list(zip(*a.values(), strict=True)), list(zip(*b.values(), strict=True)))


def test_cli_scheduler_unreachable_is_one_line(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr("woundroll.app.sweep.SCHEDULER_TIMEOUT", "2s")  # nobody listens on port 1
    case = tmp_path / "fast.toml"
    case.write_text(FAST_TOML, encoding="utf-8")
    res = CliRunner().invoke(
        app,
        ["sweep", str(case), "--vary", VARY[0], "--scheduler", "tcp://127.0.0.1:1"]
        + ["--out", str(tmp_path / "out")],
    )
    assert res.exit_code == 2
    lines = res.output.strip().splitlines()
    assert len(lines) == 1 and "--scheduler" in lines[0] and "127.0.0.1:1" in lines[0]
    assert "Traceback" not in res.output
