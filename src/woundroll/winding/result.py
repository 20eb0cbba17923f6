"""The result of a 1D winding computation: stresses and moduli from the core outward."""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

_COLUMNS = (
    ("radius", "radius_m", "radius [m]"),
    ("sigma_r", "sigma_r_Pa", "sigma_r [Pa]"),
    ("sigma_theta", "sigma_theta_Pa", "sigma_theta [Pa]"),
    ("E_r", "E_r_Pa", "E_r [Pa]"),
    ("wot", "wound_on_tension_Pa", "wound-on tension [Pa]"),
)


@dataclass(frozen=True, eq=False)
class WindingResult:
    """Stresses in a center-wound roll, per node from the core (index 0) to the surface.

    Nodes are the layer interfaces plus any sub-layer nodes; a node carries the stresses of
    the layer it is the inner face of (the outermost node: of the last layer). The hoop
    stress jumps from layer to layer (each layer is wound on stretched), the radial stress
    is continuous.

    Attributes
    ----------
    radius : ndarray [m]
    sigma_r : ndarray [Pa]
        Radial stress, compression negative; ``sigma_r[-1] = 0`` (free surface).
    sigma_theta : ndarray [Pa]
        Hoop (MD) stress.
    E_r : ndarray [Pa]
        Radial tangent modulus at the final pressure (floored, see ``docs/winding.md``).
    wot : ndarray [Pa]
        Wound-on tension of the layer the node belongs to.
    core_pressure : float [Pa]
        ``-sigma_r`` at the core surface.
    n_layers : int
        Number of layers wound.
    inputs : dict
        SI summary of web, core and tension schedule.
    options : dict
        The numerical options used.
    stats : dict
        Solver statistics (increments, largest number of iterations in an increment).
    """

    radius: FloatArray
    sigma_r: FloatArray
    sigma_theta: FloatArray
    E_r: FloatArray
    wot: FloatArray
    core_pressure: float
    n_layers: int
    inputs: dict[str, Any] = field(default_factory=dict)
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, Any] = field(default_factory=dict)
    #: the change after winding (:mod:`woundroll.winding.storage`), when one was applied
    storage: dict[str, Any] | None = None
    #: the roll wound with entrained air (:mod:`woundroll.winding.air`), when speed > 0
    air: dict[str, Any] | None = None

    @property
    def pressure(self) -> FloatArray:
        """Interlayer pressure ``P = -sigma_r`` [Pa]."""
        return -self.sigma_r

    def layer_mean_hoop_stress(self) -> tuple[FloatArray, FloatArray]:
        """Mid radius [m] and mean hoop stress [Pa] of each layer, from equilibrium.

        ``mean sigma_theta = (F_outer - F_inner) / h`` with ``F = r sigma_r`` (equilibrium
        sigma_theta = d(r sigma_r)/dr integrated over the layer). Within a layer the hoop
        stress falls outward (the increments of the layers above grow toward them), so the
        node values show a saw-tooth of layer period; this is its smooth part.
        """
        ns = (self.radius.size - 1) // self.n_layers
        idx = np.arange(0, self.radius.size, ns)
        F = self.radius[idx] * self.sigma_r[idx]
        r = self.radius[idx]
        return 0.5 * (r[1:] + r[:-1]), np.diff(F) / np.diff(r)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: profiles as lists (SI, units in the key names) and scalars."""
        out: dict[str, Any] = {key: getattr(self, attr).tolist() for attr, key, _ in _COLUMNS}
        out.update(
            core_pressure_Pa=float(self.core_pressure),
            n_layers=int(self.n_layers),
            n_nodes=int(self.radius.size),
            outer_radius_m=float(self.radius[-1]),
            max_pressure_Pa=float(np.max(-self.sigma_r)),
            inputs=self.inputs,
            options=self.options,
            stats=self.stats,
        )
        if self.storage is not None:
            out["storage"] = self.storage
        if self.air is not None:
            out["air"] = self.air
        return out

    def to_table(self) -> str:
        """CSV text, one row per node, units in the header."""
        buf = io.StringIO()
        data = np.column_stack([getattr(self, attr) for attr, _, _ in _COLUMNS])
        np.savetxt(
            buf,
            data,
            delimiter=",",
            fmt="%.9g",
            header=",".join(h for _, _, h in _COLUMNS),
            comments="",
        )
        return buf.getvalue()

    def plot(self, path: str | Path | None = None) -> Any:
        """Three panels against radius [cm]: sigma_r [kPa], sigma_theta [kPa], E_r [MPa].

        sigma_r has its own panel: the radial pressure (tens of kPa) is one to two orders of
        magnitude below the hoop stress (MPa) and would sit flat near zero on a shared axis.

        Parameters
        ----------
        path : str or Path, optional
            Save a PNG there.

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure  # pyplot-free: no GUI backend is touched

        fig = Figure(figsize=(7.0, 8.0), layout="constrained")
        ax_r, ax_t, ax_e = fig.subplots(3, 1, sharex=True)
        rc = self.radius * 100.0
        rm, st_mean = self.layer_mean_hoop_stress()
        ax_r.plot(rc, self.sigma_r / 1e3, color="C0", label=r"$\sigma_r$")
        ax_r.axhline(0.0, color="0.6", lw=0.5)
        ax_r.set_ylabel(r"radial stress $\sigma_r$ [kPa]")
        ax_r.legend(loc="lower right")
        ax_r.set_title(f"{self.n_layers} layers, core pressure {self.core_pressure / 1e3:.1f} kPa")
        ax_t.plot(
            rc,
            self.sigma_theta / 1e3,
            color="C1",
            lw=0.4,
            alpha=0.4,
            label=r"$\sigma_\theta$ (nodes)",
        )
        ax_t.plot(rm * 100.0, st_mean / 1e3, color="C1", label=r"$\sigma_\theta$ (layer mean)")
        # the tension each layer was wound on with (taper, nip, winding mode), beside what is
        # left of it in the roll
        ax_t.plot(rc, self.wot / 1e3, color="C3", ls="--", label="wound-on tension (WOT)")
        ax_t.axhline(0.0, color="0.6", lw=0.5)
        ax_t.set_ylabel(r"hoop stress $\sigma_\theta$ [kPa]")
        ax_t.legend(loc="best")
        ax_e.plot(rc, self.E_r / 1e6, color="C2")
        ax_e.set_ylabel(r"$E_r$ [MPa]")
        ax_e.set_xlabel("radius [cm]")
        for ax in (ax_r, ax_t, ax_e):
            ax.grid(alpha=0.3)
        if path is not None:
            fig.savefig(path, dpi=120)
        if self.air is not None:  # and the roll wound with entrained air
            from woundroll.winding.air_plot import plot_air

            p = None if path is None else Path(path).with_name(Path(path).stem + "_air.png")
            return [fig, plot_air(self.air, p)]
        return fig
