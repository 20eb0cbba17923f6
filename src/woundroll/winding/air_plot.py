"""The figure of a roll wound with entrained air (:mod:`woundroll.winding.air`), drawn from
the ``air`` block of result.json (no import of the winding code: the result module draws it)."""

from __future__ import annotations

from typing import Any

import numpy as np


def plot_air(air: dict[str, Any], path: Any = None) -> Any:
    """Three panels from the ``air`` block of result.json: the diameter against the wound
    length with and without air; the pressure and the wound-in (hoop) stress of the web
    against radius, at winding and after the air has left.

    Returns a matplotlib Figure (saved as PNG at ``path`` when given)."""
    from matplotlib.figure import Figure  # pyplot-free

    fig = Figure(figsize=(7.0, 8.0), layout="constrained")
    ax_d, ax_p, ax_t = fig.subplots(3, 1)
    if "wound_length_m" in air:
        L = np.asarray(air["wound_length_m"])
        ax_d.plot(L, np.asarray(air["diameter_no_air_m"]) * 1e3, color="C0", label="without air")
        ax_d.plot(L, np.asarray(air["diameter_with_air_m"]) * 1e3, color="C3", label="with air")
        ax_d.plot(
            [L[-1]], [air["outer_diameter_after_m"] * 1e3], "o", color="C2",
            label="after the air has left",
        )  # fmt: skip
        ax_d.set_xlabel("wound length [m]")
        ax_d.legend(loc="lower right")
    ax_d.set_ylabel("diameter [mm]")
    ax_d.set_title(
        f"{air['speed_m_per_s']:g} m/s: film at lay-on {air['film_at_lay_on_m'] * 1e6:.3g} um, "
        f"{air['entrained_air_m'] * 1e6:.3g} um of air per layer"
    )
    r = np.asarray(air["air_radius_m"]) * 100.0
    ax_p.plot(r, -np.asarray(air["sigma_r_at_winding_Pa"]) / 1e3, color="C3", label="at winding")
    ax_p.plot(r, -np.asarray(air["sigma_r_after_Pa"]) / 1e3, color="C2", label="after the air left")
    ax_p.set_ylabel("pressure $-\\sigma_r$ [kPa]")
    ax_p.legend(loc="upper right")
    ax_t.plot(r, np.asarray(air["sigma_theta_at_winding_Pa"]) / 1e6, color="C3", lw=0.6,
              label="at winding")  # fmt: skip
    ax_t.plot(r, np.asarray(air["sigma_theta_after_Pa"]) / 1e6, color="C2", lw=0.6,
              label="after the air left")  # fmt: skip
    ax_t.set_ylabel("wound-in stress $\\sigma_\\theta$ [MPa]")
    ax_t.set_xlabel("radius [cm]")
    ax_t.legend(loc="best")
    for ax in (ax_d, ax_p, ax_t):
        ax.grid(alpha=0.3)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig
