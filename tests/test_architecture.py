"""The import rule of docs/architecture.md, enforced: imports flow one way, down the chain.

The package is a stack of layers (lowest first). A module may import from its own layer and
the layers below it, never from a layer above; inside ``woundroll.contact`` the same holds for
its own sub-layers. Every import counts, also those inside functions and under
``TYPE_CHECKING``: a lazy upward import is still an upward dependency. The module graph has no
cycle. The check reads the source with :mod:`ast` (no import-linter dependency: the rule is
thirty lines).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parent.parent / "src"
PACKAGE = SRC / "woundroll"

#: The layers, lowest first (docs/architecture.md, "The import rule").
LAYERS: list[tuple[str, ...]] = [
    ("errors", "units", "limits", "util", "data"),  # the foundation: no model in it
    ("materials",),  # web, core and radial-modulus laws
    ("winding",),  # winder settings -> stresses in the roll
    ("instruments",),  # the striker, its reading and its scale
    ("contact",),  # the roll under the striker: roll stiffness
    ("profile",),  # across the CMD
    ("io",),  # readings and tester files
    ("case",),  # a case file -> validated objects
    ("pipeline",),  # the forward chain, run
    ("inverse",),  # readings -> stresses, causes, setpoints, site calibration
    ("assess",),  # defect risk, uncertainty bands, the profiler's check
    ("studies",),  # the reference paper's studies
    ("app",),  # command line, report, web page, sweeps
]

#: Inside ``woundroll.contact``, lowest first.
CONTACT_LAYERS: list[tuple[str, ...]] = [
    ("result", "heads", "stepping"),
    ("plane_strain",),
    ("solid3d",),
    ("layered",),
    ("models",),
    ("spring",),
    ("dynamic",),
    ("block",),
]


def _modules() -> dict[str, Path]:
    mods = {}
    for p in PACKAGE.rglob("*.py"):
        parts = p.relative_to(SRC).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        mods[".".join(parts)] = p
    return mods


MODULES = _modules()


def _targets(module: str, node: ast.Import | ast.ImportFrom) -> set[str]:
    """The woundroll modules an import statement loads (a ``from pkg import submodule``
    names the submodule, not the package)."""
    if isinstance(node, ast.ImportFrom):
        if node.level:
            base = module.split(".")
            if MODULES[module].name != "__init__.py":
                base = base[:-1]
            base = base[: len(base) - node.level + 1]
            pkg = ".".join(base + ([node.module] if node.module else []))
        else:
            pkg = node.module or ""
        subs = [f"{pkg}.{a.name}" for a in node.names]
        names = subs if all(s in MODULES for s in subs) else [pkg, *subs]
    else:
        names = [a.name for a in node.names]
    found = set()
    for name in names:
        while name and name not in MODULES:
            name = name.rpartition(".")[0]
        if name:
            found.add(name)
    return found


def _graph() -> dict[str, set[str]]:
    graph = {}
    for mod, path in MODULES.items():
        deps: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import | ast.ImportFrom):
                deps |= _targets(mod, node)
        # a module's own packages always load before it: not a dependency
        graph[mod] = {d for d in deps if d != mod and not mod.startswith(d + ".")}
    return graph


GRAPH = _graph()


def _rank(module: str, prefix: str, layers: list[tuple[str, ...]]) -> int | None:
    rest = module[len(prefix) :].split(".")[0] if module.startswith(prefix) else None
    for i, layer in enumerate(layers):
        if rest in layer:
            return i
    return None


def _upward(prefix: str, layers: list[tuple[str, ...]]) -> list[str]:
    bad = []
    for mod, deps in GRAPH.items():
        if mod == prefix.rstrip("."):  # a package's facade (its __init__) may gather all
            continue
        me = _rank(mod, prefix, layers)
        for dep in deps:
            them = _rank(dep, prefix, layers)
            if me is not None and them is not None and them > me:
                bad.append(f"{mod} imports {dep}")
    return sorted(bad)


def test_every_module_has_a_layer() -> None:
    # a new top-level package or module must be placed in LAYERS (and docs/architecture.md)
    loose = [
        m
        for m in MODULES
        if m != "woundroll" and m != "woundroll.__main__" and _rank(m, "woundroll.", LAYERS) is None
    ]
    assert loose == []
    inner = [
        m
        for m in MODULES
        if m.startswith("woundroll.contact.")
        and _rank(m, "woundroll.contact.", CONTACT_LAYERS) is None
    ]
    assert inner == []


def test_imports_flow_down_the_layers() -> None:
    assert _upward("woundroll.", LAYERS) == []


def test_contact_imports_flow_down_its_layers() -> None:
    assert _upward("woundroll.contact.", CONTACT_LAYERS) == []


def test_no_import_cycle() -> None:
    # Tarjan's strongly connected components over the module graph
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    cycles: list[list[str]] = []

    def strong(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in GRAPH.get(v, ()):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in GRAPH:
        if v not in index:
            strong(v)
    assert cycles == []


@pytest.mark.parametrize(
    ("module", "dep"),
    [
        ("woundroll.winding.hakiel", "woundroll.pipeline"),
        ("woundroll.contact.result", "woundroll.contact.spring"),
    ],
)
def test_the_check_sees_an_upward_import(module: str, dep: str) -> None:
    # the check can fail: an upward edge put into the graph is reported
    GRAPH[module].add(dep)
    try:
        prefix = "woundroll.contact." if "contact.result" in module else "woundroll."
        layers = CONTACT_LAYERS if prefix == "woundroll.contact." else LAYERS
        assert f"{module} imports {dep}" in _upward(prefix, layers)
    finally:
        GRAPH[module].discard(dep)


def test_old_module_paths_still_import_with_a_warning() -> None:
    # users' scripts written against the earlier flat layout keep working for now
    import importlib
    import sys

    sys.modules.pop("woundroll.diagnosis", None)
    with pytest.warns(DeprecationWarning, match="woundroll.inverse.diagnosis"):
        old = importlib.import_module("woundroll.diagnosis")
    from woundroll.inverse import diagnosis

    assert old.diagnose is diagnosis.diagnose
