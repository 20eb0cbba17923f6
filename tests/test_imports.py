"""Every module of the package imports: a broken import in code that only slow tests or a
rarely used command reach (a module moved, a name renamed) fails the default suite."""

from __future__ import annotations

import importlib
import pkgutil

import pytest

import woundroll

# ``__main__`` modules run the command line when imported (``python -m woundroll``)
MODULES = sorted(
    m.name
    for m in pkgutil.walk_packages(woundroll.__path__, prefix="woundroll.")
    if not m.name.endswith("__main__")
)


def test_package_has_modules() -> None:
    # the walk itself must see the package (75 modules when this test was written)
    assert len(MODULES) > 50


@pytest.mark.parametrize("name", MODULES)
def test_module_imports(name: str) -> None:
    if name.startswith("woundroll.app.web") or name == "woundroll.app.cli.serve":
        pytest.importorskip("fastapi")  # the web extra
    importlib.import_module(name)
