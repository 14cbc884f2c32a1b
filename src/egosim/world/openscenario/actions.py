"""Actions as read from the file, and what starting one does.

Private actions act on each actor. Those that move an entity (speed, lane change, lane
offset, distance keeping, synchronisation, trajectories) take over the entity's
longitudinal and/or lateral domain and run in the default controller (motion.py) until
done; the rest happen at once. An ego its stack drives is moved only by teleports: the
scenario's other motion actions on it are reported once and count as done.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.expressions import Value
from egosim.world.openscenario.following import Timing, TrajectoryRun
from egosim.world.openscenario.motion import MotionRun
from egosim.world.openscenario.parameters import text_of
from egosim.world.openscenario.positions import (
    PathSource,
    Position,
    PositionError,
    RouteSource,
    attach,
    place,
)
from egosim.world.openscenario.routes import shortest_lanes
from egosim.world.openscenario.runtime import Runtime, UnknownEntityError
from egosim.world.openscenario.xmltree import Node

MotionFactory = Callable[[Runtime, EntityState], MotionRun]


class Done:
    """An action that happened at once."""

    def done(self, rt: Runtime) -> bool:
        return True

    def stop(self, rt: Runtime) -> None:
        return None


@dataclass
class MotionRuns:
    """One MotionRun per actor; done when each is done or taken over."""

    runs: list[tuple[EntityState, MotionRun]]

    def done(self, rt: Runtime) -> bool:
        return all(run.done or run.overridden for _, run in self.runs)

    def stop(self, rt: Runtime) -> None:
        for entity, run in self.runs:
            run.release(entity)


def _actor(rt: Runtime, name: str, node: Node) -> EntityState | None:
    entity = rt.entities.get(name)
    if entity is None:
        rt.note_once(node.note(f"names no entity {name!r}; not applied"))
    return entity


@dataclass(frozen=True)
class MotionAction:
    """Any action that moves its actors through a MotionRun made for each."""

    node: Node
    make: MotionFactory

    def start(self, rt: Runtime, actors: Sequence[str]) -> MotionRuns:
        runs = []
        for name in actors:
            entity = _actor(rt, name, self.node)
            if entity is None:
                continue
            if not rt.scenario_drives(entity):
                rt.note_once(
                    self.node.note(
                        f"on {name!r} not applied: the ego is driven by its stack (in control "
                        "mode auto the scenario drives it)"
                    )
                )
                continue
            run: MotionRun | None = None
            try:
                run = self.make(rt, entity)
                run.begin(rt, entity)
            except (PositionError, UnknownEntityError) as error:
                if run is not None:
                    run.release(entity)  # the domains it took are free again
                rt.note_once(self.node.note(f"on {name!r} not applied: {error}"))
                continue
            runs.append((entity, run))
        return MotionRuns(runs)


@dataclass(frozen=True)
class TeleportAction:
    node: Node
    position: Position

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        for name in actors:
            entity = _actor(rt, name, self.node)
            if entity is None:
                continue
            try:
                placement = self.position.resolve(rt)
            except PositionError as error:
                rt.note_once(self.node.note(f"on {name!r} not applied: {error}"))
                continue
            for run in {id(r): r for r in (entity.longitudinal, entity.lateral) if r}.values():
                if run.follows_path:
                    run.overridden = True
                    run.release(entity)
            place(rt, entity, placement)
            entity.present = True
        return Done()


def follow_trajectory(
    node: Node, trajectory: PathSource, timing: Timing | None, initial_distance: float | None
) -> MotionAction:
    return MotionAction(node, lambda rt, e: TrajectoryRun(trajectory, timing, initial_distance))


@dataclass(frozen=True)
class AssignRouteAction:
    node: Node
    route: RouteSource

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        try:
            lanes = self.route.lanes(rt)
        except PositionError as error:
            rt.note_once(self.node.note(f"not applied: {error}"))
            return Done()
        for name in actors:
            entity = _actor(rt, name, self.node)
            if entity is not None:
                entity.route, entity.route_position = lanes.lanes, 0
        return Done()


@dataclass(frozen=True)
class AcquirePositionAction:
    """The entity's route becomes the shortest way along the lanes to the position."""

    node: Node
    position: Position

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        for name in actors:
            entity = _actor(rt, name, self.node)
            if entity is None or entity.lane < 0:
                continue
            try:
                placement = self.position.resolve(rt)
                goal = placement.lane or attach(rt, placement)
                if goal is None:
                    raise PositionError("the position lies on no lane")
                entity.route = tuple(shortest_lanes(rt, entity.lane, goal.lane_index))
                entity.route_position = 0
            except PositionError as error:
                rt.note_once(self.node.note(f"on {name!r} not applied: {error}"))
        return Done()


@dataclass(frozen=True)
class VisibilityAction:
    """graphics, traffic and sensors; egosim shows an entity (object lists, sensors,
    collisions) while `sensors` is true."""

    node: Node
    graphics: bool
    traffic: bool
    sensors: bool

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        for name in actors:
            entity = _actor(rt, name, self.node)
            if entity is not None:
                entity.visible = self.sensors
        return Done()


@dataclass(frozen=True)
class ControllerAction:
    """AssignControllerAction / ActivateControllerAction: an external controller hands
    the ego to its stack; the other controllers are the default controller here."""

    node: Node
    external: bool | None
    """True: the assigned controller is external; None: activation only."""

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        for name in actors:
            entity = _actor(rt, name, self.node)
            if entity is None:
                continue
            if self.external and not entity.is_ego:
                rt.note_once(
                    self.node.note(f"on {name!r}: only the ego has an external driver (its stack)")
                )
            elif self.external is False and not entity.is_ego:
                rt.note_once(
                    self.node.note(
                        f"on {name!r}: the controller is not simulated; the default "
                        "controller drives"
                    )
                )
        return Done()


@dataclass(frozen=True)
class NoteAction:
    """An action egosim reads but does not carry out: reported once, done at once."""

    node: Node
    reason: str
    """Empty: already reported when the file was read."""

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        if self.reason:
            rt.note_once(self.node.note(self.reason))
        return Done()


@dataclass(frozen=True)
class EntityAction:
    """AddEntityAction (at a position) or DeleteEntityAction of the entity named."""

    node: Node
    entity: str
    position: Position | None
    """None: delete."""

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        entity = _actor(rt, self.entity, self.node)
        if entity is None:
            return Done()
        if self.position is None:
            entity.present = False
            return Done()
        try:
            place(rt, entity, self.position.resolve(rt))
            entity.present = True
        except PositionError as error:
            rt.note_once(self.node.note(f"not applied: {error}"))
        return Done()


@dataclass(frozen=True)
class ValueAction:
    """ParameterSetAction / ParameterModifyAction and their Variable forms (1.2)."""

    node: Node
    store: str
    """"parameters" or "variables"."""
    name: str
    operation: str
    """"set", "add" or "multiply"."""
    value: Value

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        values = rt.parameters if self.store == "parameters" else rt.variables
        if self.name not in values:
            rt.note_once(self.node.note(f"names no declared {self.store[:-1]} {self.name!r}"))
            return Done()
        current = values[self.name]
        if self.operation == "set":
            values[self.name] = _like(current, self.value)
            return Done()
        try:
            number = float(current)
            change = float(self.value)
        except ValueError:
            rt.note_once(self.node.note(f"{self.name!r} is not a number; not modified"))
            return Done()
        values[self.name] = number + change if self.operation == "add" else number * change
        return Done()


def _like(current: Value, value: Value) -> Value:
    """`value` in the type of `current`."""
    if isinstance(current, bool):
        return value if isinstance(value, bool) else text_of(value).strip().lower() == "true"
    if isinstance(current, float):
        try:
            return float(value)
        except ValueError:
            return current
    return text_of(value)


@dataclass(frozen=True)
class TrafficSignalStateAction:
    node: Node
    light: str
    aspect: int

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        signals = rt.world.signals
        try:
            signals.set_light(self.light, self.aspect)
        except (KeyError, ValueError) as error:
            rt.note_once(self.node.note(f"not applied: {error}"))
        return Done()


@dataclass(frozen=True)
class SignalPhaseAction:
    """TrafficSignalControllerAction: the controller's phase starts now."""

    node: Node
    controller: str
    phase: str

    def start(self, rt: Runtime, actors: Sequence[str]) -> Done:
        controller = rt.signal_controllers.get(self.controller)
        if controller is None:
            rt.note_once(self.node.note(f"not applied: no controller {self.controller!r}"))
            return Done()
        names = [phase.name for phase in controller.phases]
        if self.phase not in names:
            rt.note_once(
                self.node.note(f"not applied: {self.controller!r} has no phase {self.phase!r}")
            )
            return Done()
        controller.jump_to(names.index(self.phase), rt.time)
        return Done()


@dataclass(frozen=True)
class SpeedInInit:
    """An Init SpeedAction on an ego its stack drives: the ego starts at that speed."""

    node: Node
    speed: Callable[[Runtime], float]
    motion: MotionAction

    def start(self, rt: Runtime, actors: Sequence[str]) -> MotionRuns | Done:
        stack_driven = [
            name
            for name in actors
            if name in rt.entities and not rt.scenario_drives(rt.entity(name))
        ]
        for name in stack_driven:
            rt.entity(name).speed = self.speed(rt)
        others = [name for name in actors if name not in stack_driven]
        return self.motion.start(rt, others) if others else Done()
