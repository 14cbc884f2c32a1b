"""The default controller against closed forms: speed changes reach their targets when
the dynamics say, lane changes end on the target lane's centre, offsets and distances
keep what they state."""

from __future__ import annotations

import math

import pytest
from tests.world.openscenario.stories import (
    DT,
    event,
    init_speed,
    lane,
    scenario,
    speed_action,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)


def one_car(action: str, speed: float = 10.0, lane_id: int = -1, trigger: str = "") -> str:
    return scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(10, 1))
        + teleport("Car", lane(100, lane_id))
        + init_speed("Car", speed),
        story("Car", event("E", action, trigger or start(time_is(1.0, "greaterOrEqual")))),
    )


def test_a_linear_speed_change_by_time_reaches_its_target_at_the_stated_time() -> None:
    world, run = start_world(one_car(speed_action(30, "linear", "time", 4)))
    car = run.rt.entity("Car")
    step(world, run, 1.0)
    x0 = car.x
    step(world, run, 2.0)
    assert car.speed == pytest.approx(20.0, abs=1e-9)
    assert run.rt.elements[("action", "EAction")].state == "runningState"
    step(world, run, 2.0)
    assert car.speed == pytest.approx(30.0, abs=1e-9)
    # Constant acceleration 5 m/s² from 10 m/s for 4 s: 80 m.
    assert car.x - x0 == pytest.approx(80.0, abs=1e-6)
    step(world, run, DT)
    assert run.rt.elements[("action", "EAction")].state == "completeState"


@pytest.mark.parametrize(
    ("shape", "dimension", "value", "duration"),
    [
        ("linear", "rate", 2.0, 5.0),  # 10 m/s down at 2 m/s²
        ("cubic", "rate", 2.0, 7.5),  # peak rate 1.5 Δv / T
        ("sinusoidal", "time", 3.0, 3.0),
        ("linear", "distance", 75.0, 7.5),  # mean speed 10 m/s over 75 m
    ],
)
def test_speed_changes_take_the_time_their_dynamics_give(
    shape: str, dimension: str, value: float, duration: float
) -> None:
    world, run = start_world(one_car(speed_action(5, shape, dimension, value), speed=15.0))
    car = run.rt.entity("Car")
    step(world, run, 1.0)
    x0 = car.x
    step(world, run, duration - DT)
    assert car.speed > 5.0 + 1e-6
    step(world, run, DT)
    assert car.speed == pytest.approx(5.0, abs=1e-9)
    if dimension == "distance":
        assert car.x - x0 == pytest.approx(value, abs=1e-6)


def test_a_lane_change_of_given_duration_ends_in_the_target_lane_centre() -> None:
    change = """<PrivateAction><LateralAction><LaneChangeAction targetLaneOffset="0">
      <LaneChangeActionDynamics dynamicsShape="sinusoidal" value="3" dynamicsDimension="time"/>
      <LaneChangeTarget><RelativeTargetLane entityRef="Car" value="1"/></LaneChangeTarget>
    </LaneChangeAction></LateralAction></PrivateAction>"""
    world, run = start_world(one_car(change, speed=20.0, lane_id=-2))
    car = run.rt.entity("Car")
    step(world, run, 1.0)
    assert car.y == pytest.approx(-5.25)
    step(world, run, 1.5)
    # Half way in time, half way across (the sinusoid is symmetric).
    assert car.y == pytest.approx(-3.5, abs=1e-9)
    step(world, run, 1.5)
    assert car.y == pytest.approx(-1.75, abs=1e-9)
    assert car.heading == pytest.approx(0.0, abs=1e-3)  # the last step's sideways motion
    assert run.rt.lane_map.lane_ids[car.lane] == "1_0_-1"
    step(world, run, 1.0)
    assert car.y == pytest.approx(-1.75, abs=1e-9)


def test_a_lane_change_by_distance_ends_after_that_distance() -> None:
    change = """<PrivateAction><LateralAction><LaneChangeAction targetLaneOffset="0.5">
      <LaneChangeActionDynamics dynamicsShape="cubic" value="50" dynamicsDimension="distance"/>
      <LaneChangeTarget><AbsoluteTargetLane value="-2"/></LaneChangeTarget>
    </LaneChangeAction></LateralAction></PrivateAction>"""
    world, run = start_world(one_car(change, speed=20.0, lane_id=-1))
    car = run.rt.entity("Car")
    step(world, run, 1.0)
    step(world, run, 2.5 - DT)
    assert car.y > -5.25 + 0.5 + 1e-6
    step(world, run, DT)
    # 0.5 m left of lane -2's centre (towards lane -1).
    assert car.y == pytest.approx(-4.75, abs=1e-9)


def test_a_lane_offset_takes_the_time_its_lateral_acceleration_allows() -> None:
    offset = """<PrivateAction><LateralAction><LaneOffsetAction continuous="false">
      <LaneOffsetActionDynamics maxLateralAcc="0.6" dynamicsShape="cubic"/>
      <LaneOffsetTarget><AbsoluteTargetLaneOffset value="-0.9"/></LaneOffsetTarget>
    </LaneOffsetAction></LateralAction></PrivateAction>"""
    world, run = start_world(one_car(offset, speed=10.0))
    car = run.rt.entity("Car")
    step(world, run, 1.0)
    duration = math.sqrt(6 * 0.9 / 0.6)  # cubic: peak lateral acceleration 6 Δ / T²
    step(world, run, round(duration / DT) * DT)
    assert car.offset == pytest.approx(-0.9, abs=1e-3)
    assert car.y == pytest.approx(-1.75 - 0.9, abs=1e-3)


def test_a_longitudinal_distance_action_puts_the_target_at_the_freespace_gap() -> None:
    keep = """<PrivateAction><LongitudinalAction><LongitudinalDistanceAction entityRef="Ego"
      distance="12" freespace="true" continuous="false" displacement="leadingReferencedEntity"
      coordinateSystem="entity"/></LongitudinalAction></PrivateAction>"""
    text = scenario(
        vehicle("Ego", length=4.5, centre_x=1.4) + vehicle("Car", length=4.0, centre_x=1.5),
        teleport("Ego", lane(50))
        + init_speed("Ego", 15.0)
        + teleport("Car", lane(200))
        + f'<Private entityRef="Car">{keep}</Private>',
    )
    _world, run = start_world(text)
    ego, car = run.rt.entity("Ego"), run.rt.entity("Car")
    ego_front = ego.box_centre()[0] + ego.definition.length / 2
    car_rear = car.box_centre()[0] - car.definition.length / 2
    assert car_rear - ego_front == pytest.approx(12.0, abs=1e-6)
    assert car.speed == pytest.approx(15.0)


def test_a_timed_trajectory_puts_the_entity_at_each_vertex_at_its_time() -> None:
    follow = """<PrivateAction><RoutingAction><FollowTrajectoryAction>
      <TrajectoryRef><Trajectory name="T" closed="false"><Shape><Polyline>
        <Vertex time="0"><Position><WorldPosition x="100" y="-1.75"/></Position></Vertex>
        <Vertex time="4"><Position><WorldPosition x="140" y="-1.75"/></Position></Vertex>
        <Vertex time="6"><Position><WorldPosition x="140" y="8.25"/></Position></Vertex>
      </Polyline></Shape></Trajectory></TrajectoryRef>
      <TimeReference><Timing domainAbsoluteRelative="relative" scale="1" offset="0"/>
        </TimeReference>
      <TrajectoryFollowingMode followingMode="position"/>
    </FollowTrajectoryAction></RoutingAction></PrivateAction>"""
    world, run = start_world(
        one_car(follow, speed=0.0, trigger=start(time_is(0.5, "greaterOrEqual")))
    )
    car = run.rt.entity("Car")
    step(world, run, 0.5 + 4.0)
    assert (car.x, car.y) == pytest.approx((140.0, -1.75), abs=1e-6)
    assert car.speed == pytest.approx(10.0, abs=1e-6)
    step(world, run, 2.0)
    assert (car.x, car.y) == pytest.approx((140.0, 8.25), abs=1e-6)


def test_synchronize_brings_the_entity_to_its_target_as_the_master_reaches_its_own() -> None:
    sync = """<PrivateAction><SynchronizeAction masterEntityRef="Ego">
      <TargetPositionMaster><LanePosition roadId="1" laneId="-1" s="200"/></TargetPositionMaster>
      <TargetPosition><LanePosition roadId="1" laneId="-2" s="180"/></TargetPosition>
    </SynchronizeAction></PrivateAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(50)) + init_speed("Ego", 15.0) + teleport("Car", lane(100, -2)),
        story("Car", event("E", sync)),
    )
    world, run = start_world(text)
    ego, car = run.rt.entity("Ego"), run.rt.entity("Car")
    step(world, run, 10.0)  # the ego covers its 150 m in 10 s
    assert ego.x == pytest.approx(200.0, abs=1e-6)
    assert car.x == pytest.approx(180.0, abs=0.2)
