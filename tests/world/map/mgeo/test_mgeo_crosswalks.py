"""MGeo single crosswalks become crosswalks pedestrians cross, waiting for the lights."""

import math

import pytest
from tests.world.map.mgeo.sample_mgeo import LANE_M, mgeo_files
from tests.world.traffic.scenes import run, world_from

from egosim.world.map import LaneMap, MapRecordError
from egosim.world.map.mgeo import build_mgeo_map
from egosim.world.signals import GREEN, RED

# Across the south arm (one lane each way, x from -LANE_M to LANE_M), 4 m wide along it,
# 4 m short of the junction box; closed like MGeo's own outlines.
SOUTH_CROSSING = [
    [-LANE_M, -16.0, 0.0],
    [LANE_M, -16.0, 0.0],
    [LANE_M, -12.0, 0.0],
    [-LANE_M, -12.0, 0.0],
    [-LANE_M, -16.0, 0.0],
]


def build_with(crosswalks: list[dict]) -> tuple[LaneMap, list[str]]:
    files = mgeo_files()
    files["singlecrosswalk_set.json"] = crosswalks
    notes: list[str] = []
    return build_mgeo_map("sample", files, notes), notes


def south_crossing(**fields) -> dict:
    return {"idx": "CW_S", "points": SOUTH_CROSSING, "sign_type": "5321", **fields}


def test_a_single_crosswalk_crosses_its_road_square_and_waits_for_its_junction():
    lane_map, _ = build_with([south_crossing()])
    walk = lane_map.crosswalks["CW_S"]
    ends = sorted([walk.start, walk.end])
    assert ends[0] == pytest.approx((-LANE_M, -14.0))
    assert ends[1] == pytest.approx((LANE_M, -14.0))
    assert walk.width == pytest.approx(4.0)
    (junction,) = lane_map.intersections
    assert walk.intersection_id == junction


def test_raised_and_untyped_crosswalks_are_read_and_bicycle_crossings_left_out():
    far = [[x, y - 40.0, z] for x, y, z in SOUTH_CROSSING]
    lane_map, notes = build_with(
        [
            south_crossing(idx="RAISED", sign_type=533),
            south_crossing(idx="UNTYPED", points=far, sign_type=None),
            south_crossing(idx="BIKE", sign_type="534"),
        ]
    )
    assert set(lane_map.crosswalks) == {"RAISED", "UNTYPED"}
    assert any("BIKE: sign_type 534 is no crosswalk" in note for note in notes)
    # Too far from the junction to wait for its lights.
    assert lane_map.crosswalks["UNTYPED"].intersection_id is None


@pytest.mark.parametrize(
    ("record", "reason"),
    [
        (south_crossing(points=[["west", -16.0, 0.0]]), "points must hold"),
        (south_crossing(points=None), "has no points"),
        ({"points": SOUTH_CROSSING}, "has no idx"),
    ],
)
def test_a_malformed_crosswalk_names_its_file_and_record(record, reason):
    with pytest.raises(MapRecordError) as caught:
        build_with([record])
    assert caught.value.source == "singlecrosswalk_set.json"
    assert "record #0" in caught.value.record
    assert reason in caught.value.reason


def test_a_pedestrian_waits_while_the_crossed_road_has_green_and_crosses_on_red():
    lane_map, _ = build_with([south_crossing()])
    scenario = {
        "map": "sample",
        "ego": {"start": {"lane": "L_E_out", "s": 90.0}},
        "pedestrians": [{"crosswalk": "CW_S", "speed_mps": 1.0}],
    }
    world = world_from(scenario, lane_map)
    start = lane_map.crosswalks["CW_S"].start
    world.signals.set_light("TL_S", GREEN)
    run(world, 5.0)
    assert world.pedestrians.position[0] == pytest.approx(start)

    world.signals.set_light("TL_S", RED)
    run(world, 3.0)
    assert math.dist(world.pedestrians.position[0], start) == pytest.approx(3.0, abs=0.02)
