"""Compact output (issue 23 item 2): `woundroll run --json` and result.json leave out the
arrays longer than COMPACT_MAX_POINTS (result.npz holds them with --out); --fields full
writes every array in the JSON."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from typer.testing import CliRunner

from woundroll.app.cli import app
from woundroll.pipeline.results import COMPACT_MAX_POINTS, compact

CASE = str(Path(__file__).resolve().parent.parent / "benchmarks" / "cases" / "film-10k.toml")
WINDING_ARRAYS = ("E_r_Pa", "radius_m", "sigma_r_Pa", "sigma_theta_Pa", "wound_on_tension_Pa")
runner = CliRunner()


def test_compact_moves_long_numeric_lists_only() -> None:
    n = COMPACT_MAX_POINTS + 1
    doc = {"a": {"x": [1.0] * n, "y": [1.0, 2.0], "s": ["t"] * n, "n": [None] + [2.0] * (n - 1)}}
    small, arrays = compact(doc)
    assert small == {"a": {"y": [1.0, 2.0], "s": ["t"] * n}, "arrays_omitted": ["a.n", "a.x"]}
    assert np.isnan(arrays["a.n"][0]) and arrays["a.x"].shape == (n,)
    assert compact({"a": [1.0]}) == ({"a": [1.0]}, {})


def test_10k_roll_json_is_compact_and_npz_holds_the_arrays(tmp_path: Path) -> None:
    """The 10,000-layer roll (benchmarks/cases/film-10k.toml): JSON <= 100 kB by default
    (measured 3.2 kB); the npz arrays are the full JSON's, bit for bit."""
    res = runner.invoke(app, ["run", CASE, "--json"])
    assert res.exit_code == 0, res.output
    assert len(res.stdout.encode()) <= 100_000
    d = json.loads(res.stdout)
    assert d["arrays_omitted"] == [f"winding.{k}" for k in WINDING_ARRAYS]
    assert d["winding"]["n_layers"] == 10_000 and "sigma_r_Pa" not in d["winding"]
    full = runner.invoke(app, ["run", CASE, "--json", "--fields", "full"])
    f = json.loads(full.stdout)
    assert "arrays_omitted" not in f and len(f["winding"]["sigma_r_Pa"]) == 20_001
    res = runner.invoke(app, ["run", CASE, "--out", str(tmp_path / "o"), "-q"])
    assert res.exit_code == 0, res.output
    data = json.loads((tmp_path / "o" / "result.json").read_text())
    assert "result.npz" in data["files"]
    with np.load(tmp_path / "o" / "result.npz") as z:
        assert sorted(z.files) == data["arrays_omitted"]
        np.testing.assert_array_equal(z["winding.sigma_r_Pa"], f["winding"]["sigma_r_Pa"])


def test_bad_fields_is_a_one_line_error() -> None:
    res = runner.invoke(app, ["run", CASE, "--json", "--fields", "some"])
    assert res.exit_code == 2 and "--fields" in res.output
