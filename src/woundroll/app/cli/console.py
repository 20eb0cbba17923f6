"""The CLI's console: one place for how a command prints, warns and fails.

Output goes to ``out`` (stdout), messages to ``err`` (stderr); :func:`fail` prints one line
``error: ...`` and exits with the status given (2 input, 1 no convergence); a long job runs
under :func:`with_progress`'s bars.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table

T = TypeVar("T")


class _LazyConsole:
    """A rich ``Console`` made on first use: rich (~45 ms of imports) is not loaded by a
    command that never prints through it (``woundroll run --json`` writes to stdout)."""

    def __init__(self, **kwargs: Any) -> None:
        self._kwargs = kwargs
        self._console: Console | None = None

    def __getattr__(self, name: str) -> Any:
        if self._console is None:
            from rich.console import Console

            self._console = Console(**self._kwargs)
        return getattr(self._console, name)


# emoji=False: ":x:" in a user file name or a CSV header stays text, never an emoji
err: Console = _LazyConsole(stderr=True, emoji=False)  # type: ignore[assignment]
out: Console = _LazyConsole(emoji=False)  # type: ignore[assignment]


def console(**kwargs: Any) -> Console:
    """A rich ``Console`` with the CLI's settings (no emoji) and ``kwargs``."""
    from rich.console import Console

    return Console(emoji=False, **kwargs)


def escape(text: str) -> str:
    """``text`` with rich markup escaped (a file name with brackets prints as written)."""
    from rich.markup import escape as rich_escape

    return rich_escape(text)


def table(*columns: Any, **kwargs: Any) -> Table:
    """A rich ``Table`` (rich is imported when a command prints one)."""
    from rich.table import Table

    return Table(*columns, **kwargs)


def fail(exc: Exception, status: int) -> None:
    """Print ``error: <message>`` on stderr and exit with ``status``."""
    import typer  # here: woundroll run's plain form runs without it (app/cli/run_core.py)

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
