"""Radial (stack) modulus laws of a wound web: E_r as a function of the radial stress.

A wound roll is soft in the radial direction and stiffens as it is compressed. Each law
here gives the tangent radial modulus ``E_r`` [Pa] at a radial stress ``sigma_r`` [Pa]
(compression negative; ``P = -sigma_r`` is the interlayer pressure) and the stack-test
curve ``P(eps)`` it corresponds to (``eps`` the compressive radial strain, positive).

Laws (registry :data:`LAWS`, keyed by the ``law`` name used in case files):

``pfeiffer``
    E_r = K2 (K1 - sigma_r) = K2 (K1 + P), {2} in the reference paper; stack curve
    P = K1 (exp(K2 eps) - 1) (Pfeiffer, Tappi J. 49(8), 1966). K1 [Pa] may be 0
    (Table 3): then E_r = 0 at zero pressure, and each model that uses it says how it
    keeps a positive stiffness there.
``constant``
    E_r independent of pressure: the linear orthotropic limit (Altmann-type solutions).
``polynomial``
    Hakiel's stack-test polynomial P = C1 eps + C2 eps^2 + C3 eps^3 (Hakiel, Tappi J.
    70(5), 1987, "Nonlinear model for wound roll stresses"); E_r = dP/deps at the strain
    where P is reached. Valid up to ``strain_max``; beyond it E_r is extrapolated linearly
    in P with the last slope.
``tabulated``
    A measured stack-test curve (strain, pressure) from a CSV file or inline arrays;
    E_r = dP/deps from a monotone (PCHIP) interpolant, as a function of P.

Pressures below zero (radial tension, which a wound roll cannot carry between layers)
use the modulus at zero pressure: a stated assumption of every law here.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError
from woundroll.units import to_si

FloatArray = NDArray[np.float64]


class RadialModulusLaw(ABC):
    """Tangent radial modulus as a function of radial stress."""

    name: ClassVar[str]

    @abstractmethod
    def modulus_at_pressure(self, pressure: ArrayLike) -> FloatArray:
        """E_r [Pa] at interlayer pressure ``P = -sigma_r`` [Pa] (P >= 0 in a roll)."""

    def modulus(self, sigma_r: ArrayLike) -> FloatArray:
        """E_r [Pa] at radial stress ``sigma_r`` [Pa], compression negative."""
        return self.modulus_at_pressure(-np.asarray(sigma_r, dtype=float))

    @abstractmethod
    def pressure(self, strain: ArrayLike) -> FloatArray:
        """Stack-test pressure P [Pa] at compressive strain ``eps`` [-]."""

    def linear_in_pressure(self) -> tuple[float, float] | None:
        """``(E0, slope)`` when E_r = E0 + slope * max(P, 0) exactly, else None.

        Compiled kernels use this to evaluate Pfeiffer and constant laws without
        tables.
        """
        return None

    def tabulate(self, p_max: float, n: int = 401) -> tuple[FloatArray, FloatArray]:
        """Knots ``(P, E_r)`` of a piecewise-linear form on [0, p_max] (exact for linear laws).

        Beyond ``p_max`` a model extrapolates with the last segment's slope; below 0 it
        uses E_r(0).
        """
        lin = self.linear_in_pressure()
        if lin is not None:
            p = np.array([0.0, max(p_max, 1.0)])
            return p, lin[0] + lin[1] * p
        # denser knots at low pressure, where the curves bend most
        p = p_max * np.linspace(0.0, 1.0, n) ** 2
        return p, self.modulus_at_pressure(p)

    @abstractmethod
    def to_dict(self) -> dict[str, Any]:
        """SI parameters, with the law name, for results and reports."""


def _clip_pressure(pressure: ArrayLike) -> FloatArray:
    return np.maximum(np.asarray(pressure, dtype=float), 0.0)


@dataclass(frozen=True)
class Pfeiffer(RadialModulusLaw):
    """E_r = K2 (K1 - sigma_r), {2}. ``K1`` [Pa] >= 0, ``K2`` [-] > 0."""

    K1: float
    K2: float
    name: ClassVar[str] = "pfeiffer"

    def __post_init__(self) -> None:
        if not (math.isfinite(self.K1) and self.K1 >= 0):
            raise InputError(f"K1 must be zero or a positive pressure, got {self.K1:g} Pa", "K1")
        if not (math.isfinite(self.K2) and self.K2 > 0):
            raise InputError(f"K2 must be positive, got {self.K2:g}", "K2")

    def modulus_at_pressure(self, pressure: ArrayLike) -> FloatArray:
        return self.K2 * (self.K1 + _clip_pressure(pressure))

    def pressure(self, strain: ArrayLike) -> FloatArray:
        return self.K1 * np.expm1(self.K2 * np.asarray(strain, dtype=float))

    def linear_in_pressure(self) -> tuple[float, float]:
        return self.K2 * self.K1, self.K2

    def to_dict(self) -> dict[str, Any]:
        return {"law": self.name, "K1_Pa": self.K1, "K2": self.K2}


@dataclass(frozen=True)
class Constant(RadialModulusLaw):
    """E_r independent of pressure [Pa] > 0."""

    E_r: float
    name: ClassVar[str] = "constant"

    def __post_init__(self) -> None:
        if not (math.isfinite(self.E_r) and self.E_r > 0):
            raise InputError(f"E_r must be positive, got {self.E_r:g} Pa", "E_r")

    def modulus_at_pressure(self, pressure: ArrayLike) -> FloatArray:
        return np.full(np.shape(pressure), self.E_r, dtype=float)

    def pressure(self, strain: ArrayLike) -> FloatArray:
        return self.E_r * np.asarray(strain, dtype=float)

    def linear_in_pressure(self) -> tuple[float, float]:
        return self.E_r, 0.0

    def to_dict(self) -> dict[str, Any]:
        return {"law": self.name, "E_r_Pa": self.E_r}


@dataclass(frozen=True)
class _CurveLaw(RadialModulusLaw):
    """A law defined by a monotone stack curve P(eps), inverted numerically."""

    _eps: FloatArray = field(init=False, repr=False, compare=False)
    _p: FloatArray = field(init=False, repr=False, compare=False)
    _e: FloatArray = field(init=False, repr=False, compare=False)

    def _set_table(self, eps: FloatArray, p: FloatArray, e: FloatArray) -> None:
        object.__setattr__(self, "_eps", eps)
        object.__setattr__(self, "_p", p)
        object.__setattr__(self, "_e", e)

    def modulus_at_pressure(self, pressure: ArrayLike) -> FloatArray:
        p = _clip_pressure(pressure)
        out = np.interp(p, self._p, self._e)
        slope = (self._e[-1] - self._e[-2]) / (self._p[-1] - self._p[-2])
        beyond = p > self._p[-1]
        if np.any(beyond):
            out = np.where(beyond, self._e[-1] + slope * (p - self._p[-1]), out)
        return out

    def tabulate(self, p_max: float, n: int = 401) -> tuple[FloatArray, FloatArray]:
        p = np.union1d(self._p[self._p < p_max], [p_max]) if p_max > self._p[-1] else None
        if p is None:
            p = self._p[self._p <= p_max]
            p = np.union1d(p, [p_max])
        return p, self.modulus_at_pressure(p)


@dataclass(frozen=True)
class Polynomial(_CurveLaw):
    """Hakiel's stack polynomial P = C1 eps + C2 eps^2 + C3 eps^3 [Pa], up to ``strain_max``."""

    C1: float = 0.0
    C2: float = 0.0
    C3: float = 0.0
    strain_max: float = 0.2
    name: ClassVar[str] = "polynomial"

    def __post_init__(self) -> None:
        if not (0 < self.strain_max < 1):
            raise InputError(
                f"strain_max must lie in (0, 1), got {self.strain_max:g}", "strain_max"
            )
        eps = np.linspace(0.0, self.strain_max, 2001)
        e = self.C1 + 2 * self.C2 * eps + 3 * self.C3 * eps**2
        if np.any(e <= 0):
            bad = eps[np.argmax(e <= 0)]
            raise InputError(
                f"the stack curve must stiffen with strain: dP/deps <= 0 at strain {bad:.3g} "
                "(check C1, C2, C3 or lower strain_max)",
                "C1",
            )
        self._set_table(eps, self.pressure(eps), e)

    def pressure(self, strain: ArrayLike) -> FloatArray:
        s = np.asarray(strain, dtype=float)
        return self.C1 * s + self.C2 * s**2 + self.C3 * s**3

    def to_dict(self) -> dict[str, Any]:
        return {
            "law": self.name,
            "C1_Pa": self.C1,
            "C2_Pa": self.C2,
            "C3_Pa": self.C3,
            "strain_max": self.strain_max,
        }


@dataclass(frozen=True)
class Tabulated(_CurveLaw):
    """A measured stack curve: ``strain`` [-] and ``pressure`` [Pa], both increasing from 0."""

    strain: tuple[float, ...] = ()
    stack_pressure: tuple[float, ...] = ()
    source: str = ""
    name: ClassVar[str] = "tabulated"

    def __post_init__(self) -> None:
        from scipy.interpolate import PchipInterpolator

        eps = np.asarray(self.strain, dtype=float)
        p = np.asarray(self.stack_pressure, dtype=float)
        if eps.shape != p.shape or eps.size < 3:
            raise InputError("needs at least 3 (strain, pressure) points of equal count", "strain")
        if not (np.all(np.isfinite(eps)) and np.all(np.isfinite(p))):
            raise InputError("strain and pressure must be finite numbers", "strain")
        if np.any(np.diff(eps) <= 0) or np.any(np.diff(p) <= 0):
            raise InputError("strain and pressure must both increase strictly", "strain")
        if eps[0] != 0 or p[0] != 0:
            eps = np.concatenate([[0.0], eps])
            p = np.concatenate([[0.0], p])
            if np.any(np.diff(eps) <= 0) or np.any(np.diff(p) <= 0):
                raise InputError("strain and pressure must be positive and increasing", "strain")
        curve = PchipInterpolator(eps, p)
        fine = np.linspace(0.0, eps[-1], 2001)
        self._set_table(fine, curve(fine), np.maximum(curve.derivative()(fine), 1e-12 * p[-1]))

    def pressure(self, strain: ArrayLike) -> FloatArray:
        return np.interp(np.asarray(strain, dtype=float), self._eps, self._p)

    def to_dict(self) -> dict[str, Any]:
        return {
            "law": self.name,
            "strain": list(self.strain),
            "pressure_Pa": list(self.stack_pressure),
            "source": self.source,
        }


#: Registry of laws by case-file name.
LAWS: dict[str, type[RadialModulusLaw]] = {
    cls.name: cls for cls in (Pfeiffer, Constant, Polynomial, Tabulated)
}


def read_stack_csv(path: Path, field_name: str = "file") -> tuple[FloatArray, FloatArray]:
    """Read a stack-test CSV: header ``strain,pressure [unit]`` (strain may be in %).

    Column names are matched case-insensitively on ``strain`` and ``pressure``; a unit in
    brackets (``pressure [psi]``, ``strain [%]``) is honoured, otherwise SI.
    """
    from woundroll.util.tables import read_columns

    cols = read_columns(path, {"strain": "dimensionless", "pressure": "pressure"}, field_name)
    return cols["strain"], cols["pressure"]


def law_from_spec(
    spec: dict[str, Any], field_name: str = "web.radial_modulus", base_dir: Path | None = None
) -> RadialModulusLaw:
    """Build a law from a case-file inline table (values may carry units)."""
    if not isinstance(spec, dict):
        raise InputError(
            'must be an inline table such as { law = "pfeiffer", K1 = "4.62 kPa", K2 = 123.88 }',
            field_name,
        )
    spec = dict(spec)
    law = spec.pop("law", None)
    if law not in LAWS:
        raise InputError(
            f"unknown law {law!r}; choose one of {', '.join(LAWS)}", f"{field_name}.law"
        )

    def take(key: str, kind: str, default: Any = None) -> float:
        if key not in spec:
            if default is None:
                raise InputError(f"missing for law {law!r}", f"{field_name}.{key}")
            return default
        return to_si(spec.pop(key), kind, f"{field_name}.{key}")

    try:
        if law == "pfeiffer":
            out: RadialModulusLaw = Pfeiffer(
                K1=take("K1", "pressure"), K2=take("K2", "dimensionless")
            )
        elif law == "constant":
            out = Constant(E_r=take("E_r", "pressure"))
        elif law == "polynomial":
            out = Polynomial(
                C1=take("C1", "pressure"),
                C2=take("C2", "pressure", 0.0),
                C3=take("C3", "pressure", 0.0),
                strain_max=take("strain_max", "dimensionless", 0.2),
            )
        else:
            if "file" in spec:
                path = Path(spec.pop("file"))
                if base_dir is not None and not path.is_absolute():
                    path = base_dir / path
                eps, p = read_stack_csv(path, f"{field_name}.file")
                source = str(path.name)
            else:
                eps = np.asarray(
                    [
                        to_si(v, "dimensionless", f"{field_name}.strain")
                        for v in spec.pop("strain", [])
                    ]
                )
                p = np.asarray(
                    [
                        to_si(v, "pressure", f"{field_name}.pressure")
                        for v in spec.pop("pressure", [])
                    ]
                )
                source = "inline"
            out = Tabulated(strain=tuple(eps), stack_pressure=tuple(p), source=source)
    except InputError as exc:
        if exc.field and exc.field.startswith(field_name):
            raise
        raise InputError(
            exc.message, f"{field_name}.{exc.field}" if exc.field else field_name
        ) from None
    if spec:
        raise InputError(f"unknown key(s) for law {law!r}: {', '.join(spec)}", field_name)
    return out
