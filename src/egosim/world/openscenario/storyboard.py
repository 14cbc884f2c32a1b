"""The storyboard's state machine: Story, Act, ManeuverGroup, Maneuver, Event, Action.

Every element is in standbyState, runningState or completeState and records its
transitions (startTransition, endTransition, stopTransition, skipTransition) with the
step they happened in. A step has three parts: `decide` evaluates the triggers at the
step's start time and starts or stops what they say, the entities then move (the
engine), and `settle` ends the actions that are done and every element whose children
are all complete.

- The storyboard runs its stories at once; its StopTrigger stops everything.
- An Act starts when its StartTrigger fires (at once without one, as 1.2+ allows) and
  stops when its StopTrigger fires.
- A ManeuverGroup runs its maneuvers; when all are complete it runs them again up to
  maximumExecutionCount times.
- An Event starts when its StartTrigger fires (at once without one); priority
  override/overwrite stops the maneuver's other running events, skip leaves it in
  standby (skipTransition) while another runs, parallel just starts it; it runs again
  up to maximumExecutionCount times (each time on a new trigger).
- An Action is complete when what it does is done (a speed reached, a lane changed) or
  when another action takes its entity's domain over.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

from egosim.world.openscenario.conditions import Trigger
from egosim.world.openscenario.runtime import Runtime
from egosim.world.openscenario.xmltree import Node

STANDBY, RUNNING, COMPLETE = "standbyState", "runningState", "completeState"
START, END, STOP, SKIP = "startTransition", "endTransition", "stopTransition", "skipTransition"
_KEPT_TRANSITIONS = 8


class ActionRun(Protocol):
    def done(self, rt: Runtime) -> bool: ...

    def stop(self, rt: Runtime) -> None: ...


class Action(Protocol):
    @property
    def node(self) -> Node: ...

    def start(self, rt: Runtime, actors: Sequence[str]) -> ActionRun: ...


@dataclass
class Element:
    kind: str
    name: str
    state: str = STANDBY
    transitions: list[tuple[int, str]] = field(default_factory=list)

    def transitioned(self, transition: str, tick: int) -> bool:
        return any(t >= tick - 1 and name == transition for t, name in self.transitions)

    def _go(self, rt: Runtime, transition: str, state: str) -> None:
        self.state = state
        self.transitions.append((rt.tick, transition))
        del self.transitions[:-_KEPT_TRANSITIONS]

    def register(self, rt: Runtime) -> None:
        rt.elements.setdefault((self.kind, self.name), self)


@dataclass
class ActionElement(Element):
    spec: Action | None = None
    run: ActionRun | None = None

    def start(self, rt: Runtime, actors: Sequence[str]) -> None:
        assert self.spec is not None
        self.run = self.spec.start(rt, actors)
        self._go(rt, START, RUNNING)

    def settle(self, rt: Runtime) -> None:
        if self.state == RUNNING and self.run is not None and self.run.done(rt):
            self.run.stop(rt)
            self._go(rt, END, COMPLETE)

    def stop(self, rt: Runtime) -> None:
        if self.state == RUNNING and self.run is not None:
            self.run.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)

    def reset(self) -> None:
        self.state, self.run = STANDBY, None


@dataclass
class EventElement(Element):
    priority: str = "override"
    maximum_executions: int = 1
    start_trigger: Trigger | None = None
    actions: list[ActionElement] = field(default_factory=list)
    executions: int = 0

    def decide(self, rt: Runtime, maneuver: ManeuverElement, actors: Sequence[str]) -> None:
        if self.state != STANDBY:
            return
        fired = self.start_trigger is None or self.start_trigger.evaluate(rt)
        if not fired:
            return
        others = [e for e in maneuver.events if e is not self and e.state == RUNNING]
        if self.priority == "skip" and others:
            self._go(rt, SKIP, STANDBY)
            return
        if self.priority in ("override", "overwrite"):
            for other in others:
                other.stop(rt)
        for action in self.actions:
            action.reset()
            action.start(rt, actors)
        self._go(rt, START, RUNNING)

    def settle(self, rt: Runtime) -> None:
        if self.state != RUNNING:
            return
        for action in self.actions:
            action.settle(rt)
        if all(a.state == COMPLETE for a in self.actions):
            self.executions += 1
            if self.executions < self.maximum_executions:
                self._go(rt, END, STANDBY)
            else:
                self._go(rt, END, COMPLETE)

    def stop(self, rt: Runtime) -> None:
        for action in self.actions:
            action.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)

    def reset(self) -> None:
        self.state, self.executions = STANDBY, 0
        for action in self.actions:
            action.reset()


@dataclass
class ManeuverElement(Element):
    events: list[EventElement] = field(default_factory=list)

    def start(self, rt: Runtime) -> None:
        for event in self.events:
            event.reset()
        self._go(rt, START, RUNNING)

    def decide(self, rt: Runtime, actors: Sequence[str]) -> None:
        if self.state == RUNNING:
            for event in self.events:
                event.decide(rt, self, actors)

    def settle(self, rt: Runtime) -> None:
        if self.state != RUNNING:
            return
        for event in self.events:
            event.settle(rt)
        if all(e.state == COMPLETE for e in self.events):
            self._go(rt, END, COMPLETE)

    def stop(self, rt: Runtime) -> None:
        for event in self.events:
            event.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)


@dataclass
class ManeuverGroupElement(Element):
    actors: tuple[str, ...] = ()
    maximum_executions: int = 1
    maneuvers: list[ManeuverElement] = field(default_factory=list)
    executions: int = 0

    def start(self, rt: Runtime) -> None:
        self.executions = 0
        self._go(rt, START, RUNNING)
        for maneuver in self.maneuvers:
            maneuver.start(rt)

    def decide(self, rt: Runtime) -> None:
        if self.state == RUNNING:
            for maneuver in self.maneuvers:
                maneuver.decide(rt, self.actors)

    def settle(self, rt: Runtime) -> None:
        if self.state != RUNNING:
            return
        for maneuver in self.maneuvers:
            maneuver.settle(rt)
        if all(m.state == COMPLETE for m in self.maneuvers):
            self.executions += 1
            if self.executions < self.maximum_executions:
                for maneuver in self.maneuvers:
                    maneuver.start(rt)
            else:
                self._go(rt, END, COMPLETE)

    def stop(self, rt: Runtime) -> None:
        for maneuver in self.maneuvers:
            maneuver.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)


@dataclass
class ActElement(Element):
    start_trigger: Trigger | None = None
    stop_trigger: Trigger | None = None
    groups: list[ManeuverGroupElement] = field(default_factory=list)

    def decide(self, rt: Runtime) -> None:
        if self.state == STANDBY:
            if self.start_trigger is None or self.start_trigger.evaluate(rt):
                self._go(rt, START, RUNNING)
                for group in self.groups:
                    group.start(rt)
                # Its events see their triggers in the step it starts (as the story's
                # acts do): an act adds no step of delay to what it holds.
                for group in self.groups:
                    group.decide(rt)
        elif self.state == RUNNING:
            if self.stop_trigger is not None and self.stop_trigger.evaluate(rt):
                self.stop(rt)
                return
            for group in self.groups:
                group.decide(rt)

    def settle(self, rt: Runtime) -> None:
        if self.state != RUNNING:
            return
        for group in self.groups:
            group.settle(rt)
        if all(g.state == COMPLETE for g in self.groups):
            self._go(rt, END, COMPLETE)

    def stop(self, rt: Runtime) -> None:
        for group in self.groups:
            group.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)


@dataclass
class StoryElement(Element):
    acts: list[ActElement] = field(default_factory=list)

    def decide(self, rt: Runtime) -> None:
        if self.state == STANDBY:
            self._go(rt, START, RUNNING)
        if self.state == RUNNING:
            for act in self.acts:
                act.decide(rt)

    def settle(self, rt: Runtime) -> None:
        if self.state != RUNNING:
            return
        for act in self.acts:
            act.settle(rt)
        if all(a.state == COMPLETE for a in self.acts):
            self._go(rt, END, COMPLETE)

    def stop(self, rt: Runtime) -> None:
        for act in self.acts:
            act.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)


@dataclass
class Storyboard(Element):
    init: list[tuple[ActionElement, tuple[str, ...]]] = field(default_factory=list)
    stories: list[StoryElement] = field(default_factory=list)
    stop_trigger: Trigger | None = None

    def elements(self) -> list[Element]:
        found: list[Element] = []
        for story in self.stories:
            found.append(story)
            for act in story.acts:
                found.append(act)
                for group in act.groups:
                    found.append(group)
                    for maneuver in group.maneuvers:
                        found.append(maneuver)
                        for event in maneuver.events:
                            found.append(event)
                            found.extend(event.actions)
        return found

    def begin(self, rt: Runtime) -> None:
        for element in self.elements():
            element.register(rt)
        self._go(rt, START, RUNNING)
        for action, actors in self.init:
            action.start(rt, actors)

    def decide(self, rt: Runtime) -> None:
        if self.state != RUNNING:
            return
        if self.stop_trigger is not None and self.stop_trigger.evaluate(rt):
            self.stop(rt)
            return
        for story in self.stories:
            story.decide(rt)

    def settle(self, rt: Runtime) -> None:
        for action, _ in self.init:
            action.settle(rt)
        if self.state != RUNNING:
            return
        for story in self.stories:
            story.settle(rt)

    def stop(self, rt: Runtime) -> None:
        for action, _ in self.init:
            action.stop(rt)
        for story in self.stories:
            story.stop(rt)
        if self.state != COMPLETE:
            self._go(rt, STOP, COMPLETE)
