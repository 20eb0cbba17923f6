"""Fitting radial-modulus laws to a stack test (pressure against compressive strain).

A stack test compresses a pile of web sheets and records the pressure ``P`` against the
strain ``eps``. Each law of :mod:`woundroll.materials.radial_modulus` implies a stack
curve; the fit finds its parameters. Stack data span decades of pressure, and relative
errors are what matter for E_r, so the curved laws are fitted in relative terms.

``pfeiffer``
    P = K1 (exp(K2 eps) - 1) (integral of {2}); nonlinear least squares on log P
    (Levenberg-Marquardt in log K1, log K2). Start: K2 = slope of a straight-line fit of
    log P against eps over the upper half of the strains (where exp(K2 eps) >> 1, so
    log P ~ log K1 + K2 eps), at least 1; K1 = median of ``P / (exp(K2 eps) - 1)`` over the
    points with that K2.
``polynomial``
    P = C1 eps + C2 eps^2 + C3 eps^3 (Hakiel 1987); linear least squares on the relative
    error ``(P_fit - P)/P``, **constrained** to ``C1 > 0, C2 >= 0, C3 >= 0`` (bounded-variable
    least squares, ``scipy.optimize.lsq_linear(method="bvls")`` on scaled columns). Non-negative
    coefficients make ``dP/deps = C1 + 2 C2 eps + 3 C3 eps^2 > 0`` for every eps >= 0, so the
    fitted law is always a stiffening curve (an unconstrained fit can return a negative
    coefficient and a curve that softens inside the data range). ``C1`` has the lower bound
    ``1e-9 max(P)/max(eps)`` so that E_r(0) > 0. A cubic cannot follow an exponential stack
    curve over several decades of pressure: check R^2 and the relative errors.
``constant``
    P = E_r eps, linear least squares through the origin.

Quality reported: R^2 of P, RMS and maximum relative error of P over the points with
P > 0.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import least_squares, lsq_linear

from woundroll.errors import ConvergenceError, InputError
from woundroll.materials.radial_modulus import Constant, Pfeiffer, Polynomial, RadialModulusLaw

FIT_LAWS = ("pfeiffer", "polynomial", "constant")


@dataclass(frozen=True)
class StackFit:
    """A fitted law and how well it fits the stack data."""

    law: RadialModulusLaw
    r2: float
    rms_rel_error: float
    max_rel_error: float
    n_points: int
    strain_max: float
    pressure_max: float
    #: Covariance of the fitted parameters (Pfeiffer: K1 [Pa], K2 [-]) from the
    #: least-squares Jacobian at the optimum, ``s^2 (J^T J)^-1`` in (ln K1, ln K2) mapped
    #: to (K1, K2); None for laws fitted without it.
    covariance: tuple[tuple[float, ...], ...] | None = None

    def uncertainty(self) -> dict[str, float] | None:
        """SDs and correlation of K1, K2 (Pfeiffer) for the case's ``[uncertainty]``."""
        if self.covariance is None:
            return None
        c = np.asarray(self.covariance)
        sd = np.sqrt(np.diag(c))
        rho = float(c[0, 1] / (sd[0] * sd[1])) if sd[0] > 0 and sd[1] > 0 else 0.0
        return {"K1_sd_Pa": float(sd[0]), "K2_sd": float(sd[1]), "K1_K2_correlation": rho}

    def uncertainty_toml(self) -> str:
        """The ``[uncertainty]`` lines for K1, K2 (empty without a covariance)."""
        u = self.uncertainty()
        if u is None:
            return ""
        return (
            f'K1 = "{u["K1_sd_Pa"] / 1e3:.4g} kPa"\nK2 = {u["K2_sd"]:.4g}\n'
            f"K1_K2_correlation = {u['K1_K2_correlation']:.4f}"
        )

    def to_dict(self) -> dict[str, Any]:
        extra: dict[str, Any] = {}
        if self.covariance is not None:
            extra = {"covariance": [list(r) for r in self.covariance], **self.uncertainty()}
        return {
            **extra,
            **self.law.to_dict(),
            "r2": self.r2,
            "rms_rel_error": self.rms_rel_error,
            "max_rel_error": self.max_rel_error,
            "n_points": self.n_points,
            "strain_max": self.strain_max,
            "pressure_max_Pa": self.pressure_max,
        }

    def toml(self) -> str:
        """The case-file inline table for ``web.radial_modulus``."""
        d = self.law.to_dict()
        if d["law"] == "pfeiffer":
            return f'{{ law = "pfeiffer", K1 = "{d["K1_Pa"] / 1e3:.6g} kPa", K2 = {d["K2"]:.6g} }}'
        if d["law"] == "constant":
            return f'{{ law = "constant", E_r = "{d["E_r_Pa"] / 1e6:.6g} MPa" }}'
        return (
            f'{{ law = "polynomial", C1 = "{d["C1_Pa"]:.6g} Pa", C2 = "{d["C2_Pa"]:.6g} Pa", '
            f'C3 = "{d["C3_Pa"]:.6g} Pa", strain_max = {d["strain_max"]:.4g} }}'
        )


def _check(strain: ArrayLike, pressure: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    eps = np.asarray(strain, dtype=float)
    p = np.asarray(pressure, dtype=float)
    if eps.ndim != 1 or eps.shape != p.shape:
        raise InputError("strain and pressure must be 1-D arrays of equal length", "stack")
    if eps.size < 3:
        raise InputError(f"needs at least 3 points, got {eps.size}", "stack")
    if not (np.all(np.isfinite(eps)) and np.all(np.isfinite(p))):
        raise InputError("strain and pressure must be finite numbers", "stack")
    if np.any(eps < 0) or np.any(p < 0):
        raise InputError("strain and pressure must be >= 0 (compression positive)", "stack")
    if np.count_nonzero(p > 0) < 3:
        raise InputError("needs at least 3 points with positive pressure", "stack")
    order = np.argsort(eps, kind="stable")
    e_s, p_s = eps[order], p[order]
    if not p_s[-1] > p_s[0]:
        raise InputError(
            "the pressure does not rise with the strain (constant or falling): a stack test's "
            "pressure rises as the stack is compressed; check the columns and their order",
            "stack",
        )
    if np.any(np.diff(p_s) < -1e-3 * p_s.max()):
        i = int(np.argmax(np.diff(p_s) < -1e-3 * p_s.max()))
        raise InputError(
            f"the pressure falls from {p_s[i]:.4g} Pa to {p_s[i + 1]:.4g} Pa between strains "
            f"{e_s[i]:.4g} and {e_s[i + 1]:.4g}: a loading curve rises monotonically (give the "
            "loading branch only)",
            "stack",
        )
    return eps, p


def check_stack_data(strain: ArrayLike, pressure: ArrayLike) -> None:
    """Raise :class:`InputError` (field ``stack``) unless the data can be fitted: at least 3
    finite points, non-negative, pressure rising with strain (every law's curve rises)."""
    _check(strain, pressure)


def _quality(law: RadialModulusLaw, eps: np.ndarray, p: np.ndarray) -> StackFit:
    model = law.pressure(eps)
    ss_res = float(np.sum((model - p) ** 2))
    ss_tot = float(np.sum((p - p.mean()) ** 2))
    pos = p > 0
    rel = np.abs(model[pos] - p[pos]) / p[pos]
    return StackFit(
        law,
        1.0 - ss_res / ss_tot if ss_tot > 0 else float("nan"),
        float(np.sqrt(np.mean(rel**2))),
        float(rel.max()),
        int(eps.size),
        float(eps.max()),
        float(p.max()),
    )


def _fit_polynomial(eps: np.ndarray, p: np.ndarray) -> np.ndarray:
    """(C1, C2, C3) minimising the relative error, non-negative (module docstring)."""
    pos = p > 0
    A = np.column_stack([eps, eps**2, eps**3])[pos] / p[pos, None]
    scale = np.abs(A).max(axis=0)
    scale = np.where(scale > 0, scale, 1.0)  # all-zero column (eps = 0 only): keep it at 0
    lower = np.array([1e-9 * p.max() / eps.max(), 0.0, 0.0])
    sol = lsq_linear(
        A / scale,
        np.ones(A.shape[0]),
        bounds=(lower * scale, np.inf),
        method="bvls",
        tol=1e-15,
    )
    if sol.status < 1 or not np.all(np.isfinite(sol.x)):
        raise ConvergenceError(f"polynomial stack fit did not converge: {sol.message}")
    return np.maximum(sol.x / scale, lower)


def fit_stack(strain: ArrayLike, pressure: ArrayLike, law: str = "pfeiffer") -> StackFit:
    """Fit ``law`` to stack-test data.

    Parameters
    ----------
    strain : array [-]
        Compressive strain (positive).
    pressure : array [Pa]
        Stack pressure at each strain.
    law : {"pfeiffer", "polynomial", "constant"}

    Returns
    -------
    StackFit
    """
    eps, p = _check(strain, pressure)
    if law == "constant":
        E = float(np.dot(eps, p) / np.dot(eps, eps))
        return _quality(Constant(E), eps, p)
    if law == "polynomial":
        c = _fit_polynomial(eps, p)
        try:
            fitted = Polynomial(C1=c[0], C2=c[1], C3=c[2], strain_max=float(min(eps.max(), 0.99)))
        except InputError as exc:
            raise InputError(
                f"the fitted polynomial is not a stiffening curve ({exc.message})", "stack"
            ) from None
        return _quality(fitted, eps, p)
    if law != "pfeiffer":
        raise InputError(f"cannot fit law {law!r}; choose one of {', '.join(FIT_LAWS)}", "law")

    pos = (p > 0) & (eps > 0)
    e_pos, p_pos = eps[pos], p[pos]
    # Start: K2 from the slope of log P at high strain, K1 from the low-strain secant.
    hi = e_pos >= np.median(e_pos)
    k2_0 = max(np.polyfit(e_pos[hi], np.log(p_pos[hi]), 1)[0], 1.0)
    k1_0 = max(float(np.median(p_pos / np.expm1(k2_0 * e_pos))), 1e-6 * p_pos.max())

    def resid(x: np.ndarray) -> np.ndarray:
        k1, k2 = np.exp(x)
        return np.log(k1 * np.expm1(k2 * e_pos)) - np.log(p_pos)

    sol = least_squares(resid, np.log([k1_0, k2_0]), method="lm", x_scale="jac")
    if not sol.success or not np.all(np.isfinite(sol.x)):
        raise ConvergenceError(f"Pfeiffer stack fit did not converge: {sol.message}")
    k1, k2 = (float(v) for v in np.exp(sol.x))
    fit = _quality(Pfeiffer(K1=k1, K2=k2), eps, p)
    return replace(fit, covariance=_log_covariance(sol, np.exp(sol.x)))


def _log_covariance(sol: Any, k: np.ndarray) -> tuple[tuple[float, ...], ...] | None:
    """Covariance of K from a least-squares fit in ln K: ``D s^2 (J^T J)^-1 D``, D = diag(K),
    s^2 the residual variance with n - 2 degrees of freedom (first order, Gauss-Newton)."""
    J = np.asarray(sol.jac, dtype=float)
    dof = J.shape[0] - J.shape[1]
    if dof <= 0:
        return None
    s2 = float(np.sum(sol.fun**2)) / dof
    try:
        cov_x = s2 * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        return None
    cov = cov_x * np.outer(k, k)
    return tuple(tuple(float(v) for v in row) for row in cov)
