"""The axisymmetric winding against stored answers of an earlier revision: a guard for
same-answer speed-ups of the FE kernel (``winding/_axisym_fe.py``, docs/performance.md).

``data/axisym_reference.npz`` holds sigma_r (groups x sectors) and the core pressure of the
cases below, computed by the kernel as it was at commit 83d4856 (before the speed-ups of
issue 14 item 3: closed-form material inverse, one batched product for the radial
integrals, LAPACK ``pbtrf`` called directly). Regenerate it only on purpose, with
``PYTHONPATH=<old src> python tests/winding/test_axisym_reference.py --write``.

Tolerance 1e-9 relative (of the largest |sigma_r| of the case, and of each core pressure):
the speed-ups only reorder floating-point operations, which moves the answers by ~1e-13
(measured 6.5e-14 of the peak on the Table 3 case, 400 groups); 1e-9 leaves room for BLAS
and platform round-off while any change of the scheme (window, levels, tolerances, shape
functions, quadrature) moves them by > 1e-6.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from woundroll.materials.radial_modulus import Pfeiffer
from woundroll.materials.thickness_profile import bundled_profile
from woundroll.materials.web import Core, Web
from woundroll.winding.axisymmetric import wind_axisymmetric
from woundroll.winding.tension import TensionSchedule

REF = Path(__file__).resolve().parent / "data" / "axisym_reference.npz"
RTOL = 1e-9

WEB = Web(  # Table 3
    thickness=76e-6,
    width=0.61,
    E_theta=4999e6,
    E_z=4999e6,
    radial_modulus=Pfeiffer(0.0, 246.5),
    nu_theta_r=0.01,
    nu_z_r=0.01,
    nu_theta_z=0.3,
)
TUBE = Core.tube(0.1016, 0.095, 69e9, 0.33)
RIGID = Core(0.1016, math.inf)

# (name, core, keyword arguments): the default lazy deep part in levels, the single frozen
# stack, the whole stack every increment with linear shapes on a rigid core
CASES = [
    ("levels", TUBE, {}),
    ("single", TUBE, {"levels": False}),
    ("linear_rigid", RIGID, {"shape": "linear", "window": None}),
]


def run(core: Core, kw: dict) -> tuple[np.ndarray, np.ndarray]:
    w = wind_axisymmetric(
        WEB,
        core,
        0.2032,
        TensionSchedule(web_stress=2.3e6),
        bundled_profile(),
        n_sectors=9,
        n_groups=60,
        **kw,
    )
    return w.sigma_r, w.core_pressure


@pytest.mark.parametrize(("name", "core", "kw"), CASES, ids=[c[0] for c in CASES])
def test_same_answers_as_stored_reference(name, core, kw):
    ref = np.load(REF)
    s_r, p_c = run(core, kw)
    s_ref, p_ref = ref[f"{name}_sigma_r"], ref[f"{name}_core"]
    assert s_r.shape == s_ref.shape
    assert np.max(np.abs(s_r - s_ref)) <= RTOL * np.max(np.abs(s_ref))
    np.testing.assert_allclose(p_c, p_ref, rtol=RTOL, atol=0)


if __name__ == "__main__" and "--write" in sys.argv:
    out = {}
    for name, core, kw in CASES:
        out[f"{name}_sigma_r"], out[f"{name}_core"] = run(core, kw)
    np.savez_compressed(REF, **out)
    print(f"wrote {REF}")
