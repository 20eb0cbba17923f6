"""The compiled winding kernels as machine code loaded without numba (issue 23, start-up).

:mod:`woundroll.winding._kernels` is compiled by numba; numba's own import costs 0.5 s or
more per process before its cached kernels are even read. This module compiles the same
kernels once (numba, through a C-callable wrapper: :func:`_build`) to an object file for
this machine's CPU and later loads that object file with llvmlite alone (numba's compiler
back end, ~0.08 s to import) into an in-memory executable, called through ``ctypes``.

The machine code is numba's own: the same functions, compiled by the same LLVM with the same
options, so the results are bit for bit those of :mod:`woundroll.winding._kernels` (asserted in
``tests/winding/test_kernels_aot.py``).

Cache: ``__pycache__/_kernels_aot-<key>.o`` next to this file, or, if that folder is not
writable, ``$XDG_CACHE_HOME/woundroll`` (``~/.cache/woundroll``). The key hashes this file,
``_kernels.py``, the numba/llvmlite versions and the CPU name and features, so a changed
kernel or another machine builds anew (a few seconds, once; ``make demo`` does it).

Assumption: the kernels allocate nothing and raise nothing (no numba runtime, no Python
objects): :func:`_build` rejects an object file with any undefined symbol but the C math
library's, and :func:`load` returns ``None`` on any failure, so that
:func:`woundroll.winding.hakiel.wind` falls back to numba's dispatcher.
"""

from __future__ import annotations

import ctypes
import hashlib
import os
from pathlib import Path
from typing import Any

import numpy as np

_HERE = Path(__file__).resolve().parent
_SOURCES = ("_kernels.py", "_kernels_aot.py")
_NAME_RUN = "woundroll_run_groups"
_NAME_FLUSH = "woundroll_flush_all"

#: argument kinds of run_groups, in order: "i"/"f" scalars (int64/float64), "I"/"F" arrays
#: (int64/float64, C-contiguous), "b" booleans (passed as int64)
#: (g0 g1 gnode | r .. beta, hist | thist | dF dFold kp ke | Et c floor w | iterate |
#: w_deep rtol | maxit wnodes flush_every nsub | body | B S state_i)
_RUN_ARGS = "iiI" + "F" * 11 + "I" + "FFFF" + "ffff" + "b" + "ff" + "iiii" + "b" + "IFI"
_FLUSH_ARGS = "iIFFFFFFf"


def _cache_dirs() -> list[Path]:
    xdg = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return [_HERE / "__pycache__", Path(xdg) / "woundroll"]


def _key(llvm: Any) -> str:
    import llvmlite

    h = hashlib.sha256()
    for name in _SOURCES:
        h.update((_HERE / name).read_bytes())
    h.update(llvmlite.__version__.encode())
    h.update(llvm.get_host_cpu_name().encode())
    h.update(llvm.get_host_cpu_features().flatten().encode())
    h.update(llvm.get_process_triple().encode())
    return h.hexdigest()[:20]


def _signature(kinds: str, types: Any) -> list[Any]:
    m = {
        "i": types.int64,
        "f": types.float64,
        "b": types.int64,
        "I": types.CPointer(types.int64),
        "F": types.CPointer(types.float64),
    }
    return [m[k] for k in kinds]


def _kernels_numpy_error_model() -> Any:
    """A private copy of :mod:`._kernels` compiled with numba's ``error_model="numpy"``:
    a division by zero gives inf/nan (as the NumPy twin) instead of raising, so the machine
    code needs no Python exception machinery (numba's run-time helpers are not loaded)."""
    import importlib.util

    from numba import njit
    from numba.core.registry import CPUDispatcher

    spec = importlib.util.spec_from_file_location("_woundroll_kernels_aot", _HERE / "_kernels.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    for name, obj in list(vars(mod).items()):
        if isinstance(obj, CPUDispatcher):
            opts = {k: v for k, v in obj.targetoptions.items() if k in ("inline",)}
            setattr(mod, name, njit(error_model="numpy", **opts)(obj.py_func))
    return mod


def _build() -> tuple[bytes, list[str]]:
    """Compile the kernels' C-callable wrappers with numba: the object file's bytes and the
    external symbols it names."""
    from numba import carray, cfunc, types

    K = _kernels_numpy_error_model()

    i8p = types.CPointer(types.int64)
    run_sig = types.int64(*_signature(_RUN_ARGS, types), i8p)
    flush_sig = types.void(*_signature(_FLUSH_ARGS, types), i8p)

    # sizes[j] is the length (rows for the 2D ones) of the j-th array argument
    @cfunc(run_sig, nopython=True)
    def run_c(
        g0, g1, gnode, r, invr, dlog, invd, F, st, Fself, stself, alpha, beta, hist, thist,
        dF, dFold, kp, ke, Et, c, floor, w, iterate, w_deep, rtol, maxit, wnodes,
        flush_every, nsub, body, B, S, state_i, sizes,
    ):  # fmt: skip
        return K.run_groups(
            g0, g1, carray(gnode, sizes[0]), carray(r, sizes[1]), carray(invr, sizes[2]),
            carray(dlog, sizes[3]), carray(invd, sizes[4]), carray(F, sizes[5]),
            carray(st, sizes[6]), carray(Fself, sizes[7]), carray(stself, sizes[8]),
            carray(alpha, sizes[9]), carray(beta, sizes[10]), carray(hist, (sizes[11], 2)),
            carray(thist, (sizes[12], 2)), carray(dF, sizes[13]), carray(dFold, sizes[14]),
            carray(kp, sizes[15]), carray(ke, sizes[16]), Et, c, floor, w, iterate != 0,
            w_deep, rtol, maxit, wnodes, flush_every, nsub, body != 0, carray(B, sizes[17]),
            carray(S, sizes[18]), carray(state_i, sizes[19]),
        )  # fmt: skip

    @cfunc(flush_sig, nopython=True)
    def flush_c(nlev, B, S, r, F, st, alpha, beta, c, sizes):
        K.flush_all(
            nlev, carray(B, sizes[0]), carray(S, sizes[1]), carray(r, sizes[2]),
            carray(F, sizes[3]), carray(st, sizes[4]), carray(alpha, sizes[5]),
            carray(beta, sizes[6]), c,
        )  # fmt: skip

    import llvmlite.binding as llvm

    mod = llvm.parse_assembly(run_c._library.get_llvm_str())
    mod.link_in(llvm.parse_assembly(flush_c._library.get_llvm_str()), preserve=False)
    mod.get_function(run_c.native_name).name = _NAME_RUN
    mod.get_function(flush_c.native_name).name = _NAME_FLUSH
    mod.verify()
    externs = sorted(
        {f.name for f in mod.functions if f.is_declaration and not f.name.startswith("llvm.")}
        | {g.name for g in mod.global_variables if g.is_declaration}
    )
    target = llvm.Target.from_triple(llvm.get_process_triple())
    tm = target.create_target_machine(
        cpu=llvm.get_host_cpu_name(),
        features=llvm.get_host_cpu_features().flatten(),
        opt=3,
        reloc="static",
        codemodel="jitdefault",
    )
    return tm.emit_object(mod), externs


def _resolve(llvm: Any, names: list[str]) -> None:
    """Give MCJIT the address of each external symbol: the Python C API's from the running
    interpreter, the C math library's; numba's run-time helpers (``numba_*``, ``NRT_*``),
    named only by the wrappers' exception and reference-count paths that the kernels never
    take (``error_model="numpy"``, no allocation), get ``abort``."""
    import ctypes.util

    libm = ctypes.CDLL(ctypes.util.find_library("m") or "libm.so.6")
    libc = ctypes.CDLL(None)
    abort = ctypes.cast(libc.abort, ctypes.c_void_p).value
    for name in names:
        if llvm.address_of_symbol(name):
            continue
        if name.startswith("PyExc_"):
            addr = ctypes.addressof(ctypes.c_void_p.in_dll(ctypes.pythonapi, name))
        elif name.startswith(("Py", "_Py")):
            addr = ctypes.cast(getattr(ctypes.pythonapi, name), ctypes.c_void_p).value
        elif name.startswith(("numba_", "NRT_")):
            addr = abort
        else:
            addr = ctypes.cast(getattr(libm, name), ctypes.c_void_p).value
        llvm.add_symbol(name, addr)


_ENGINE: Any = None
_LOADED: dict[bool, Kernels | None] = {}


class Kernels:
    """``run_groups`` and ``flush_all`` with the signatures of :mod:`._kernels`."""

    def __init__(self, run_addr: int, flush_addr: int) -> None:
        ctypes_of = {
            "i": ctypes.c_int64,
            "f": ctypes.c_double,
            "b": ctypes.c_int64,
            "I": ctypes.c_void_p,
            "F": ctypes.c_void_p,
        }
        self._run = ctypes.CFUNCTYPE(
            ctypes.c_int64, *[ctypes_of[k] for k in _RUN_ARGS], ctypes.c_void_p
        )(run_addr)
        self._flush = ctypes.CFUNCTYPE(None, *[ctypes_of[k] for k in _FLUSH_ARGS], ctypes.c_void_p)(
            flush_addr
        )

    @staticmethod
    def _marshal(kinds: str, args: tuple[Any, ...]) -> tuple[list[Any], np.ndarray, list[Any]]:
        out: list[Any] = []
        sizes: list[int] = []
        keep: list[Any] = []
        for k, a in zip(kinds, args, strict=True):
            if k in "IF":
                arr = np.ascontiguousarray(a, dtype=np.int64 if k == "I" else np.float64)
                if arr is not a:
                    raise TypeError("the compiled kernels need C-contiguous arrays of the type")
                keep.append(arr)
                out.append(arr.ctypes.data)
                sizes.append(arr.shape[0])
            elif k == "f":
                out.append(float(a))
            else:
                out.append(int(a))
        s = np.asarray(sizes, dtype=np.int64)
        return out, s, keep

    def run_groups(self, *args: Any) -> int:
        out, s, _keep = self._marshal(_RUN_ARGS, args)
        return int(self._run(*out, s.ctypes.data))

    def flush_all(self, *args: Any) -> None:
        out, s, _keep = self._marshal(_FLUSH_ARGS, args)
        self._flush(*out, s.ctypes.data)


def _write(path: Path, data: bytes) -> bool:
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_bytes(data)
        os.replace(tmp, path)
        return True
    except OSError:
        return False


def load(build: bool = True) -> Kernels | None:
    """The kernels from the cached object file (built first if missing and ``build``);
    ``None`` if llvmlite or the build is not available (the caller then uses numba).
    Loaded once per process."""
    if _LOADED.get(True) is not None or build in _LOADED:
        return _LOADED.get(True) or _LOADED[build]
    _LOADED[build] = k = _load(build)
    return k


def _load(build: bool) -> Kernels | None:
    global _ENGINE
    try:
        import llvmlite.binding as llvm

        llvm.initialize_native_target()
        llvm.initialize_native_asmprinter()
        name = f"_kernels_aot-{_key(llvm)}"
        data = None
        for d in _cache_dirs():
            if (d / f"{name}.o").is_file() and (d / f"{name}.syms").is_file():
                data = (d / f"{name}.o").read_bytes()
                externs = (d / f"{name}.syms").read_text().split()
                break
        if data is None:
            if not build:
                return None
            data, externs = _build()
            for d in _cache_dirs():
                if _write(d / f"{name}.syms", " ".join(externs).encode()) and _write(
                    d / f"{name}.o", data
                ):
                    break
        _resolve(llvm, externs)
        target = llvm.Target.from_triple(llvm.get_process_triple())
        tm = target.create_target_machine(codemodel="jitdefault")
        engine = llvm.create_mcjit_compiler(llvm.parse_assembly(""), tm)
        engine.add_object_file(llvm.ObjectFileRef.from_data(data))
        engine.finalize_object()
        run_addr = engine.get_function_address(_NAME_RUN)
        flush_addr = engine.get_function_address(_NAME_FLUSH)
        if not run_addr or not flush_addr:
            return None
        _ENGINE = engine  # keep the code alive for the process
        return Kernels(run_addr, flush_addr)
    except Exception:  # noqa: BLE001 -- any failure: the caller falls back to numba
        return None
