"""What a layer above the app (the live view) gets of a running simulator: the app
knows nothing of what is attached. An attachment that works per tick adds a stage to
`context.pipeline` (TickPipeline.with_stage) when it is built, before the loop runs."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from ..bridge import BridgeContext
from ..ros1 import Node
from ..world.scenario import Scenario
from .inbox import Inbox
from .options import RunOptions


@dataclass(frozen=True)
class RunningSimulator:
    options: RunOptions
    context: BridgeContext
    inbox: Inbox
    node: Node
    startup_scenario: Callable[[], Scenario] | None
    """Reads the scenario the run started with again (None: it started with none)."""


class Attachment(Protocol):
    def close(self) -> None:
        """Stop (the simulator is stopping)."""


Attach = Callable[[RunningSimulator], Attachment]
"""Builds an attachment once the simulator is up; may raise StartupError."""
