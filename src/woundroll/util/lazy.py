"""Names a package loads on first use: ``__getattr__ = lazy_names(__name__, {...})`` keeps
``import woundroll`` and ``woundroll --help`` light (no pydantic, scipy or models behind them)."""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable
from typing import Any


def lazy_names(package: str, names: dict[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` for ``package`` that imports ``names[name]`` (a module path)
    on first use of ``name`` and keeps the value in the package's namespace."""

    def __getattr__(name: str) -> Any:
        if name in names:
            value = getattr(importlib.import_module(names[name]), name)
            setattr(sys.modules[package], name, value)
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return __getattr__
