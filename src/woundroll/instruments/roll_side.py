"""The roll side of the 1.5D impact models: the roll spring and the roll's active mass.

Roll spring (loading)
    ``F(d) = alpha d^2 + beta d`` {3}, ``d = x_s - x_gap`` the depth the head has pushed the
    roll surface in [m]. :class:`QuadraticLaw` is that law; :class:`TabulatedLaw` is any
    monotone loading curve given as points (a Hertz curve, a 2D contact model's output), linear
    between them, so both the FD model and the energy model see exactly the same curve.

Roll spring (unloading)
    The paper's models are elastic. Rebound-type readouts (Schmidt R, Parotester L) need energy
    loss, so :class:`RollSpring` carries an *energetic coefficient of restitution* ``e`` in
    (0, 1]: the roll gives back ``e^2`` of the energy ``W = E_roll(d_max)`` {20} it stored while
    loading. The unloading branch is the loading curve compressed in depth towards the turning
    point ``(d_max, F_max)``::

        F_u(d) = F(d_max (d - d_res) / (d_max - d_res)),   d_res = (1 - e^2) d_max

    It starts at ``F_max``, is ``1/e^2`` times stiffer than loading, reaches zero force at the
    residual depth ``d_res`` and returns ``int F_u = (d_max - d_res)/d_max W = e^2 W`` (exact,
    for any loading curve). ``e = 1`` unloads along the loading curve: the paper's elastic roll.
    Why ``e``: for a free mass hitting the roll spring alone (no striker spring, no roll mass)
    the exit speed is ``e`` times the entry speed, the usual meaning of a coefficient of
    restitution (the energetic definition: ``e^2`` = energy released / energy absorbed).

Active roll mass (tapered column, {14}-{18})
    The pressure under a line load spreads through the roll as ``p(z) = p_max a/sqrt(a^2+z^2)``
    {14}; force equilibrium ``p(z) A(z) = P`` {15} gives the per-unit-length area
    ``A(z) = 2 sqrt(a^2+z^2) ~ 2 (z + a)`` {16}, a trapezoid whose volume down to the pile height
    ``H`` is ``V = (2a + H) H`` per unit length along the CMD {17}; the active mass is
    ``m_r = kappa rho V`` {18}. kappa follows from the static shape of a column of area A(z)
    loaded at its top and fixed at depth H: ``u(z) ~ ln((H + a)/(z + a))``; kinetic-energy
    equivalence ``m_r = int rho A (u/u(0))^2 dz`` gives the paper's formula with
    ``lambda = a/(a+H)``. A uniform column (``lambda -> 1``) gives the textbook 1/3.

    {17} is a volume per unit length along the CMD (a plane-strain quantity). woundroll
    multiplies it by the **head length along the CMD** (``Instrument.head_length``) to get a
    mass: the slice of roll under the head is what the head pushes. This is an assumption the
    paper leaves open; pass ``length`` explicitly to use another.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError

__all__ = [
    "ForceLaw",
    "QuadraticLaw",
    "RollSpring",
    "TabulatedLaw",
    "as_roll_spring",
    "roll_effective_mass",
    "tapered_column_factor",
]


def _finite(value: float, field: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"must be a number, got {value!r}", field) from None
    if not math.isfinite(v):
        raise InputError(f"must be a finite number, got {value!r}", field)
    return v


def _nonneg(value: float, field: str, *, strict: bool = False) -> float:
    v = _finite(value, field)
    if v < 0 or (strict and v == 0):
        raise InputError(f"must be {'' if strict else 'zero or '}positive, got {v:g}", field)
    return v


@runtime_checkable
class ForceLaw(Protocol):
    """A loading curve of the roll spring: force [N] and stored energy [J] at depth d [m]."""

    def force(self, d: ArrayLike) -> NDArray[np.float64]: ...

    def energy(self, d: ArrayLike) -> NDArray[np.float64]: ...


@dataclass(frozen=True)
class QuadraticLaw:
    """The roll spring of the paper, ``F(d) = alpha d^2 + beta d`` {3}.

    Parameters
    ----------
    alpha : float [N/m^2]
        Quadratic (stiffening) coefficient, >= 0.
    beta : float [N/m]
        Linear coefficient, >= 0; ``alpha + beta > 0``.
    """

    alpha: float
    beta: float

    def __post_init__(self) -> None:
        _nonneg(self.alpha, "roll_spring.alpha")
        _nonneg(self.beta, "roll_spring.beta")
        if self.alpha == 0 and self.beta == 0:
            raise InputError(
                "alpha and beta are both zero: the roll has no stiffness", "roll_spring"
            )

    def force(self, d: ArrayLike) -> NDArray[np.float64]:
        """F(d) [N] {3}."""
        d = np.asarray(d, dtype=float)
        return (self.alpha * d + self.beta) * d

    def energy(self, d: ArrayLike) -> NDArray[np.float64]:
        """E_roll(d) = alpha d^3/3 + beta d^2/2 [J] {20}."""
        d = np.asarray(d, dtype=float)
        return (self.alpha / 3.0 * d + self.beta / 2.0) * d * d

    def force_scalar(self, d: float) -> float:
        """Fast scalar F(d) for the time-stepping loop."""
        return (self.alpha * d + self.beta) * d


class TabulatedLaw:
    """A loading curve given by points, linear in between (a table from a contact model).

    Parameters
    ----------
    depth : array [m]
        Strictly increasing, starting at 0.
    force : array [N]
        Starting at 0, non-decreasing.
    field : str
        Dotted name for error messages.

    Beyond the last point the curve is continued along its last segment's slope (a warning-free
    linear extrapolation); :attr:`max_depth` tells how far the table itself reaches.
    The stored energy is the exact integral of the piecewise-linear curve.
    """

    def __init__(self, depth: ArrayLike, force: ArrayLike, field: str = "roll_spring") -> None:
        d = np.asarray(depth, dtype=float).ravel()
        f = np.asarray(force, dtype=float).ravel()
        if d.shape != f.shape or d.size < 2:
            raise InputError("depth and force need the same length, at least 2 points", field)
        if not (np.all(np.isfinite(d)) and np.all(np.isfinite(f))):
            raise InputError("depth and force must be finite", field)
        if d[0] != 0.0 or f[0] != 0.0:
            raise InputError("the curve must start at (0 m, 0 N)", field)
        if np.any(np.diff(d) <= 0):
            raise InputError("depths must increase strictly", field)
        if np.any(np.diff(f) < 0):
            raise InputError("force must not decrease with depth (the roll spring stiffens)", field)
        self.depth = d
        self.force_table = f
        self._slope = np.diff(f) / np.diff(d)
        seg = 0.5 * (f[1:] + f[:-1]) * np.diff(d)
        self._energy_nodes = np.concatenate([[0.0], np.cumsum(seg)])
        self._dl = d.tolist()
        self._fl = f.tolist()
        self._sl = self._slope.tolist()
        self.max_depth = float(d[-1])

    def _segment(self, d: NDArray[np.float64]) -> NDArray[np.intp]:
        return np.clip(np.searchsorted(self.depth, d, side="right") - 1, 0, self.depth.size - 2)

    def force(self, d: ArrayLike) -> NDArray[np.float64]:
        """F(d) [N], linear between the points."""
        d = np.asarray(d, dtype=float)
        i = self._segment(d)
        return self.force_table[i] + self._slope[i] * (d - self.depth[i])

    def energy(self, d: ArrayLike) -> NDArray[np.float64]:
        """Stored energy E_roll(d) = int_0^d F [J] {20} (exact for the piecewise-linear curve)."""
        d = np.asarray(d, dtype=float)
        i = self._segment(d)
        s = d - self.depth[i]
        return self._energy_nodes[i] + self.force_table[i] * s + 0.5 * self._slope[i] * s * s

    def force_scalar(self, d: float) -> float:
        """Fast scalar F(d) for the time-stepping loop."""
        i = min(max(bisect_right(self._dl, d) - 1, 0), len(self._dl) - 2)
        return self._fl[i] + self._sl[i] * (d - self._dl[i])

    @classmethod
    def from_callable(
        cls,
        F: Callable[[NDArray[np.float64]], ArrayLike],
        max_depth: float,
        n: int = 2001,
        field: str = "roll_spring",
    ) -> TabulatedLaw:
        """Tabulate a callable F(d) [N] on ``n`` points over [0, max_depth] [m]."""
        _nonneg(max_depth, f"{field}.max_depth", strict=True)
        d = np.linspace(0.0, max_depth, n)
        try:
            f = np.asarray(F(d), dtype=float)
        except Exception as exc:  # the callable is user code
            raise InputError(f"the force callable failed: {exc}", field) from None
        if f.shape != d.shape:
            f = np.array([float(F(x)) for x in d])
        f = f - f[0]
        return cls(d, f, field)


@dataclass(frozen=True)
class RollSpring:
    """The roll as the striker sees it: loading curve, active mass and restitution.

    Parameters
    ----------
    law : ForceLaw
        Loading curve F(d) (e.g. :class:`QuadraticLaw` {3} or :class:`TabulatedLaw`).
    effective_mass : float [kg]
        Dynamically active roll mass m_r {18}; 0 allowed.
    restitution : float [-]
        Energetic coefficient of restitution e in (0, 1]: the roll returns ``e^2`` of the
        energy it stored (module docstring). 1 = elastic, as in the paper.
    """

    law: ForceLaw
    effective_mass: float = 0.0
    restitution: float = 1.0

    def __post_init__(self) -> None:
        if not isinstance(self.law, ForceLaw):
            raise InputError("needs a force law with force(d) and energy(d)", "roll_spring")
        object.__setattr__(
            self, "effective_mass", _nonneg(self.effective_mass, "roll_spring.effective_mass")
        )
        e = _finite(self.restitution, "roll_spring.restitution")
        if not 0.0 < e <= 1.0:
            raise InputError(f"must lie in (0, 1], got {e:g}", "roll_spring.restitution")

    @classmethod
    def quadratic(
        cls, alpha: float, beta: float, effective_mass: float = 0.0, restitution: float = 1.0
    ) -> RollSpring:
        """The paper's roll: ``F = alpha d^2 + beta d`` {3} [N/m^2, N/m], mass [kg]."""
        return cls(
            QuadraticLaw(_finite(alpha, "roll_spring.alpha"), _finite(beta, "roll_spring.beta")),
            effective_mass,
            restitution,
        )

    def residual_depth(self, d_max: float) -> float:
        """Depth where the unloading branch reaches zero force, ``(1 - e^2) d_max`` [m]."""
        return (1.0 - self.restitution**2) * d_max

    def unloading_force(self, d: ArrayLike, d_max: float) -> NDArray[np.float64]:
        """Unloading branch from the turning point ``d_max`` [m]: ``F_u(d)`` [N].

        ``F_u(d) = F(d_max (d - d_res)/(d_max - d_res))`` with ``d_res = (1 - e^2) d_max``
        (module docstring); negative below ``d_res`` (the contact has ended there).
        """
        scale = 1.0 / self.restitution**2
        return self.law.force(d_max + (np.asarray(d, dtype=float) - d_max) * scale)


def as_roll_spring(
    source: object,
    effective_mass: float = 0.0,
    restitution: float = 1.0,
    max_depth: float = 0.02,
    field: str = "roll_spring",
) -> RollSpring:
    """Turn any roll-stiffness source into a :class:`RollSpring`.

    Parameters
    ----------
    source : RollSpring, ForceLaw, (alpha, beta) pair or callable F(d)
        A callable is tabulated over [0, ``max_depth``] [m] (2001 points).
    effective_mass : float [kg]
        Used unless ``source`` is already a :class:`RollSpring`.
    restitution : float [-]
        Used unless ``source`` is already a :class:`RollSpring`.
    """
    if isinstance(source, RollSpring):
        return source
    if isinstance(source, ForceLaw):
        return RollSpring(source, effective_mass, restitution)
    if isinstance(source, tuple | list) and len(source) == 2:
        return RollSpring.quadratic(source[0], source[1], effective_mass, restitution)
    if callable(source):
        law = TabulatedLaw.from_callable(source, max_depth, field=field)
        return RollSpring(law, effective_mass, restitution)
    raise InputError(
        f"cannot use {type(source).__name__} as a roll spring: give (alpha, beta), a force law "
        "or a callable F(d)",
        field,
    )


def tapered_column_factor(a: ArrayLike, H: ArrayLike) -> NDArray[np.float64]:
    """Effective-mass factor kappa of the tapered pressure column {18}.

    ``lambda = a/(a+H)``, ``kappa = (2 lambda^2 (ln lambda - 1) ln lambda + lambda^2 - 1)
    / (2 (lambda^2 - 1) ln^2 lambda)``. Evaluated without cancellation as
    ``P(3, 2u) / (2 u^2 (1 - exp(-2u)))`` with ``u = -ln lambda`` and ``P`` the regularised lower
    incomplete gamma function (the numerator equals ``1 - e^{-2u}(1 + 2u + 2u^2)``), so the
    uniform-column limit ``kappa -> 1/3`` (H -> 0) is reached smoothly.

    Parameters
    ----------
    a : float or array [m]
        Semi-contact width, > 0.
    H : float or array [m]
        Pile height (depth of the active column), > 0.
    """
    a = np.asarray(a, dtype=float)
    H = np.asarray(H, dtype=float)
    if np.any(~np.isfinite(a)) or np.any(a <= 0):
        raise InputError("must be positive and finite", "tester.semi_contact_width")
    if np.any(~np.isfinite(H)) or np.any(H <= 0):
        raise InputError("must be positive and finite", "tester.pile_height")
    u = np.log1p(H / a)  # = -ln(lambda)
    return _regularised_gamma3(2.0 * u) / (2.0 * u * u * (-np.expm1(-2.0 * u)))


def _regularised_gamma3(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """``P(3, x) = 1 - e^{-x} (1 + x + x^2/2)``, the regularised lower incomplete gamma
    function of order 3, for ``x >= 0``: the closed form for ``x >= 1``, and below it the
    series ``e^{-x} sum_{k>=3} x^k / k!`` (no cancellation; 20 terms reach round-off).
    Written out so that a run does not import scipy.special (0.2 s of start-up)."""
    x = np.asarray(x, dtype=float)
    small = x < 1.0
    xs = np.where(small, x, 0.0)
    term = xs**3 / 6.0
    series = term.copy()
    for k in range(4, 24):
        term = term * xs / k
        series = series + term
    closed = -np.expm1(-x) - np.exp(-x) * (x + 0.5 * x * x)
    return np.where(small, np.exp(-xs) * series, closed)


def roll_effective_mass(a: float, H: float, density: float, length: float) -> float:
    """Dynamically active roll mass ``m_r = kappa rho (2a + H) H L`` [kg] {17}, {18}.

    Parameters
    ----------
    a : float [m]
        Semi-contact width (the paper accepts 0.6 cm).
    H : float [m]
        Pile height (wound thickness under the head, outer radius minus core radius).
    density : float [kg/m^3]
        Roll (web) density.
    length : float [m]
        Length along the CMD that multiplies the per-unit-length volume {17}; woundroll uses
        the head length (module docstring).
    """
    _nonneg(density, "tester.density", strict=True)
    _nonneg(length, "tester.head_length", strict=True)
    kappa = float(tapered_column_factor(a, H))
    return kappa * density * (2.0 * a + H) * H * length
