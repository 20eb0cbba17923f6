"""Thickness input: CSV profiles with units, CMD x MD maps, validation, sector averages."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.materials.thickness_profile import (
    FIELD,
    ThicknessProfile,
    bundled_profile,
    read_thickness_map,
    read_thickness_profile,
)


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def test_si_header(tmp_path: Path) -> None:
    p = _write(tmp_path / "p.csv", "position_m,thickness_m\n0,7.6e-5\n0.1,7.7e-5\n0.2,7.5e-5\n")
    prof = read_thickness_profile(p)
    np.testing.assert_array_equal(prof.position, [0.0, 0.1, 0.2])
    np.testing.assert_array_equal(prof.thickness, [7.6e-5, 7.7e-5, 7.5e-5])


def test_us_units_header(tmp_path: Path) -> None:
    # 1 in = 0.0254 m and 1 mil = 25.4 um exactly: conversions must be exact to round-off
    p = _write(
        tmp_path / "p.csv", "# a comment\nposition [in],thickness [mil]\n0,3\n1,3.1\n2,2.9\n"
    )
    prof = read_thickness_profile(p)
    np.testing.assert_allclose(prof.position, [0.0, 0.0254, 0.0508], rtol=1e-14)
    np.testing.assert_allclose(prof.thickness, [76.2e-6, 78.74e-6, 73.66e-6], rtol=1e-12)


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ("0,7e-5\n0.2,7e-5\n0.1,7e-5\n", "increase strictly"),
        ("0,7e-5\n0.1,-7e-5\n0.2,7e-5\n", "positive"),
        ("0,7e-5\n0.1,0\n0.2,7e-5\n", "positive"),
        ("0,7e-5\n0.1,nan\n0.2,7e-5\n", "not finite"),
        ("0,7e-5\n0.1,abc\n0.2,7e-5\n", "not a number"),
        ("0,7e-5\n0.01,7e-5\n0.02,7e-5\n0.03,7e-5\n0.2,7e-5\n", "gap"),
        ("0,7e-5\n", "at least"),
    ],
)
def test_bad_profiles_name_the_field(tmp_path: Path, body: str, words: str) -> None:
    p = _write(tmp_path / "p.csv", "position_m,thickness_m\n" + body)
    with pytest.raises(InputError, match=words) as exc:
        read_thickness_profile(p)
    assert exc.value.field == FIELD


def test_missing_file_and_column(tmp_path: Path) -> None:
    with pytest.raises(InputError) as exc:
        read_thickness_profile(tmp_path / "nope.csv")
    assert exc.value.field == FIELD
    p = _write(tmp_path / "p.csv", "position_m,gauge_m\n0,1\n1,1\n")
    with pytest.raises(InputError, match="no column 'thickness'"):
        read_thickness_profile(p)


def test_gap_criterion_boundary() -> None:
    # spacing exactly 3 x the median is accepted; just above is a gap (GAP_FACTOR = 3)
    ThicknessProfile(np.array([0.0, 1.0, 2.0, 5.0]), np.ones(4))
    with pytest.raises(InputError, match="gap"):
        ThicknessProfile(np.array([0.0, 1.0, 2.0, 5.001]), np.ones(4))


def test_csv_map_is_md_averaged(tmp_path: Path) -> None:
    rng = np.random.default_rng(1)
    data = 70 + rng.random((5, 4))  # um
    rows = ["thickness [um],0 mm,10 mm,20 mm,30 mm"]
    rows += [f"{i * 0.5} m," + ",".join(f"{v:.6f}" for v in row) for i, row in enumerate(data)]
    p = _write(tmp_path / "map.csv", "# synthetic\n" + "\n".join(rows) + "\n")
    prof = read_thickness_map(p)
    np.testing.assert_allclose(prof.position, [0.0, 0.01, 0.02, 0.03], rtol=1e-14)
    expect = np.round(data, 6).mean(axis=0) * 1e-6
    np.testing.assert_allclose(prof.thickness, expect, rtol=1e-12)


def test_csv_map_rejects_nan_cell(tmp_path: Path) -> None:
    p = _write(tmp_path / "map.csv", "thickness [um],0 mm,10 mm\n0,70,71\n1,70,\n")
    with pytest.raises(InputError, match="MD scan 2") as exc:
        read_thickness_map(p)
    assert exc.value.field == FIELD


def test_npy_map_layout(tmp_path: Path) -> None:
    data = np.array([[70e-6, 72e-6, 74e-6], [72e-6, 74e-6, 76e-6]])
    path = tmp_path / "map.npy"
    np.save(path, data)
    prof = read_thickness_map(path, width=0.6)
    # cell centres of 3 equal cells over [0, 0.6]
    np.testing.assert_allclose(prof.position, [0.1, 0.3, 0.5], rtol=1e-14)
    np.testing.assert_allclose(prof.thickness, [71e-6, 73e-6, 75e-6], rtol=1e-14)
    with pytest.raises(InputError, match="width"):
        read_thickness_map(path)


def test_sector_average_exact_for_linear_profile() -> None:
    # cell averages of a linear profile equal its values at the cell centres (exact)
    x = np.linspace(0.0, 0.6, 13)
    prof = ThicknessProfile(x, 70e-6 + 1e-5 * x)
    z, h = prof.sector_average(7)
    np.testing.assert_allclose(h, 70e-6 + 1e-5 * z, rtol=1e-13)
    np.testing.assert_allclose(z, (np.arange(7) + 0.5) * 0.6 / 7, rtol=1e-13)


def test_sector_average_conserves_the_integral() -> None:
    # any sector count: sum(h_j w_j) equals the trapezoid integral of the profile (round-off)
    prof = bundled_profile()
    exact = np.trapezoid(prof.thickness, prof.position)
    for n in (1, 7, 61, 200):
        z, h = prof.sector_average(n)
        assert np.sum(h) * prof.extent / n == pytest.approx(exact, rel=1e-12)
    with pytest.raises(InputError):
        prof.sector_average(0)


def test_bundled_profile_is_the_table3_case() -> None:
    prof = bundled_profile()
    # Table 3: 76 um mean, 61 cm wide; "a few per cent" variation with thick and thin bands
    assert prof.mean == pytest.approx(76e-6, rel=1e-3)
    assert prof.extent == pytest.approx(0.61, rel=1e-12)
    p2p = np.ptp(prof.thickness) / prof.mean
    assert 0.02 < p2p < 0.06
    with pytest.raises(InputError, match="no bundled profile"):
        bundled_profile("nonexistent")


def test_bundled_file_says_it_is_synthetic() -> None:
    from importlib import resources

    text = resources.files("woundroll.data").joinpath("profiles", "table3_synthetic_pet.csv")
    first = text.read_text(encoding="utf-8").splitlines()[0]
    assert first.startswith("#") and "SYNTHETIC" in first
