"""Every junction form of OpenDRIVE 1.4-1.8 on small networks: common junctions (the
shared junction.xodr), direct junctions (1.7, linkedRoad), virtual junctions (1.8 road
links at an elementS of the main road, and 1.7 virtual connections with their own links),
crossings (1.8, no connections), and connections the loader cannot follow."""

from __future__ import annotations

import pytest
from tests.world.traffic.scenes import run, world_from

from egosim.world.map import LaneMap
from egosim.world.map.opendrive import build_opendrive_map


def build(text: str) -> tuple[LaneMap, list[str]]:
    notes: list[str] = []
    return build_opendrive_map("forms", text, notes), notes


def road(
    road_id: str,
    x: float,
    y: float,
    hdg: float,
    length: float,
    lanes: str,
    link: str = "",
    junction: str = "-1",
) -> str:
    return f"""<road id="{road_id}" length="{length}" junction="{junction}">
      <link>{link}</link>
      <planView><geometry s="0" x="{x}" y="{y}" hdg="{hdg}" length="{length}"><line/>
      </geometry></planView>
      <lanes><laneSection s="0">{lanes}</laneSection></lanes>
    </road>"""


def right_lanes(*lanes: tuple[int, str]) -> str:
    """Right lanes (RHT: along +s) with their lane links, e.g. (-1, '<predecessor id="-1"/>')."""
    body = "".join(
        f'<lane id="{i}" type="driving"><link>{link}</link>'
        f'<width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>'
        for i, link in lanes
    )
    return f"<right>{body}</right>"


TWO_WAY = (
    '<left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/>'
    "</lane></left>" + right_lanes((-1, ""))
)


def document(*elements: str, minor: int = 8) -> str:
    header = (
        f'<header revMajor="1" revMinor="{minor}">'
        "<geoReference><![CDATA[+proj=utm +zone=52 +datum=WGS84]]></geoReference></header>"
    )
    return f"<OpenDRIVE>{header}{''.join(elements)}</OpenDRIVE>"


# A motorway (road 1, two lanes) ends at a direct junction: its inner lane goes on as road 2,
# its outer lane leaves as the exit ramp road 3, both ordinary roads.
DIRECT = document(
    road(
        "1",
        0,
        0,
        0,
        100,
        right_lanes((-1, ""), (-2, "")),
        '<successor elementType="junction" elementId="10"/>',
    ),
    road(
        "2",
        100,
        0,
        0,
        100,
        right_lanes((-1, "")),
        '<predecessor elementType="junction" elementId="10"/>',
    ),
    road(
        "3",
        100,
        -3.5,
        -0.2,
        80,
        right_lanes((-1, "")),
        '<predecessor elementType="junction" elementId="10"/>',
    ),
    """<junction id="10" type="direct">
      <connection id="0" incomingRoad="1" linkedRoad="2" contactPoint="start">
        <laneLink from="-1" to="-1"/></connection>
      <connection id="1" incomingRoad="1" linkedRoad="3" contactPoint="start">
        <laneLink from="-2" to="-1"/></connection>
    </junction>""",
    minor=7,
)


def test_a_direct_junction_links_the_incoming_lanes_to_the_linked_roads() -> None:
    lane_map, notes = build(DIRECT)
    assert notes == []
    assert lane_map.lane("1_0_-1").successors == ("2_0_-1",)
    assert lane_map.lane("1_0_-2").successors == ("3_0_-1",)
    assert lane_map.lane("3_0_-1").predecessors == ("1_0_-2",)
    # The linked roads are ordinary roads, not paths through a junction.
    assert not lane_map.lane("2_0_-1").is_junction
    assert not lane_map.lane("3_0_-1").is_junction


def test_an_npc_takes_the_exit_of_a_direct_junction() -> None:
    lane_map, _ = build(DIRECT)
    world = world_from(
        {
            "map": "forms",
            "ego": {"start": {"lane": "2_0_-1", "s": 90.0}},
            "npcs": [{"start": {"lane": "1_0_-2", "s": 60.0}, "route": ["1_0_-2", "3_0_-1"]}],
        },
        lane_map,
    )
    run(world, 8.0)
    assert world.map.lane_ids[world.npcs.lane[0]] == "3_0_-1"


# A two-way main road (road 1, 200 m) with a parking lot off its right side: road 2 leaves
# it at s=50, road 99 is the lot's aisle, road 4 rejoins it at s=70 (a virtual junction,
# the main road is not cut).
VIRTUAL_AT_ROADS = document(
    road("1", 0, 0, 0, 200, TWO_WAY),
    road(
        "2",
        50,
        0,
        -0.5,
        20,
        right_lanes((-1, '<predecessor id="-1"/><successor id="-1"/>')),
        '<predecessor elementType="road" elementId="1" elementS="50" elementDir="+"/>'
        '<successor elementType="road" elementId="99" contactPoint="start"/>',
        junction="20",
    ),
    road(
        "99",
        67.55,
        -9.59,
        0,
        4,
        right_lanes((-1, '<predecessor id="-1"/><successor id="-1"/>')),
        '<predecessor elementType="road" elementId="2" contactPoint="end"/>'
        '<successor elementType="road" elementId="4" contactPoint="start"/>',
    ),
    road(
        "4",
        71.55,
        -9.59,
        0.5,
        20,
        right_lanes((-1, '<predecessor id="-1"/><successor id="-1"/>')),
        '<predecessor elementType="road" elementId="99" contactPoint="end"/>'
        '<successor elementType="road" elementId="1" elementS="70" elementDir="+"/>',
        junction="20",
    ),
    """<junction id="20" type="virtual" mainRoad="1" sStart="50" sEnd="70" orientation="+">
      <connection id="0" incomingRoad="1" connectingRoad="2"><laneLink from="-1" to="-1"/>
      </connection>
    </junction>""",
)

# The same lot written as OpenDRIVE 1.7 did: the virtual connections carry the links to
# the main road, the connecting roads' lanes name no lane of it.
VIRTUAL_AT_CONNECTIONS = document(
    road("1", 0, 0, 0, 200, TWO_WAY),
    road(
        "2",
        50,
        0,
        -0.5,
        20,
        right_lanes((-1, '<successor id="-1"/>')),
        '<successor elementType="road" elementId="99" contactPoint="start"/>',
        junction="20",
    ),
    road(
        "99",
        67.55,
        -9.59,
        0,
        4,
        right_lanes((-1, '<predecessor id="-1"/><successor id="-1"/>')),
        '<predecessor elementType="road" elementId="2" contactPoint="end"/>'
        '<successor elementType="road" elementId="4" contactPoint="start"/>',
    ),
    road(
        "4",
        71.55,
        -9.59,
        0.5,
        20,
        right_lanes((-1, '<predecessor id="-1"/><successor id="-1"/>')),
        '<predecessor elementType="road" elementId="99" contactPoint="end"/>'
        '<successor elementType="road" elementId="1" elementS="70" elementDir="+"/>',
        junction="20",
    ),
    """<junction id="20" type="virtual" mainRoad="1" sStart="50" sEnd="70" orientation="+">
      <connection id="0" type="virtual" incomingRoad="1" connectingRoad="2">
        <predecessor elementType="road" elementId="1" elementS="50" elementDir="+"/>
        <laneLink from="-1" to="-1"/>
      </connection>
    </junction>""",
    minor=7,
)


@pytest.mark.parametrize("text", [VIRTUAL_AT_ROADS, VIRTUAL_AT_CONNECTIONS], ids=["1.8", "1.7"])
def test_a_virtual_junction_joins_the_main_road_part_way_along_it(text: str) -> None:
    lane_map, notes = build(text)
    assert notes == []
    # The main road's lanes end and start where the lot's roads join it...
    first, middle, last = (lane_map.lane(f"1_{k}_-1") for k in range(3))
    assert (first.length, middle.length, last.length) == pytest.approx((50.0, 20.0, 130.0))
    # ...its traffic goes on, or turns into the lot at s=50, and the lot's exit rejoins at 70.
    assert set(first.successors) == {"1_1_-1", "2_0_-1"}
    assert middle.successors == ("1_2_-1",)
    assert set(last.predecessors) == {"1_1_-1", "4_0_-1"}
    assert lane_map.lane("2_0_-1").successors == ("99_0_-1",)
    # The other direction passes by: nothing joins it.
    assert lane_map.lane("1_2_1").successors == ("1_1_1",)
    assert lane_map.lane("1_1_1").successors == ("1_0_1",)
    assert lane_map.lane("2_0_-1").is_junction and not first.is_junction


def test_an_npc_drives_through_the_lot_of_a_virtual_junction() -> None:
    lane_map, _ = build(VIRTUAL_AT_ROADS)
    route = ["1_0_-1", "2_0_-1", "99_0_-1", "4_0_-1", "1_2_-1"]
    world = world_from(
        {
            "map": "forms",
            "ego": {"start": {"lane": "1_0_1", "s": 40.0}},
            "npcs": [{"start": {"lane": "1_0_-1", "s": 30.0}, "route": route}],
        },
        lane_map,
    )
    seen = []
    for _ in range(round(20.0 / world.physics_step_s)):
        world.step()
        lane = world.map.lane_ids[world.npcs.lane[0]]
        if not seen or seen[-1] != lane:
            seen.append(lane)
    assert seen[: len(route)] == route


# Two two-way roads crossing at grade (1.8 crossing: no connections, nobody turns).
CROSSING = document(
    road("1", 0, 0, 0, 100, TWO_WAY),
    road("2", 50, -50, 1.5707963267948966, 100, TWO_WAY),
    """<junction id="30" type="crossing">
      <roadSection id="0" roadId="1" sStart="45" sEnd="55"/>
      <roadSection id="1" roadId="2" sStart="45" sEnd="55"/>
    </junction>""",
)


def test_a_crossing_lets_both_roads_run_through_unlinked() -> None:
    lane_map, notes = build(CROSSING)
    assert notes == []
    assert sorted(lane_map.lanes) == ["1_0_-1", "1_0_1", "2_0_-1", "2_0_1"]
    assert all(not lane.successors and not lane.predecessors for lane in lane_map.lanes.values())
    assert lane_map.lane("1_0_-1").length == pytest.approx(100.0)


def test_a_connection_naming_no_road_to_lead_into_is_noted_and_the_rest_loads() -> None:
    text = DIRECT.replace('linkedRoad="3" ', "").replace('type="direct"', 'type="merge"')
    lane_map, notes = build(text)
    assert notes == [
        "junction id='10': type 'merge' is unknown, read as a default junction",
        "junction id='10' connection id='1': names no connectingRoad nor linkedRoad, left out",
    ]
    assert lane_map.lane("1_0_-1").successors == ("2_0_-1",)
    assert lane_map.lane("1_0_-2").successors == ()
