"""Worker pools that stop cleanly: Ctrl-C, SIGTERM and a killed parent leave no process behind.

Why: a :class:`concurrent.futures.ProcessPoolExecutor` leaving its ``with`` block on an
exception waits for the running tasks (a contact solution: tens of seconds), and workers of a
parent killed with SIGKILL or SIGTERM live on with parent 1, keeping the resource tracker alive
with them.

* :func:`process_pool` -- a spawned process pool registered here; its workers ignore SIGINT
  (the terminal sends Ctrl-C to the whole process group; the parent decides) and exit by
  themselves within :data:`PARENT_POLL` seconds when their parent is gone.
* :func:`clean_stop` -- a context manager for the main program (the CLI): while it is active,
  SIGINT and SIGTERM terminate the workers of every registered pool at once, then raise
  :class:`Interrupted` in the main thread, so ``with pool:`` blocks return at once and no
  output file is published (output is staged and renamed, :mod:`woundroll.util.output`).
* :func:`stop_pools` -- terminate the registered pools' workers (used by the handler; callable
  by any code that abandons a pool).
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import weakref
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    # imported when a pool is made: a single-roll run does not pay for multiprocessing
    from concurrent.futures import ProcessPoolExecutor

#: Seconds between a worker's checks that its parent is alive.
PARENT_POLL = 0.5

_POOLS: weakref.WeakSet[ProcessPoolExecutor] = weakref.WeakSet()  # the live pools


class Interrupted(KeyboardInterrupt):
    """The run was stopped by a signal (``signum``); workers are already terminated."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _watch_parent(parent: int) -> None:
    while True:
        if os.getppid() != parent:
            os._exit(1)  # parent gone: nothing will collect our results
        threading.Event().wait(PARENT_POLL)


def _worker_init(parent: int, user_init: Any, user_args: tuple[Any, ...]) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    if user_init is not None:
        user_init(*user_args)


def process_pool(
    workers: int, initializer: Any = None, initargs: tuple[Any, ...] = ()
) -> ProcessPoolExecutor:
    """A ``spawn`` process pool of ``workers`` processes that :func:`clean_stop` can stop."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(
        max_workers=workers,
        mp_context=multiprocessing.get_context("spawn"),
        initializer=_worker_init,
        initargs=(os.getpid(), initializer, initargs),
    )
    _POOLS.add(pool)
    return pool


def stop_pools(timeout: float = 2.0) -> int:
    """Terminate the workers of every registered pool (SIGTERM, then SIGKILL after
    ``timeout``); return how many were running."""
    procs = []
    for pool in list(_POOLS):
        for p in list((getattr(pool, "_processes", None) or {}).values()):
            if p.is_alive():
                procs.append(p)
                with contextlib.suppress(Exception):
                    p.terminate()
    for p in procs:
        p.join(timeout)
        if p.is_alive():
            with contextlib.suppress(Exception):
                p.kill()
                p.join(timeout)
    for pool in list(_POOLS):
        with contextlib.suppress(Exception):
            pool.shutdown(wait=False, cancel_futures=True)
    return len(procs)


@contextlib.contextmanager
def clean_stop() -> Iterator[None]:
    """While active (main thread only): SIGINT/SIGTERM stop the pools and raise
    :class:`Interrupted`. Elsewhere (a worker thread) it does nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: Any) -> None:
        stop_pools()
        raise Interrupted(signum)

    old = {s: signal.signal(s, handler) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)
