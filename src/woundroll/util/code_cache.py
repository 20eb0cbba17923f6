"""Code that the standard library compiles at run time, compiled once per machine.

Two parts of the standard library compile source text they write while a program runs,
anew in every process: ``@dataclass`` writes and compiles each class's ``__init__``,
``__repr__``, ``__eq__``, ``__hash__`` (and a frozen class's ``__setattr__`` and
``__delattr__``), about 1-2 ms a class, and :class:`typing.ForwardRef` compiles every
annotation written as text (``from __future__ import annotations``; pydantic-core's schema
types alone hold some 700). A ``woundroll run`` process creates some 100 dataclasses (its
own, pydantic's, annotated_types', typer's) and some 900 forward references: 0.1-0.2 s of a
Table 2 roll's whole process on this project's machine, 0.3x the import yardstick (issue 23
item 1). Python compiles a module's own code once into ``__pycache__``, but not these.

:func:`install` (the command line calls it first, for its own process only; the library
leaves the standard library alone) makes ``dataclasses`` and ``typing`` compile each such
text once and keep the code object, keyed by the whole text and the mode, in a file read at
the next start (``marshal``, the format of .pyc files, one file per Python version). The
classes and annotations are the same: the same text compiled the same way (no
``__future__`` flags, file name ``"<string>"``), only not again. A text never seen is
compiled as before and added; a text that does not compile raises as before; an
unreadable, stale or broken file is ignored and rewritten; a folder that cannot be written
leaves every run as it was. One file per command (``run``, ``report``, ...: each reads only
what its own processes compiled, ~0.6 MB for ``run``), holding the texts of its runs since
it was last started anew (at most :data:`MAX_ENTRIES`). Like Python's .pyc files, it is not
written when bytecode is not (``PYTHONDONTWRITEBYTECODE``, ``python -B``). Set
``WOUNDROLL_CODE_CACHE=0`` to turn it off.
"""

from __future__ import annotations

import atexit
import builtins
import dataclasses
import importlib.util
import marshal
import os
import sys
import typing
from pathlib import Path
from types import CodeType
from typing import Any

#: the environment variable that turns the cache off (value ``0``)
ENV = "WOUNDROLL_CODE_CACHE"
#: more texts than this: the file starts anew with those of the current run
MAX_ENTRIES = 3000

_code: dict[tuple[str, str], CodeType] = {}
_used: set[tuple[str, str]] = set()
_added = 0
_path: Path | None = None


def _file_name(label: str) -> str:
    magic = importlib.util.MAGIC_NUMBER.hex()
    # a command's name; an option (--help) or anything else: "other"
    ok = label[:1].isalpha() and label.replace("-", "").isalnum() and len(label) <= 40
    label = label if ok else "other"
    return f"runtime-code.{label}.{sys.implementation.cache_tag}-{magic}.marshal"


def _cache_dirs() -> list[Path]:
    """Where the file may live: the package's ``__pycache__``, else the user's cache."""
    xdg = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    here = Path(__file__).resolve().parent.parent / "__pycache__"
    return [here, Path(xdg) / "woundroll"]


def _compiled(source: str, mode: str) -> CodeType:
    """The code of ``source`` (file name ``"<string>"``, no inherited ``__future__`` flags)."""
    global _added
    key = (mode, source)
    code = _code.get(key)
    if code is None:
        code = compile(source, "<string>", mode, dont_inherit=True)  # raises as before
        _code[key] = code
        _added += 1
    _used.add(key)
    return code


def _cached_exec(source: Any, globals: Any = None, locals: Any = None) -> None:  # noqa: A002
    """``exec`` for :mod:`dataclasses`: the code of a text compiled once."""
    if isinstance(source, str):
        source = _compiled(source, "exec")
    return builtins.exec(source, globals, locals)


def _cached_compile(source: Any, filename: Any, mode: str, *args: Any, **kwargs: Any) -> Any:
    """``compile`` for :mod:`typing` (its forward references: ``"<string>"``, ``"eval"``)."""
    if isinstance(source, str) and filename == "<string>" and not args and not kwargs:
        return _compiled(source, mode)
    return builtins.compile(source, filename, mode, *args, **kwargs)


def _read(path: Path) -> dict[tuple[str, str], CodeType]:
    try:
        # loads of the whole file: marshal.load reads a file object piece by piece, ~6x slower
        data = marshal.loads(path.read_bytes())
    except (OSError, EOFError, ValueError, TypeError):
        return {}
    if not isinstance(data, dict):
        return {}
    return {
        k: v
        for k, v in data.items()
        if isinstance(k, tuple)
        and len(k) == 2
        and k[0] in ("exec", "eval")
        and isinstance(k[1], str)
        and isinstance(v, CodeType)
    }


def _write() -> None:
    """Write the file if this run compiled a text it did not hold (atomic replace)."""
    if not _added or _path is None or sys.dont_write_bytecode:
        return
    import tempfile

    keep = _code if len(_code) <= MAX_ENTRIES else {k: _code[k] for k in _used}
    for folder in [_path.parent, *(d for d in _cache_dirs() if d != _path.parent)]:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(dir=folder, prefix=".runtime-code-")
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


def install(label: str) -> None:
    """Compile the standard library's run-time code once per machine (module docstring);
    for the command's own process, ``label`` its name (the file's). Does nothing when
    already installed or turned off."""
    global _path
    if _path is not None or os.environ.get(ENV, "1") == "0":
        return
    name = _file_name(label)
    dirs = _cache_dirs()
    found = [d / name for d in dirs if (d / name).is_file()]
    _path = found[0] if found else dirs[0] / name
    if found:
        _code.update(_read(found[0]))
    dataclasses.exec = _cached_exec  # type: ignore[attr-defined]
    typing.compile = _cached_compile  # type: ignore[attr-defined]
    atexit.register(_write)


def uninstall() -> None:
    """Undo :func:`install` (tests): each text is compiled each time again."""
    global _path, _added
    if getattr(dataclasses, "exec", None) is _cached_exec:
        del dataclasses.exec  # type: ignore[attr-defined]
    if getattr(typing, "compile", None) is _cached_compile:
        del typing.compile  # type: ignore[attr-defined]
    atexit.unregister(_write)
    _path = None
    _added = 0
    _code.clear()
    _used.clear()
