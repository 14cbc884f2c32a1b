"""What running the same scenarios in egosim and in esmini (docs/openscenario.md,
"Cross-checked against esmini") showed, pinned to OpenSCENARIO's semantics with
closed-form expectations: time conditions on the exact step, an act's events starting
in the act's step, a speed relative to the entity itself, a synchronised entity that
arrives with its master at a continuous speed, triggers at the gaps they state."""

from __future__ import annotations

import math

import pytest
from tests.world.openscenario.stories import (
    DT,
    event,
    init_speed,
    lane,
    scenario,
    set_variable,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)

FLAG = '<VariableDeclaration name="fired" variableType="boolean" value="false"/>'


def started_at(world, run, seconds: float, name: str) -> list[float]:  # type: ignore[no-untyped-def]
    """Scenario times (at the steps' starts) the event started."""
    event = run.rt.elements[("event", name)]
    seen: list[float] = []
    for _ in range(round(seconds / DT)):
        before, tick = run.rt.time, run.rt.tick
        run.step(DT, True)
        world.step(DT)
        if any(t == tick and what == "startTransition" for t, what in event.transitions):
            seen.append(before)
    return seen


@pytest.mark.parametrize(
    ("rule", "value", "first"),
    [("greaterThan", 3.0, 3.01), ("greaterOrEqual", 3.0, 3.0), ("greaterOrEqual", 12.0, 12.0)],
)
def test_a_time_condition_fires_on_the_step_its_rule_first_holds(
    rule: str, value: float, first: float
) -> None:
    # 300 steps of 0.01 s summed in floating point make 2.99999999999998 s: the
    # storyboard's clock must not drift a step.
    text = scenario(
        vehicle("Ego"),
        teleport("Ego", lane(10)),
        story("Ego", event("E", set_variable("fired", "true"), start(time_is(value, rule)))),
        variables=FLAG,
    )
    world, run = start_world(text)
    assert started_at(world, run, value + 0.05, "E") == [pytest.approx(first, abs=1e-9)]


def test_an_acts_events_see_their_triggers_in_the_step_the_act_starts() -> None:
    # The act starts at t = 1; its event waits 2 s (delay) on a condition true from then.
    act_start = (
        '<StartTrigger><ConditionGroup><Condition name="a" delay="0" conditionEdge="none">'
        '<ByValueCondition><SimulationTimeCondition value="1" rule="greaterOrEqual"/>'
        "</ByValueCondition></Condition></ConditionGroup></StartTrigger>"
    )
    text = scenario(
        vehicle("Ego"),
        teleport("Ego", lane(10)),
        story(
            "Ego",
            event("E", set_variable("fired", "true"), start(time_is(0, "greaterOrEqual", delay=2))),
            act_trigger=act_start,
        ),
        variables=FLAG,
    )
    world, run = start_world(text)
    assert started_at(world, run, 3.5, "E") == [pytest.approx(3.0, abs=1e-9)]


def test_a_speed_relative_to_the_entity_itself_adds_the_delta_to_its_speed_of_then() -> None:
    # Three runs of "+2 m/s over 1 s" from 10 m/s: 12, 14, 16 m/s at 2, 3 and 4 s.
    plus_two = """<PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="linear" value="1" dynamicsDimension="time"/>
      <SpeedActionTarget><RelativeTargetSpeed entityRef="Ego" value="2"
        speedTargetValueType="delta" continuous="false"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction>"""
    text = scenario(
        vehicle("Ego"),
        teleport("Ego", lane(10)) + init_speed("Ego", 10.0),
        story("Ego", event("E", plus_two, start(time_is(1.0, "greaterOrEqual")), count=3)),
    )
    world, run = start_world(text)
    ego = run.rt.entity("Ego")
    step(world, run, 1.0)
    for expected in (12.0, 14.0, 16.0):
        step(world, run, 1.0)
        assert ego.speed == pytest.approx(expected, abs=1e-9), expected
    step(world, run, 2.0)
    assert ego.speed == pytest.approx(16.0, abs=1e-9)


def test_a_synchronised_entity_arrives_with_its_master_at_the_final_speed_smoothly() -> None:
    # The master covers 280 m at 20 m/s (14 s); the car, at 10 m/s, must cover 300 m in
    # that time and arrive at 20 m/s, its speed changing continuously.
    sync = """<PrivateAction><SynchronizeAction masterEntityRef="Ego">
      <TargetPositionMaster><LanePosition roadId="1" laneId="-1" s="300"/></TargetPositionMaster>
      <TargetPosition><LanePosition roadId="1" laneId="-2" s="300"/></TargetPosition>
      <FinalSpeed><AbsoluteSpeed value="20"/></FinalSpeed></SynchronizeAction></PrivateAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(20))
        + init_speed("Ego", 20.0)
        + teleport("Car", lane(0, -2))
        + init_speed("Car", 10.0),
        story("Car", event("E", sync)),
    )
    world, run = start_world(text)
    car = run.rt.entity("Car")
    biggest_change = 0.0
    for _ in range(round(14.0 / DT)):
        before = car.speed
        step(world, run, DT)
        biggest_change = max(biggest_change, abs(car.speed - before))
    assert car.x == pytest.approx(300.0, abs=20.0 * DT)  # the step it arrives in
    assert car.speed == pytest.approx(20.0, abs=1e-6)
    # The profile v0 + (vf - v0) t/T + k t (T - t): its acceleration is at most
    # |vf - v0|/T + k T = 10/14 + 6 (300 - 210)/14² ≈ 3.47 m/s²: never a jump.
    assert biggest_change < 3.5 * DT


def test_triggers_fire_at_the_gaps_they_state_between_boxes_or_reference_points() -> None:
    # Ego at 20 m/s, 100 m (reference points) behind a car at 10 m/s; boxes: Ego 4 m with
    # its centre 1.5 m ahead of the reference (front +3.5), the car's rear 0.5 m behind
    # its reference. Freespace gap 96 - 10 t, reference gap 100 - 10 t.
    def condition(body: str) -> str:
        return f"""<Condition name="c" delay="0" conditionEdge="none"><ByEntityCondition>
          <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/>
          </TriggeringEntities><EntityCondition>{body}</EntityCondition></ByEntityCondition>
          </Condition>"""

    bodies = {
        # 96 - 10 t < 2 * 20  ->  t > 5.6
        "headway_free": '<TimeHeadwayCondition entityRef="Car" value="2" freespace="true" '
        'rule="lessThan" coordinateSystem="entity" relativeDistanceType="longitudinal"/>',
        # 100 - 10 t < 2 * 20  ->  t > 6.0
        "headway_ref": '<TimeHeadwayCondition entityRef="Car" value="2" freespace="false" '
        'rule="lessThan" coordinateSystem="entity" relativeDistanceType="longitudinal"/>',
        # (96 - 10 t) / 10 < 3  ->  t > 6.6
        "ttc_free": '<TimeToCollisionCondition value="3" freespace="true" rule="lessThan" '
        'coordinateSystem="entity" relativeDistanceType="longitudinal">'
        '<TimeToCollisionConditionTarget><EntityRef entityRef="Car"/>'
        "</TimeToCollisionConditionTarget></TimeToCollisionCondition>",
        # 96 - 10 t < 25  ->  t > 7.1 (boxes side by side: the Euclidean gap is the
        # longitudinal one)
        "distance_free": '<RelativeDistanceCondition entityRef="Car" value="25" '
        'freespace="true" rule="lessThan" relativeDistanceType="euclidianDistance" '
        'coordinateSystem="entity"/>',
    }
    expected = {"headway_free": 5.6, "headway_ref": 6.0, "ttc_free": 6.6, "distance_free": 7.1}
    events = "".join(
        event(name, set_variable("fired", "true"), start(condition(body)), priority="parallel")
        for name, body in bodies.items()
    )
    text = scenario(
        vehicle("Ego", length=4.0, centre_x=1.5) + vehicle("Car", length=4.0, centre_x=1.5),
        teleport("Ego", lane(10))
        + init_speed("Ego", 20.0)
        + teleport("Car", lane(110))
        + init_speed("Car", 10.0),
        story("Ego", events),
        variables=FLAG,
    )
    world, run = start_world(text)
    starts: dict[str, float] = {}
    for _ in range(round(8.0 / DT)):
        before, tick = run.rt.time, run.rt.tick
        run.step(DT, True)
        world.step(DT)
        for name in bodies:
            transitions = run.rt.elements[("event", name)].transitions
            if any(t == tick and what == "startTransition" for t, what in transitions):
                starts[name] = before
    for name, at in expected.items():
        # A strict rule first holds on the step after the exact crossing time (ties at
        # the threshold fall either side by rounding: one step).
        assert starts[name] == pytest.approx(at + DT, abs=DT + 1e-9), name


def test_a_car_turned_round_onto_the_oncoming_lane_follows_that_lane_and_its_gaps() -> None:
    # Euro NCAP's CCFhol: the target is placed on lane -1 offset 3.5 m (onto lane 1, the
    # westbound lane's centre) facing west; a car keeps 19.4 m of free space ahead of it.
    keep = """<PrivateAction><LongitudinalAction><LongitudinalDistanceAction entityRef="Target"
      distance="19.4" freespace="true" continuous="true" displacement="leadingReferencedEntity"
      coordinateSystem="road"/></LongitudinalAction></PrivateAction>"""
    turned = (
        '<LanePosition roadId="1" laneId="-1" s="500" offset="3.5">'
        '<Orientation h="3.14159265"/></LanePosition>'
    )
    text = scenario(
        vehicle("Ego")
        + vehicle("Target", length=4.0, centre_x=1.3)
        + vehicle("Leader", length=4.4, centre_x=1.4),
        teleport("Ego", lane(10))
        + teleport("Target", turned)
        + init_speed("Target", 15.0)
        + teleport("Leader", '<RelativeObjectPosition entityRef="Target" dx="10" dy="0"/>')
        + f'<Private entityRef="Leader">{keep}</Private>',
    )
    world, run = start_world(text)
    step(world, run, 2.0)
    target, leader = run.rt.entity("Target"), run.rt.entity("Leader")
    assert target.x == pytest.approx(500.0 - 30.0, abs=1e-6)
    assert target.y == pytest.approx(1.75, abs=1e-6)
    # Both face west: the target's front is at x - (1.3 + 2), the leader's rear at
    # x + (2.2 - 1.4).
    assert (target.x - 3.3) - (leader.x + 0.8) == pytest.approx(19.4, abs=1e-6)


def test_a_master_reversing_to_its_target_synchronises_the_other() -> None:
    # Euro NCAP's CPRA: the ego reverses at 1 m/s from s = 100 to its target at s = 90
    # (10 s); a walker standing 15 m before its crossing point must get there then.
    sync = """<PrivateAction><SynchronizeAction masterEntityRef="Ego">
      <TargetPositionMaster><WorldPosition x="90" y="-1.75"/></TargetPositionMaster>
      <TargetPosition><WorldPosition x="60" y="-1.75"/></TargetPosition>
    </SynchronizeAction></PrivateAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Walker", length=0.5, centre_x=0.0),
        teleport("Ego", lane(100))
        + init_speed("Ego", -1.0)
        + teleport("Walker", '<WorldPosition x="45" y="-1.75" h="0"/>'),
        story("Walker", event("E", sync)),
    )
    world, run = start_world(text)
    walker = run.rt.entity("Walker")
    step(world, run, 10.0)
    assert run.rt.entity("Ego").x == pytest.approx(90.0, abs=1e-6)
    assert walker.x == pytest.approx(60.0, abs=0.05)


@pytest.mark.parametrize(
    ("orientation", "heading"),
    [
        ('<Orientation h="0" type="relative"/>', 0.0),  # along the route, eastwards
        ('<Orientation h="3.14159265" type="relative"/>', math.pi),  # against it
        ("", math.pi),  # none: the named lane's own direction (lane 1 runs west)
    ],
)
def test_a_route_positions_orientation_is_to_the_routes_direction(
    orientation: str, heading: float
) -> None:
    # Euro NCAP's obstruction cars stand on the far lane of a route, turned relative to
    # the route (their rear bumpers where the parameters put them).
    route = """<Route name="East" closed="false">
      <Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1"
        s="10"/></Position></Waypoint>
      <Waypoint routeStrategy="shortest"><Position><LanePosition roadId="1" laneId="-1"
        s="500"/></Position></Waypoint></Route>"""
    position = f"""<RoutePosition><RouteRef>{route}</RouteRef>{orientation}<InRoutePosition>
      <FromLaneCoordinates pathS="100" laneId="1" laneOffset="0"/></InRoutePosition>
      </RoutePosition>"""
    text = scenario(
        vehicle("Ego") + vehicle("Parked"),
        teleport("Ego", lane(10)) + teleport("Parked", position),
    )
    _, run = start_world(text)
    parked = run.rt.entity("Parked")
    assert (parked.x, parked.y) == (pytest.approx(110.0, abs=1e-6), pytest.approx(1.75))
    assert math.cos(parked.heading - heading) == pytest.approx(1.0, abs=1e-9)
