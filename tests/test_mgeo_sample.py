"""The MGeo sample map shipped with egosim: made by examples/maps/make_mgeo_sample.py,
loadable by name, and holding what a MORAI user expects to find in an MGeo folder."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from egosim.maps import SHIPPED_MAPS_DIR, map_names, read_map
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.map.mgeo import MGEO_FILES, build_mgeo_map, mgeo_files
from egosim.world.scenario import parse_scenario

REPOSITORY = Path(__file__).parents[1]
SAMPLE = SHIPPED_MAPS_DIR / "mgeo_sample"


def sample_files() -> dict[str, object]:
    return {p.name: json.loads(p.read_text("utf-8")) for p in SAMPLE.glob("*.json")}


def test_the_shipped_folder_is_what_the_generator_writes(tmp_path: Path) -> None:
    subprocess.run(
        [sys.executable, str(REPOSITORY / "examples" / "maps" / "make_mgeo_sample.py"), tmp_path],
        check=True,
        timeout=120,
    )
    written = sorted(p.name for p in tmp_path.iterdir())
    assert written == sorted(p.name for p in SAMPLE.iterdir())
    for name in written:
        assert (tmp_path / name).read_bytes() == (SAMPLE / name).read_bytes(), name


def test_every_file_the_loader_reads_is_there() -> None:
    assert sorted(MGEO_FILES) == sorted(p.name for p in SAMPLE.iterdir())


@pytest.mark.parametrize("name_or_path", ["mgeo_sample", str(SAMPLE)])
def test_loads_by_name_or_path_with_nothing_left_out(name_or_path: str) -> None:
    loaded = read_map(name_or_path)
    assert loaded.notes == ()
    lane_map = loaded.lane_map
    assert lane_map.name == "mgeo_sample"
    assert len(lane_map.lanes) == 26
    assert sum(lane.is_junction for lane in lane_map.lanes.values()) == 14
    assert sorted(lane_map.traffic_lights) == ["TL1_E", "TL1_N", "TL1_S", "TL1_W"]
    assert list(lane_map.intersections) == [1]
    assert sorted(lane_map.crosswalks) == ["CW1_E", "CW1_N", "CW1_S", "CW1_W"]
    assert "mgeo_sample" in map_names()


def test_each_approach_stops_at_its_light_before_the_crosswalk() -> None:
    lane_map = read_map("mgeo_sample").lane_map
    approaches = [lane for lane in lane_map.lanes.values() if lane.traffic_light_ids]
    assert len(approaches) == 6
    for lane in approaches:
        assert lane.stop_line_s == pytest.approx(lane.length)
        stop = lane.centerline[-1, :2]
        (light,) = lane.traffic_light_ids
        walk = lane_map.crosswalks[f"CW1_{light[-1]}"]
        middle = np.mean([walk.start, walk.end], axis=0)
        # The line is before the crossing: farther from the junction centre than it.
        assert np.hypot(*stop) > np.hypot(*middle) + walk.width / 2


def test_lane_boundaries_carry_marking_types_and_give_the_widths() -> None:
    files = sample_files()
    boundaries = {b["idx"]: b for b in files["lane_boundary_set.json"]}  # type: ignore[union-attr]
    kinds = {(b["lane_type"], b["lane_color"], tuple(b["lane_shape"])) for b in boundaries.values()}
    assert kinds == {
        (501, "yellow", ("Solid", "Solid")),
        (503, "white", ("Broken",)),
        (505, "white", ("Solid",)),
    }
    # 2 arms with 2 lanes each way (centre, 2 lane lines, 2 edges) + 2 with 1 (centre, 2 edges).
    assert len(boundaries) == 16
    lane_map = read_map("mgeo_sample").lane_map
    for link in files["link_set.json"]:  # type: ignore[union-attr]
        if lane_map.lanes[link["idx"]].is_junction:
            continue
        assert link["lane_mark_left"][0] in boundaries
        assert link["lane_mark_right"][0] in boundaries
        assert np.allclose(lane_map.lanes[link["idx"]].widths, 3.5, atol=0.01)


def test_npcs_drive_through_its_junction_obeying_the_lights() -> None:
    world = World(read_map("mgeo_sample").lane_map)
    crossed: set[str] = set()
    scenario = parse_scenario(
        "map: mgeo_sample\n"
        "ego: {start: {lane: R1_E_2, s: 90}}\n"
        "npcs:\n"
        "  - {start: {lane: R3_E_1, s: 20}, route: [R3_E_1, R1_E_1]}\n"
        "  - {start: {lane: R1_W_2, s: 20}, route: [R1_W_2, R3_W_2]}\n"
        "  - {start: {lane: R2_S_1, s: 40}, route: [R2_S_1, R4_S_1]}\n"
    )
    world.load_scenario(scenario)
    for _ in range(6000):
        world.step(0.02)
        lanes = {world.map.lane_ids[k] for k in world.npcs.lane}
        crossed |= {lane for lane in lanes if world.map.lanes[lane].is_junction}
    assert world.vehicle_collisions == []
    assert len(crossed) >= 3


def test_a_town_written_as_mgeo_reads_back_as_the_same_network() -> None:
    town = build_builtin_map("town")
    notes: list[str] = []
    back = build_mgeo_map("town", mgeo_files(town), notes)
    assert sorted(back.lanes) == sorted(town.lanes)
    assert sorted(back.traffic_lights) == sorted(town.traffic_lights)
    assert sorted(back.intersections) == sorted(town.intersections)
    assert sorted(back.crosswalks) == sorted(town.crosswalks)
    for lane_id, lane in town.lanes.items():
        assert back.lanes[lane_id].successors == lane.successors
        assert back.lanes[lane_id].traffic_light_ids == lane.traffic_light_ids
    assert notes == []
