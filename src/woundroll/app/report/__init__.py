"""A self-contained HTML report of one run: ``woundroll report CASE --out DIR``.

One file, ``DIR/report.html``: the inputs with their units and sources (material and
instrument presets, case file, model defaults), the stresses wound into the roll, the
predicted hardness (and across the CMD the profile), the measured readings and the
diagnosis when given, the warnings and assumptions, the woundroll version and a hash of the
case. Figures are PNG embedded as base64 data URIs; the CSS is inline; nothing is fetched
from the network. The page prints on A4 and Letter (``@page`` margins, no fixed page size,
figures and tables kept whole).

Templating: Jinja2 (autoescaping of every string that comes from a user's file: titles,
file names, notes; loops and optional sections without string surgery; the same engine the
web page renders with, :mod:`woundroll.app.web`).

Readings and diagnosis come from the reverse road (``woundroll.io.readings`` and the diagnosis
module): any object with ``to_dict()`` is accepted, and the sections render what it holds
(:func:`readings_section`, :func:`diagnosis_section`), so the report needs no change when
those results grow fields.
"""

from woundroll.app.report.build import build_report, write_report
from woundroll.app.report.inputs import Row, case_hash, input_sections
from woundroll.app.report.sections import (
    ID_FIELDS,
    defects_section,
    diagnosis_section,
    profile_check_section,
    readings_section,
    summary_section,
    trend_section,
)

__all__ = [
    "ID_FIELDS",
    "Row",
    "build_report",
    "case_hash",
    "defects_section",
    "diagnosis_section",
    "input_sections",
    "profile_check_section",
    "readings_section",
    "summary_section",
    "trend_section",
    "write_report",
]
