"""The result of an indentation: F(d), a(d), the spring fit {3}, fields and slip factor {23}."""

from __future__ import annotations

from dataclasses import dataclass, fields
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FloatArray = NDArray[np.float64]


def fit_spring(delta: FloatArray, force: FloatArray) -> tuple[float, float, float, float]:
    """Least-squares fit of the roll spring F = alpha d^2 + beta d through the origin, {3}.

    Parameters
    ----------
    delta : ndarray
        Depths [m].
    force : ndarray
        Forces on the head [N].

    Returns
    -------
    alpha : float
        [N/m^2].
    beta : float
        [N/m].
    r2 : float
        Coefficient of determination 1 - SS_res / SS_tot, SS_tot about the mean force [-].
    max_rel_residual : float
        Largest |F_fit - F| over the points, divided by the largest |F| [-].
    """
    d = np.asarray(delta, dtype=float)
    f = np.asarray(force, dtype=float)
    A = np.stack([d * d, d], axis=1)
    # scale columns so the normal equations are well conditioned
    scale = np.array([1.0 / max(d.max(), 1e-300) ** 2, 1.0 / max(d.max(), 1e-300)])
    coef, *_ = np.linalg.lstsq(A * scale, f, rcond=None)
    alpha, beta = (coef * scale).tolist()
    fit = alpha * d * d + beta * d
    ss_res = float(np.sum((f - fit) ** 2))
    ss_tot = float(np.sum((f - f.mean()) ** 2))
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else 1.0
    fmax = float(np.max(np.abs(f)))
    max_rel = float(np.max(np.abs(f - fit)) / fmax) if fmax > 0 else 0.0
    return alpha, beta, r2, max_rel


def _readonly(a: Any) -> Any:
    if isinstance(a, np.ndarray):
        a = a.copy()
        a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class ContactResult:
    """Indentation of a roll by a rigid cylindrical head (see :func:`woundroll.contact.indent`).

    Attributes
    ----------
    delta : ndarray [m]
        Head depths, from 0 to ``depth_max``.
    force : ndarray [N]
        Total force on the head: per-length force x head length.
    force_per_length : ndarray [N/m]
        Plane-strain force per unit CMD length.
    half_width : ndarray [m]
        Semi-contact width a(d) (arc length on the undeformed surface, interpolated).
    peak_pressure : ndarray [Pa]
        Largest nodal contact pressure (nodal force / tributary arc) at each depth.
    alpha, beta : float [N/m^2], [N/m]
        Fit F = alpha d^2 + beta d of eq. {3}; ``fit_r2`` and ``fit_max_rel_residual`` its
        quality (:func:`fit_spring`).
    contact_s, contact_pressure : ndarray [m], [Pa]
        Surface-node arc coordinates and nodal contact pressures (nodal force / tributary
        arc) at the largest depth.
    element_x, element_y, element_r, element_theta : ndarray [m], [rad]
        Element centres (contact axis along +x, theta = 0).
    sigma_r : ndarray [Pa]
        Total radial stress at ``depth_max`` (pre-impact + contact), compression negative.
    sigma_r_pre : ndarray [Pa]
        Pre-impact radial stress at the element centres.
    sigma_theta, tau_r_theta : ndarray [Pa]
        Contact-induced hoop stress and r-theta shear stress at ``depth_max`` (the winding
        model's hoop stress is not added: the input profile carries sigma_r only; the
        pre-impact shear is zero in an axisymmetric roll).
    slip_factor : ndarray [-]
        In-plane part of eq. {23}: |tau_r_theta| / (mu P), P = max(-sigma_r, 0); inf where
        the layers carry shear without pressure, 0 where neither.
    """

    delta: FloatArray
    force: FloatArray
    force_per_length: FloatArray
    half_width: FloatArray
    peak_pressure: FloatArray
    alpha: float
    beta: float
    fit_r2: float
    fit_max_rel_residual: float
    contact_s: FloatArray
    contact_pressure: FloatArray
    element_x: FloatArray
    element_y: FloatArray
    element_r: FloatArray
    element_theta: FloatArray
    sigma_r: FloatArray
    sigma_r_pre: FloatArray
    sigma_theta: FloatArray
    tau_r_theta: FloatArray
    slip_factor: FloatArray
    friction: float
    head_radius: float
    head_length: float
    outer_radius: float
    update_modulus: bool
    n_elements: int
    n_dof: int
    mesh_shape: tuple[int, int]
    solve_time_s: float

    def __post_init__(self) -> None:
        for f in fields(self):
            object.__setattr__(self, f.name, _readonly(getattr(self, f.name)))

    @property
    def semi_contact_width(self) -> float:
        """Semi-contact width a at the largest depth [m] (the paper's ``a``, {14}-{18})."""
        return float(self.half_width[-1])

    @property
    def slip(self) -> NDArray[np.bool_]:
        """Elements where slip is expected, SF >= 1 (eq. {23})."""
        return self.slip_factor >= 1.0

    def slip_extent(self, window: float | None = None) -> tuple[float, float]:
        """Depth below the surface and arc half-width [m] of the SF >= 1 region near the head.

        Only elements within the arc ``|s| <= window`` of the contact axis count (default:
        three semi-contact widths), because the outermost ring, whose interlayer pressure is
        close to zero after winding, can show SF >= 1 far from the head too.
        """
        w = 3.0 * self.semi_contact_width if window is None else window
        s = self.outer_radius * np.abs(self.element_theta)
        m = self.slip & (s <= w)
        if not np.any(m):
            return 0.0, 0.0
        depth = self.outer_radius - self.element_r[m]
        return float(depth.max()), float(s[m].max())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary, SI with the unit in each key.

        Slip-factor entries cover the elements within 3 a of the contact axis; the maximum is
        over finite values, and elements sheared without any pressure (SF = inf) are counted.
        """
        depth, width = self.slip_extent()
        near = self.outer_radius * np.abs(self.element_theta) <= 3.0 * self.semi_contact_width
        sf_near = self.slip_factor[near]
        return {
            "delta_m": self.delta.tolist(),
            "force_N": self.force.tolist(),
            "force_per_length_N_per_m": self.force_per_length.tolist(),
            "half_width_m": self.half_width.tolist(),
            "peak_pressure_Pa": self.peak_pressure.tolist(),
            "alpha_N_per_m2": self.alpha,
            "beta_N_per_m": self.beta,
            "fit_r2": self.fit_r2,
            "fit_max_rel_residual": self.fit_max_rel_residual,
            "semi_contact_width_m": self.semi_contact_width,
            "max_force_N": float(self.force[-1]),
            "friction": self.friction,
            "slip_region_depth_m": depth,
            "slip_region_halfwidth_m": width,
            "max_slip_factor_near_contact": float(np.max(sf_near[np.isfinite(sf_near)],
                                                         initial=0.0)),
            "unbounded_slip_elements_near_contact": int(np.sum(np.isinf(sf_near))),
            "head_radius_m": self.head_radius,
            "head_length_m": self.head_length,
            "outer_radius_m": self.outer_radius,
            "update_modulus": self.update_modulus,
            "n_elements": self.n_elements,
            "n_dof": self.n_dof,
            "solve_time_s": self.solve_time_s,
        }

    def plot(self, path: str | Path | None = None) -> Figure:
        """F(d) with the eq. {3} fit, and a(d); saved as PNG if ``path`` is given.

        The figure is a bare :class:`matplotlib.figure.Figure` (no pyplot, the backend is
        left alone); show it in a notebook by displaying the returned object.
        """
        from matplotlib.figure import Figure

        fig = Figure(figsize=(9, 3.8), layout="constrained")
        ax1, ax2 = fig.subplots(1, 2)
        d_mm = self.delta * 1e3
        dd = np.linspace(0.0, self.delta[-1], 200)
        ax1.plot(d_mm, self.force, "o", ms=4, label="FE")
        ax1.plot(dd * 1e3, self.alpha * dd**2 + self.beta * dd, "-",
                 label=rf"$\alpha d^2+\beta d$, $R^2$={self.fit_r2:.4f}")
        ax1.set_xlabel("depth d [mm]")
        ax1.set_ylabel("force on head F [N]")
        ax1.legend()
        ax1.set_title(("updated" if self.update_modulus else "no update") + r" $E_r$")
        ax2.plot(d_mm, self.half_width * 1e3, "o-", ms=4)
        ax2.set_xlabel("depth d [mm]")
        ax2.set_ylabel("semi-contact width a [mm]")
        if path is not None:
            fig.savefig(path, dpi=120)
        return fig


def plot_slip_factor(result: ContactResult, path: str | Path | None = None, *,
                     window: float | None = None, depth: float | None = None) -> Figure:
    """Map of the slip factor {23} near the contact (log colour scale, SF = 1 contour).

    Parameters
    ----------
    result : ContactResult
    path : str or Path, optional
        PNG file to write.
    window, depth : float, optional
        Arc half-width and depth of the plotted zone [m]; default 4 a and 4 a.
    """
    from matplotlib.colors import LogNorm
    from matplotlib.figure import Figure

    a = max(result.semi_contact_width, 1e-6)
    w = 4.0 * a if window is None else window
    h = 4.0 * a if depth is None else depth
    s = result.outer_radius * result.element_theta
    z = result.outer_radius - result.element_r
    m = (np.abs(s) <= w) & (z <= h)
    sf = np.clip(result.slip_factor[m], 1e-3, 1e3)
    fig = Figure(figsize=(7, 3.8), layout="constrained")
    ax = fig.subplots()
    tri = ax.tricontourf(s[m] * 1e3, -z[m] * 1e3, sf, levels=np.logspace(-3, 3, 25),
                         norm=LogNorm(1e-3, 1e3), cmap="viridis")
    if np.nanmin(sf) < 1.0 < np.nanmax(sf):
        ax.tricontour(s[m] * 1e3, -z[m] * 1e3, sf, levels=[1.0], colors="w", linewidths=1.2)
    fig.colorbar(tri, ax=ax, label=rf"slip factor SF, $\mu$ = {result.friction:g}")
    ax.set_xlabel("arc from the contact axis [mm]")
    ax.set_ylabel("depth below surface [mm]")
    ax.set_title(f"slip factor at d = {result.delta[-1] * 1e3:.3g} mm (white: SF = 1)")
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


__all__ = ["ContactResult", "fit_spring", "plot_slip_factor"]

