"""Two heads over one stop line, as at K-City's C119BS010027/028 (a round-green head and
a left-arrow head over the same lanes): GetTrafficLightStatus names the nearest of them,
and drivers, the red-light rule and the loader read both."""

from __future__ import annotations

import math

import pytest
from tests.evaluation.drives import DT, drive, straight
from tests.world.map.mgeo.sample_mgeo import BOX_M, incoming_line, mgeo_files_with_twin_heads
from tests.world.traffic.scenes import run, world_from

from egosim.bridge import HANDLERS, simulation_context
from egosim.evaluation import DriveEvaluator, InfractionKind
from egosim.world import World
from egosim.world.map import LaneMap
from egosim.world.map.mgeo import build_mgeo_map
from egosim.world.signals import (
    GREEN,
    GREEN_LEFT,
    OFF,
    RED,
    YELLOW,
    LightType,
    combined_aspect,
)
from egosim.world.traffic import LightsView
from egosim.world.vehicle import Pose

EGO_OUT_OF_THE_WAY = {"start": {"lane": "L_S_out", "s": 90.0}}


def twin_map(files: dict[str, object] | None = None) -> tuple[LaneMap, list[str]]:
    notes: list[str] = []
    return build_mgeo_map("twins", files or mgeo_files_with_twin_heads(), notes), notes


TWINS, TWIN_NOTES = twin_map()


def test_both_heads_govern_every_lane_of_their_approach() -> None:
    for arm in "ENWS":
        lane = TWINS.lane(f"L_{arm}_in")
        assert lane.traffic_light_ids == (f"TL_{arm}", f"TL_{arm}2")
        assert lane.stop_line_s == pytest.approx(lane.length)
        first, twin = (TWINS.traffic_lights[i] for i in lane.traffic_light_ids)
        assert twin.lane_ids == first.lane_ids
        # Both face the traffic they govern.
        assert twin.heading == pytest.approx(first.heading)
    assert TWINS.lane("L_W_in2").traffic_light_ids == ("TL_W", "TL_W2")
    assert not [note for note in TWIN_NOTES if "TL_" in note]


@pytest.mark.parametrize("before_line_m", [60.0, 12.0, 0.5])
@pytest.mark.parametrize(("lane_id", "nearest"), [("L_W_in", "TL_W2"), ("L_W_in2", "TL_W")])
def test_the_ego_is_told_the_nearest_head_over_its_lane(
    lane_id: str, nearest: str, before_line_m: float
) -> None:
    world = World(TWINS)
    lane = TWINS.lane(lane_id)
    x, y, z, yaw = TWINS.pose_at(lane_id, lane.length - before_line_m)
    world.egos[0].vehicle.teleport(Pose(x=x, y=y, z=z, yaw=yaw))
    distance = {
        i: math.dist(TWINS.traffic_lights[i].position[:2], (x, y)) for i in lane.traffic_light_ids
    }
    light = world.ego_traffic_light()
    assert light is not None
    assert light.light_id == nearest == min(distance, key=distance.__getitem__)


def test_get_traffic_light_status_reports_the_nearest_heads_index_type_and_state() -> None:
    world = World(TWINS)
    x, y, z, yaw = TWINS.pose_at("L_W_in", TWINS.lane("L_W_in").length - 12.0)
    world.egos[0].vehicle.teleport(Pose(x=x, y=y, z=z, yaw=yaw))
    world.signals.set_light("TL_W2", RED | GREEN_LEFT)
    world.signals.set_light("TL_W", RED)
    context = simulation_context(world)
    row = context.row("traffic_light_status")
    message_type = context.profile.message("morai_msgs/GetTrafficLightStatus")
    wire = message_type.serialize(HANDLERS.publishers["traffic_light_status"](context, row))
    message = message_type.deserialize(wire)
    assert message.trafficLightIndex == "TL_W2"
    assert message.trafficLightType == LightType.RYG_LEFT_GREEN
    assert message.trafficLightStatus == RED | GREEN_LEFT


def _npc_world(route: list[str]) -> World:
    return world_from(
        {
            "map": "twins",
            "ego": EGO_OUT_OF_THE_WAY,
            "npcs": [{"start": {"lane": route[0], "s": 60.0}, "speed_mps": 10.0, "route": route}],
        },
        TWINS,
    )


LEFT_FROM_WEST = ["L_W_in", "C_WN", "L_N_out"]
STRAIGHT_FROM_WEST = ["L_W_in", "C_WE", "L_E_out"]


@pytest.mark.parametrize(
    ("route", "plain_head", "arrow_head", "goes"),
    [
        # The arrow lit on the twin lets the left turn go; the round red holds the rest.
        (LEFT_FROM_WEST, RED, RED | GREEN_LEFT, True),
        (STRAIGHT_FROM_WEST, RED, RED | GREEN_LEFT, False),
        # A dark head adds nothing: the lit red still holds everyone.
        (LEFT_FROM_WEST, RED, OFF, False),
        (STRAIGHT_FROM_WEST, OFF, RED, False),
        (STRAIGHT_FROM_WEST, GREEN, GREEN, True),
    ],
)
def test_npcs_obey_both_heads_read_together(
    route: list[str], plain_head: int, arrow_head: int, goes: bool
) -> None:
    world = _npc_world(route)
    world.signals.set_light("TL_W", plain_head)
    world.signals.set_light("TL_W2", arrow_head)
    run(world, 15.0)
    lane = world.map.lane_ids[world.npcs.lane[0]]
    assert (lane != "L_W_in") == goes
    if not goes:
        assert world.npcs.speed[0] == pytest.approx(0.0, abs=1e-3)


@pytest.mark.parametrize(
    ("first", "twin", "red_run"),
    [
        (RED, RED, True),
        (RED | GREEN_LEFT, RED, False),
        (RED, OFF, True),
        (OFF, OFF, False),
    ],
)
def test_a_red_light_run_is_crossing_when_no_head_over_the_line_shows_a_go(
    first: int, twin: int, red_run: bool
) -> None:
    world = World(TWINS)
    world.signals.set_light("TL_S", first)
    world.signals.set_light("TL_S2", twin)
    evaluator = DriveEvaluator(world)
    # Northbound on the south approach, 20 m before its line (which ends the lane).
    x = float(incoming_line("S")[0][0])
    drive(world, evaluator, straight(x, -BOX_M - 20.0, 10.0, math.pi / 2), 3.0)
    runs = [i for i in evaluator.infractions() if i.kind is InfractionKind.RED_LIGHT]
    assert len(runs) == int(red_run)
    if red_run:
        assert runs[0].time_s == pytest.approx(2.0, abs=DT + 1e-9)
        assert (runs[0].x, runs[0].y) == pytest.approx((x, -BOX_M), abs=1e-6)
        assert "TL_S/TL_S2" in runs[0].detail


def test_lamps_lit_on_any_head_make_the_stop_lines_aspect() -> None:
    assert combined_aspect([RED, RED | GREEN_LEFT]) == RED | GREEN_LEFT
    assert combined_aspect([OFF, RED]) == RED
    assert combined_aspect([OFF, OFF]) == combined_aspect([]) == OFF
    # The vectorised signals the agents read agree with it through a whole program.
    world = World(TWINS)
    graph_signal = world.signals.lane_signals.of_lane
    seen = set()
    for _ in range(round(120.0 / 0.5)):
        world.signals.step(0.5)
        view = LightsView.of(world.signals)
        for k, lane_id in enumerate(TWINS.lane_ids):
            heads = TWINS.lanes[lane_id].traffic_light_ids
            if heads:
                aspect = combined_aspect(world.signals.light(i).aspect for i in heads)
                assert view.aspects[graph_signal[k]] == aspect
                seen.add(aspect)
    assert {RED, RED | GREEN_LEFT, GREEN, YELLOW} <= seen
    for arm in "ENWS":
        signal = graph_signal[TWINS.lane_index(f"L_{arm}_in")]
        assert view.arrow_head[signal] and not view.arrow_only[signal] and not view.flashing[signal]


def test_a_flashing_head_beside_a_cycling_one_adds_nothing() -> None:
    files = mgeo_files_with_twin_heads()
    for light in files["traffic_light_set.json"]:  # type: ignore[attr-defined]
        if light["idx"] == "TL_W2":
            light["sub_type"] = ["yellow"]
    lane_map, _ = twin_map(files)
    world = World(lane_map)
    world.signals.set_light("TL_W", RED)
    view = LightsView.of(world.signals)
    signal = world.signals.lane_signals.of_lane[lane_map.lane_index("L_W_in")]
    assert world.signals.light("TL_W2").aspect == YELLOW
    assert view.aspects[signal] == RED
    assert not view.flashing[signal]
