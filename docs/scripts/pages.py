"""Generators of the numbers in docs/web.md and docs/report.md (docs/scripts/regenerate.py
runs them): the plotted hoop stress's saw-tooth on the web tests' fast roll, the Rho-meter's
free flight, the page's plotting code, a diagnosis sentence and the size of a report, all on
today's code, presets and defaults. Cost: about 30 s (one full run of ``pet1-26.7N``, its
report and one diagnosis)."""

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


@cache
def _web_tests() -> Any:
    """tests/web/test_api.py as a module: its fast roll (``FAST_TOML``)."""
    path = ROOT / "tests" / "web" / "test_api.py"
    spec = importlib.util.spec_from_file_location("docs_web_test_api", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


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


BLOCKS: dict[str, Callable[[], str]] = {
    "hoop_node_sawtooth": hoop_node_sawtooth,
    "hoop_layer_mean_wiggle": hoop_layer_mean_wiggle,
    "rho_release_to_contact": rho_release_to_contact,
    "plot_code_lines": plot_code_lines,
    "diagnosis_sentence": diagnosis_sentence,
    "report_size": report_size,
}
