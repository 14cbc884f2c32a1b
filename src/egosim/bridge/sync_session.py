"""The state of MORAI's synchronous mode: who runs it, the frame, the tick length, and the
requests kept for later frames (the services are in bridge/sync_mode.py)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

MAX_PENDING_ACTIONS = 10_000

# An action applied in a later tick: (context) -> whether it succeeded.
Action = Callable[[Any], bool]


@dataclass
class SyncSession:
    """The synchronous-mode state of a `--clock sync` run."""

    active: bool = False
    user_id: str = ""
    frame: int = 0
    time_step_ms: int = 0
    _pending: dict[int, list[tuple[str, Action]]] = field(default_factory=dict)
    _pending_count: int = 0

    def schedule(self, frame: int, service: str, action: Action) -> bool:
        """Keep `action` for the tick producing `frame`; False when too many wait."""
        if self._pending_count >= MAX_PENDING_ACTIONS:
            return False
        self._pending.setdefault(frame, []).append((service, action))
        self._pending_count += 1
        return True

    def due(self, frame: int) -> list[tuple[str, Action]]:
        """The (service, action) pairs kept for `frame`, in arrival order, now taken."""
        actions = self._pending.pop(frame, [])
        self._pending_count -= len(actions)
        return actions

    def drop_pending(self) -> None:
        self._pending.clear()
        self._pending_count = 0
