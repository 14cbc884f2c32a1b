"""A worker slot of the local pool: one case after another on its warm simulator, each
case's start and end overlapping the case before and after.

- A case's stack ends (told to stop once its simulator is done with it) while the next
  case runs; at most one stack of the slot is still ending at a time.
- The next case's master and stack are started ahead, while this case drives, at the
  point where, by the batch's drives and stack starts so far, the stack is about ready
  when this case's drive ends (DriveTimes): it waits for its simulator as it would for
  any simulator coming up, and its start (a new Python, importing rospy: about half a
  second) no longer stands between two drives. A stack started ahead whose simulator is
  still busy AHEAD_LIMIT_S past a stack's usual start is stopped and its case started
  afresh once the simulator is free, so no stack waits for its simulator much longer
  than at any simulator's start.
"""

from __future__ import annotations

import statistics
import threading
import time
from collections.abc import Callable

from egosim.batch.case import CaseSpec
from egosim.batch.case_runner import EndingCase, StartedCase, drive_case, start_case
from egosim.batch.interrupt import Interrupt
from egosim.batch.warm_simulator import WarmSimulator

AHEAD_LIMIT_S = 5.0
"""How much longer than a stack's start (DriveTimes) a stack started ahead waits for its
simulator before it is started afresh."""
HANDOVER_S = 0.1
"""From a drive's end to the next case's services being up on the same simulator (its
last case's shutdown, the next one's world and registration), about."""


class DriveTimes:
    """The wall time of the batch's drives, and of its stacks' starts (from starting the
    stack to its drive's beginning, for stacks started with their simulator), so far."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._drives: list[float] = []
        self._starts: list[float] = []

    def drove(self, seconds: float) -> None:
        with self._lock:
            self._drives.append(seconds)

    def started(self, seconds: float) -> None:
        with self._lock:
            self._starts.append(seconds)

    def ahead_after(self) -> float:
        """How long after a drive begins to start the next case's stack: the median drive
        less the median stack start, plus HANDOVER_S (at once while either is unknown:
        a first drive longer than that only costs a stack started again)."""
        with self._lock:
            if not self._drives or not self._starts:
                return 0.0
            drive, start = statistics.median(self._drives), statistics.median(self._starts)
        return max(drive - start + HANDOVER_S, 0.0)

    def ahead_limit(self) -> float:
        """How long a stack started ahead may wait for its simulator: AHEAD_LIMIT_S more
        than a stack's median start."""
        with self._lock:
            start = statistics.median(self._starts) if self._starts else 0.0
        return start + AHEAD_LIMIT_S


class LocalSlot:
    def __init__(
        self,
        out_dir: str,
        simulator: WarmSimulator,
        take: Callable[[], CaseSpec | None],
        give_back: Callable[[], None],
        deliver: Callable[[EndingCase], None],
        times: DriveTimes,
        interrupt: Interrupt,
        name: str,
    ) -> None:
        """The slot's cases run on `simulator` (the slot ends it). `take` gives the
        batch's next case (None: none is left, or the batch stops), `give_back` is told of
        a case taken and not run (the batch stopped), `deliver` ends a case and reports
        its result (in a thread of its own)."""
        self._out_dir = out_dir
        self._take = take
        self._give_back = give_back
        self._deliver = deliver
        self._times = times
        self._interrupt = interrupt
        self.name = name
        self._simulator = simulator
        self._ahead: StartedCase | None = None
        self._pending: CaseSpec | None = None
        self._discarding: threading.Thread | None = None
        self._none_left = False
        self._current: StartedCase | None = None
        self._timed = False
        """The current case's stack start is noted (or not to be: it started ahead)."""

    def run(self) -> None:
        ending: threading.Thread | None = None
        try:
            start = self._next()
            while start is not None:
                self._current, self._timed = start, start.ahead
                driven = drive_case(start, self._simulator, self._interrupt, self._watch)
                if driven.drive_wall_s is not None:
                    self._times.drove(driven.drive_wall_s)
                if ending is not None:
                    ending.join()
                ending = threading.Thread(
                    target=self._deliver, args=(driven,), name=f"{self.name}: ending"
                )
                ending.start()
                start = self._next()
        finally:
            if self._ahead is not None:  # the drive raised
                self._ahead.discard(self._interrupt.hurry)
            if self._discarding is not None:
                self._discarding.join()
            if ending is not None:
                ending.join()
            self._simulator.close(self._interrupt.hurry)

    def _next(self) -> StartedCase | None:
        """The next case, started: the one started ahead, else the one to start afresh,
        else the batch's next; None when none is left or the batch stops."""
        if self._discarding is not None:  # its folder is gone before it is made anew
            self._discarding.join()
            self._discarding = None
        ahead, self._ahead = self._ahead, None
        pending, self._pending = self._pending, None
        if self._interrupt.stop.is_set():
            if ahead is not None:
                ahead.discard(self._interrupt.hurry)
            if ahead is not None or pending is not None:
                self._give_back()
            return None
        if ahead is not None:
            return ahead
        case = pending if pending is not None else self._take()
        return None if case is None else start_case(case, self._out_dir)

    def _watch(self, driving_s: float) -> None:
        """While a case drives: start the next one's stack when due; start it afresh
        later if its simulator is still busy too long after (DriveTimes.ahead_limit)."""
        if not self._timed and self._current is not None:
            self._timed = True
            began = time.monotonic() - driving_s
            self._times.started(began - self._current.stack.started)
        if self._ahead is not None:
            if time.monotonic() - self._ahead.started > self._times.ahead_limit():
                # In a thread: the drive is still watched while the stack stops.
                self._discarding = threading.Thread(
                    target=self._ahead.discard,
                    args=(self._interrupt.hurry,),
                    name=f"{self.name}: restarting",
                )
                self._discarding.start()
                self._pending, self._ahead = self._ahead.case, None
            return
        if self._pending is not None or self._none_left:
            return
        if driving_s < self._times.ahead_after():
            return
        case = self._take()
        if case is None:
            self._none_left = True
            return
        self._ahead = start_case(case, self._out_dir, ahead=True)
