"""The CLI's console: one place for how a command prints, warns and fails.

Output goes to ``out`` (stdout), messages to ``err`` (stderr); :func:`fail` prints one line
``error: ...`` and exits with the status given (2 input, 1 no convergence); a long job runs
under :func:`with_progress`'s bars.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import typer
from rich.console import Console
from rich.markup import escape

T = TypeVar("T")

# emoji=False: ":x:" in a user file name or a CSV header stays text, never an emoji
err = Console(stderr=True, emoji=False)
out = Console(emoji=False)


def fail(exc: Exception, status: int) -> None:
    """Print ``error: <message>`` on stderr and exit with ``status``."""
    err.print(f"[bold red]error:[/] {escape(str(exc))}", highlight=False, soft_wrap=True)
    raise typer.Exit(status)


def warn(text: str) -> None:
    """Print ``warning: <text>`` on stderr."""
    err.print(f"[yellow]warning:[/] {escape(text)}", highlight=False, soft_wrap=True)


def with_progress(job: Callable[[Callable[[str, float], None]], T]) -> T:
    """Run ``job(progress)`` under a rich progress bar on stderr (one bar per stage)."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeElapsedColumn(),
        console=err,
        transient=True,
    ) as bar:
        tasks: dict[str, int] = {}

        def progress(stage: str, fraction: float) -> None:
            if stage not in tasks:
                tasks[stage] = bar.add_task(stage, total=1.0)
            bar.update(tasks[stage], completed=min(max(fraction, 0.0), 1.0))

        return job(progress)
