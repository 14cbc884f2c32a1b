"""What a layer above the app (the live view) gets of a running simulator, and the hooks
it gives back: the app knows nothing of what is attached."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from ..bridge.context import BridgeContext
from ..bridge.network import NetworkSettings
from ..ros1 import Node
from ..world.scenario import Scenario
from .inbox import Inbox
from .options import RunOptions


@dataclass(frozen=True)
class RunningSimulator:
    options: RunOptions
    context: BridgeContext
    settings: NetworkSettings
    inbox: Inbox
    node: Node
    startup_scenario: Callable[[], Scenario] | None
    """Reads the scenario the run started with again (None: it started with none)."""


class Attachment(Protocol):
    def after_step(self) -> None:
        """Run on the loop thread after every tick; must not wait on anything."""

    def close(self) -> None:
        """Stop (the simulator is stopping)."""


Attach = Callable[[RunningSimulator], Attachment]
"""Builds an attachment once the simulator is up; may raise StartupError."""
