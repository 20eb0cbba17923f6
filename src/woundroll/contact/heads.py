"""Rigid instrument heads for the 3D contact model: their surface as a lift over the tip.

A head is described by ``lift(y, z)`` [m]: how far its surface lies above its lowest point
(the tip, at y = z = 0) at the tangential offset y and the CMD offset z, measured along the
pressing direction; ``inf`` where the head has no surface. The head presses along -x at the
roll's top (theta = 0, z = 0), so a roll-surface point at (R cos theta, R sin theta, z) is in
contact when it reaches ``x = R - d + lift(R sin theta, z)``.

Shapes (the instrument file's ``head_shape``):

* ``"cylinder"``: radius ``radius``, axis along the CMD, length ``length``; its ends rounded
  with ``edge_radius`` (0: sharp ends). The Rho-meter head.
* ``"sphere"``: radius ``radius`` (Schmidt hammers' plunger, Parotester).
* ``"punch"``: flat circular face of radius ``radius`` (axis along the pressing direction),
  edge rounded with ``edge_radius``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from woundroll.errors import InputError

FloatArray = NDArray[np.float64]
HEAD_SHAPES = ("cylinder", "sphere", "punch")


@dataclass(frozen=True)
class Head:
    """A rigid head (module docstring); lengths in m.

    Attributes
    ----------
    shape : {"cylinder", "sphere", "punch"}
    radius : float [m]
        Cylinder or sphere radius, or the punch face radius.
    length : float or None [m]
        Cylinder length along the CMD (cylinder only).
    edge_radius : float [m]
        Rounding of the cylinder's ends or of the punch's edge (0: sharp).
    """

    shape: str
    radius: float
    length: float | None = None
    edge_radius: float = 0.0

    def __post_init__(self) -> None:
        if self.shape not in HEAD_SHAPES:
            raise InputError(
                f"must be one of {', '.join(HEAD_SHAPES)}, got {self.shape!r}", "head.shape"
            )
        if not (math.isfinite(self.radius) and self.radius > 0):
            raise InputError(f"must be a positive length, got {self.radius!r}", "head.radius")
        if self.shape == "cylinder":
            if self.length is None or not (math.isfinite(self.length) and self.length > 0):
                raise InputError("a cylindrical head needs a positive length", "head.length")
        if not (math.isfinite(self.edge_radius) and self.edge_radius >= 0):
            raise InputError(
                f"must be zero or a positive length, got {self.edge_radius!r}", "head.edge_radius"
            )
        limit = {
            "cylinder": min(self.radius, 0.5 * (self.length or 0.0)),
            "sphere": math.inf,
            "punch": self.radius,
        }[self.shape]
        if self.edge_radius > limit:
            raise InputError(
                f"must not exceed {limit:g} m for this {self.shape}", "head.edge_radius"
            )

    @classmethod
    def from_instrument(cls, instrument: Any) -> Head:
        """The head of an :class:`woundroll.instruments.Instrument` (its ``head_shape``,
        ``head_radius``, ``head_length`` and, if it has one, ``head_edge_radius``)."""
        edge = getattr(instrument, "head_edge_radius", None)
        try:
            return cls(
                shape=instrument.head_shape,
                radius=float(instrument.head_radius),
                length=None if instrument.head_length is None else float(instrument.head_length),
                edge_radius=0.0 if edge is None else float(edge),
            )
        except InputError as exc:
            raise InputError(exc.message, "tester.instrument") from None

    @property
    def cmd_halfwidth(self) -> float:
        """Half the head's extent along the CMD [m]."""
        return 0.5 * self.length if self.shape == "cylinder" else self.radius  # type: ignore[operator]

    @property
    def curvature_radius(self) -> float:
        """Radius of the head's profile in the tangential (y) direction at the tip [m]
        (``inf`` for the flat punch)."""
        return math.inf if self.shape == "punch" else self.radius

    def lift(self, y: ArrayLike, z: ArrayLike) -> FloatArray:
        """Height of the head surface above its tip at offsets (y, z) [m] (inf: no surface)."""
        y = np.abs(np.asarray(y, dtype=float))
        z = np.abs(np.asarray(z, dtype=float))
        R, e = self.radius, self.edge_radius
        with np.errstate(invalid="ignore"):
            if self.shape == "sphere":
                rho2 = y * y + z * z
                out = np.where(rho2 < R * R, R - np.sqrt(np.maximum(R * R - rho2, 0.0)), np.inf)
            elif self.shape == "cylinder":
                L2 = 0.5 * float(self.length)  # type: ignore[arg-type]
                zs = L2 - e  # start of the rounded end
                over = np.maximum(z - zs, 0.0)
                prof = np.where(
                    z <= L2, R - e + np.sqrt(np.maximum(e * e - over * over, 0.0)), -1.0
                )  # radius of the cross-section at z
                if e == 0.0:
                    prof = np.where(z <= L2, R, -1.0)
                out = np.where(
                    (prof > 0) & (y < prof), R - np.sqrt(np.maximum(prof**2 - y * y, 0.0)), np.inf
                )
            else:  # punch
                rho = np.hypot(y, z)
                over = np.maximum(rho - (R - e), 0.0)
                out = np.where(rho <= R, e - np.sqrt(np.maximum(e * e - over * over, 0.0)), np.inf)
        return out

    def footprint(self, depth: float, roll_radius: float) -> tuple[float, float]:
        """Half extents (tangential arc, CMD) [m] of the head's geometric intersection with
        the undeformed roll at ``depth`` (the contact of a rigid roll): the size the mesh's
        fine zone must cover."""
        Ry = self.curvature_radius
        inv = (0.0 if math.isinf(Ry) else 1.0 / Ry) + 1.0 / roll_radius
        if self.shape == "punch":
            a_y = min(self.radius, math.sqrt(2.0 * roll_radius * depth))
            return a_y, self.radius
        a_y = math.sqrt(2.0 * depth / inv)
        if self.shape == "sphere":
            return a_y, math.sqrt(2.0 * self.radius * depth)
        return a_y, 0.5 * float(self.length)  # type: ignore[arg-type]

    def to_dict(self) -> dict[str, Any]:
        return {
            "shape": self.shape,
            "radius_m": self.radius,
            "length_m": self.length,
            "edge_radius_m": self.edge_radius,
        }


def head_length_of(instrument: Any) -> float:
    """The head length [m] of a cylindrical head; other heads are not in the 2D model."""
    if instrument.head_shape != "cylinder" or instrument.head_length is None:
        raise InputError(
            f"the {instrument.name} has a {instrument.head_shape} head, but the 2D "
            "(plane-strain) contact model takes a cylindrical head with its axis along the "
            "CMD: give [tester.roll_spring] for this instrument",
            "tester.instrument",
        )
    return float(instrument.head_length)
