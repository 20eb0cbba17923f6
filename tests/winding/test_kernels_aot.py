"""The compiled winding kernels loaded without numba (:mod:`woundroll.winding._kernels_aot`).

They are numba's machine code (compiled once per machine with ``error_model="numpy"``,
loaded with llvmlite): the winding must be bit for bit that of numba's dispatcher, with the
same iteration and work counts, and a large roll must not import numba once the code is
cached.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from woundroll.materials import Core, Pfeiffer, Web
from woundroll.winding import _kernels, _kernels_aot, hakiel
from woundroll.winding.hakiel import WindingOptions, wind
from woundroll.winding.tension import Taper, TensionSchedule

ENGINE_OPTIONS = [
    {},
    {"new_layer": "elastic"},
    {"modulus_update": "end", "load_substeps": 3},
    {"modulus_update": "explicit", "layers_per_increment": 3},
    {"window_layers": 4, "flush_interval": 2, "subdivisions": 3},
    {"window_layers": None},
]


def _film() -> Web:
    return Web(thickness=12e-6, width=1.0, E_theta=5e9, radial_modulus=Pfeiffer(10e3, 100.0))


@pytest.mark.parametrize("extra", ENGINE_OPTIONS)
def test_loaded_kernels_equal_numba_dispatcher(extra: dict, monkeypatch) -> None:
    """Same machine code, same arithmetic: equal bit for bit (tolerance 0)."""
    aot = _kernels_aot.load()
    assert aot is not None, "llvmlite could not load the compiled kernels"
    web, core = _film(), Core(0.076, stiffness=3e9)
    R, sched = 0.076 + 1500 * 12e-6, TensionSchedule(1.5e6, taper=Taper("linear", 0.3))
    opts = WindingOptions(**extra)
    monkeypatch.setattr(hakiel, "_NUMPY_MAX_NODES", 0)
    monkeypatch.setattr(hakiel, "_kernels_for", lambda n, o: aot)
    a = wind(web, core, R, sched, options=opts)
    monkeypatch.setattr(hakiel, "_kernels_for", lambda n, o: _kernels)
    b = wind(web, core, R, sched, options=opts)
    np.testing.assert_array_equal(a.sigma_r, b.sigma_r)
    np.testing.assert_array_equal(a.sigma_theta, b.sigma_theta)
    assert a.stats == b.stats


def test_large_roll_does_not_import_numba() -> None:
    """Above ``_NUMPY_MAX_NODES`` the cached machine code is loaded by llvmlite alone
    (numba's import is 0.5 s or more; docs/performance.md). Fresh interpreter."""
    assert _kernels_aot.load() is not None  # builds the cache if missing
    code = (
        "import sys\n"
        "from woundroll.materials import Core, Pfeiffer, Web\n"
        "from woundroll.winding.hakiel import wind\n"
        "from woundroll.winding.tension import TensionSchedule\n"
        "web = Web(thickness=12e-6, width=1.0, E_theta=5e9, radial_modulus=Pfeiffer(1e4, 100))\n"
        "r = wind(web, Core(0.076), 0.076 + 10000 * 12e-6, TensionSchedule(1.5e6))\n"
        "assert r.n_layers == 10000 and r.core_pressure > 0\n"
        "print('numba' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
