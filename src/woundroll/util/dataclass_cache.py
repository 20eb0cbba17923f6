"""The compiled code of dataclasses' generated methods, kept between runs of the command.

``@dataclass`` writes the source of each class's ``__init__``, ``__repr__``, ``__eq__``,
``__hash__`` (and a frozen class's ``__setattr__``/``__delattr__``) and compiles it with
``exec`` every time the class is created, in every process: about 1-2 ms a class, and a
``woundroll run`` process creates some 100 (its own, pydantic's, annotated_types', typer's):
0.11-0.21 s of a Table 2 roll's whole process on this project's machine, 0.3x the import
yardstick (issue 23 item 1). Python compiles a module's code once into ``__pycache__``, but
not these methods.

:func:`install` (the command line calls it first, for its own process only; the library
leaves ``dataclasses`` alone) makes ``dataclasses`` compile each such source text once and
keep the code object, keyed by the whole text, in a file read at the next start
(``marshal``, the format of .pyc files, so one file per Python version). The classes are
the same: the same source compiled the same way (no ``__future__`` flags, file name
``"<string>"``), only not again. A text never seen is compiled as before and added; an
unreadable, stale or broken file is ignored and rewritten; a folder that cannot be written
leaves every run as it was. The file holds the texts of the runs since it was last
started anew (at most :data:`MAX_ENTRIES`). Like Python's own .pyc files, it is not written
when bytecode is not (``PYTHONDONTWRITEBYTECODE``, ``python -B``). Set
``WOUNDROLL_DATACLASS_CACHE=0`` to turn it off.
"""

from __future__ import annotations

import atexit
import builtins
import dataclasses
import importlib.util
import marshal
import os
import sys
from pathlib import Path
from types import CodeType
from typing import Any

#: the environment variable that turns the cache off (value ``0``)
ENV = "WOUNDROLL_DATACLASS_CACHE"
#: more texts than this: the file starts anew with those of the current run
MAX_ENTRIES = 4000

_code: dict[str, CodeType] = {}
_used: set[str] = set()
_added = 0
_path: Path | None = None


def _file_name() -> str:
    magic = importlib.util.MAGIC_NUMBER.hex()
    return f"dataclass-code.{sys.implementation.cache_tag}-{magic}.marshal"


def _cache_dirs() -> list[Path]:
    """Where the file may live: the package's ``__pycache__``, else the user's cache."""
    xdg = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    here = Path(__file__).resolve().parent.parent / "__pycache__"
    return [here, Path(xdg) / "woundroll"]


def _cached_exec(source: Any, globals: Any = None, locals: Any = None) -> None:  # noqa: A002
    """``exec`` for :mod:`dataclasses`: the code of ``source`` compiled once."""
    global _added
    if not isinstance(source, str):
        return builtins.exec(source, globals, locals)
    code = _code.get(source)
    if code is None:
        # dont_inherit: the flags of dataclasses' own exec (no __future__ of this module)
        code = compile(source, "<string>", "exec", dont_inherit=True)
        _code[source] = code
        _added += 1
    _used.add(source)
    return builtins.exec(code, globals, locals)


def _read(path: Path) -> dict[str, CodeType]:
    try:
        # loads of the whole file: marshal.load reads a file object piece by piece, ~6x slower
        data = marshal.loads(path.read_bytes())
    except (OSError, EOFError, ValueError, TypeError):
        return {}
    if not isinstance(data, dict):
        return {}
    return {k: v for k, v in data.items() if isinstance(k, str) and isinstance(v, CodeType)}


def _write() -> None:
    """Write the file if this run compiled a text it did not hold (atomic replace)."""
    if not _added or _path is None or sys.dont_write_bytecode:
        return
    import tempfile

    keep = _code if len(_code) <= MAX_ENTRIES else {k: _code[k] for k in _used}
    for folder in [_path.parent, *(d for d in _cache_dirs() if d != _path.parent)]:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=folder, prefix=".dataclass-code-")
            try:
                with os.fdopen(fd, "wb") as fh:
                    marshal.dump(keep, fh)
                os.chmod(tmp, 0o644)  # as a .pyc: readable by every user of the install
                os.replace(tmp, folder / _path.name)
            except BaseException:
                Path(tmp).unlink(missing_ok=True)
                raise
            return
        except OSError:
            continue


def install() -> None:
    """Compile dataclasses' generated methods once per machine (module docstring); for the
    command's own process. Does nothing when already installed or turned off."""
    global _path
    if _path is not None or os.environ.get(ENV, "1") == "0":
        return
    name = _file_name()
    dirs = _cache_dirs()
    found = [d / name for d in dirs if (d / name).is_file()]
    _path = found[0] if found else dirs[0] / name
    if found:
        _code.update(_read(found[0]))
    dataclasses.exec = _cached_exec  # type: ignore[attr-defined]
    atexit.register(_write)


def uninstall() -> None:
    """Undo :func:`install` (tests): ``dataclasses`` compiles each time again."""
    global _path, _added
    if getattr(dataclasses, "exec", None) is _cached_exec:
        del dataclasses.exec  # type: ignore[attr-defined]
    atexit.unregister(_write)
    _path = None
    _added = 0
    _code.clear()
    _used.clear()
