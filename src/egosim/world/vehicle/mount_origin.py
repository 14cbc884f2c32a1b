"""Where MORAI SIM measures sensor mounts from, in a vehicle's base_link.

MORAI's vehicle coordinate system (its manual, "Vehicle coordinate system") has its
origin at the midpoint of the rear axle, x forward, y left, z up; a sensor's mount
x, y, z and roll, pitch, yaw are given in it. That origin sits at the height of the
wheels' centres, which is why code written for MORAI adds the wheel radius to a mount's
z to get the sensor's height above the road.

egosim's base_link is the reference point of the vehicle's pose: for a car, MORAI's
origin itself, the midpoint of the rear axle, on the road; for a skid-steer ground
vehicle, the middle of its axles on the ground. The origin below is the rear-axle point,
at wheel-centre height, in base_link: the one place to change if the pose's reference
point moves.
"""

from __future__ import annotations

from egosim.world.vehicle.catalogue import VehicleModel
from egosim.world.vehicle.ego_kinds import EgoModel


def sensor_mount_origin(model: EgoModel) -> tuple[float, float, float]:
    """MORAI's sensor mount origin in base_link (x forward, y left, z up), m."""
    # A car's base_link is the rear axle's midpoint already; a skid-steer's is midway.
    rear_axle_x = 0.0 if isinstance(model, VehicleModel) else -model.wheelbase / 2.0
    return (rear_axle_x, 0.0, model.wheel_radius)
