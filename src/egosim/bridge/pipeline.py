"""The tick pipeline: what one simulation tick does, in order, as named stages.

The real-time loop, sync mode's WaitForTick, the benchmarks and the tests all advance
the simulation through one `TickPipeline`, so a new per-tick job (render the cameras,
feed the live view) is one more stage in one list and nowhere else. The standard
stages are in `bridge/stages.py`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Generic, TypeVar

Context = TypeVar("Context")


@dataclass(frozen=True)
class Tick:
    """One tick of the simulation loop."""

    dt: float
    """The world's step, s."""
    loop_time: float
    """Loop time at the end of this tick, s. It advances while the world is paused, so
    rows keep publishing at their rates (headers still carry the simulator's clock)."""


@dataclass(frozen=True)
class Stage(Generic[Context]):
    """A named part of a tick; `run` gets the context the handlers see and the tick."""

    name: str
    run: Callable[[Context, Tick], None]


class TickPipeline(Generic[Context]):
    """Runs its stages in order, once per tick."""

    def __init__(self, stages: Sequence[Stage[Context]]) -> None:
        names = [stage.name for stage in stages]
        if len(set(names)) != len(names):
            raise ValueError(f"stage names must be unique: {names}")
        self.stages = tuple(stages)
        self.loop_time = 0.0

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(stage.name for stage in self.stages)

    def with_stage(
        self, stage: Stage[Context], *, after: str | None = None, before: str | None = None
    ) -> TickPipeline[Context]:
        """This pipeline with `stage` run right after the stage named `after`, or right
        before the one named `before` (one of the two)."""
        if (after is None) == (before is None):
            raise ValueError("give one of after= and before=")
        index = self.names.index(after) + 1 if after is not None else self.names.index(before)
        return TickPipeline([*self.stages[:index], stage, *self.stages[index:]])

    def run(self, context: Context, dt: float) -> Tick:
        """Advance one tick of `dt` s through every stage; the tick that ran."""
        self.loop_time += dt
        tick = Tick(dt, self.loop_time)
        for stage in self.stages:
            stage.run(context, tick)
        return tick
