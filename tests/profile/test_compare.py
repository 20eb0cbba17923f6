"""A measured CMD hardness profile compared with the predicted one."""

from pathlib import Path

import numpy as np
import pytest

from woundroll.errors import InputError
from woundroll.profile.compare import MeasuredProfile, compare_profiles, read_measured_profile


def test_read_averages_repeat_hits_and_converts_units(tmp_path: Path) -> None:
    f = tmp_path / "m.csv"
    f.write_text("# shop-floor readings\nposition [in],rho\n2,50\n1,40\n1,44\n3,60\n")
    m = read_measured_profile(f)
    np.testing.assert_allclose(m.position, [0.0254, 0.0508, 0.0762], rtol=1e-12)
    np.testing.assert_allclose(m.reading, [42.0, 50.0, 60.0], rtol=1e-12)


def test_comparison_numbers_by_hand() -> None:
    z = np.array([0.0, 0.1, 0.2])
    pred = np.array([50.0, 60.0, 70.0])
    meas = MeasuredProfile(np.array([0.05, 0.15]), np.array([50.0, 70.0]))
    c = compare_profiles(z, pred, meas)
    # prediction interpolated at 0.05 and 0.15: 55 and 65; differences +5 and -5
    np.testing.assert_allclose(c.predicted, [55.0, 65.0], rtol=1e-12)
    assert c.bias == pytest.approx(0.0, abs=1e-12)
    assert c.rms == pytest.approx(5.0, rel=1e-12)
    assert c.rms_shape == pytest.approx(5.0, rel=1e-12)
    assert c.correlation == pytest.approx(1.0, rel=1e-12)


def test_pure_offset_has_no_shape_error() -> None:
    z = np.linspace(0, 0.6, 7)
    pred = 50 + 10 * np.sin(z * 10)
    meas = MeasuredProfile(z.copy(), pred - 8.0)
    c = compare_profiles(z, pred, meas)
    assert c.bias == pytest.approx(8.0, rel=1e-12)
    assert c.rms == pytest.approx(8.0, rel=1e-12)
    assert c.rms_shape == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize(
    "text",
    [
        "position [in],depth [mm]\n1,2\n2,3\n",
        "position [in],rho\n1,40\n",
        "position [kg],rho\n1,2\n2,3\n",
    ],
)
def test_bad_files_name_the_field(tmp_path: Path, text: str) -> None:
    f = tmp_path / "m.csv"
    f.write_text(text)
    with pytest.raises(InputError) as exc:
        read_measured_profile(f)
    assert exc.value.field.startswith("profile.measured")


def test_positions_outside_the_roll_are_rejected() -> None:
    with pytest.raises(InputError) as exc:
        compare_profiles(
            [0.0, 0.1], [1.0, 2.0], MeasuredProfile(np.array([0.0, 0.5]), np.array([1.0, 1.0]))
        )
    assert exc.value.field == "profile.measured"


def test_undecodable_file_is_an_input_error(tmp_path: Path) -> None:
    f = tmp_path / "m.csv"
    f.write_bytes(b"position [in],rho\n1,\xff\xfe40\n")
    with pytest.raises(InputError) as exc:
        read_measured_profile(f)
    assert exc.value.field == "profile.measured"
