"""How a batch is told to stop: once (SIGINT or SIGTERM) it ends every running case in
order, keeping its drive; twice, it ends what is left at once; a third time, the process
exits there and then."""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from types import FrameType

SIGNALS = (signal.SIGINT, signal.SIGTERM)
EXIT_SIGNALLED = 128
"""Stopped by a signal: 128 + its number (130 after Ctrl-C, 143 after SIGTERM)."""


@dataclass
class Interrupt:
    stop: threading.Event = field(default_factory=threading.Event)
    """Stop every running case (stack first, then its simulator, which scores the drive)
    and start no other."""
    hurry: threading.Event = field(default_factory=threading.Event)
    """Do not wait for anything to end by itself: SIGKILL what is still running."""
    signal_number: int | None = None
    """The signal that stopped the batch, if one did."""

    def request(self, signal_number: int | None = None) -> None:
        """The first request stops, the next hurries."""
        if self.stop.is_set():
            self.hurry.set()
        elif self.signal_number is None:
            self.signal_number = signal_number
        self.stop.set()


@contextlib.contextmanager
def interrupted_by_signals(interrupt: Interrupt) -> Iterator[Callable[[], None]]:
    """While inside, SIGINT and SIGTERM request `interrupt`, whatever the process had
    (an ignored SIGINT, as a script's background job has; Ray's SIGTERM handler, which
    just exits). Yields what installs the handlers again, for after a library replaced
    them; the previous handlers are back after."""
    if threading.current_thread() is not threading.main_thread():
        yield lambda: None
        return

    def handle(number: int, frame: FrameType | None) -> None:
        if interrupt.hurry.is_set():
            os._exit(EXIT_SIGNALLED + number)
        interrupt.request(number)

    previous = {number: signal.getsignal(number) for number in SIGNALS}
    mask = signal.pthread_sigmask(signal.SIG_UNBLOCK, SIGNALS)

    def install() -> None:
        for number in SIGNALS:
            signal.signal(number, handle)

    install()
    try:
        yield install
    finally:
        for number, handler in previous.items():
            if handler is not None:
                signal.signal(number, handler)
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
