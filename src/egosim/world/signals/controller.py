"""A fixed-time controller running one intersection's phase program."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from egosim.world.signals.errors import UnknownPhaseError
from egosim.world.signals.phases import Phase


@dataclass(frozen=True)
class IntersectionStatus:
    """IntersectionStatus semantics: the phase in force and the time spent in it (s)."""

    intersection_id: int
    phase_index: int
    elapsed_s: float


class IntersectionController:
    """Cycles through `program`; phase_index and elapsed_s say where it is."""

    def __init__(
        self,
        intersection_id: int,
        light_ids: Sequence[str],
        program: Sequence[Phase],
        phase_index: int = 0,
        elapsed_s: float = 0.0,
    ) -> None:
        if not program:
            raise ValueError(f"intersection {intersection_id} has an empty phase program")
        self.intersection_id = intersection_id
        self.light_ids = tuple(light_ids)
        self.program = tuple(program)
        self._slot = {light_id: k for k, light_id in enumerate(self.light_ids)}
        self.phase_index = 0
        self.elapsed_s = 0.0
        self.jump(phase_index, elapsed_s)

    def jump(self, phase_index: int, elapsed_s: float = 0.0) -> None:
        """Put the program in phase `phase_index`, `elapsed_s` into it (longer rolls on)."""
        if not 0 <= phase_index < len(self.program):
            raise UnknownPhaseError(self.intersection_id, phase_index, len(self.program))
        if not elapsed_s >= 0.0:
            raise ValueError(f"elapsed time must be >= 0 s, got {elapsed_s}")
        self.phase_index = phase_index
        self.elapsed_s = 0.0
        self.step(elapsed_s)

    def step(self, dt: float) -> bool:
        """Run on dt s; True if a new phase began."""
        self.elapsed_s += dt
        if self.elapsed_s < self.program[self.phase_index].duration_s:
            return False
        while self.elapsed_s >= self.program[self.phase_index].duration_s:
            self.elapsed_s -= self.program[self.phase_index].duration_s
            self.phase_index = (self.phase_index + 1) % len(self.program)
        return True

    @property
    def phase(self) -> Phase:
        return self.program[self.phase_index]

    def aspect(self, light_id: str) -> int:
        return self.phase.aspects[self._slot[light_id]]

    def status(self) -> IntersectionStatus:
        return IntersectionStatus(self.intersection_id, self.phase_index, self.elapsed_s)
