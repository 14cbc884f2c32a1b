"""A ScenarioLoad's file is read off the loop, and only if it is a regular file."""

from __future__ import annotations

import logging
import os
import threading
from pathlib import Path

from egosim.bridge import simulation_context
from egosim.bridge.scene.scenarios import ScenarioRequest, on_scenario_load, prepare_scenario
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map

PROFILE = get_profile("26.r1")
READ_DEADLINE_S = 5.0


def read_in_thread(context, file_name: str) -> ScenarioRequest:
    """prepare_scenario on another thread, as the transport runs it; fails if it blocks."""
    request = PROFILE.message("morai_msgs/ScenarioLoad").new(
        file_name=file_name, load_ego_vehicle_data=True
    )
    prepared: list[ScenarioRequest] = []
    reader = threading.Thread(
        target=lambda: prepared.append(
            prepare_scenario(context, context.row("scenario_load"), request)
        ),
        daemon=True,
    )
    reader.start()
    reader.join(READ_DEADLINE_S)
    assert prepared, f"reading {file_name} blocked for {READ_DEADLINE_S} s"
    return prepared[0]


def test_a_named_pipe_is_refused_at_once_and_nothing_changes(tmp_path: Path, caplog) -> None:
    pipe = tmp_path / "fifo.yaml"
    os.mkfifo(pipe)
    world = World(build_builtin_map("straight"))
    context = simulation_context(world, data_roots=(tmp_path,))
    before = world.ego_status().pose
    try:
        prepared = read_in_thread(context, "fifo.yaml")
    finally:
        # Whatever happened, nothing may stay blocked on the pipe.
        descriptor = os.open(pipe, os.O_RDWR | os.O_NONBLOCK)
        os.close(descriptor)
    assert prepared.scenario is None
    assert "not a regular file" in prepared.error
    with caplog.at_level(logging.ERROR):
        on_scenario_load(context, context.row("scenario_load"), prepared)
    assert "not a regular file" in caplog.text
    assert world.ego_status().pose == before


def test_a_regular_scenario_file_is_read_then_applied(tmp_path: Path) -> None:
    (tmp_path / "start.yaml").write_text(
        "map: straight\nego:\n  start: {lane: R1_E_1, s: 42.0}\n", encoding="utf-8"
    )
    world = World(build_builtin_map("straight"))
    context = simulation_context(world, data_roots=(tmp_path,))
    prepared = read_in_thread(context, "start")
    assert prepared.error == ""
    on_scenario_load(context, context.row("scenario_load"), prepared)
    lane = world.ego_lane_state()
    assert (lane.lane_id, round(lane.s, 6)) == ("R1_E_1", 42.0)
