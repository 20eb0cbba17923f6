"""Bundled web-material presets, each with its source, looked up by name.

Presets are TOML tables in ``woundroll/data/materials/*.toml``; a case file uses one with
``[web] preset = "PET1"`` and may override any key.
"""

from __future__ import annotations

import tomllib
from functools import lru_cache
from importlib import resources
from typing import Any

from woundroll.errors import InputError

#: preset keys that document the material and are not web keys
_INFO_KEYS = frozenset({"description", "source", "friction"})


@lru_cache(maxsize=1)
def _all_presets() -> dict[str, dict[str, Any]]:
    out: dict[str, dict[str, Any]] = {}
    for entry in resources.files("woundroll.data.materials").iterdir():
        if entry.name.endswith(".toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            for name, table in data.items():
                out[name.upper()] = dict(table)
    return out


def list_materials() -> dict[str, dict[str, Any]]:
    """All presets: name -> table (with ``description`` and ``source``)."""
    return {k: dict(v) for k, v in sorted(_all_presets().items())}


def material_preset(name: str, field: str = "web.preset") -> dict[str, Any]:
    """The web keys of preset ``name`` (case-insensitive), without the keys that document
    it (``description``, ``source``, ``friction``: the interlayer friction a case gives as
    ``winding.friction`` / ``contact.friction``)."""
    table = _all_presets().get(str(name).upper())
    if table is None:
        raise InputError(
            f"unknown material preset {name!r}; bundled: {', '.join(_all_presets())}", field
        )
    return {k: v for k, v in table.items() if k not in _INFO_KEYS}
