"""Roll stiffness under the striker: the 2D plane-strain contact model (issue 4).

``indent(web, core, radius, sigma_r, head_radius=..., head_length=..., depth_max=...)``
presses a rigid cylindrical head into the roll cross-section and returns a
:class:`ContactResult` with F(d), the semi-contact width a(d), the fit of eq. {3}
(F = alpha d^2 + beta d), the stress fields at the largest depth and the slip factor {23}.
See docs/contact.md for the formulation, assumptions and verification.
"""

from woundroll.contact.result import ContactResult, fit_spring, plot_slip_factor
from woundroll.contact.solver import ContactOptions, indent

__all__ = ["ContactOptions", "ContactResult", "fit_spring", "indent", "plot_slip_factor"]
