"""<PrivateAction> and <GlobalAction> elements -> action objects (actions.py)."""

from __future__ import annotations

import math
from collections.abc import Callable

from egosim.world.map.road_coordinates import LanePlace, UnknownRoadError
from egosim.world.openscenario.actions import (
    AcquirePositionAction,
    AssignRouteAction,
    ControllerAction,
    EntityAction,
    MotionAction,
    NoteAction,
    SignalPhaseAction,
    SpeedInInit,
    TeleportAction,
    TrafficSignalStateAction,
    ValueAction,
    VisibilityAction,
    follow_trajectory,
)
from egosim.world.openscenario.distances import relative
from egosim.world.openscenario.dynamics import DIMENSIONS, SHAPES
from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.following import Timing
from egosim.world.openscenario.geometry_path import SampledPath
from egosim.world.openscenario.lane_paths import advance, distance_along
from egosim.world.openscenario.lateral import LaneChangeRun, LaneOffsetRun, LateralDistanceRun
from egosim.world.openscenario.longitudinal import (
    DistanceRun,
    SpeedProfileRun,
    SpeedRun,
    SpeedTarget,
    SynchronizeRun,
)
from egosim.world.openscenario.positions import (
    Position,
    PositionError,
    TrajectoryPosition,
    attach,
    lane_pose,
    neighbour,
)
from egosim.world.openscenario.read_conditions import UnsupportedElementError
from egosim.world.openscenario.read_positions import (
    CatalogResolver,
    position,
    route_ref,
    trajectory,
    trajectory_ref,
)
from egosim.world.openscenario.reading import Element
from egosim.world.openscenario.runtime import Runtime
from egosim.world.openscenario.signal_states import parse_state
from egosim.world.openscenario.storyboard import Action

ENVIRONMENT_NOTE = "not applied: egosim has no weather, lighting or time of day"


def is_external_controller(controller: Element) -> bool:
    """A controller that hands the entity to a driver outside the scenario (the user's
    stack): named or typed so (ExternalController, esminiController=ExternalController,
    controllerType=external, CARLA's ROS agent module), case-insensitive."""
    texts = [controller.text("name", "")]
    properties = controller.child("Properties")
    if properties is not None:
        for prop in properties.children("Property"):
            name, value = prop.text("name", ""), prop.text("value", "")
            if name.lower() == "module":
                return True
            texts += [name, value]
    return any("external" in text.lower() for text in texts)


def private_action(element: Element, catalogs: CatalogResolver, in_init: bool = False) -> Action:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    tag = choice.tag
    if tag == "LongitudinalAction":
        return _longitudinal(choice, catalogs, in_init)
    if tag == "LateralAction":
        return _lateral(choice)
    if tag == "TeleportAction":
        return TeleportAction(choice.node, position(choice.require("Position"), catalogs))
    if tag == "RoutingAction":
        return _routing(choice, catalogs)
    if tag == "SynchronizeAction":
        return _synchronize(choice, catalogs)
    if tag == "VisibilityAction":
        return VisibilityAction(
            choice.node,
            choice.boolean("graphics", True),
            choice.boolean("traffic", True),
            choice.boolean("sensors", True),
        )
    if tag == "ActivateControllerAction":
        return ControllerAction(choice.node, None)
    if tag == "ControllerAction":
        return _controller(choice, catalogs)
    if tag == "AppearanceAction":
        return NoteAction(
            choice.node, "not applied: egosim shows no lamps or animations of entities"
        )
    raise UnsupportedElementError(choice.node, "is not carried out by egosim")


def _speed_target(element: Element) -> SpeedTarget:
    target = element.require("SpeedActionTarget").only_child()
    if target is None:
        raise element.node.error("needs a speed target")
    if target.tag == "AbsoluteTargetSpeed":
        return SpeedTarget(target.number("value"))
    if target.tag == "RelativeTargetSpeed":
        return SpeedTarget(
            target.number("value"),
            target.text("entityRef"),
            target.choice("speedTargetValueType", ("delta", "factor")),
            target.boolean("continuous", False),
        )
    raise target.node.error("is not a speed target")


def _dynamics(element: Element) -> tuple[str, str, float]:
    return (
        element.choice("dynamicsShape", SHAPES),
        element.choice("dynamicsDimension", DIMENSIONS),
        element.number("value"),
    )


def _constraints(element: Element) -> tuple[float, float, float]:
    limits = element.child("DynamicConstraints")
    if limits is None:
        return math.inf, math.inf, math.inf
    return (
        limits.number("maxAcceleration", math.inf, finite=False),
        limits.number("maxDeceleration", math.inf, finite=False),
        limits.number("maxSpeed", math.inf, finite=False),
    )


def _longitudinal(element: Element, catalogs: CatalogResolver, in_init: bool) -> Action:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    if choice.tag == "SpeedAction":
        target = _speed_target(choice)
        shape, dimension, value = _dynamics(choice.require("SpeedActionDynamics"))
        motion = MotionAction(choice.node, lambda rt, e: SpeedRun(target, shape, dimension, value))
        if in_init:
            return SpeedInInit(choice.node, target.speed, motion)
        return motion
    if choice.tag == "LongitudinalDistanceAction":
        return _distance_keeping(choice)
    if choice.tag == "SpeedProfileAction":
        entries = [
            (entry.number("speed"), entry.optional_number("time"))
            for entry in choice.children("SpeedProfileEntry")
        ]
        accel, _, _ = _constraints(choice)
        reference = choice.text("entityRef", "")
        return MotionAction(
            choice.node,
            lambda rt, e: SpeedProfileRun(
                entries, reference, accel if math.isfinite(accel) else 1e9
            ),
        )
    raise UnsupportedElementError(choice.node, "is not carried out by egosim")


def _distance_keeping(element: Element) -> Action:
    reference = element.text("entityRef")
    freespace = element.boolean("freespace", False)
    continuous = element.boolean("continuous", False)
    displacement = element.text("displacement", "trailingReferencedEntity")
    distance = element.optional_number("distance")
    time_gap = element.optional_number("timeGap")
    if distance is None and time_gap is None:
        raise element.node.error("needs a distance or a timeGap")
    accel, decel, top = _constraints(element)

    def wanted(rt: Runtime) -> float:
        if distance is not None:
            return distance
        return (time_gap or 0.0) * abs(rt.entity(reference).speed)

    def ahead_sign(rt: Runtime, entity: EntityState) -> float:
        if displacement == "leadingReferencedEntity":
            return 1.0
        if displacement == "trailingReferencedEntity":
            return -1.0
        now = relative(rt, rt.entity(reference), entity, "longitudinal", freespace)
        return 1.0 if now >= 0 else -1.0

    def gap(rt: Runtime, entity: EntityState) -> float | None:
        ref = rt.entity(reference)
        now = relative(rt, ref, entity, "longitudinal", freespace)
        # Positive while the entity must move forward to get where it should be.
        return ahead_sign(rt, entity) * wanted(rt) - now

    def jump(rt: Runtime, entity: EntityState) -> bool:
        ref = rt.entity(reference)
        if ref.lane < 0:
            return False
        reach = 0.0
        if freespace:
            reach = (ref.definition.length + entity.definition.length) / 2.0
        along = ahead_sign(rt, entity) * (wanted(rt) + reach)
        # Boxes' centres, not reference points, are `reach` apart: shift by the offsets.
        along += ref.definition.centre[0] - entity.definition.centre[0]
        lane, station, _, _ = advance(
            rt.lane_map, ref.lane, ref.station, along, ref.route, ref.route_position
        )
        target_lane = entity.lane if entity.lane >= 0 else lane
        if target_lane != lane:
            lengths = rt.lane_map.lane_lengths
            station = float(
                min(station * lengths[target_lane] / max(lengths[lane], 1e-9), lengths[target_lane])
            )
        entity.lane, entity.station = target_lane, station
        x, y, z, heading = lane_pose(rt, LanePlace(target_lane, station, entity.offset))
        entity.x, entity.y, entity.z, entity.heading = x, y, z, heading
        return True

    return MotionAction(
        element.node,
        lambda rt, e: DistanceRun(gap, reference, continuous, jump, accel, decel, top),
    )


def _lateral(element: Element) -> Action:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    if choice.tag == "LaneChangeAction":
        shape, dimension, value = _dynamics(choice.require("LaneChangeActionDynamics"))
        target = choice.require("LaneChangeTarget").only_child()
        if target is None:
            raise choice.node.error("needs a lane change target")
        offset = choice.number("targetLaneOffset", 0.0)
        if target.tag == "RelativeTargetLane":
            ref, count = target.text("entityRef"), target.integer("value")

            def target_lane(rt: Runtime, entity: EntityState) -> int:
                reference = rt.entity(ref)
                if reference.lane < 0:
                    raise PositionError(f"entity {ref!r} is on no lane")
                return neighbour(rt, reference.lane, count)

        elif target.tag == "AbsoluteTargetLane":
            lane_id = target.integer("value")

            def target_lane(rt: Runtime, entity: EntityState) -> int:
                if entity.lane < 0:
                    raise PositionError(f"entity {entity.name!r} is on no lane")
                try:
                    point = rt.roads.locate(entity.lane, entity.station, 0.0)
                    return rt.roads.lane_place(point.road, lane_id, point.s, 0.0).lane_index
                except UnknownRoadError as error:
                    raise PositionError(str(error)) from None

        else:
            raise target.node.error("is not a lane change target")
        return MotionAction(
            choice.node, lambda rt, e: LaneChangeRun(target_lane, offset, shape, dimension, value)
        )
    if choice.tag == "LaneOffsetAction":
        dynamics = choice.require("LaneOffsetActionDynamics")
        shape = dynamics.choice("dynamicsShape", SHAPES)
        max_accel = dynamics.number("maxLateralAcc", math.inf, finite=False)
        target = choice.require("LaneOffsetTarget").only_child()
        if target is None:
            raise choice.node.error("needs a lane offset target")
        value = target.number("value")
        if target.tag == "AbsoluteTargetLaneOffset":

            def goal(rt: Runtime, entity: EntityState) -> float:
                return value

        elif target.tag == "RelativeTargetLaneOffset":
            ref = target.text("entityRef")

            def goal(rt: Runtime, entity: EntityState) -> float:
                return rt.entity(ref).offset + value

        else:
            raise target.node.error("is not a lane offset target")
        continuous = choice.boolean("continuous", False)
        return MotionAction(
            choice.node, lambda rt, e: LaneOffsetRun(goal, shape, max_accel, continuous)
        )
    if choice.tag == "LateralDistanceAction":
        ref = choice.text("entityRef")
        distance = choice.number("distance", 0.0)
        continuous = choice.boolean("continuous", False)
        limits = choice.child("DynamicConstraints")
        max_speed = (
            math.inf if limits is None else limits.number("maxSpeed", math.inf, finite=False)
        )
        return MotionAction(
            choice.node, lambda rt, e: LateralDistanceRun(ref, distance, continuous, max_speed)
        )
    raise UnsupportedElementError(choice.node, "is not carried out by egosim")


def _routing(element: Element, catalogs: CatalogResolver) -> Action:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    if choice.tag == "AssignRouteAction":
        return AssignRouteAction(choice.node, route_ref(choice, catalogs))
    if choice.tag == "AcquirePositionAction":
        return AcquirePositionAction(choice.node, position(choice.require("Position"), catalogs))
    if choice.tag == "FollowTrajectoryAction":
        inline = choice.child("Trajectory")
        path = (
            trajectory(inline, catalogs) if inline is not None else trajectory_ref(choice, catalogs)
        )
        timing = None
        reference = choice.child("TimeReference")
        timed = None if reference is None else reference.child("Timing")
        if timed is not None:
            timing = Timing(
                timed.choice("domainAbsoluteRelative", ("absolute", "relative")) == "relative",
                timed.number("scale", 1.0),
                timed.number("offset", 0.0),
            )
        return follow_trajectory(
            choice.node, path, timing, choice.optional_number("initialDistanceOffset")
        )
    raise UnsupportedElementError(choice.node, "is not carried out by egosim")


def _controller(element: Element, catalogs: CatalogResolver) -> Action:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    if choice.tag == "AssignControllerAction":
        controller = choice.child("Controller")
        reference = choice.child("CatalogReference")
        if controller is None and reference is not None:
            controller = catalogs.entry(reference)
        if controller is None:
            return ControllerAction(choice.node, None)
        return ControllerAction(choice.node, is_external_controller(controller))
    if choice.tag == "ActivateControllerAction":
        return ControllerAction(choice.node, None)
    return NoteAction(choice.node, "not applied: controller values are not overridden in egosim")


def _path_distance(target: Position) -> Callable[[Runtime, EntityState], float | None]:
    """Distance from an entity to a target position along the way it goes (backwards when
    it reverses): along its trajectory (for a TrajectoryPosition of the one it follows),
    along its lanes, else straight ahead."""
    cached: dict[str, SampledPath] = {}

    def distance(rt: Runtime, entity: EntityState) -> float | None:
        try:
            placement = target.resolve(rt)
        except PositionError:
            return None
        following = (
            entity.lateral if entity.lateral is not None and entity.lateral.follows_path else None
        )
        if isinstance(target, TrajectoryPosition):
            path = cached.get("path")
            if path is None:
                path = cached["path"] = target.trajectory.path(rt, None)
            here = getattr(following, "s", None) if following is not None else None
            if here is None or getattr(following, "trajectory", None) is not target.trajectory:
                here = path.project(entity.x, entity.y)
            return target.s - float(here)
        # An entity reversing goes the other way: its target lies behind it.
        way = -1.0 if entity.speed < 0.0 else 1.0
        if entity.lane >= 0 and following is None:
            goal = placement.lane or attach(rt, placement)
            if goal is not None:
                along = distance_along(
                    rt.lane_map, entity.lane, entity.station, goal.lane_index, goal.station
                )
                if along is not None:
                    return way * along
        dx, dy = placement.x - entity.x, placement.y - entity.y
        return way * (dx * math.cos(entity.heading) + dy * math.sin(entity.heading))

    return distance


def _synchronize(element: Element, catalogs: CatalogResolver) -> Action:
    master = element.text("masterEntityRef")
    master_target = position(element.require("TargetPositionMaster"), catalogs)
    own_target = position(element.require("TargetPosition"), catalogs)
    final_speed: Callable[[Runtime], float] | None = None
    steady_distance = steady_time = 0.0
    final = element.child("FinalSpeed")
    if final is not None:
        choice = final.only_child()
        if choice is None:
            raise final.node.error("is empty")
        steady = choice.child("SteadyState")
        steady_state = steady.only_child() if steady is not None else None
        if steady_state is None:
            steady_state = choice.child("TargetDistanceSteadyState") or choice.child(
                "TargetTimeSteadyState"
            )
        if steady_state is not None and steady_state.tag == "TargetDistanceSteadyState":
            steady_distance = steady_state.number("distance")
        elif steady_state is not None and steady_state.tag == "TargetTimeSteadyState":
            steady_time = steady_state.number("time")
        value = choice.number("value")
        if choice.tag == "AbsoluteSpeed":
            final_speed = lambda rt: value  # noqa: E731
        elif choice.tag == "RelativeSpeedToMaster":
            kind = choice.choice("speedTargetValueType", ("delta", "factor"))
            final_speed = (  # noqa: E731
                lambda rt: (
                    rt.entity(master).speed * value
                    if kind == "factor"
                    else rt.entity(master).speed + value
                )
            )
        else:
            raise choice.node.error("is not a final speed")
    tolerance = element.number("targetTolerance", 0.0)
    master_tolerance = element.number("targetToleranceMaster", 0.0)
    master_distance = _path_distance(master_target)
    own_distance = _path_distance(own_target)
    return MotionAction(
        element.node,
        lambda rt, e: SynchronizeRun(
            master,
            master_distance,
            own_distance,
            final_speed,
            steady_distance,
            steady_time,
            tolerance,
            master_tolerance,
        ),
    )


def global_action(element: Element, catalogs: CatalogResolver) -> Action:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("is empty")
    tag = choice.tag
    if tag == "EnvironmentAction":
        return NoteAction(choice.node, ENVIRONMENT_NOTE)
    if tag == "EntityAction":
        entity = choice.text("entityRef")
        add = choice.child("AddEntityAction")
        if add is not None:
            return EntityAction(choice.node, entity, position(add.require("Position"), catalogs))
        if choice.child("DeleteEntityAction") is not None:
            return EntityAction(choice.node, entity, None)
        raise choice.node.error("needs an AddEntityAction or a DeleteEntityAction")
    if tag in ("ParameterAction", "VariableAction"):
        store = "parameters" if tag == "ParameterAction" else "variables"
        name = choice.text("parameterRef" if store == "parameters" else "variableRef")
        set_action = choice.child("SetAction")
        if set_action is not None:
            return ValueAction(choice.node, store, name, "set", set_action.text("value"))
        rule = choice.require("ModifyAction").require("Rule").only_child()
        if rule is None or rule.tag not in ("AddValue", "MultiplyByValue"):
            raise choice.node.error("needs a Rule of AddValue or MultiplyByValue")
        operation = "add" if rule.tag == "AddValue" else "multiply"
        return ValueAction(choice.node, store, name, operation, rule.number("value"))
    if tag == "InfrastructureAction":
        signal = choice.require("TrafficSignalAction").only_child()
        if signal is not None and signal.tag == "TrafficSignalStateAction":
            state = signal.text("state")
            aspect = parse_state(state)
            if aspect is None:
                raise UnsupportedElementError(signal.node, f"state {state!r} is unknown")
            return TrafficSignalStateAction(signal.node, signal.text("name"), aspect)
        if signal is not None and signal.tag == "TrafficSignalControllerAction":
            return SignalPhaseAction(
                signal.node, signal.text("trafficSignalControllerRef"), signal.text("phase")
            )
        raise UnsupportedElementError(
            signal.node if signal is not None else choice.node, "is not carried out by egosim"
        )
    raise UnsupportedElementError(choice.node, "is not carried out by egosim")
