"""Generators of the numbers in docs/web.md, docs/report.md and the prose of
docs/instruments.md (docs/scripts/regenerate.py runs them): the plotted hoop stress's
saw-tooth on the web tests' fast roll, the page's plotting code, a diagnosis sentence and the
size of a report; the Rho-meter's head and free flight, the FD model against the energy model
and its time step on tests/instruments/test_fd.py's own problems, the block's mass; all on
today's code, presets and defaults. Cost: about 30 s (one full run of ``pet1-26.7N``, its
report, one diagnosis and the Hertz calibration of the head)."""

from __future__ import annotations

import importlib.util
import math
import tomllib
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
#: the readings of the diagnosis example: the bundled sample for ``pet1-26.7N``
SAMPLE_READINGS = ROOT / "examples" / "data" / "readings_rho_3passes.csv"
#: the page's template and the comment that opens its plotting code
TEMPLATE = ROOT / "src" / "woundroll" / "app" / "web" / "templates" / "index.html"
PLOT_CODE_START = "// --- a small SVG plot"


def _web_tests() -> Any:
    """tests/web/test_api.py as a module (records.test_module): its fast roll
    (``FAST_TOML``)."""
    import records

    return records.test_module("web/test_api.py")


def _roughness(y: Any) -> float:
    """test_plots_hoop_stress_smooth_and_impact_from_contact's measure: the median
    node-to-node second difference over the plotted range."""
    import numpy as np

    y = np.asarray(y)
    return float(np.median(np.abs(np.diff(y, 2))) / (y.max() - y.min()))


@cache
def _fast_winding() -> Any:
    import woundroll

    case = woundroll.load_case(tomllib.loads(_web_tests().FAST_TOML))
    return woundroll.run(case).winding


def hoop_node_sawtooth() -> str:
    """The node values' saw-tooth on the web tests' fast roll, in % of the plotted range."""
    return f"{100 * _roughness(_fast_winding().sigma_theta):.0f} %"


def hoop_layer_mean_wiggle() -> str:
    """The same measure on the plotted layer means."""
    _, mean = _fast_winding().layer_mean_hoop_stress()
    return f"{100 * _roughness(mean):.2g} %"


def rho_release_to_contact() -> str:
    """The Rho-meter's free flight from release to first contact, t_c = arccos(-x_gap/x_in)
    / omega (woundroll.instruments.impact.impact_fd)."""
    from woundroll.instruments import get_instrument

    inst = get_instrument("rho-meter")
    t_c = math.acos(-inst.contact_position / inst.release_position) / inst.omega
    return f"{1e3 * t_c:.1f} ms"


def plot_code_lines() -> str:
    """Lines of the page's plotting JavaScript (from its opening comment to the script's
    end)."""
    text = TEMPLATE.read_text()
    start = text.index(PLOT_CODE_START)
    end = text.index("</script>", start)
    return f"{len(text[start:end].strip().splitlines())} lines"


@cache
def _diagnosis() -> Any:
    from woundroll.inverse.diagnosis import diagnose

    return diagnose("pet1-26.7N", SAMPLE_READINGS)


def diagnosis_sentence() -> str:
    """The diagnosis sentence of the bundled sample readings."""
    return f"`{_diagnosis().sentence()}`"


def report_size() -> str:
    """The size of the report of ``pet1-26.7N`` (no readings), rounded to 10 kB, and its
    figure count."""
    import woundroll
    from woundroll.app.report import build_report

    html = build_report(woundroll.run("pet1-26.7N"))
    kb = len(html.encode()) / 1e3
    figures = html.count('src="data:image/png;base64,')
    return f"has {figures} figures and is about {10 * round(kb / 10):.0f} kB"


@cache
def _script(name: str) -> Any:
    """A module of docs/scripts (instruments.py: its cached Hertz calibration)."""
    path = Path(__file__).resolve().parent / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"docs_pages_{name}", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _test_fd() -> Any:
    """tests/instruments/test_fd.py as a module (records.test_module): its springs
    (``BLOCK_LIKE``)."""
    import records

    return records.test_module("instruments/test_fd.py")


def _rho_meter() -> Any:
    from woundroll.instruments import get_instrument

    return get_instrument("rho-meter")


def rho_head_radius() -> str:
    """The bundled Rho-meter's head radius."""
    return f"{1e3 * _rho_meter().head_radius:.3f} mm"


def rho_contact_speed() -> str:
    """v_c = omega sqrt(x_in^2 - x_gap^2) of the Rho-meter."""
    inst = _rho_meter()
    v = inst.omega * math.sqrt(inst.release_position**2 - inst.contact_position**2)
    return f"{v:.4f} m/s"


def rho_contact_momentum() -> str:
    """m v_c of the Rho-meter."""
    inst = _rho_meter()
    v = inst.omega * math.sqrt(inst.release_position**2 - inst.contact_position**2)
    return f"{inst.mass * v:.4f} N s"


def column_energy_gain() -> str:
    """The kinetic energy eq. {9} creates, m_r v_c^2/2, against the striker's m_s v_c^2/2:
    m_r/m_s for the PET rolls' column mass (section 2's example)."""
    ins = _script("instruments")
    return f"+{100 * ins._column_mass() / _rho_meter().mass:.0f} %"


def fd_energy_depth() -> str:
    """test_fd_equals_energy_model_but_for_the_striker_spring_force: the largest relative
    difference of d_max between the FD and the energy model over the test's springs."""
    from woundroll.instruments import impact_energy, impact_fd

    t = _test_fd()
    springs = [t.BLOCK_LIKE, (0.0, 2e5), (5e9, 1e4), (1e7, 3e6)]
    err = max(
        abs(impact_fd(t.RM, s).max_depth / impact_energy(t.RM, s).max_depth - 1) for s in springs
    )
    return f"{err:.0e}".replace("e-0", "e-")


def fd_energy_block() -> str:
    """FD minus energy reading on the calibration block (Hertz head)."""
    cal = _script("instruments")._hertz()
    d = cal.rho_fd - cal.rho_energy
    return f"{d:.2f} Rho ({100 * d / cal.rho_fd:.1f} %)"


def paper_time_step() -> str:
    """test_time_step_convergence: the paper's dt = 1e-5 s on the test's spring, its steps
    per contact and its Rho against the converged run."""
    from woundroll.instruments import RollSpring, impact_fd

    t = _test_fd()
    spring = RollSpring.quadratic(*t.BLOCK_LIKE, effective_mass=0.019)
    ref = impact_fd(t.RM, spring, steps_per_contact=32000)
    coarse = impact_fd(t.RM, spring, time_step=1e-5)
    steps = coarse.contact_time / 1e-5
    err = abs(coarse.rho / ref.rho - 1)
    return (
        f"~{steps:.0f} steps per contact on the test's block-like spring) differs from the "
        f"finest run by {100 * err:.2g} % in Rho"
    )


def block_column_mass() -> str:
    """The tapered-column mass of the block under the Hertz head: a the Hertz half-width,
    H = the block thickness, L = the head length."""
    from woundroll.instruments.roll_side import roll_effective_mass

    ins = _script("instruments")
    cal = ins._hertz()
    block = ins._block()
    L = cal.instrument.head_length
    m = roll_effective_mass(cal.half_width, block.thickness, block.density, L)
    return (
        f"a = {1e3 * cal.half_width:.2f} mm, H = h, L = {100 * L:g} cm gives {1e3 * m:.1f} g, "
        f"{100 * m / cal.instrument.mass:.1f} % of the striker mass"
    )


def parotester_reach() -> str:
    """The contact model's reach under the Parotester's sphere (woundroll.contact.spring:
    just below half the head radius), on a roll much thicker than the sphere."""
    import numpy as np

    from woundroll.contact.spring import _model_reach
    from woundroll.instruments import get_instrument

    reach = _model_reach(get_instrument("parotester"), np.array([0.05, 0.1]))
    return f"{1e3 * reach:.3f} mm"


def energy_start() -> str:
    """The energy model's Newton start (woundroll.instruments.impact._depth_chunk):
    (d_q^-2 + d_c^-2)^-1/2 against the root over the Rho-meter and a log grid of alpha
    1e6..1e11 N/m^2, beta 1e3..1e7 N/m; and the Newton steps until a step falls below
    4e-16 d (the code's rtol) from it and from the smaller bound (the iteration restated
    here in whole arrays)."""
    import numpy as np

    from woundroll.instruments.impact import energy_max_depth

    rm = _rho_meter()
    k, xi, xg = rm.spring_stiffness, rm.release_position, rm.contact_position
    a, b = np.meshgrid(np.logspace(6, 11, 201), np.logspace(3, 7, 161))
    a, b = a.ravel(), b.ravel()
    A, B, C = 0.5 * (b + k), k * xg, 0.5 * k * (xg * xg - xi * xi)
    dq = -2 * C / (B + np.sqrt(B * B - 4 * A * C))
    dc = np.cbrt(-3 * C / a)
    d0 = (dq**-2 + dc**-2) ** -0.5
    err = float(np.max(np.abs(d0 / energy_max_depth(a, b, k, xi, xg) - 1)))

    def steps(d: Any) -> int:
        n = np.zeros(d.size, int)
        done = np.zeros(d.size, bool)
        for _ in range(60):
            s = (a * d**3 / 3 + A * d**2 + B * d + C) / (a * d**2 + 2 * A * d + B)
            d = np.where(done, d, d - s)
            n += ~done
            done |= np.abs(s) <= 4e-16 * d
            if done.all():
                break
        return int(n.max())

    return (
        f"within {100 * err:.1f} % of the root over alpha = 1e6..1e11 N/m^2, beta = 1e3..1e7 N/m"
        f" (Rho-meter), {steps(d0)} Newton steps to rounding ({steps(np.minimum(dq, dc))} from "
        "the smaller bound)"
    )


BLOCKS: dict[str, Callable[[], str]] = {
    "energy_start": energy_start,
    "rho_head_radius": rho_head_radius,
    "rho_contact_speed": rho_contact_speed,
    "rho_contact_momentum": rho_contact_momentum,
    "column_energy_gain": column_energy_gain,
    "fd_energy_depth": fd_energy_depth,
    "fd_energy_block": fd_energy_block,
    "paper_time_step": paper_time_step,
    "block_column_mass": block_column_mass,
    "parotester_reach": parotester_reach,
    "hoop_node_sawtooth": hoop_node_sawtooth,
    "hoop_layer_mean_wiggle": hoop_layer_mean_wiggle,
    "rho_release_to_contact": rho_release_to_contact,
    "plot_code_lines": plot_code_lines,
    "diagnosis_sentence": diagnosis_sentence,
    "report_size": report_size,
}
