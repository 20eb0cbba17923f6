"""Winder settings as a validated case (the first step of the chain).

* :mod:`~woundroll.case.schema` -- the sections of a case file (``[web]``, ``[core]``,
  ``[winding]``, ``[tester]``, ``[contact]``, ...) as typed objects with SI values, and the
  provenance of every value (case file, ``--set``, web form, default);
* :mod:`~woundroll.case.loading` -- reading a TOML file, a bundled case or a dict, with
  overrides, into a :class:`Case`.

Plausibility limits and work bounds live in :mod:`woundroll.limits` (the solvers read them too).
"""

from woundroll.case.loading import (
    bundled_cases,
    case_from_dict,
    load_case,
    parse_override,
    resolve_case_path,
    set_dotted,
)
from woundroll.case.schema import (
    FROM_CASE_FILE,
    FROM_DEFAULT,
    FROM_SET,
    FROM_WEB_FORM,
    Case,
    ContactSpec,
    CoreSpec,
    InputValue,
    WebSpec,
    WindingSpec,
)

__all__ = [
    "FROM_CASE_FILE",
    "FROM_DEFAULT",
    "FROM_SET",
    "FROM_WEB_FORM",
    "Case",
    "ContactSpec",
    "CoreSpec",
    "InputValue",
    "WebSpec",
    "WindingSpec",
    "bundled_cases",
    "case_from_dict",
    "load_case",
    "parse_override",
    "resolve_case_path",
    "set_dotted",
]
