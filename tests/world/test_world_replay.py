"""A replay's recorded agents among the simulated ones: simulated drivers react to them,
contacts treat them as immovable, and a replay is deterministic bit for bit and shows
the object tables the world showed before its agents became populations."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest
from tests import morai_scenarios as morai
from tests.world.traffic.scenes import EGO_OUT_OF_THE_WAY, run, world_from

from egosim.world import World
from egosim.world.collision import EgoCollision
from egosim.world.map import build_builtin_map
from egosim.world.recorded_scene import RecordedEgo, RecordedScene
from egosim.world.scenario import load_default_scenario
from egosim.world.scenario.morai import read_morai_scenario
from egosim.world.traffic import ObjectTable, ObjectType
from egosim.world.vehicle import ControlCommand, LongitudinalMode, Pose

REFERENCE = Path(__file__).parents[1] / "data" / "world" / "replay_object_tables.npz"
COLUMNS = ("unique_ids", "object_types", "positions", "headings", "velocities", "accelerations")
SAMPLE_EVERY = 10  # steps
SIZES = {  # length, width, height, m
    ObjectType.NPC_VEHICLE: (4.5, 1.8, 1.5),
    ObjectType.PEDESTRIAN: (0.6, 0.6, 1.8),
    ObjectType.OBSTACLE: (0.4, 0.4, 0.7),
}
Recorded = tuple[int, str, tuple[float, float], float, float]


def recorded_table(kind: ObjectType, rows: list[Recorded]) -> ObjectTable:
    """Recorded objects of one kind: (unique id, model, (x, y), heading, speed along it)."""
    n = len(rows)
    return ObjectTable(
        unique_ids=np.array([r[0] for r in rows], np.int64),
        object_types=np.full(n, int(kind), np.int64),
        names=tuple(r[1] for r in rows),
        positions=np.array([(*r[2], 0.0) for r in rows], np.float64).reshape(n, 3),
        headings=np.array([r[3] for r in rows], np.float64),
        velocities=np.array(
            [(r[4] * math.cos(r[3]), r[4] * math.sin(r[3]), 0.0) for r in rows], np.float64
        ).reshape(n, 3),
        accelerations=np.zeros((n, 3)),
        sizes=np.tile(SIZES[kind], (n, 1)),
    )


# -- simulated drivers among recorded agents ---------------------------------------------


def test_a_simulated_npc_stops_behind_a_recorded_pedestrian_in_its_lane() -> None:
    world = world_from(
        {
            "map": "straight",
            "ego": EGO_OUT_OF_THE_WAY,
            "npcs": [{"start": {"lane": "R1_E_1", "s": 50.0}, "speed_mps": 10.0}],
        }
    )
    walker = recorded_table(ObjectType.PEDESTRIAN, [(70, "Man", (150.0, -1.75), 0.0, 0.0)])
    world.show_recorded(RecordedScene(pedestrians=walker))
    run(world, 20.0)
    front = world.npcs.pose[0, 0] + world.npcs.dims[0, 0] / 2.0
    assert world.npcs.speed[0] < 0.05
    assert 150.0 - 0.3 - 3.0 < front < 150.0 - 0.3  # short of the walker, within a gap
    assert world.ego_collision_log == [] and world.vehicle_collisions == []


def test_simulated_npcs_stop_for_recorded_obstacles_and_pass_the_hidden_simulated_ones() -> None:
    world = world_from(
        {
            "map": "straight",
            "ego": EGO_OUT_OF_THE_WAY,
            "npcs": [{"start": {"lane": "R1_E_1", "s": 20.0}, "speed_mps": 10.0}],
            "obstacles": [{"model": "Barrier", "pose": {"x": 100.0, "y": -1.75, "heading_deg": 0}}],
        }
    )
    cone = recorded_table(ObjectType.OBSTACLE, [(80, "Cone", (250.0, -1.75), 0.0, 0.0)])
    world.show_recorded(RecordedScene(obstacles=cone))
    run(world, 40.0)
    front = world.npcs.pose[0, 0] + world.npcs.dims[0, 0] / 2.0
    assert world.npcs.speed[0] < 0.05
    assert 200.0 < front < 250.0  # past the barrier that is not shown, short of the cone
    assert world.shown_tables()[2].unique_ids.tolist() == [80]
    assert world.vehicle_collisions == []


def test_dormant_npcs_wait_frozen_under_a_replay_and_wake_for_an_ego_that_came_near() -> None:
    # MORAI active distances: the first NPC sets off once an ego has been within 40 m of
    # it (while a replay stands in for the NPCs), the second never sees the ego that near.
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(100.0, -1.75, 0.0)),
        vehicles=(
            morai.npc(morai.at_pose(200.0, -1.75, 0.0), 7, kmh=20.0, active_distance=40.0),
            morai.npc(morai.at_pose(400.0, -1.75, 0.0), 8, kmh=20.0, active_distance=40.0),
        ),
    )
    world = World(build_builtin_map("straight"), read_morai_scenario(morai.text(document)).scenario)
    start = world.npcs.pose[:, 0].copy()
    world.show_recorded(RecordedScene(npcs=ObjectTable.empty()))
    ego = world.egos[0].vehicle
    # The ego drives through the first one's place (hidden: no contact) and beyond reach.
    while world.ego_status().pose.x < 250.0:
        ego.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=10.0))
        world.step(0.02)
        assert world.sim_time < 30.0, "the ego should have driven 150 m"
    run(world, 4.0, ego_speed_mps=0.0)
    assert 200.0 + 40.0 < world.ego_status().pose.x < 400.0 - 40.0
    assert world.ego_collision_log == []
    assert world.npcs.pose[:, 0].tolist() == start.tolist()  # frozen under the replay
    world.show_recorded(RecordedScene())
    run(world, 2.0)
    moved = world.npcs.pose[:, 0] - start
    assert moved[0] > 1.0 and world.npcs.speed[0] > 0.0
    assert moved[1] == 0.0 and world.npcs.speed[1] == 0.0


# -- contacts with recorded agents -----------------------------------------------------


def test_the_ego_bounces_off_a_recorded_car_that_stays_where_the_recording_puts_it() -> None:
    world = world_from(
        {"map": "straight", "ego": {"start": {"lane": "R1_E_1", "s": 20.0}, "speed_mps": 10.0}}
    )
    parked: Recorded = (90, "2016_Hyundai_Ioniq", (60.0, -1.75), 0.0, 0.0)
    car = recorded_table(ObjectType.NPC_VEHICLE, [parked])
    world.show_recorded(RecordedScene(npcs=car))
    ego = world.egos[0].vehicle
    ego.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=10.0))
    bounced = None
    for _ in range(round(10.0 / world.physics_step_s)):
        world.step()
        if world.ego_collision_log and bounced is None:
            bounced = world.ego_status().velocity[0]
            ego.command(ControlCommand(brake=1.0))
    assert [(r.ego_id, r.other.unique_id) for r in world.ego_collision_log] == [
        (world.egos[0].unique_id, 90)
    ]
    assert bounced is not None and bounced < 0.0  # an immovable body: the ego comes back
    shown = world.shown_tables()[0]
    assert shown.positions[0].tolist() == [60.0, -1.75, 0.0]
    assert shown.velocities[0].tolist() == [0.0, 0.0, 0.0]


# -- determinism -------------------------------------------------------------------------

REPLAY_S = 5.0


def replay_frame(t: float) -> RecordedScene:
    """What a recording shows t s into the replay of `replayed_town`: the ego and a
    pedestrian standing in an NPC's lane, then NPC vehicles and obstacles (a parked car
    the simulated ego runs into), then nothing (full simulation again)."""
    if t < 2.0:
        pose = Pose(x=-46.0 + 6.0 * t, y=-91.75)
        walkers = [
            (501, "Man", (-30.0, -95.25), 0.0, 0.0),
            (502, "Woman", (-20.0 + 0.5 * t, -85.0 - 1.2 * t), -1.2, 1.3),
        ]
        return RecordedScene(
            ego=RecordedEgo(pose, 6.0, 0.0, 0.0, (0.2, 0.0, 0.0), 0.3, 0.0),
            pedestrians=recorded_table(ObjectType.PEDESTRIAN, walkers),
        )
    if t < 4.0:
        cars = [(601, "2016_Hyundai_Ioniq", (-20.0, -91.75), 0.0, 0.0)]
        cones = [(602, "Cone", (-10.0, -95.25), 0.0, 0.0)]
        return RecordedScene(
            npcs=recorded_table(ObjectType.NPC_VEHICLE, cars),
            obstacles=recorded_table(ObjectType.OBSTACLE, cones),
        )
    return RecordedScene()


@dataclass(frozen=True)
class Replayed:
    tables: list[ObjectTable]
    """The object table every SAMPLE_EVERY steps."""
    ego_collisions: list[EgoCollision]


def replayed_town() -> Replayed:
    """The town's default scenario, its ego under a velocity command, while replay_frame
    plays."""
    world = World(build_builtin_map("town"), load_default_scenario())
    tables = []
    for k in range(round(REPLAY_S / world.physics_step_s)):
        world.show_recorded(replay_frame(k * world.physics_step_s))
        world.egos[0].vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=8.0))
        world.step()
        if k % SAMPLE_EVERY == 0:
            tables.append(world.objects())
    return Replayed(tables, world.ego_collision_log)


@pytest.fixture(scope="module")
def replay() -> Replayed:
    return replayed_town()


def test_the_simulated_ego_runs_into_the_recorded_car_and_only_into_it(replay: Replayed) -> None:
    assert [(round(r.time_s, 2), r.other.unique_id) for r in replay.ego_collisions] == [(3.21, 601)]
    shown = {int(i) for table in replay.tables for i in table.unique_ids}
    assert {501, 502, 601, 602} <= shown


def test_a_replay_gives_bit_identical_object_tables_run_after_run(replay: Replayed) -> None:
    again = replayed_town().tables
    assert len(again) == len(replay.tables)
    for k, (first, second) in enumerate(zip(replay.tables, again, strict=True)):
        for column in COLUMNS:
            assert np.array_equal(getattr(first, column), getattr(second, column)), (k, column)


def test_a_replay_shows_the_object_tables_the_world_showed_before_populations(
    replay: Replayed,
) -> None:
    """REFERENCE was written by the world before its agents became populations (commit
    e94b598) running replayed_town, with write_reference."""
    reference = np.load(REFERENCE)
    assert reference["rows"].tolist() == rows_of(replay.tables)
    for column in COLUMNS:
        shown = np.concatenate([getattr(t, column) for t in replay.tables])
        # Equal bit for bit on the machine that wrote it; another CPU's maths library
        # may round a last digit differently.
        np.testing.assert_allclose(shown, reference[column], rtol=0.0, atol=1e-9, err_msg=column)


def rows_of(tables: list[ObjectTable]) -> list[int]:
    """Where each sampled table starts in the concatenated columns, and the end."""
    return list(itertools.accumulate((len(t) for t in tables), initial=0))


def write_reference(path: Path) -> None:
    """REFERENCE from this world: `python -c "from tests.world.test_world_replay import
    REFERENCE, write_reference; write_reference(REFERENCE)"` in the worktree."""
    tables = replayed_town().tables
    columns = {c: np.concatenate([getattr(t, c) for t in tables]) for c in COLUMNS}
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(path, rows=np.array(rows_of(tables)), **columns)
