"""A scenario with several mistakes reports all of them at once, each with file:line."""

from __future__ import annotations

import pytest

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import ScenarioError, parse_scenario

SCHEMA_MISTAKES = """\
map: straight
seed: lots
ego:
  start: {lane: R1_E_1, s: -5}
npcs:
  - start: {lane: R1_E_1}
    colour: red
    speed_mps: fast
  - start: {x: 1}
pedestrians:
  - {crosswalk: CW1, sidewalk: SW1}
"""

PLACEMENT_MISTAKES = """\
map: straight
ego:
  model: Trabant
  start: {lane: R1_E_1, s: 10}
npcs:
  - start: {lane: R9_E_1}
    model: Zeppelin
  - start: {lane: R1_E_1, s: 20}
    route: [R1_E_1, R7_W_3]
    lane_change: {lane: R4_E_4}
obstacles:
  - {model: Piano, pose: {x: 1, y: 2}}
signals:
  intersections:
    - {id: 3}
"""


def problems_of(error: ScenarioError) -> list[str]:
    return [f"{p.line}: {p.field}: {p.message}" for p in error.problems]


def test_every_schema_mistake_is_reported_with_its_line() -> None:
    with pytest.raises(ScenarioError) as caught:
        parse_scenario(SCHEMA_MISTAKES, "bad.yaml")
    lines = str(caught.value).splitlines()
    assert lines == [
        "bad.yaml:2: seed: 'lots' is not of type 'integer'",
        "bad.yaml:4: ego.start.s: -5 is less than the minimum of 0",
        "bad.yaml:7: npcs[0].colour: unknown field 'colour'",
        "bad.yaml:8: npcs[0].speed_mps: 'fast' is not of type 'number'",
        "bad.yaml:9: npcs[1].start: 'y' is a required property",
        lines[5],
    ]
    assert lines[5].startswith("bad.yaml:11: pedestrians[0]: ")
    # The first problem is also the error's own location.
    assert (caught.value.line, caught.value.field) == (2, "seed")


def test_every_placement_mistake_is_reported_and_the_world_is_unchanged() -> None:
    world = World(build_builtin_map("straight"))
    before = world.ego_status().pose
    with pytest.raises(ScenarioError) as caught:
        world.load_scenario(parse_scenario(PLACEMENT_MISTAKES, "bad.yaml"))
    got = problems_of(caught.value)
    assert [line.split(": ")[:2] for line in got] == [
        ["3", "ego.model"],
        ["6", "npcs[0].start.lane"],
        ["7", "npcs[0].model"],
        ["9", "npcs[1].route[1]"],
        ["10", "npcs[1].lane_change.lane"],
        ["12", "obstacles[0].model"],
        ["15", "signals.intersections[0].id"],
    ]
    assert "no lane 'R9_E_1' in map 'straight'" in got[1]
    assert "no intersection 3 in the map" in got[6]
    assert str(caught.value).count("\n") == 6
    assert world.ego_status().pose == before
    assert len(world.npcs) == 0


def test_one_mistake_is_one_line_as_before() -> None:
    with pytest.raises(ScenarioError) as caught:
        parse_scenario("map: town\nseed: -1\n", "one.yaml")
    assert str(caught.value) == "one.yaml:2: seed: -1 is less than the minimum of 0"
    assert caught.value.problems == (caught.value,)
