"""Malformed and odd OpenSCENARIO files: the gallery's files with attribute values
replaced by odd ones, elements taken out or doubled, and texts cut short. Each is
either read, loaded and run for a while without an exception, or refused with one
ScenarioError naming the file and line; never another exception."""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree
from tests.world.openscenario.stories import (
    event,
    highway,
    init_speed,
    lane,
    pedestrian,
    scenario,
    start,
    story,
    teleport,
    time_is,
    vehicle,
)

from egosim.scenario_files import openscenario_scenario
from egosim.world import World
from egosim.world.openscenario import read_openscenario
from egosim.world.scenario import ScenarioError, ScenarioLoadOptions

GALLERY = Path(__file__).parents[3] / "examples" / "openscenario"
FILES = ("cut_in.xosc", "braking_target.xosc", "pedestrian_crossing.xosc")
CORPUS = (*FILES, "many_actions.xosc")
ODD_VALUES = (
    "",
    " ",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "-1",
    "0",
    "-0",
    "1e308",
    "-1e308",
    "1e-320",
    "99999999999999999999",
    "abc",
    "true",
    "${1/0}",
    "${1 % 0}",
    "${",
    "${sqrt(-1)}",
    "${pow(10, 400)}",
    "${acos(2)}",
    "$undeclared",
    "$",
    "${$x + }",
    "Ego",
    "Target",
    "-1.5",
    "3",
)
ATTRIBUTE = re.compile(r'(\w+)="([^"]*)"')
ERROR_LINE = re.compile(r"^\S+\.xosc(:\d+)?: \S")
CHECKED = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


# Actions the gallery does not hold, so that mutations reach their readers and runs too.
MANY_ACTIONS = scenario(
    vehicle("Ego") + vehicle("Car") + vehicle("Other"),
    teleport("Ego", lane(20))
    + init_speed("Ego", 15.0)
    + teleport("Car", lane(10, -2))
    + init_speed("Car", 10.0)
    + teleport("Other", '<RelativeObjectPosition entityRef="Ego" dx="30" dy="0"/>'),
    story(
        "Car",
        event(
            "Lc",
            """<PrivateAction><LateralAction><LaneChangeAction targetLaneOffset="0.2">
            <LaneChangeActionDynamics dynamicsShape="sinusoidal" value="3"
              dynamicsDimension="time"/><LaneChangeTarget><RelativeTargetLane entityRef="Car"
              value="1"/></LaneChangeTarget></LaneChangeAction></LateralAction></PrivateAction>""",
            start(time_is(0.5)),
        ),
        event(
            "Sync",
            """<PrivateAction><SynchronizeAction masterEntityRef="Ego">
            <TargetPositionMaster><LanePosition roadId="1" laneId="-1" s="200"/>
            </TargetPositionMaster><TargetPosition><LanePosition roadId="1" laneId="-1"
              s="190"/></TargetPosition><FinalSpeed><RelativeSpeedToMaster value="-2"
              speedTargetValueType="delta"><TargetTimeSteadyState time="1"/>
            </RelativeSpeedToMaster></FinalSpeed></SynchronizeAction></PrivateAction>""",
            start(time_is(0.2)),
            priority="parallel",
        ),
        event(
            "Traj",
            """<PrivateAction><RoutingAction><FollowTrajectoryAction><Trajectory name="T"
              closed="false"><Shape><Polyline><Vertex time="0"><Position><WorldPosition
              x="60" y="-1.75"/></Position></Vertex><Vertex time="2"><Position>
              <WorldPosition x="80" y="-5.25"/></Position></Vertex></Polyline></Shape>
              </Trajectory><TimeReference><Timing domainAbsoluteRelative="relative"
              scale="1" offset="0"/></TimeReference><TrajectoryFollowingMode
              followingMode="position"/></FollowTrajectoryAction></RoutingAction>
              </PrivateAction>""",
            start(time_is(1.5)),
            priority="skip",
            count=2,
        ),
    ),
)


@cache
def texts() -> dict[str, str]:
    found = {name: (GALLERY / name).read_text() for name in FILES}
    found["many_actions.xosc"] = MANY_ACTIONS
    return found


@cache
def catalogs() -> tuple[tuple[str, str], ...]:
    return tuple(
        (str(path), path.read_text()) for path in sorted((GALLERY / "catalogs").glob("*.xosc"))
    )


def read_load_and_run(text: str | bytes, label: str = "fuzzed.xosc") -> None:
    try:
        program = read_openscenario(text, label, catalogs())
        world = World(highway())
        world.load_scenario(
            openscenario_scenario(program), ScenarioLoadOptions(scenario_drives_ego=True)
        )
    except ScenarioError as error:
        # One line per mistake, each naming its file (and line where it has one).
        lines = str(error).strip().splitlines()
        assert lines, "an empty error"
        for line in lines:
            assert ERROR_LINE.match(line), line
        return
    run = world.storyboard
    assert run is not None
    for _ in range(20):
        run.step(0.1, True)
        world.step(0.1)


@CHECKED
@given(
    st.sampled_from(CORPUS),
    st.lists(
        st.tuples(st.integers(0, 10_000), st.sampled_from(ODD_VALUES)), min_size=1, max_size=3
    ),
)
def test_odd_attribute_values_are_read_or_refused_with_the_line(
    name: str, changes: list[tuple[int, str]]
) -> None:
    text = texts()[name]
    for where, value in changes:
        matches = list(ATTRIBUTE.finditer(text))
        match = matches[where % len(matches)]
        text = text[: match.start(2)] + value + text[match.end(2) :]
    read_load_and_run(text)


@CHECKED
@given(st.sampled_from(CORPUS), st.integers(0, 10_000), st.booleans())
def test_elements_taken_out_or_doubled_are_read_or_refused(
    name: str, where: int, double: bool
) -> None:
    root = etree.fromstring(texts()[name].encode())
    elements = [e for e in root.iter() if isinstance(e.tag, str) and e is not root]
    element = elements[where % len(elements)]
    parent = element.getparent()
    assert parent is not None
    if double:
        parent.insert(parent.index(element), etree.fromstring(etree.tostring(element)))
    else:
        parent.remove(element)
    read_load_and_run(etree.tostring(root))


@CHECKED
@given(st.sampled_from(CORPUS), st.integers(0, 10_000))
def test_texts_cut_short_are_refused_with_the_line(name: str, where: int) -> None:
    text = texts()[name]
    read_load_and_run(text[: where % len(text)])


@CHECKED
@given(st.binary(max_size=200))
def test_bytes_that_are_no_scenario_are_refused(data: bytes) -> None:
    read_load_and_run(data)


def test_actions_and_conditions_naming_an_entity_the_load_left_out_are_notes() -> None:
    # ScenarioLoad without pedestrians: the car's speed follows the walker's (said once,
    # the car keeps its speed) and a condition watches the walker (it never holds).
    follow_walker = """<PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="linear" value="2" dynamicsDimension="time"/>
      <SpeedActionTarget><RelativeTargetSpeed entityRef="Walker" value="1"
        speedTargetValueType="delta" continuous="true"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction>"""
    near_walker = """<Condition name="near" delay="0" conditionEdge="none"><ByEntityCondition>
      <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/>
      </TriggeringEntities><EntityCondition><RelativeDistanceCondition entityRef="Walker"
        value="5" freespace="false" rule="lessThan" relativeDistanceType="longitudinal"
        coordinateSystem="entity"/></EntityCondition></ByEntityCondition></Condition>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car") + pedestrian("Walker"),
        teleport("Ego", lane(10))
        + init_speed("Ego", 10.0)
        + teleport("Car", lane(50))
        + teleport("Walker", '<WorldPosition x="80" y="-8" h="1.57"/>'),
        story(
            "Car", event("Follow", follow_walker), event("Near", follow_walker, start(near_walker))
        ),
    )
    world = World(highway())
    world.load_scenario(
        openscenario_scenario(read_openscenario(text, "t.xosc")),
        ScenarioLoadOptions(load_pedestrian_data=False, scenario_drives_ego=True),
    )
    run = world.storyboard
    assert run is not None
    notes = []
    for _ in range(100):
        notes += run.step(0.01, True)
        world.step(0.01)
    assert any("'Walker'" in note and "not applied" in note for note in notes), notes
    assert run.rt.elements[("event", "Near")].state == "standbyState"
    assert run.rt.entity("Ego").x == pytest.approx(20.0, abs=1e-6)  # the rest runs
    assert run.rt.entity("Car").speed == 0.0
