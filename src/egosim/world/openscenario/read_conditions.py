"""<Condition> and trigger elements -> Condition and Trigger objects."""

from __future__ import annotations

import math
from collections.abc import Callable

from egosim.world.openscenario.conditions import (
    EDGES,
    Check,
    Condition,
    EntityCheck,
    Trigger,
    by_entities,
    element_state_check,
    rule_check,
    value_check,
)
from egosim.world.openscenario.distances import (
    COORDINATE_SYSTEMS,
    DISTANCE_TYPES,
    EUCLIDEAN,
    relative,
    time_headway,
    time_to_collision,
)
from egosim.world.openscenario.entities import EntityKind, EntityState
from egosim.world.openscenario.parameters import RULES
from egosim.world.openscenario.positions import Position, PositionError
from egosim.world.openscenario.read_positions import CatalogResolver, position
from egosim.world.openscenario.reading import Element
from egosim.world.openscenario.runtime import Runtime
from egosim.world.openscenario.signal_states import aspect_matches, parse_state
from egosim.world.openscenario.xmltree import Node

ELEMENT_TYPES = ("story", "act", "maneuverGroup", "maneuver", "event", "action")
ELEMENT_STATES = (
    "standbyState",
    "runningState",
    "completeState",
    "startTransition",
    "endTransition",
    "stopTransition",
    "skipTransition",
)
_COLLISION_TYPES = {
    "vehicle": EntityKind.VEHICLE,
    "pedestrian": EntityKind.PEDESTRIAN,
    "miscellaneous": EntityKind.MISC_OBJECT,
}


class UnsupportedElementError(Exception):
    """An element egosim reads but does not carry out or evaluate; the message is a note
    naming it, its file:line and why."""

    def __init__(self, node: Node, reason: str) -> None:
        super().__init__(node.note(reason))


def trigger(element: Element | None, reader: CatalogResolver, notes: list[str]) -> Trigger | None:
    if element is None:
        return None
    groups = []
    for group in element.children("ConditionGroup"):
        conditions = []
        for node in group.children("Condition"):
            try:
                conditions.append(condition(node, reader))
            except UnsupportedElementError as unsupported:
                notes.append(f"{unsupported}; the condition never holds")
                conditions.append(Condition(node.text("name", ""), lambda rt: False))
        groups.append(conditions)
    return Trigger(groups)


def condition(element: Element, catalogs: CatalogResolver) -> Condition:
    edge = element.choice("conditionEdge", EDGES, "none")
    delay = element.number("delay", 0.0)
    by_entity = element.child("ByEntityCondition")
    by_value = element.child("ByValueCondition")
    if by_entity is not None:
        check = _by_entity(by_entity, catalogs)
    elif by_value is not None:
        check = _by_value(by_value)
    else:
        raise element.node.error("needs a <ByEntityCondition> or <ByValueCondition>")
    return Condition(element.text("name", ""), check, edge, delay)


def _rule(element: Element) -> str:
    return element.choice("rule", RULES)


def _by_entity(element: Element, catalogs: CatalogResolver) -> Check:
    triggering = element.require("TriggeringEntities")
    rule = triggering.choice("triggeringEntitiesRule", ("any", "all"))
    names = [ref.text("entityRef") for ref in triggering.children("EntityRef")]
    choice = element.require("EntityCondition").only_child()
    if choice is None:
        raise element.node.error("has an empty <EntityCondition>")
    return by_entities(names, rule, _entity_check(choice, catalogs))


def _coordinates(element: Element) -> tuple[str, str, bool]:
    """(relative distance type, coordinate system, freespace) with the 1.0 spellings."""
    distance_type = element.text("relativeDistanceType", "euclidianDistance")
    if distance_type not in DISTANCE_TYPES:
        raise element.node.error(
            f"relativeDistanceType {distance_type!r} is not one of {DISTANCE_TYPES}"
        )
    system = element.text("coordinateSystem", "entity")
    if element.boolean("alongRoute", False):
        system = "road"
    if system not in COORDINATE_SYSTEMS:
        raise element.node.error(f"coordinateSystem {system!r} is not one of {COORDINATE_SYSTEMS}")
    return distance_type, system, element.boolean("freespace", False)


def _point(rt: Runtime, target: Position) -> tuple[float, float] | None:
    try:
        placement = target.resolve(rt)
    except PositionError:
        return None
    return placement.x, placement.y


def _entity_check(choice: Element, catalogs: CatalogResolver) -> EntityCheck:
    tag = choice.tag
    if tag == "SpeedCondition":
        direction = choice.text("direction", "longitudinal")

        def speed(rt: Runtime, e: EntityState) -> float:
            if direction == "lateral":
                return e.lateral_speed
            if direction == "vertical":
                return 0.0
            return e.speed

        return rule_check(_rule(choice), choice.number("value", finite=False), speed)
    if tag == "AccelerationCondition":
        return rule_check(
            _rule(choice), choice.number("value", finite=False), lambda rt, e: e.acceleration
        )
    if tag == "RelativeSpeedCondition":
        other = choice.text("entityRef")
        return rule_check(
            _rule(choice),
            choice.number("value", finite=False),
            lambda rt, e: e.speed - rt.entity(other).speed if other in rt.entities else math.nan,
        )
    if tag == "StandStillCondition":
        duration = choice.number("duration")
        return lambda rt, e: e.standstill_s >= duration - 1e-9
    if tag == "TraveledDistanceCondition":
        distance = choice.number("value", finite=False)
        return lambda rt, e: e.odometer >= distance
    if tag == "EndOfRoadCondition":
        duration = choice.number("duration")
        return lambda rt, e: e.end_of_road_s > 0.0 and e.end_of_road_s >= duration - 1e-9
    if tag == "OffroadCondition":
        duration = choice.number("duration")
        return lambda rt, e: e.offroad_s > 0.0 and e.offroad_s >= duration - 1e-9
    if tag == "CollisionCondition":
        ref = choice.child("EntityRef")
        if ref is not None:
            other = ref.text("entityRef")
            return lambda rt, e: other in e.collisions
        kind = _COLLISION_TYPES.get(choice.require("ByType").text("type"))
        if kind is None:
            by_type = choice.require("ByType")
            raise UnsupportedElementError(by_type.node, f"type {by_type.text('type')!r} is unknown")
        return lambda rt, e: any(
            n in rt.entities and rt.entity(n).definition.kind is kind for n in e.collisions
        )
    if tag == "ReachPositionCondition":
        target = position(choice.require("Position"), catalogs)
        tolerance = choice.number("tolerance")

        def reached(rt: Runtime, e: EntityState) -> bool:
            point = _point(rt, target)
            return point is not None and math.hypot(point[0] - e.x, point[1] - e.y) <= tolerance

        return reached
    if tag == "DistanceCondition":
        target = position(choice.require("Position"), catalogs)
        distance_type, system, freespace = _coordinates(choice)

        def to_position(rt: Runtime, e: EntityState) -> float:
            point = _point(rt, target)
            if point is None:
                return math.nan
            return abs(relative(rt, e, point, distance_type, freespace, system))

        return rule_check(_rule(choice), choice.number("value", finite=False), to_position)
    if tag == "RelativeDistanceCondition":
        other = choice.text("entityRef")
        distance_type, system, freespace = _coordinates(choice)
        return rule_check(
            _rule(choice),
            choice.number("value", finite=False),
            lambda rt, e: (
                abs(relative(rt, e, rt.entity(other), distance_type, freespace, system))
                if _there(rt, other)
                else math.nan
            ),
        )
    if tag == "TimeHeadwayCondition":
        other = choice.text("entityRef")
        _, system, freespace = _coordinates(choice)
        return rule_check(
            _rule(choice),
            choice.number("value", finite=False),
            lambda rt, e: (
                time_headway(rt, e, rt.entity(other), freespace, system)
                if _there(rt, other)
                else math.nan
            ),
        )
    if tag == "TimeToCollisionCondition":
        target_element = choice.require("TimeToCollisionConditionTarget")
        distance_type, system, freespace = _coordinates(choice)
        if distance_type in EUCLIDEAN and not choice.has("relativeDistanceType"):
            distance_type = "longitudinal"
        ref = target_element.child("EntityRef")
        if ref is not None:
            other = ref.text("entityRef")
            return rule_check(
                _rule(choice),
                choice.number("value", finite=False),
                lambda rt, e: (
                    time_to_collision(rt, e, rt.entity(other), freespace, distance_type, system)
                    if _there(rt, other)
                    else math.nan
                ),
            )
        target = position(target_element.require("Position"), catalogs)

        def ttc(rt: Runtime, e: EntityState) -> float:
            point = _point(rt, target)
            if point is None:
                return math.nan
            return time_to_collision(rt, e, point, freespace, distance_type, system)

        return rule_check(_rule(choice), choice.number("value", finite=False), ttc)
    if tag == "AngleCondition":
        angle_type = choice.choice("angleType", ("heading", "pitch", "roll"))
        if angle_type != "heading":
            raise UnsupportedElementError(
                choice.node, f"angleType {angle_type!r} is not evaluated (vehicles stay level)"
            )
        angle, tolerance = choice.number("angle"), choice.number("angleTolerance")
        system = choice.text("coordinateSystem", "world")
        return lambda rt, e: (
            abs(math.remainder(_heading(rt, e, system) - angle, math.tau)) <= tolerance
        )
    raise UnsupportedElementError(choice.node, "is not evaluated by egosim")


def _heading(rt: Runtime, e: EntityState, system: str) -> float:
    if system in ("road", "lane") and e.lane >= 0:
        _, _, _, lane_heading = rt.lane_map.poses_at([e.lane], [e.station])[0]
        return e.heading - float(lane_heading)
    return e.heading


def _there(rt: Runtime, name: str) -> bool:
    entity = rt.entities.get(name)
    return entity is not None and entity.in_world()


def _by_value(element: Element) -> Check:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    tag = choice.tag
    if tag == "SimulationTimeCondition":
        return value_check(_rule(choice), choice.number("value", finite=False), lambda rt: rt.time)
    if tag == "ParameterCondition":
        name = choice.text("parameterRef")
        return value_check(_rule(choice), choice.text("value"), lambda rt: rt.parameters.get(name))
    if tag == "VariableCondition":
        name = choice.text("variableRef")
        return value_check(_rule(choice), choice.text("value"), lambda rt: rt.variables.get(name))
    if tag == "StoryboardElementStateCondition":
        return element_state_check(
            choice.choice("storyboardElementType", ELEMENT_TYPES),
            choice.text("storyboardElementRef"),
            choice.choice("state", ELEMENT_STATES),
        )
    if tag == "TrafficSignalCondition":
        light, wanted = choice.text("name"), parse_state(choice.text("state"))
        if wanted is None:
            raise UnsupportedElementError(choice.node, f"state {choice.text('state')!r} is unknown")
        return _light_check(light, wanted)
    if tag == "TrafficSignalControllerCondition":
        return _phase_check(choice.text("trafficSignalControllerRef"), choice.text("phase"))
    raise UnsupportedElementError(choice.node, "is not evaluated by egosim")


def _phase_check(name: str, phase: str) -> Callable[[Runtime], bool]:
    def check(rt: Runtime) -> bool:
        controller = rt.signal_controllers.get(name)
        if controller is None:
            rt.note_once(f"TrafficSignalControllerCondition: no controller {name!r}")
            return False
        return controller.phase_name == phase

    return check


def _light_check(light: str, wanted: int) -> Callable[[Runtime], bool]:
    def check(rt: Runtime) -> bool:
        try:
            return aspect_matches(rt.world.signals.light(light).aspect, wanted)
        except KeyError:
            rt.note_once(f"TrafficSignalCondition: no traffic light {light!r} in the map")
            return False

    return check
