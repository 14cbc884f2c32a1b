"""A replayed ego reports what was recorded, including what placing it cannot reproduce."""

from __future__ import annotations

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.recorded_scene import RecordedEgo, RecordedScene
from egosim.world.vehicle import Pose


def test_replayed_ego_reports_recorded_acceleration_and_pedals() -> None:
    world = World(build_builtin_map("straight"))
    recorded = RecordedEgo(
        Pose(x=50.0, y=-1.75),
        speed=12.0,
        front_steer=0.02,
        rear_steer=0.0,
        acceleration=(1.5, 0.2, 0.0),
        accel_pedal=0.4,
        brake_pedal=0.0,
    )
    world.show_recorded(RecordedScene(ego=recorded))
    world.step()
    status = world.ego_status()
    assert (status.pose.x, status.velocity[0]) == (50.0, 12.0)
    assert status.acceleration == (1.5, 0.2, 0.0)
    assert (status.accel_pedal, status.brake_pedal) == (0.4, 0.0)

    # Back to simulation: the ego has had no command, so it sits on full brake.
    world.show_recorded(RecordedScene())
    world.step()
    simulated = world.ego_status()
    assert (simulated.accel_pedal, simulated.brake_pedal) == (0.0, 1.0)
