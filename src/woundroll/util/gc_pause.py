"""No cyclic garbage collection while the command starts (issue 23 item 1).

A command's start-up creates some hundred thousand long-lived objects (the modules of
typer, pydantic, the case schema, the models; the case itself) and almost no garbage; Python's
collector, triggered by the count of new objects, goes over them again and again as they
accumulate: 135 young, 13 middle and one full collection in a Table 2 roll's process,
0.08-0.19 s of it on this project's machine (0.2-0.3x the import yardstick), for nothing.

:func:`pause` (the command line calls it first, for its own process only) turns the
collector off; :func:`resume` moves every object alive at that point out of the
collector's sight (``gc.freeze``: they were made to last the process) and turns it back on,
so that the models' own work is collected as before. ``woundroll run`` resumes once the
case is read and checked (the models' modules are imported by then); every other command
as it starts. The cost: garbage in cycles made during the start-up stays until the process
ends (a Table 2 roll: ``gc.collect()`` at that point finds 854 unreachable objects among
56,000).
"""

from __future__ import annotations

import gc

_paused = False


def pause() -> None:
    """Turn the cyclic collector off until :func:`resume` (if it is on)."""
    global _paused
    if gc.isenabled():
        gc.disable()
        _paused = True


def resume() -> None:
    """Freeze what start-up made and turn the collector back on, if :func:`pause` turned it
    off; else nothing (a library caller, a test runner: their collector is left alone)."""
    global _paused
    if _paused:
        _paused = False
        gc.freeze()
        gc.enable()
