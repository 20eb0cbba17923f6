"""Module paths that moved when the package took the layout of docs/architecture.md.

``import woundroll.diagnosis`` (and every other path below) still works: a finder at the end of
``sys.meta_path`` loads the module's new home under the old name and warns once with
:class:`DeprecationWarning`. Only the paths a user could have imported are listed (the public
modules named in the docs of the earlier layout); private helpers moved without a shim.
"""

from __future__ import annotations

import importlib
import sys
import warnings
from types import ModuleType
from typing import Any

#: old module path -> its new home
MOVED: dict[str, str] = {
    "woundroll.cli": "woundroll.app.cli",
    "woundroll.sweep": "woundroll.app.sweep",
    "woundroll.report": "woundroll.app.report",
    "woundroll.web": "woundroll.app.web",
    "woundroll.readings": "woundroll.io.readings",
    "woundroll.tester_files": "woundroll.io.tester_files",
    "woundroll.diagnosis": "woundroll.inverse.diagnosis",
    "woundroll.causes": "woundroll.inverse.causes",
    "woundroll.design": "woundroll.inverse.design",
    "woundroll.site_calibration": "woundroll.inverse.site_calibration",
    "woundroll.defects": "woundroll.assess.defects",
    "woundroll.uncertainty": "woundroll.assess.uncertainty",
    "woundroll.profile_check": "woundroll.assess.profile_check",
    "woundroll.contact.solver": "woundroll.contact.plane_strain.solver",
    "woundroll.contact.solver3d": "woundroll.contact.solid3d.solver",
    "woundroll.contact.cmd_spread": "woundroll.contact.plane_strain.cmd_spread",
    "woundroll.contact.dynamic3d": "woundroll.contact.dynamic.solid3d",
}


class _Alias:  # an importlib Loader (duck-typed: importlib.abc costs ~15 ms of start-up)
    def __init__(self, new: str) -> None:
        self.new = new

    def create_module(self, spec: Any) -> ModuleType:
        return importlib.import_module(self.new)

    def exec_module(self, module: ModuleType) -> None:  # already executed under its new name
        pass


class MovedFinder:  # an importlib MetaPathFinder (duck-typed, as _Alias)
    """Finds an old module path of :data:`MOVED`, after every other finder has failed."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> Any:
        new = MOVED.get(fullname)
        if new is None:
            return None
        warnings.warn(
            f"{fullname} moved to {new}; the old path will be removed (docs/architecture.md)",
            DeprecationWarning,
            stacklevel=2,
        )
        import importlib.util

        return importlib.util.spec_from_loader(fullname, _Alias(new))


def install() -> None:
    """Put the finder at the end of ``sys.meta_path`` (once)."""
    if not any(isinstance(f, MovedFinder) for f in sys.meta_path):
        sys.meta_path.append(MovedFinder())
