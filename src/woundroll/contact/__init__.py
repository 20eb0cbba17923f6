"""Roll stiffness under the striker: the 2D plane-strain contact model (issue 4).

``indent(web, core, radius, sigma_r, head_radius=..., head_length=..., depth_max=...)``
presses a rigid cylindrical head into the roll cross-section and returns a
:class:`ContactResult` with F(d), the semi-contact width a(d), the fit of eq. {3}
(F = alpha d^2 + beta d), the stress fields and the slip factor {23} at every depth
(:meth:`ContactResult.at_depth`).
:func:`roll_stiffness` does that for an instrument's head and fits the roll spring {3} over
the depths its striker reaches (:mod:`woundroll.contact.spring`).
See docs/contact.md for the formulation, assumptions and verification.
"""

from woundroll.contact.plane_strain.solver import ContactOptions, indent
from woundroll.contact.result import (
    ContactResult,
    ContactState,
    fit_spring,
    plot_slip_factor,
    slip_factor,
)
from woundroll.contact.spring import RollStiffness, SpringFit, fit_roll_spring, roll_stiffness

__all__ = [
    "ContactOptions",
    "ContactResult",
    "ContactState",
    "RollStiffness",
    "SpringFit",
    "fit_roll_spring",
    "fit_spring",
    "indent",
    "plot_slip_factor",
    "roll_stiffness",
    "slip_factor",
]
