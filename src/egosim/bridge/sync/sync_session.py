"""The state of MORAI's synchronous mode: who runs it, the frame, the tick length, and the
requests kept for later frames (the services are in bridge/sync/sync_mode.py).

Any run can be switched into synchronous mode (SyncModeCmd start) and back out of it
(stop); while it is on, the world advances only on WaitForTick and the loop does not
step it. `--clock sync` starts a run holding the world for the first client's start.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Generic, TypeVar

MAX_PENDING_ACTIONS = 10_000

Context = TypeVar("Context")
"""What an action is applied to: the bridge's context (bridge/context.py, which holds
the session)."""

# An action applied in a later tick: (context) -> whether it succeeded.
Action = Callable[[Context], bool]


@dataclass
class SyncSession(Generic[Context]):
    """The synchronous-mode state of a run."""

    active: bool = False
    """A client has started synchronous mode and owns time."""
    awaiting_client: bool = False
    """The run started in synchronous mode (--clock sync): the world waits for a client's
    start before it moves."""
    user_id: str = ""
    frame: int = 0
    time_step_ms: int = 0
    capture_cameras: bool = False
    """The tick being produced publishes the camera frames (SyncModeCtrlCmd's
    sensor_capture); cleared when the tick ends."""
    _pending: dict[int, list[tuple[str, Action[Context]]]] = field(default_factory=dict)
    _pending_count: int = 0

    @property
    def holds_time(self) -> bool:
        """The loop must not step the world: only WaitForTick advances it."""
        return self.active or self.awaiting_client

    def start(self, user_id: str, time_step_ms: int) -> None:
        self.active, self.awaiting_client = True, False
        self.user_id, self.time_step_ms = user_id, time_step_ms

    def stop(self) -> None:
        """Give time back to the loop; requests kept for later frames are dropped."""
        self.active, self.awaiting_client = False, False
        self.drop_pending()

    def schedule(self, frame: int, service: str, action: Action[Context]) -> bool:
        """Keep `action` for the tick producing `frame`; False when too many wait."""
        if self._pending_count >= MAX_PENDING_ACTIONS:
            return False
        self._pending.setdefault(frame, []).append((service, action))
        self._pending_count += 1
        return True

    def due(self, frame: int) -> list[tuple[str, Action[Context]]]:
        """The (service, action) pairs kept for `frame`, in arrival order, now taken."""
        actions = self._pending.pop(frame, [])
        self._pending_count -= len(actions)
        return actions

    def drop_pending(self) -> None:
        self._pending.clear()
        self._pending_count = 0
