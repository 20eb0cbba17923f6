"""Figures of the report: matplotlib figures as PNG data URIs, legible when printed."""

from __future__ import annotations

import base64
import io
import math
import sys
import threading
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    pass


def _png(fig: Any, dpi: int = 110) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt = sys.modules.get("matplotlib.pyplot")
    if plt is not None:  # figures made with pyplot are registered there: release them
        plt.close(fig)
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _legible(fig: Any) -> None:
    """Log axes for a printed page: labels as plain numbers (0.2, 0.5, 1, 2), the minor ones
    only at 2 and 5 and only on an axis of less than 3 decades; matplotlib's default
    ``3 x 10^-1``-style minor labels run into each other at print size."""
    from matplotlib.ticker import FuncFormatter, NullFormatter

    def plain(v: float, _pos: Any = None) -> str:
        return f"{v:g}"

    def two_five(v: float, _pos: Any = None) -> str:
        if v <= 0:
            return ""
        mant = v / 10 ** math.floor(math.log10(v) + 1e-9)
        return f"{v:g}" if round(mant, 6) in (2.0, 5.0) else ""

    for ax in fig.axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale != "log":
                continue
            lo, hi = sorted(axis.get_view_interval())
            decades = math.log10(hi / lo) if lo > 0 and hi > lo else 99.0
            if decades < 3:
                axis.set_major_formatter(FuncFormatter(plain))
                axis.set_minor_formatter(FuncFormatter(two_five))
            else:
                axis.set_minor_formatter(NullFormatter())


# pyplot keeps one global figure registry and current-figure state, which is not safe when
# two threads draw at once (the web server renders reports from its worker threads): every
# figure of a report is drawn, saved and released under this lock.
_PLOT_LOCK = threading.RLock()


def _figures(part: Any, captions: list[str]) -> list[dict[str, str]]:
    out = []
    with _PLOT_LOCK:
        figs = part.plot()
        figs = list(figs) if isinstance(figs, list | tuple) else [figs]
        for i, fig in enumerate(figs):
            _legible(fig)
            cap = captions[i] if i < len(captions) else ""
            out.append({"src": _png(fig), "caption": cap})
    return out


def storage_and_mode_figures(result: Any) -> list[dict[str, str]]:
    """The roll before and after its storage time (pressure against radius) and the wound-on
    tension against radius, for a run with ``[storage] time`` or a surface winding mode;
    none otherwise (a centre-wound roll without storage time: the winding figure says it)."""
    w = result.winding
    if w is None:
        return []
    st = w.storage or {}
    creep = "pressure_after_creep_Pa" in st
    mode = getattr(result.case.winding, "mode", "center")
    if not creep and mode == "center":
        return []
    import numpy as np
    from matplotlib.figure import Figure

    with _PLOT_LOCK:
        fig = Figure(figsize=(8.0, 3.4))
        ax1, ax2 = fig.subplots(1, 2)
        r_cm = np.asarray(w.radius) * 100
        if creep:
            ax1.plot(r_cm, np.asarray(st["pressure_wound_in_Pa"]) / 1e3, label="as wound")
            before = np.asarray(st["pressure_before_creep_Pa"])
            if not np.array_equal(before, np.asarray(st["pressure_wound_in_Pa"])):
                ax1.plot(r_cm, before / 1e3, "--", label="after the temperature/moisture change")
            days = st["storage_time_s"] / 86400
            ax1.plot(
                r_cm, np.asarray(st["pressure_after_creep_Pa"]) / 1e3, label=f"after {days:.3g} d"
            )
            ax1.legend(fontsize=8)
        else:
            ax1.plot(r_cm, -np.asarray(w.sigma_r) / 1e3)
        ax1.set_xlabel("radius [cm]")
        ax1.set_ylabel("interlayer pressure P [kPa]")
        ax2.plot(r_cm, np.asarray(w.wot) / 1e6)
        ax2.set_xlabel("radius [cm]")
        ax2.set_ylabel("wound-on tension [MPa]")
        ax2.set_title(f"winding.mode = {mode}", fontsize=9)
        fig.tight_layout()
        caption = (
            "Interlayer pressure against radius before and after storage; wound-on tension "
            "against radius."
            if creep
            else "Interlayer pressure and wound-on tension against radius."
        )
        return [{"src": _png(fig), "caption": caption}]
