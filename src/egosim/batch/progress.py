"""The progress bar: cases done / failed / running, elapsed time, estimate (rich)."""

from __future__ import annotations

from types import TracebackType

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)


class BatchProgress:
    """`with BatchProgress(total) as bar: bar.update(done=..., failed=..., running=...)`;
    drawn on stderr, quiet when it is not a terminal."""

    def __init__(self, total: int, enabled: bool = True) -> None:
        console = Console(stderr=True)
        self._progress = Progress(
            TextColumn("[bold]batch"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("{task.fields[failed]} failed, {task.fields[running]} running"),
            TimeElapsedColumn(),
            TextColumn("eta"),
            TimeRemainingColumn(),
            console=console,
            disable=not enabled or not console.is_terminal,
        )
        self._task = self._progress.add_task("cases", total=total, failed=0, running=0)

    def log(self, text: str) -> None:
        """A line above the bar (on stderr), never cut into several: a log line copied
        from it must read as it was written."""
        self._progress.console.print(text, highlight=False, markup=False, soft_wrap=True)

    def update(self, done: int, failed: int, running: int) -> None:
        self._progress.update(self._task, completed=done, failed=failed, running=running)

    def __enter__(self) -> BatchProgress:
        self._progress.start()
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        value: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self._progress.stop()
