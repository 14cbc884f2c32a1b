"""Positions placed on the map (closed forms on the straight highway, an OpenDRIVE curve
read back in road coordinates), trajectory shapes, and the actions that place, hide or
add entities and set lights."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from tests.world.openscenario.stories import (
    event,
    init_speed,
    lane,
    pedestrian,
    scenario,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)

from egosim.maps import load_map
from egosim.world.openscenario.geometry_path import SampledPath
from egosim.world.signals import RED

JUNCTION = Path(__file__).parents[2] / "data" / "maps" / "junction.xodr"


def placed(position: str, reference: str = lane(100)) -> tuple[float, float, float]:
    text = scenario(
        vehicle("Ego") + vehicle("Car"), teleport("Ego", reference) + teleport("Car", position)
    )
    _, run = start_world(text)
    car = run.rt.entity("Car")
    return car.x, car.y, car.heading


@pytest.mark.parametrize(
    ("position", "expected"),
    [
        ('<WorldPosition x="12" y="3" h="0.5"/>', (12.0, 3.0, 0.5)),
        (lane(200, -2, offset=0.5), (200.0, -4.75, 0.0)),
        (lane(200, 1), (200.0, 1.75, math.pi)),  # a westbound lane faces west
        ('<RoadPosition roadId="1" s="300" t="-5.25"/>', (300.0, -5.25, 0.0)),
        (
            '<RelativeLanePosition entityRef="Ego" dLane="-1" ds="25" offset="0"/>',
            (125.0, -5.25, 0.0),
        ),
        ('<RelativeObjectPosition entityRef="Ego" dx="10" dy="-3.5"/>', (110.0, -5.25, 0.0)),
        ('<RelativeWorldPosition entityRef="Ego" dx="-20" dy="0"/>', (80.0, -1.75, 0.0)),
        ('<RelativeRoadPosition entityRef="Ego" ds="-30" dt="-3.5"/>', (70.0, -5.25, 0.0)),
    ],
)
def test_positions_on_the_highway(position: str, expected: tuple[float, float, float]) -> None:
    x, y, heading = placed(position)
    assert (x, y) == pytest.approx(expected[:2], abs=1e-9)
    assert math.remainder(heading - expected[2], math.tau) == pytest.approx(0.0, abs=1e-9)


def test_a_relative_orientation_turns_from_the_lanes_direction() -> None:
    crossing = lane(150, -1).replace(
        "/>", '><Orientation type="relative" h="1.5707963"/></LanePosition>'
    )
    _, y, heading = placed(crossing)
    assert heading == pytest.approx(math.pi / 2, abs=1e-6) and y == pytest.approx(-1.75)


def test_opendrive_road_coordinates_round_trip_on_a_curve() -> None:
    lane_map = load_map(str(JUNCTION))
    roads = lane_map.roads
    assert roads is not None
    # Road 5 is a quarter circle of radius 50 from (0, 110) heading north, turning right.
    for s in (0.0, 20.0, 60.0):
        place = roads.lane_place("5", -1, s, 0.3)
        point = roads.locate(place.lane_index, place.station, place.offset)
        assert (point.road, point.lane, point.s) == ("5", -1, pytest.approx(s, abs=0.05))
        x, y, _, _ = roads.pose("5", s, point.t)
        centre = np.array([50.0, 110.0])
        assert np.hypot(x - centre[0], y - centre[1]) == pytest.approx(50.0 + point.t, abs=0.05)


def test_a_clothoid_of_constant_curvature_is_a_circular_arc() -> None:
    radius = 20.0
    follow = f"""<PrivateAction><RoutingAction><FollowTrajectoryAction>
      <Trajectory name="arc" closed="false"><Shape><Clothoid curvature="{1 / radius}"
        curvaturePrime="0" length="{math.pi / 2 * radius}">
        <Position><WorldPosition x="100" y="-1.75" h="0"/></Position></Clothoid></Shape>
      </Trajectory>
      <TimeReference><None/></TimeReference><TrajectoryFollowingMode followingMode="position"/>
    </FollowTrajectoryAction></RoutingAction></PrivateAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(10)) + f'<Private entityRef="Car">{follow}</Private>',
    )
    world, run = start_world(text)
    car = run.rt.entity("Car")
    car.speed = 10.0
    step(world, run, 3.14)  # 31.4 m of the arc's 31.42
    assert (car.x, car.y) == pytest.approx((100.0 + radius, -1.75 + radius), abs=0.03)
    assert car.heading == pytest.approx(math.pi / 2, abs=0.01)


def test_a_degree_one_nurbs_runs_through_its_control_points() -> None:
    points = "".join(
        f'<ControlPoint weight="1"><Position><WorldPosition x="{x}" y="{y}"/></Position>'
        "</ControlPoint>"
        for x, y in ((0, 0), (10, 0), (10, 10))
    )
    text = scenario(
        vehicle("Ego"),
        teleport("Ego", lane(10)),
        story(
            "Ego",
            event(
                "E",
                f"""<PrivateAction><RoutingAction><FollowTrajectoryAction><Trajectory name="n"
                  closed="false"><Shape><Nurbs order="2">{points}<Knot value="0"/><Knot value="0"/>
                  <Knot value="1"/><Knot value="2"/><Knot value="2"/></Nurbs></Shape></Trajectory>
                  <TimeReference><None/></TimeReference>
                  <TrajectoryFollowingMode followingMode="position"/></FollowTrajectoryAction>
                  </RoutingAction></PrivateAction>""",
            ),
        ),
    )
    world, run = start_world(text)
    step(world, run, 0.02)
    run_entity = run.rt.entity("Ego")
    path = run_entity.lateral.path  # type: ignore[union-attr]
    assert isinstance(path, SampledPath)
    assert path.length == pytest.approx(20.0, abs=1e-6)
    assert path.pose_at(10.0)[:2] == pytest.approx((10.0, 0.0), abs=1e-6)


def test_add_delete_visibility_and_traffic_light_actions() -> None:
    lights = load_map(str(JUNCTION))
    add = """<GlobalAction><EntityAction entityRef="Walker"><AddEntityAction><Position>
      <WorldPosition x="30" y="-10"/></Position></AddEntityAction></EntityAction></GlobalAction>"""
    hide = """<PrivateAction><VisibilityAction graphics="true" traffic="true" sensors="false"/>
      </PrivateAction>"""
    red = """<GlobalAction><InfrastructureAction><TrafficSignalAction>
      <TrafficSignalStateAction name="TL1" state="on;off;off"/></TrafficSignalAction>
      </InfrastructureAction></GlobalAction>"""
    delete = """<GlobalAction><EntityAction entityRef="Car"><DeleteEntityAction/></EntityAction>
      </GlobalAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car") + pedestrian("Walker"),
        teleport("Ego", lane(50, -1, road="1")) + teleport("Car", lane(20, 1, road="2")),
        story(
            "Car",
            event("Add", add, start(time_is(0.5))),
            event("Hide", hide, start(time_is(1.0)), "parallel"),
            event("Red", red, start(time_is(1.5)), "parallel"),
            event("Gone", delete, start(time_is(2.0)), "parallel"),
        ),
    ).replace("highway.xodr", "junction.xodr")
    world, run = start_world(text, lane_map=lights)
    assert "walker" not in world.objects().names
    step(world, run, 0.6)
    assert "walker" in world.objects().names
    car_name = "Car_model"
    assert car_name in world.objects().names
    step(world, run, 0.5)
    assert car_name not in world.objects().names  # not for the sensors any more
    step(world, run, 0.5)
    assert world.signals.light("TL1").aspect == RED
    step(world, run, 0.5)
    assert not run.rt.entity("Car").in_world()


def test_on_an_mgeo_map_a_lane_position_names_a_link_and_runs_along_it() -> None:
    mgeo = load_map("mgeo_sample")
    link = "R1_W_1"
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", f'<LanePosition roadId="{link}" laneId="-1" s="5"/>')
        + teleport("Car", f'<LanePosition roadId="{link}" laneId="-1" s="20" offset="0.5"/>')
        + init_speed("Car", 5.0),
    ).replace('filepath="highway.xodr"', 'filepath="mgeo_sample"')
    world, run = start_world(text, lane_map=mgeo)
    car = run.rt.entity("Car")
    assert mgeo.lane_ids[car.lane] == link
    assert (car.station, car.offset) == pytest.approx((20.0, 0.5))
    step(world, run, 2.0)
    assert mgeo.lane_ids[car.lane] == link and car.station == pytest.approx(30.0)
    # 0.5 m left of the link's centreline, facing along it.
    x, y, _, heading = mgeo.pose_at(link, 30.0)
    left = (-math.sin(heading), math.cos(heading))
    assert (car.x, car.y) == pytest.approx((x + 0.5 * left[0], y + 0.5 * left[1]), abs=1e-6)
    assert math.remainder(car.heading - heading, math.tau) == pytest.approx(0.0, abs=1e-6)
