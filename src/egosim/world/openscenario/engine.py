"""A storyboard running on a world: the step the tick pipeline's storyboard stage runs.

Each step: the ego's state is read from the world (when its stack drives it), the
entities' contacts and whereabouts are brought up to date, the storyboard decides
(triggers at the step's start time), the entities the scenario drives move by dt, the
storyboard settles (what is done ends), and the world is handed the new poses: the
scripted objects' table, and the ego's pose when the scenario drives it (or a teleport
put it somewhere).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from egosim.world.collision import Footprints, touching_pairs
from egosim.world.openscenario.conditions import Trigger
from egosim.world.openscenario.ego_model import UnusableFiguresError, scenario_ego_model
from egosim.world.openscenario.entities import EntityDefinition, EntityKind, EntityState
from egosim.world.openscenario.motion import move_all
from egosim.world.openscenario.runtime import Runtime, UnknownEntityError
from egosim.world.openscenario.signal_controllers import SignalController
from egosim.world.openscenario.storyboard import COMPLETE, Storyboard
from egosim.world.scenario.model import Outcome, StoryboardWorld
from egosim.world.traffic.scripted import ScriptedObject
from egosim.world.vehicle import Pose, Vehicle
from egosim.world.vehicle.catalogue import VehicleModel


@dataclass
class Evaluation:
    """MORAI's <Evaluation>: the scenario succeeds when a success group fires and fails
    when a failure group does; either ends it."""

    success: Trigger | None
    failure: Trigger | None

    def decide(self, rt: Runtime) -> str | None:
        failed = self.failure is not None and self.failure.evaluate(rt)
        succeeded = self.success is not None and self.success.evaluate(rt)
        if failed:
            return "failure"
        if succeeded:
            return "success"
        return None


class ScenarioRun:
    """An OpenSCENARIO storyboard on a world (world.storyboard)."""

    def __init__(
        self,
        world: StoryboardWorld,
        storyboard: Storyboard,
        evaluation: Evaluation,
        signal_controllers: dict[str, SignalController],
        definitions: list[EntityDefinition],
        ego: str | None,
        parameters: dict[str, object],
        variables: dict[str, object],
        load_ego: bool,
        kinds: frozenset[str],
        drives_ego: bool,
    ) -> None:
        self.world = world
        self.storyboard = storyboard
        self.evaluation = evaluation
        self.verdict: str | None = None
        self._ended_at: float | None = None
        """Scenario time the storyboard ended (its stop trigger or a verdict fired, or its
        stories all completed)."""
        entities: dict[str, EntityState] = {}
        notes: list[str] = []
        for definition in definitions:
            if definition.name == ego:
                entities[definition.name] = EntityState(
                    self._ego_definition(definition, load_ego, notes), is_ego=True
                )
            elif definition.kind.value in kinds:
                entities[definition.name] = EntityState(definition)
        self.rt = Runtime(world, entities, dict(parameters), dict(variables), ego)  # type: ignore[arg-type]
        self.rt.ego_driven = drives_ego
        self.rt.signal_controllers = signal_controllers
        for note in notes:
            self.rt.note_once(note)
        self.load_ego = load_ego
        others = [e for e in entities.values() if not e.is_ego]
        self._ids = dict(zip((e.name for e in others), world.reserve_ids(len(others)), strict=True))
        self._footprints: Footprints | None = None
        self._names: list[str] = []
        self._ego_last: tuple[float, float] | None = None
        if ego is not None and ego in entities:
            self._read_ego(entities[ego])
            entities[ego].placed = True
        self._run_signal_controllers()
        storyboard.begin(self.rt)
        storyboard.settle(self.rt)
        for entity in entities.values():
            if not entity.placed:
                self.rt.note_once(
                    f"entity {entity.name!r} has no position after Init: it appears when an "
                    "action places it"
                )
        self._publish(initial=True)

    def _ego_definition(
        self, definition: EntityDefinition, load_ego: bool, notes: list[str]
    ) -> EntityDefinition:
        """The ego becomes the scenario's car (scenario_ego_model) when the scenario
        places it and its model is a car; its box is then the scenario's."""
        main = self.world.egos[0]
        base = main.catalogue_model
        model = main.vehicle.model
        if load_ego and isinstance(base, VehicleModel):
            model = base
            if definition.kind is EntityKind.VEHICLE:
                try:
                    model = scenario_ego_model(definition, base)
                except UnusableFiguresError as error:
                    notes.append(
                        f"the ego {definition.name!r} keeps the figures of {base.name}: "
                        f"the scenario's {error}"
                    )
            main.use_model(model, self.world.command_timeout_s)
        return EntityDefinition(
            definition.name,
            EntityKind.VEHICLE,
            model.name,
            definition.category,
            model.length,
            model.width,
            model.height,
            (model.box_centre_ahead_of_reference, 0.0, model.height / 2.0),
            external=definition.external,
        )

    # -- what the scenario says --------------------------------------------------------

    @property
    def finished(self) -> bool:
        return self.storyboard.state == COMPLETE or self.verdict is not None

    @property
    def ego(self) -> EntityState | None:
        name = self.rt.ego
        return None if name is None else self.rt.entities.get(name)

    def outcome(self) -> Outcome:
        if self.verdict is not None:
            state = self.verdict
        elif self.storyboard.state == COMPLETE:
            state = "stopped"
        else:
            state = "running"
        return Outcome(
            state, self.rt.time if self._ended_at is None else self._ended_at, self.verdict
        )

    def entity_ids(self) -> dict[str, int]:
        """The egosim object id of each entity (the ego's is the main ego's)."""
        ids = dict(self._ids)
        if self.rt.ego is not None and self.rt.ego in self.rt.entities:
            ids[self.rt.ego] = self.world.egos[0].unique_id
        return ids

    # -- stepping ----------------------------------------------------------------------

    def step(self, dt: float, ego_driven: bool) -> list[str]:
        rt = self.rt
        if self.finished:
            return self._drain()
        rt.ego_driven = ego_driven
        ego = self.ego
        if ego is not None and not ego_driven:
            self._read_ego(ego)
        self._observe(dt)
        self._run_signal_controllers()
        try:
            self.storyboard.decide(rt)
            if self.verdict is None:
                self.verdict = self.evaluation.decide(rt)
        except UnknownEntityError as error:
            # Actions and conditions say so themselves; this is for what starts with one.
            rt.note_once(f"a storyboard element was left out: it refers to {error}")
        if self.finished:
            # A stop trigger or a verdict ends the scenario at the time it fired.
            self._ended_at = rt.time
        movers = [e for e in rt.entities.values() if e.in_world() and rt.scenario_drives(e)]
        move_all(rt, movers, dt)
        self._take_out_the_lost(movers)
        self.storyboard.settle(rt)
        # Rounded to the nanosecond: summing steps of 0.01 s drifts (300 of them make
        # 2.99999999999998), which would move a condition on time by a whole step.
        rt.time = round(rt.time + dt, 9)
        rt.tick += 1
        if self.finished and self._ended_at is None:
            self._ended_at = rt.time
        self._publish()
        return self._drain()

    def _take_out_the_lost(self, movers: list[EntityState]) -> None:
        """An entity whose motion stopped being finite (a speed of 1e308 m/s, say) leaves
        the world, said once, rather than reach the world's lanes and contacts."""
        for entity in movers:
            values = (entity.x, entity.y, entity.z, entity.heading, entity.speed)
            if not all(map(math.isfinite, values)):
                entity.present = False
                self.rt.note_once(
                    f"entity {entity.name!r} left the world: its motion is not finite"
                )

    def _run_signal_controllers(self) -> None:
        """Each controller's phase now; a phase it enters sets its lights."""
        rt = self.rt
        for controller in rt.signal_controllers.values():
            if not controller.phases:
                continue
            phase, _ = controller.phase_at(rt.time)
            if phase == controller.current:
                continue
            controller.current = phase
            for light, aspect in controller.phases[phase].states:
                try:
                    rt.world.signals.set_light(light, aspect)
                except (KeyError, ValueError) as error:
                    rt.note_once(controller.node.note(f"phase {controller.phase_name!r}: {error}"))

    def _drain(self) -> list[str]:
        notes, self.rt.notes = self.rt.notes, []
        return notes

    def _read_ego(self, ego: EntityState) -> None:
        vehicle = self.world.egos[0].vehicle
        status = vehicle.status()
        pose = status.pose
        ego.x, ego.y, ego.z, ego.heading = pose.x, pose.y, pose.z, pose.yaw
        ego.speed = status.velocity[0]
        ego.acceleration = status.acceleration[0]
        ego.lateral_speed = status.velocity[1]
        lane = self.world.ego_lane_state(0)
        ego.lane = self.rt.lane_map.lane_index(lane.lane_id)
        ego.station, ego.offset = lane.s, lane.lateral_offset

    def _observe(self, dt: float) -> None:
        """Contacts between the entities (swept over the last step), time off the road,
        the ego's odometer and standstill when its stack drives it."""
        rt = self.rt
        present = [e for e in rt.entities.values() if e.in_world() and e.visible]
        for entity in rt.entities.values():
            entity.collisions = set()
        if present:
            centres = np.array([e.box_centre() for e in present])
            now = Footprints(
                centres,
                np.array([e.heading for e in present]),
                np.array([e.definition.length for e in present]),
                np.array([e.definition.width for e in present]),
            )
            before = self._footprints
            names = [e.name for e in present]
            if before is None or len(before.headings) != len(present) or self._names != names:
                before = now
            self._footprints, self._names = now, names
            for i, j in touching_pairs(before, now):
                present[i].collisions.add(present[j].name)
                present[j].collisions.add(present[i].name)
            for entity, is_off in zip(present, self._offroad(present, centres), strict=True):
                entity.offroad_s = entity.offroad_s + dt if is_off else 0.0
        ego = self.ego
        if ego is not None and not rt.ego_driven:
            if self._ego_last is not None:
                x0, y0 = self._ego_last
                ego.odometer += math.hypot(ego.x - x0, ego.y - y0)
            self._ego_last = (ego.x, ego.y)
            ego.standstill_s = ego.standstill_s + dt if abs(ego.speed) < 1e-3 else 0.0

    def _offroad(self, entities: list[EntityState], centres: np.ndarray) -> list[bool]:
        """Per entity: its box centre lies off every lane (those on a lane: past its
        edge; the others: where they project)."""
        lane_map = self.rt.lane_map
        result = [False] * len(entities)
        loose = []
        for k, entity in enumerate(entities):
            if entity.lane >= 0:
                lane = lane_map.lanes[lane_map.lane_ids[entity.lane]]
                width = float(np.interp(entity.station, lane.stations, lane.widths))
                result[k] = abs(entity.offset) > width / 2.0
            else:
                loose.append(k)
        if loose:
            projection = lane_map.project_many(centres[loose])
            for k, off in zip(
                loose, np.abs(projection.lateral) > projection.width / 2.0, strict=True
            ):
                result[k] = bool(off)
        return result

    def _publish(self, initial: bool = False) -> None:
        """Hand the world the scripted objects and, where it moved by the scenario, the ego."""
        world = self.world
        rt = self.rt
        objects = []
        for entity in rt.entities.values():
            entity_is_ego = entity.is_ego
            if entity_is_ego:
                self._publish_ego(entity, initial)
                continue
            entity.teleported = False
            if not (entity.in_world() and entity.visible):
                continue
            definition = entity.definition
            c, s = math.cos(entity.heading), math.sin(entity.heading)
            x, y = entity.box_centre()
            vx = entity.speed * c - entity.lateral_speed * s
            vy = entity.speed * s + entity.lateral_speed * c
            objects.append(
                ScriptedObject(
                    self._ids[entity.name],
                    definition.kind.object_type,
                    definition.model,
                    (x, y, entity.z + definition.centre[2] - definition.height / 2.0),
                    entity.heading,
                    (vx, vy),
                    (entity.acceleration * c, entity.acceleration * s),
                    (definition.length, definition.width, definition.height),
                    None if entity.lane < 0 else (entity.lane, entity.station),
                )
            )
        world.scripted.place(objects)

    def _publish_ego(self, ego: EntityState, initial: bool) -> None:
        world = self.world
        main = world.egos[0]
        driven = self.rt.ego_driven
        if driven:
            world.scripted_egos.add(main.unique_id)
        else:
            world.scripted_egos.discard(main.unique_id)
        place_it = driven or ego.teleported or (initial and self.load_ego)
        ego.teleported = False
        if not place_it or (initial and not self.load_ego):
            return
        pose = Pose(x=ego.x, y=ego.y, z=ego.z, yaw=ego.heading)
        main.vehicle.teleport(pose, ego.speed)
        if (initial or driven) and isinstance(main.vehicle, Vehicle):
            # The ego holds the speed it was given until its stack commands it (with no
            # dead-man timeout before then: the stack has not spoken yet).
            main.vehicle.hold_speed(ego.speed)
