"""`egosim run` whose simulation loop gets stuck after STUCK_AFTER ticks (it prints
`stuck` then), as a step or a call that never returns would: what is left to end it is the
stop watcher (a second signal, or the clean stop's deadline). Run by the venv's Python;
argv as `egosim`'s."""

import itertools
import sys
import threading
from collections.abc import Callable
from typing import Any

from egosim.app import loop
from egosim.cli import main

STUCK_AFTER = 50

run_loop = loop.SimulationLoop.__init__


def stuck_after(step: Callable[[], None], ticks: int) -> Callable[[], None]:
    count = itertools.count()

    def tick() -> None:
        if next(count) == ticks:
            print("stuck", flush=True)
            threading.Event().wait()  # never set: the main thread waits in a lock for good
        step()

    return tick


def init(self: loop.SimulationLoop, step: Callable[[], None], *args: Any, **kwargs: Any) -> None:
    run_loop(self, stuck_after(step, STUCK_AFTER), *args, **kwargs)


loop.SimulationLoop.__init__ = init  # type: ignore[method-assign]
sys.exit(main())
