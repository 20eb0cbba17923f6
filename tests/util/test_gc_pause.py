"""No garbage collection while the command starts (woundroll.util.gc_pause): paused, then
frozen and on again; a process that did not pause it (a library caller, this test run) is
left alone."""

from __future__ import annotations

import gc

from woundroll.util import gc_pause


def test_pause_then_resume_freezes_and_turns_it_back_on() -> None:
    assert gc.isenabled()
    frozen = gc.get_freeze_count()
    try:
        gc_pause.pause()
        assert not gc.isenabled()
        gc_pause.resume()
        assert gc.isenabled()
        assert gc.get_freeze_count() > frozen
        gc_pause.resume()  # a second resume changes nothing
        assert gc.isenabled()
    finally:
        gc.unfreeze()
        gc.enable()


def test_resume_without_pause_leaves_the_collector_alone() -> None:
    gc.disable()
    try:
        gc_pause.resume()
        assert not gc.isenabled()  # the caller's choice, not ours
    finally:
        gc.enable()
