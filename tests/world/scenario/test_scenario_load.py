"""Every ScenarioLoad flag, as World.load_scenario applies it."""

import pytest

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import ScenarioError, ScenarioLoadOptions, parse_scenario

STRAIGHT = build_builtin_map("straight")

FIRST = parse_scenario(
    {
        "map": "straight",
        "ego": {"start": {"lane": "R1_E_1", "s": 10.0}},
        "npcs": [
            {"start": {"lane": "R1_E_1", "s": 100.0}},
            {"start": {"lane": "R1_E_2", "s": 100.0}},
        ],
        "pedestrians": [{"waypoints": [[0, 20], [50, 20]]}],
        "obstacles": [{"model": "Cone", "pose": {"x": 500, "y": 20}}],
    },
    "first.yaml",
)
SECOND = parse_scenario(
    {
        "map": "straight",
        "network": {"settings_file": "net.json"},
        "ego": {"model": "2019_Hyundai_Sonata", "start": {"x": 300.0, "y": -5.25}},
        "npcs": [{"start": {"lane": "R1_W_1", "s": 50.0}}],
        "pedestrians": [{"waypoints": [[0, 25], [50, 25]]}],
        "obstacles": [{"model": "Drum", "pose": {"x": 600, "y": 20}}],
    },
    "second.yaml",
)
NOTHING = ScenarioLoadOptions(
    delete_all=False,
    load_network_connection_data=False,
    load_ego_vehicle_data=False,
    load_surrounding_vehicle_data=False,
    load_pedestrian_data=False,
    load_object_data=False,
    set_pause=False,
)


def _world() -> World:
    return World(STRAIGHT, FIRST)


def _counts(world: World) -> tuple[int, int, int]:
    return len(world.npcs), len(world.pedestrians), len(world.obstacles)


def test_delete_all_removes_every_object_but_the_ego() -> None:
    world = _world()
    ego_id = world.egos[0].unique_id
    world.load_scenario(SECOND, ScenarioLoadOptions(delete_all=True, load_ego_vehicle_data=False))
    assert _counts(world) == (1, 1, 1)
    assert [e.unique_id for e in world.egos] == [ego_id]


def test_without_delete_all_loaded_objects_join_the_others() -> None:
    world = _world()
    world.load_scenario(SECOND, ScenarioLoadOptions(delete_all=False))
    assert _counts(world) == (3, 2, 2)
    ids = world.objects().unique_ids.tolist()
    assert len(ids) == len(set(ids)) == 1 + 3 + 2 + 2


def test_each_object_flag_loads_only_its_kind() -> None:
    for flag, expected in (
        ("load_surrounding_vehicle_data", (3, 1, 1)),
        ("load_pedestrian_data", (2, 2, 1)),
        ("load_object_data", (2, 1, 2)),
    ):
        world = _world()
        report = world.load_scenario(SECOND, NOTHING.__class__(**{**NOTHING.__dict__, flag: True}))
        assert _counts(world) == expected, flag
        spawned = (report.npcs_spawned, report.pedestrians_spawned, report.obstacles_spawned)
        assert spawned == tuple(e - b for e, b in zip(expected, (2, 1, 1), strict=True))


def test_ego_data_moves_the_ego_and_changes_its_model() -> None:
    world = _world()
    before = world.ego_status().pose
    world.load_scenario(SECOND, NOTHING)
    assert world.ego_status().pose == before
    report = world.load_scenario(
        SECOND, ScenarioLoadOptions(delete_all=False, load_ego_vehicle_data=True)
    )
    assert report.ego_placed
    pose = world.ego_status().pose
    assert (pose.x, pose.y) == (300.0, -5.25)
    assert world.egos[0].vehicle.model.name == "2019_Hyundai_Sonata"


def test_network_connection_data_is_reported_only_when_asked() -> None:
    world = _world()
    report = world.load_scenario(SECOND, NOTHING)
    assert report.network_settings is None and world.network_settings_request is None
    report = world.load_scenario(
        SECOND, ScenarioLoadOptions(delete_all=False, load_network_connection_data=True)
    )
    assert report.network_settings == {"settings_file": "net.json"}
    assert world.network_settings_request == {"settings_file": "net.json"}


def test_set_pause_freezes_time_and_agents_until_unpaused() -> None:
    world = _world()
    world.load_scenario(SECOND, ScenarioLoadOptions(set_pause=True))
    assert world.paused
    time_before, s_before = world.sim_time, world.npcs.s.copy()
    for _ in range(100):
        world.step()
    assert world.sim_time == time_before
    assert (world.npcs.s == s_before).all()
    world.paused = False
    for _ in range(100):
        world.step()
    assert world.sim_time == pytest.approx(time_before + 1.0)
    world.load_scenario(SECOND, ScenarioLoadOptions(set_pause=False))
    assert not world.paused


def test_a_failed_load_changes_nothing() -> None:
    world = _world()
    broken = parse_scenario(
        {"map": "straight", "npcs": [{"start": {"lane": "R1_E_1"}}, {"start": {"lane": "nope"}}]},
        "broken.yaml",
    )
    with pytest.raises(ScenarioError):
        world.load_scenario(broken)
    assert _counts(world) == (2, 1, 1)
