"""Generators of the checks in docs/winding.md's storage and creep sections
(docs/scripts/regenerate.py runs them): each value is the measurement of a test in
tests/winding/test_storage.py or tests/winding/test_creep.py, computed on the test's own
problem (imported from the test module), beside the tolerance the test asserts. Cost: a few
seconds."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]


def _test_module(name: str) -> Any:
    """tests/winding/<name>.py as a module: the page shows the tests' own problems."""
    import records

    return records.test_module(f"winding/{name}.py")


def _fixture(fn: Any) -> Any:
    """The function behind a pytest fixture (called directly, outside pytest)."""
    for attr in ("__wrapped__", "_fixture_function"):
        if hasattr(fn, attr):
            return getattr(fn, attr)
    wrapped = getattr(fn, "__pytest_wrapped__", None)
    return wrapped.obj if wrapped is not None else fn


def _e(x: float) -> str:
    return f"{x:.1e}".replace("e-0", "e-")


def _orders(errs: list[float]) -> str:
    return ", ".join(f"{math.log2(a / b):.2f}" for a, b in zip(errs, errs[1:], strict=False))


def storage_closed_form() -> str:
    """test_linear_roll_after_storage_matches_the_closed_form: relative error of the storage
    change on the winding's own mesh."""
    t = _test_module("test_storage")
    web, core, w = _fixture(t.linear_roll)()
    _res, _c, err = t.storage_against_closed_form(web, core, w)
    return (
        f"A {w.n_layers}-layer roll with a constant E_r of 200 MPa, cooled by 20 K and wetted "
        f"by 1 %, matches it to {_e(err)}"
    )


def storage_convergence() -> str:
    """test_second_order_convergence, with 1601 nodes added."""
    t = _test_module("test_storage")
    errs = [t._error(n) for n in (101, 201, 401, 801, 1601)]
    return ", ".join(_e(e) for e in errs) + f", observed order {_orders(errs)}"


def creep_sls_annulus() -> str:
    """test_sls_annulus_tends_to_the_relaxed_elastic_annulus."""
    import numpy as np

    from woundroll.materials.creep import PronyCreep
    from woundroll.winding.creep import apply_creep

    t = _test_module("test_creep")
    c, E_r = 0.5, 2e8
    w = t.loaded_annulus(1601, E_r)
    res = apply_creep(w, t.WEB, t.CORE, PronyCreep((c,), (3600.0,)), 100 * 3600.0)
    relaxed, _ = t.annulus(w.radius, E_r / (1.0 + c))
    change = np.max(np.abs(relaxed - w.sigma_r))
    err = np.max(np.abs(res.winding.sigma_r - relaxed)) / change
    share = 100 * change / t.P_OUT
    return f"{_e(err)} of the change (the change is {share:.0f} % of the outer pressure)"


def creep_sls_layer() -> str:
    """test_single_layer_relaxes_as_the_sls_closed_form."""
    import numpy as np

    from woundroll.materials.creep import PronyCreep, relaxation

    c, tau = 0.5, 3600.0
    t = np.array([0.0, 600.0, 3600.0, 7200.0, 36000.0])
    g = relaxation(PronyCreep((c,), (tau,)), t)
    exact = 1 / (1 + c) + c / (1 + c) * np.exp(-t * (1 + c) / tau)
    return _e(float(np.max(np.abs(g - exact))))


def creep_power_layer() -> str:
    """test_single_layer_relaxes_as_the_power_law_closed_form."""
    import numpy as np
    from scipy.special import erfcx

    from woundroll.materials.creep import PowerCreep, relaxation

    tau = 3600.0
    t = np.array([0.0, 1.0, 60.0, 600.0, 3600.0, 36000.0, 360000.0, 3.6e6])
    exact = erfcx(math.gamma(1.5) * np.sqrt(t / tau))
    errs = [
        float(np.max(np.abs(relaxation(PowerCreep(0.5, tau), t, steps_per_decade=k) - exact)))
        for k in (10, 20, 40, 80)
    ]
    return f"{_e(errs[2])} at the default 40 steps per decade, orders {_orders(errs)}"


def creep_time_steps() -> str:
    """test_time_steps_converge_at_second_order."""
    import numpy as np

    from woundroll.materials.creep import PowerCreep
    from woundroll.winding.creep import apply_creep

    t = _test_module("test_creep")
    w = t.loaded_annulus(201)
    law, T = PowerCreep(0.2, 30 * 86400.0), 30 * 86400.0
    sols = {
        k: apply_creep(w, t.WEB, t.CORE, law, T, steps=k).winding.sigma_r
        for k in (10, 20, 40, 80, 320)
    }
    change = np.max(np.abs(sols[320] - w.sigma_r))
    errs = [float(np.max(np.abs(sols[k] - sols[320])) / change) for k in (10, 20, 40, 80)]
    return (
        ", ".join(_e(e) for e in errs)
        + f" of the change, observed order {_orders(errs)}. The default (40 steps) is "
        f"{_e(errs[2])}"
    )


def air_free_strain() -> str:
    """test_free_strain_solve_matches_the_annulus_closed_form, rigid and elastic core."""
    import numpy as np

    from woundroll.winding.air import _banded_increment
    from woundroll.winding.storage import closed_form_linear

    a, b, Er, Et, nu, eps = 0.038, 0.05, 5e6, 4.9e9, 0.0, -0.02
    out = []
    for core_stiffness, label in ((math.inf, "rigid core"), (2e9, "elastic core")):
        errs = []
        for n in (250, 500, 1000, 2000):
            r = np.linspace(a, b, n + 1)
            s = _banded_increment(
                r,
                np.full(r.size, Er),
                Et,
                nu,
                np.full(r.size, eps),
                core_stiffness,
                np.zeros(r.size, dtype=bool),
                np.zeros(r.size),
            )
            exact = closed_form_linear(r, a, b, Er, Et, nu, eps, 0.0, core_stiffness, 0.0)
            errs.append(float(np.max(np.abs(s - exact)) / np.max(np.abs(exact))))
        out.append(f"{label} " + ", ".join(_e(e) for e in errs) + f" (order {_orders(errs)})")
    return "; ".join(out)


def air_convergence() -> str:
    """test_roll_with_air_converges_under_refinement: core pressure at winding and after the
    air has left, subdivisions 1, 2, 4, 8."""
    from dataclasses import replace

    from woundroll.winding.air import AirSettings, wind_with_air
    from woundroll.winding.hakiel import WindingOptions

    t = _test_module("test_air")
    nipt = replace(t.TENSION, nip_load=300.0)
    air = AirSettings(speed=8.0, roughness=0.05e-6)
    pw, pa = [], []
    for ns in (1, 2, 4, 8):
        res = wind_with_air(
            t.WEB, t.CORE, t.R_OUT, nipt, air, options=WindingOptions(subdivisions=ns)
        )
        pw.append(res.at_winding.core_pressure)
        pa.append(res.after.core_pressure)
    return (
        "the core pressure at winding "
        + ", ".join(f"{p:.2f}" for p in pw)
        + " Pa and after the air has left "
        + ", ".join(f"{p:.2f}" for p in pa)
        + " Pa"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "storage_closed_form": storage_closed_form,
    "storage_convergence": storage_convergence,
    "creep_sls_annulus": creep_sls_annulus,
    "creep_sls_layer": creep_sls_layer,
    "creep_power_layer": creep_power_layer,
    "creep_time_steps": creep_time_steps,
    "air_free_strain": air_free_strain,
    "air_convergence": air_convergence,
}
