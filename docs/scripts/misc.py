"""Generators of the numbers in docs/sweeps.md and docs/case-files.md (docs/scripts/
regenerate.py runs them): the sweep's reading band and its surrogate check on
tests/test_sweep.py's own roll, and the winding time estimate of ``woundroll.limits``. Cost:
a few seconds (one roll with 10 uncertainty samples)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]


def _sweep_tests() -> Any:
    """tests/test_sweep.py as a module: the page shows the test's own roll."""
    import records

    return records.test_module("test_sweep.py")


def sweep_surrogate() -> str:
    """test_uncertainty_reading_band_with_contact_model: the surrogate's check against full
    runs on the 6 cm PET1 roll, against the width of its reading band."""
    t = _sweep_tests()
    v = t.contact_model_band_row()
    lo, hi = v["hardness.reading_low [rho]"], v["hardness.reading_high [rho]"]
    err = v["uncertainty.surrogate_error [rho]"]
    roll = t.UQ_CASE["winding"]["outer_radius"]
    return (
        f"the tests' {roll} PET1 roll, read at {v['hardness.reading_model [rho]']:.0f} Rho by "
        f"the model (the instrument's scale ends at 100), K2 SD 5, 10 samples: the check "
        f"differs by {err:.2g} Rho, {100 * err / (hi - lo):.2g} % of the 95 % reading band "
        f"({lo:.1f}-{hi:.1f} Rho)"
    )


def winding_estimate() -> str:
    """``limits.winding_estimate`` on both paths (the estimate the warning uses) and its
    constants."""
    from woundroll import limits

    def est(n: int, kernels: str = "compiled") -> str:
        t = limits.winding_estimate(n, 2, kernels).seconds
        return f"{t:.2g} s" if t < 120 else limits.fmt_seconds(t)

    big = [f"{est(n)} for {n:,}" for n in (10_000, 100_000, limits.MAX_INCREMENTS)]
    return (
        f"compiled, {limits.WINDING_COMPILED_SECONDS * 1e6:.2g} us an increment times 1 + n / "
        f"{limits.WINDING_COMPILED_DOUBLING:.0e}: {', '.join(big[:-1])} and {big[-1]} "
        f"increments; the NumPy twin {1e3 * limits.WINDING_NUMPY_SECONDS:.2g} ms an "
        f"increment: {est(2_000, 'numpy')} for 2,000. Both for 2 elements a layer, in seconds "
        f"of the development machine when quiet (its yardstick {limits.YARDSTICK_SECONDS:g} s)"
    ).replace("e+0", "e")


def long_runs() -> str:
    """The other `long run:` warnings of ``woundroll.limits`` (their fixed constants)."""
    from woundroll.limits import (
        LONG_RUN_SECONDS,
        PROFILE_REFERENCE_SECONDS,
        THIN_WEB_CONTACT,
        fmt_seconds,
    )

    return (
        f"runs of the contact model on webs thinner than {THIN_WEB_CONTACT * 1e6:g} um (the "
        "contact mesh follows the web thickness; the warning quotes the times measured when "
        "the threshold was set) and CMD profiles estimated above "
        f"{fmt_seconds(LONG_RUN_SECONDS)} (the bundled pet3 case's "
        f"{fmt_seconds(PROFILE_REFERENCE_SECONDS)} for 61 sectors on 2 workers, a fixed "
        "reference in `woundroll.limits`, scaled by `profile.sectors` and `profile.workers`)"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "sweep_surrogate": sweep_surrogate,
    "winding_estimate": winding_estimate,
    "long_runs": long_runs,
}
