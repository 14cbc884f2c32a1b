"""Conditions and triggers: what each condition measures, its edge and its delay.

A condition's measurement is a Check (a function of the running scenario). The edge is
applied to the measured truth first (rising: false before, true now; falling; either;
none: the truth itself; MORAI's `once`: true from the first time it was true), then the
delay: the condition reads the edge's result of `delay` s ago. The first evaluation
sees no edge (a condition true from the start has not risen), and the delayed result
counts as false until `delay` s of results exist. A ConditionGroup holds when all its conditions
do, a Trigger when any of its groups does; every condition is evaluated at every step
its element waits on it, so edges and delays see every step.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.expressions import Value
from egosim.world.openscenario.parameters import compare
from egosim.world.openscenario.runtime import Runtime, UnknownEntityError

EDGES = ("rising", "falling", "risingOrFalling", "none", "once")
Check = Callable[[Runtime], bool]
EntityCheck = Callable[[Runtime, EntityState], bool]


@dataclass
class Condition:
    name: str
    check: Check
    edge: str = "none"
    delay: float = 0.0
    _previous: bool | None = None
    _latched: bool = False
    _history: deque[tuple[float, bool]] = field(default_factory=deque)

    def evaluate(self, rt: Runtime) -> bool:
        try:
            now = bool(self.check(rt))
        except UnknownEntityError as error:
            rt.note_once(f"condition {self.name!r} does not hold: {error}")
            now = False
        previous = now if self._previous is None else self._previous
        self._previous = now
        if self.edge == "rising":
            result = now and not previous
        elif self.edge == "falling":
            result = previous and not now
        elif self.edge == "risingOrFalling":
            result = now != previous
        elif self.edge == "once":
            self._latched = self._latched or now
            result = self._latched
        else:
            result = now
        if self.delay <= 0.0:
            return result
        history = self._history
        history.append((rt.time, result))
        due = rt.time - self.delay + 1e-9
        while len(history) > 1 and history[1][0] <= due:
            history.popleft()
        return history[0][1] if history[0][0] <= due else False


@dataclass
class Trigger:
    """Condition groups (OR of ANDs); an empty trigger never fires."""

    groups: list[list[Condition]]

    def evaluate(self, rt: Runtime) -> bool:
        fired = False
        for group in self.groups:
            results = [condition.evaluate(rt) for condition in group]
            fired = fired or (bool(results) and all(results))
        return fired


def by_entities(entities: Sequence[str], rule: str, check: EntityCheck) -> Check:
    """TriggeringEntities: the check holds for any (or all) of the entities in the world."""

    def evaluate(rt: Runtime) -> bool:
        results = []
        for name in entities:
            entity = rt.entities.get(name)
            results.append(entity is not None and entity.in_world() and check(rt, entity))
        return any(results) if rule == "any" else bool(results) and all(results)

    return evaluate


def rule_check(
    rule: str, value: float, measure: Callable[[Runtime, EntityState], float]
) -> EntityCheck:
    def check(rt: Runtime, entity: EntityState) -> bool:
        measured = measure(rt, entity)
        if math.isnan(measured):
            return False
        return compare(rule, measured, value)

    return check


def value_check(rule: str, value: Value, read: Callable[[Runtime], Value | None]) -> Check:
    def check(rt: Runtime) -> bool:
        current = read(rt)
        return current is not None and compare(rule, current, value)

    return check


def element_state_check(element_type: str, name: str, state: str) -> Check:
    """StoryboardElementStateCondition: a state (standbyState, runningState,
    completeState) or a transition of the last step (startTransition, endTransition,
    stopTransition, skipTransition)."""

    def check(rt: Runtime) -> bool:
        element = rt.elements.get((element_type, name))
        if element is None:
            return False
        if state.endswith("State"):
            return element.state == state
        return element.transitioned(state, rt.tick)

    return check
