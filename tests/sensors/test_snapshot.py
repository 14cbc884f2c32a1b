"""SaveSensorData snapshot of GPS and IMU."""

from __future__ import annotations

import json

import numpy as np

from egosim.sensors import EgoKinematics, GpsModel, ImuModel, Pose, gps_imu_snapshot
from egosim.world.map.georef import GeoReference


def test_snapshot_survives_json_round_trip() -> None:
    georef = GeoReference(52, True, 302459.942, 4122635.537, 0.0)
    fix = GpsModel(georef).measure(Pose(x=1.0, y=2.0))
    reading = ImuModel().measure(EgoKinematics(yaw=0.5))
    snapshot = gps_imu_snapshot(12.5, fix, reading)
    restored = json.loads(json.dumps(snapshot))
    assert restored == snapshot
    assert restored["gps"]["latitude"] == fix.latitude
    assert restored["gps"]["eastOffset"] == georef.origin_east
    assert restored["imu"]["linear_acceleration"]["z"] == reading.linear_acceleration[2]
    np.testing.assert_allclose(
        [restored["imu"]["orientation"][k] for k in "xyzw"], reading.orientation
    )
