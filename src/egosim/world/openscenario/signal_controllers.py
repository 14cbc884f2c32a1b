"""RoadNetwork's TrafficSignalControllers: each cycles through its phases, and on
entering a phase sets the lights the phase names (OpenDRIVE signal ids).

A controller's `delay` (with a `reference`, after that controller's start) shifts its
cycle: its first phase virtually starts `delay` s after the reference's first phase
(without a reference, after the scenario's start), so at the start it stands where its
cycle is then. TrafficSignalControllerAction jumps a controller to the start of a
phase; TrafficSignalControllerCondition holds while a controller is in a phase. A
TrafficSignalStateAction sets a light until its controller's next phase sets it again.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from egosim.world.openscenario.xmltree import Node


@dataclass(frozen=True)
class Phase:
    name: str
    duration: float
    states: tuple[tuple[str, int], ...]
    """(light id, aspect) the phase sets."""


@dataclass
class SignalController:
    """One TrafficSignalController while the scenario runs."""

    node: Node
    name: str
    phases: tuple[Phase, ...]
    delay: float = 0.0
    reference: str = ""
    start: float = 0.0
    """Scenario time its first phase (virtually) starts, s."""
    current: int = -1
    """The phase it is in (-1: none yet)."""
    _entered: float = field(default=0.0, repr=False)

    @property
    def cycle(self) -> float:
        return sum(phase.duration for phase in self.phases)

    def phase_at(self, time: float) -> tuple[int, float]:
        """The phase of the cycle at `time` and when that phase began."""
        cycle = self.cycle
        if cycle <= 0.0:
            return 0, self.start
        into = (time - self.start) % cycle
        began = time - into
        for k, phase in enumerate(self.phases):
            if into < phase.duration:
                return k, began
            into -= phase.duration
            began += phase.duration
        return len(self.phases) - 1, began

    def jump_to(self, phase: int, time: float) -> None:
        """TrafficSignalControllerAction: the phase starts now."""
        self.start = time - sum(p.duration for p in self.phases[:phase])
        self.current = -1

    @property
    def phase_name(self) -> str:
        return self.phases[self.current].name if 0 <= self.current < len(self.phases) else ""


def start_times(controllers: dict[str, SignalController]) -> list[str]:
    """Give each controller its start from its delay and reference chain; the problems
    (an unknown reference, a loop) as lines."""
    problems = []
    for controller in controllers.values():
        start, seen, current = 0.0, {controller.name}, controller
        while True:
            start += current.delay
            if not current.reference:
                break
            nxt = controllers.get(current.reference)
            if nxt is None:
                problems.append(
                    current.node.note(f"reference {current.reference!r}: no such controller")
                )
                break
            if nxt.name in seen:
                problems.append(current.node.note("references form a loop; delays ignored"))
                start = controller.delay
                break
            seen.add(nxt.name)
            current = nxt
        controller.start = start
    return problems
