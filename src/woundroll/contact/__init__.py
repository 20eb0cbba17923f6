"""Roll stiffness under the striker: the 2D plane-strain contact model (issue 4).

``indent(web, core, radius, sigma_r, head_radius=..., head_length=..., depth_max=...)``
presses a rigid cylindrical head into the roll cross-section and returns a
:class:`ContactResult` with F(d), the semi-contact width a(d), the fit of eq. {3}
(F = alpha d^2 + beta d), the stress fields and the slip factor {23} at every depth
(:meth:`ContactResult.at_depth`).
See docs/contact.md for the formulation, assumptions and verification.
"""

from woundroll.contact.result import (
    ContactResult,
    ContactState,
    fit_spring,
    plot_slip_factor,
    slip_factor,
)
from woundroll.contact.solver import ContactOptions, indent

__all__ = [
    "ContactOptions",
    "ContactResult",
    "ContactState",
    "fit_spring",
    "indent",
    "plot_slip_factor",
    "slip_factor",
]
