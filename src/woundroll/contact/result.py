"""The result of an indentation: F(d), a(d), the spring fit {3}, fields and slip factor {23}."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from woundroll.errors import InputError
from woundroll.units import to_si

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


def slip_factor(tau_r_theta: FloatArray, sigma_r: FloatArray, friction: float) -> FloatArray:
    """In-plane slip factor of eq. {23}: SF = |tau_r_theta| / (mu P), P = max(-sigma_r, 0).

    Parameters
    ----------
    tau_r_theta : ndarray
        Shear stress [Pa].
    sigma_r : ndarray
        Total radial stress [Pa], compression negative.
    friction : float
        Interlayer friction coefficient mu [-].

    Returns
    -------
    ndarray
        SF [-]; inf where shear acts without pressure (or mu = 0), 0 where neither.
    """
    tau = np.abs(np.asarray(tau_r_theta, dtype=float))
    capacity = friction * np.maximum(-np.asarray(sigma_r, dtype=float), 0.0)  # Coulomb [Pa]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(capacity > 0, tau / capacity, np.where(tau > 0, np.inf, 0.0))


def _slip_extent(
    slip: NDArray[np.bool_],
    element_r: FloatArray,
    element_theta: FloatArray,
    outer_radius: float,
    window: float,
) -> tuple[float, float]:
    s = outer_radius * np.abs(element_theta)
    m = slip & (s <= window)
    if not np.any(m):
        return 0.0, 0.0
    depth = outer_radius - element_r[m]
    return float(depth.max()), float(s[m].max())


def _readonly(a: Any) -> Any:
    if isinstance(a, np.ndarray):
        a = a.copy()
        a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class ContactState:
    """The fields under the head at one depth ``d`` (:meth:`ContactResult.at_depth`).

    Between two computed increments every quantity is interpolated linearly in ``d``; the slip
    factor is then recomputed from the interpolated stresses (eq. {23}), not interpolated.

    Attributes
    ----------
    depth : float [m]
        Head depth d.
    force : float [N]
        Force on the head at d.
    half_width : float [m]
        Semi-contact width a(d).
    sigma_r : ndarray [Pa]
        Total radial stress (pre-impact + contact) at the element centres.
    sigma_theta, tau_r_theta : ndarray [Pa]
        Contact-induced hoop and r-theta shear stress.
    slip_factor : ndarray [-]
        In-plane slip factor {23} from these stresses (:func:`slip_factor`).
    contact_pressure : ndarray [Pa]
        Nodal contact pressures at the surface nodes (``ContactResult.contact_s``).
    friction : float [-]
    element_r, element_theta : ndarray [m], [rad]
        Element centres (as in the result).
    outer_radius : float [m]
    """

    depth: float
    force: float
    half_width: float
    sigma_r: FloatArray
    sigma_theta: FloatArray
    tau_r_theta: FloatArray
    slip_factor: FloatArray
    contact_pressure: FloatArray
    friction: float
    element_r: FloatArray
    element_theta: FloatArray
    outer_radius: float

    def __post_init__(self) -> None:
        for f in fields(self):
            object.__setattr__(self, f.name, _readonly(getattr(self, f.name)))

    @property
    def semi_contact_width(self) -> float:
        """Semi-contact width a at this depth [m] (the paper's ``a``, {14}-{18})."""
        return float(self.half_width)

    @property
    def slip(self) -> NDArray[np.bool_]:
        """Elements where slip is expected at this depth, SF >= 1 (eq. {23})."""
        return self.slip_factor >= 1.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary at this depth: force, a, pressures, slip region {23}."""
        depth, width = self.slip_extent()
        near = self.outer_radius * np.abs(self.element_theta) <= 3.0 * self.half_width
        sf = self.slip_factor[near]
        return {
            "depth_m": self.depth,
            "force_N": self.force,
            "semi_contact_width_m": self.half_width,
            "max_contact_pressure_Pa": float(np.max(self.contact_pressure, initial=0.0)),
            "max_radial_pressure_Pa": float(np.max(-self.sigma_r, initial=0.0)),
            "friction": self.friction,
            "slip_region_depth_m": depth,
            "slip_region_halfwidth_m": width,
            "max_slip_factor_near_contact": float(np.max(sf[np.isfinite(sf)], initial=0.0)),
            "unbounded_slip_elements_near_contact": int(np.sum(np.isinf(sf))),
        }

    def slip_extent(self, window: float | None = None) -> tuple[float, float]:
        """Depth below the surface and arc half-width [m] of the SF >= 1 region within the
        arc ``|s| <= window`` of the contact axis (default: three semi-contact widths at
        this depth); see :meth:`ContactResult.slip_extent`."""
        w = 3.0 * self.half_width if window is None else window
        return _slip_extent(self.slip, self.element_r, self.element_theta, self.outer_radius, w)


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
    sigma_r_history, sigma_theta_history, tau_r_theta_history : ndarray (n_steps + 1, n_el) [Pa]
        The same three stress fields at every computed depth ``delta[k]`` (row 0: before
        contact; the last row equals ``sigma_r``, ``sigma_theta``, ``tau_r_theta``). Use
        :meth:`at_depth` for the fields at any depth.
    contact_pressure_history : ndarray (n_steps + 1, n_surface_nodes) [Pa]
        ``contact_pressure`` at every computed depth.
    surface_deflection_history : ndarray (n_steps + 1, n_surface_nodes) [m] or None
        Inward radial displacement -u_r of the surface nodes (at ``contact_s``) at every
        computed depth (2D model; the CMD-spreading correction reads the deflection basin
        from it, :mod:`woundroll.contact.plane_strain.cmd_spread`).
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
    sigma_r_history: FloatArray
    sigma_theta_history: FloatArray
    tau_r_theta_history: FloatArray
    contact_pressure_history: FloatArray
    friction: float
    head_radius: float
    head_length: float
    outer_radius: float
    update_modulus: bool
    n_elements: int
    n_dof: int
    mesh_shape: tuple[int, int]
    solve_time_s: float
    factorisations: int = 0
    #: elements with reduced shear at depth_max (slip emulation, Figure 19); None: off
    slipped: NDArray[np.bool_] | None = None
    #: increments' slip-zone passes in all (slip emulation)
    slip_passes: int = 0
    surface_deflection_history: FloatArray | None = None

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
        return _slip_extent(self.slip, self.element_r, self.element_theta, self.outer_radius, w)

    def at_depth(self, depth: float | str) -> ContactState:
        """Stress fields, slip factor {23}, slip region and semi-contact width at depth ``d``.

        The increments are stored at the depths ``delta``; at one of them the state is that
        increment's exactly (at ``depth_max`` it equals ``sigma_r``, ``slip_factor``,
        ``semi_contact_width``, ...), in between every field is interpolated linearly in d
        and the slip factor recomputed from the interpolated stresses. Use it for the fields
        at the impact's maximum depth, which is below ``depth_max``.

        Parameters
        ----------
        depth : float or str
            Head depth [m] in ``[0, delta[-1]]`` (a string with a unit, ``"0.8 mm"``, works).

        Raises
        ------
        InputError
            ``depth`` not a finite number in ``[0, depth_max]`` (field ``depth``).
        """
        if isinstance(depth, bool):
            raise InputError(f"must be a number, got {depth!r}", "depth")
        if isinstance(depth, str):
            d = to_si(depth, "length", "depth")
        else:
            try:
                d = float(depth)
            except (TypeError, ValueError):
                raise InputError(f"must be a number, got {depth!r}", "depth") from None
        d_max = float(self.delta[-1])
        if not (math.isfinite(d) and 0.0 <= d <= d_max):
            raise InputError(f"must lie in [0, depth_max = {d_max:g} m], got {depth!r}", "depth")
        k = int(np.searchsorted(self.delta, d, side="left"))
        if self.delta[k] == d:  # a computed increment: its values exactly

            def at(a: FloatArray) -> Any:
                return a[k]
        else:  # delta[k - 1] < d < delta[k]
            w = (d - self.delta[k - 1]) / (self.delta[k] - self.delta[k - 1])

            def at(a: FloatArray) -> Any:
                return (1.0 - w) * a[k - 1] + w * a[k]

        sigma_r = at(self.sigma_r_history)
        tau = at(self.tau_r_theta_history)
        return ContactState(
            depth=d,
            force=float(at(self.force)),
            half_width=float(at(self.half_width)),
            sigma_r=sigma_r,
            sigma_theta=at(self.sigma_theta_history),
            tau_r_theta=tau,
            slip_factor=slip_factor(tau, sigma_r, self.friction),
            contact_pressure=at(self.contact_pressure_history),
            friction=self.friction,
            element_r=self.element_r,
            element_theta=self.element_theta,
            outer_radius=self.outer_radius,
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary, SI with the unit in each key.

        Slip-factor entries cover the elements within 3 a of the contact axis; the maximum is
        over finite values, and elements sheared without any pressure (SF = inf) are counted.
        """
        last = self.at_depth(float(self.delta[-1])).to_dict()  # the fields at depth_max
        return {
            "depth_m": self.delta.tolist(),
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
            **{
                key: last[key]
                for key in (
                    "friction",
                    "slip_region_depth_m",
                    "slip_region_halfwidth_m",
                    "max_slip_factor_near_contact",
                    "unbounded_slip_elements_near_contact",
                )
            },
            "head_radius_m": self.head_radius,
            "head_length_m": self.head_length,
            "outer_radius_m": self.outer_radius,
            "update_modulus": self.update_modulus,
            "n_elements": self.n_elements,
            "n_dof": self.n_dof,
            "solve_time_s": self.solve_time_s,
            "factorisations": self.factorisations,
            **(
                {}
                if self.slipped is None
                else {
                    "slipped_elements": int(np.count_nonzero(self.slipped)),
                    "slip_passes": self.slip_passes,
                }
            ),
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
        ax1.plot(
            dd * 1e3,
            self.alpha * dd**2 + self.beta * dd,
            "-",
            label=rf"$\alpha d^2+\beta d$, $R^2$={self.fit_r2:.4f}",
        )
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


def plot_slip_factor(
    result: ContactResult | ContactState,
    path: str | Path | None = None,
    *,
    window: float | None = None,
    depth: float | None = None,
) -> Figure:
    """Map of the slip factor {23} near the contact (log colour scale, SF = 1 contour).

    Parameters
    ----------
    result : ContactResult or ContactState
        The fields at the largest depth, or at any depth (:meth:`ContactResult.at_depth`).
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
    tri = ax.tricontourf(
        s[m] * 1e3,
        -z[m] * 1e3,
        sf,
        levels=np.logspace(-3, 3, 25),
        norm=LogNorm(1e-3, 1e3),
        cmap="viridis",
    )
    if np.nanmin(sf) < 1.0 < np.nanmax(sf):
        ax.tricontour(s[m] * 1e3, -z[m] * 1e3, sf, levels=[1.0], colors="w", linewidths=1.2)
    fig.colorbar(tri, ax=ax, label=rf"slip factor SF, $\mu$ = {result.friction:g}")
    ax.set_xlabel("arc from the contact axis [mm]")
    ax.set_ylabel("depth below surface [mm]")
    head_depth = result.depth if isinstance(result, ContactState) else float(result.delta[-1])
    ax.set_title(f"slip factor at d = {head_depth * 1e3:.3g} mm (white: SF = 1)")
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


__all__ = ["ContactResult", "ContactState", "fit_spring", "plot_slip_factor", "slip_factor"]
