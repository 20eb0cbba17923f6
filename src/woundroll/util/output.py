"""Safe output: strict JSON, atomic files, and the set of files of a run.

* :func:`strict_json` -- JSON with every non-finite float written as ``null`` (the JSON
  standard has no NaN or Infinity; ``json.dumps`` would write invalid tokens).
* :func:`check_out_dir` -- create ``--out`` and prove it writable *before* a run starts.
* :class:`OutputDir` -- write a run's files into a hidden temporary directory inside the
  output directory and move each into place with :func:`os.replace` (atomic on POSIX): a run
  killed while writing leaves either the previous file or the new one, never a partial
  one. ``result.json`` goes last and lists the run's files (``"files"``); files listed by the
  previous ``result.json`` that the new run did not write are removed, other files that look
  like an earlier run's plots are reported.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from pathlib import Path
from typing import Any

from woundroll.errors import InputError

#: Prefix of the temporary directories :class:`OutputDir` makes (leftovers of a killed run
#: are removed by the next one).
TMP_PREFIX = ".woundroll-tmp-"


def finite_or_none(obj: Any) -> Any:
    """``obj`` with NaN and infinities (also inside numpy arrays and scalars) as None."""
    import numpy as np

    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {str(k): finite_or_none(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [finite_or_none(v) for v in obj]
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "iub":  # integers and booleans: finite already
            return obj.tolist()
        if obj.dtype.kind == "f":  # whole-array test: no per-element recursion
            ok = np.isfinite(obj)
            if ok.all():
                return obj.tolist()
            out = obj.astype(object)
            out[~ok] = None
            return out.tolist()
        return finite_or_none(obj.tolist())
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, np.generic):
        return finite_or_none(obj.item())
    if isinstance(obj, Path):
        return str(obj)
    return obj


def strict_json(obj: Any, **kw: Any) -> str:
    """Standard JSON (``allow_nan=False``): non-finite numbers become ``null``."""
    return json.dumps(finite_or_none(obj), allow_nan=False, **kw)


def check_out_dir(out_dir: str | Path) -> Path:
    """Create ``out_dir`` if needed and check that files can be created in it.

    Raises
    ------
    InputError
        Field ``--out``: not a directory, cannot be created, or not writable.
    """
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=TMP_PREFIX, dir=out)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise InputError(f"cannot write to {out}: {exc.strerror or exc}", "--out") from None
    return out


class OutputDir:
    """Stage a run's files in a temporary directory inside ``out`` and publish them atomically.

    Use as a context manager: files are written under :attr:`tmp`; :meth:`publish` moves them
    into ``out`` (``result.json`` last); leaving the block without publishing removes the
    temporary directory.
    """

    def __init__(self, out_dir: str | Path) -> None:
        self.out = check_out_dir(out_dir)
        for old in self.out.glob(TMP_PREFIX + "*"):
            if old.is_dir():  # left by a killed run
                shutil.rmtree(old, ignore_errors=True)
        self.tmp = Path(tempfile.mkdtemp(prefix=TMP_PREFIX, dir=self.out))

    def __enter__(self) -> OutputDir:
        return self

    def __exit__(self, *exc: object) -> None:
        shutil.rmtree(self.tmp, ignore_errors=True)

    def previous_files(self) -> list[str]:
        """Files the previous run recorded in ``result.json`` (none if unreadable)."""
        try:
            data = json.loads((self.out / "result.json").read_text(encoding="utf-8"))
            files = data.get("files", []) if isinstance(data, dict) else []
            return [f for f in files if isinstance(f, str) and "/" not in f and f != ".."]
        except (OSError, ValueError):
            return []

    def publish(
        self, names: list[str], stale_patterns: tuple[str, ...] = (), *, replaces_run: bool = True
    ) -> tuple[list[Path], list[str]]:
        """Move ``names`` from :attr:`tmp` into ``out`` (the last one last); with
        ``replaces_run`` (a run's own output), remove files the previous ``result.json``
        listed and this run did not write. False: files beside a run (``defects.json``,
        ``design.json``) that leave the run's files alone.

        Returns the written paths and notes on stale files (removed or left).
        """
        notes: list[str] = []
        keep = set(names)
        removed = []
        for name in self.previous_files() if replaces_run else []:
            if name not in keep and (self.out / name).is_file():
                (self.out / name).unlink()
                removed.append(name)
        if removed:
            notes.append(f"removed the previous run's {', '.join(sorted(removed))} from {self.out}")
        left = sorted(
            p.name
            for pat in stale_patterns
            for p in self.out.glob(pat)
            if p.name not in keep and p.name not in removed
        )
        if left:
            notes.append(
                f"{self.out} also holds {', '.join(left)}, not written by this run "
                "(from an earlier run?)"
            )
        written = []
        try:
            for name in names:
                os.replace(self.tmp / name, self.out / name)
                written.append(self.out / name)
        except OSError as exc:
            raise InputError(
                f"cannot write to {self.out}: {exc.strerror or exc}", "--out"
            ) from None
        return written, notes


def write_result_files(
    out_dir: str | Path, name: str, result: Any, head: dict[str, Any] | None = None
) -> list[Path]:
    """``name.json`` (strict JSON of ``head`` followed by ``result.to_dict()``: ``head``
    carries the ``schema_version``) and ``name.png`` (``result.plot(path)``) into
    ``out_dir``, atomically beside whatever is there."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    with OutputDir(out_dir) as od:
        (od.tmp / f"{name}.json").write_text(
            strict_json({**(head or {}), **result.to_dict()}), encoding="utf-8"
        )
        plt.close(result.plot(od.tmp / f"{name}.png"))
        written, _ = od.publish([f"{name}.png", f"{name}.json"], replaces_run=False)
    return written
