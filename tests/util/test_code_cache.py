"""The command's cache of code that dataclasses and typing compile at run time
(woundroll.util.code_cache): the classes and annotations are those compiled anew, a second
process compiles nothing it has seen, a broken file or a text that does not compile behaves
as without the cache."""

from __future__ import annotations

import dataclasses
import typing
from pathlib import Path

import pytest

from woundroll.util import code_cache


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):  # type: ignore[no-untyped-def]
    """The cache installed with its file under ``tmp_path``; uninstalled afterwards."""
    monkeypatch.setattr(code_cache, "_cache_dirs", lambda: [tmp_path / "a", tmp_path / "b"])
    monkeypatch.setattr("sys.dont_write_bytecode", False)
    monkeypatch.delenv(code_cache.ENV, raising=False)
    code_cache.uninstall()
    yield tmp_path
    code_cache.uninstall()


def _make_class():  # type: ignore[no-untyped-def]
    @dataclasses.dataclass(frozen=True)
    class Point:
        x: float
        y: float = 2.0
        tags: list[str] = dataclasses.field(default_factory=list)

    return Point


def _restart() -> None:
    """As a new process would: write the file, forget the texts, read the file again."""
    code_cache._write()
    code_cache.uninstall()
    code_cache.install("test")


def test_second_process_compiles_nothing_and_classes_are_the_same(cache: Path) -> None:
    code_cache.install("test")
    first = _make_class()
    ref = typing.ForwardRef("list[int] | None")
    assert code_cache._added >= 5  # __init__, __repr__, __eq__, __hash__, __setattr__, ...
    _restart()
    assert (cache / "a" / code_cache._file_name("test")).is_file()
    again = _make_class()
    ref2 = typing.ForwardRef("list[int] | None")
    assert code_cache._added == 0 and len(code_cache._used) >= 6
    a, b = first(1.0), again(1.0)
    assert repr(a) == repr(b) == "_make_class.<locals>.Point(x=1.0, y=2.0, tags=[])"
    assert again(1.0) == b and hash(again(1.0, 3.0, ())) == hash(first(1.0, 3.0, ()))
    with pytest.raises(dataclasses.FrozenInstanceError):
        b.x = 2.0  # type: ignore[misc]
    assert again.__init__.__annotations__ == first.__init__.__annotations__  # type: ignore[misc]
    assert again.__init__.__code__.co_code == first.__init__.__code__.co_code  # type: ignore[misc]
    assert ref2.__forward_code__.co_code == ref.__forward_code__.co_code
    assert typing.get_type_hints(again) == typing.get_type_hints(first)


def test_a_text_that_does_not_compile_raises_as_before(cache: Path) -> None:
    code_cache.install("test")
    with pytest.raises(SyntaxError, match="Forward reference must be an expression"):
        typing.ForwardRef("not an expression")


def test_broken_file_is_ignored_and_rewritten(cache: Path) -> None:
    (cache / "a").mkdir()
    path = cache / "a" / code_cache._file_name("test")
    path.write_bytes(b"\x00not marshal data")
    code_cache.install("test")
    _make_class()
    assert code_cache._added > 0  # compiled: nothing was read
    _restart()
    _make_class()
    assert code_cache._added == 0


def test_unwritable_folder_falls_back_and_bytecode_off_writes_nothing(
    cache: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (cache / "a").write_text("a file where the folder would be")
    code_cache.install("test")
    _make_class()
    code_cache._write()
    assert (cache / "b" / code_cache._file_name("test")).is_file()
    code_cache.uninstall()
    monkeypatch.setattr("sys.dont_write_bytecode", True)
    monkeypatch.setattr(code_cache, "_cache_dirs", lambda: [cache / "c"])
    code_cache.install("test")
    _make_class()
    code_cache._write()
    assert not (cache / "c").exists()


def test_turned_off_by_the_environment(cache: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(code_cache.ENV, "0")
    code_cache.install("test")
    assert getattr(dataclasses, "exec", None) is None
    assert getattr(typing, "compile", None) is None
