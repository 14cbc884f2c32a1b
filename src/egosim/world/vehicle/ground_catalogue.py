"""Skid-steer ground vehicle models: dimensions, drive limits and turning slip.

Every quantity is SI (m, kg, m/s, m/s², s). Where each number comes from is
listed in docs/vehicle.md ("Skid-steer ground vehicles").
"""

from __future__ import annotations

from dataclasses import dataclass

from egosim.world.vehicle.body import VehicleBody


@dataclass(frozen=True)
class GroundVehicleModel(VehicleBody):
    """A differential-drive (skid-steer) platform; the body origin is the middle of the axles."""

    wheel_count: int
    wheel_radius: float
    """m."""
    max_track_speed: float
    """Fastest ground speed of one side's wheels, m/s (also the top speed in a straight line)."""
    max_track_accel: float
    """Largest rate of change of one side's speed (motor torque and traction limit), m/s²."""
    motor_time_constant: float
    """Time constant of a side's speed following its motor command, s."""
    turn_efficiency: float
    """Yaw rate achieved over the slip-free differential-drive one, 0..1 (1: no skid)."""

    max_steer_front = 0.0
    """No steered wheels (VehicleSpec.max_steering reads it)."""
    max_steer_rear = 0.0

    @property
    def effective_track_width(self) -> float:
        """Track width a slip-free differential drive with the same turning would have, m."""
        return self.track_width / self.turn_efficiency

    @property
    def bounding_box_center_offset(self) -> float:
        """Centre of the bounding box ahead of the body origin along body x, m."""
        return (self.front_overhang - self.rear_overhang) / 2.0

    @property
    def box_centre_ahead_of_reference(self) -> float:
        """The same: a skid-steer's reference point is its body origin, m."""
        return self.bounding_box_center_offset


GROUND_VEHICLE_CATALOGUE: dict[str, GroundVehicleModel] = {
    model.name: model
    for model in (
        GroundVehicleModel(
            name="WeBOT_Indoor_Robot",
            length=0.508,
            width=0.430,
            height=0.250,
            wheelbase=0.262,
            front_overhang=0.123,
            rear_overhang=0.123,
            track_width=0.376,
            wheel_count=4,
            mass=17.0,
            wheel_radius=0.098,
            max_track_speed=1.5,
            max_track_accel=1.0,
            motor_time_constant=0.1,
            turn_efficiency=0.8,
        ),
        GroundVehicleModel(
            name="UGV_6W_Skid_Steer",
            length=2.000,
            width=1.400,
            height=1.000,
            wheelbase=1.500,
            front_overhang=0.250,
            rear_overhang=0.250,
            track_width=1.150,
            wheel_count=6,
            mass=450.0,
            wheel_radius=0.300,
            max_track_speed=5.0,
            max_track_accel=2.0,
            motor_time_constant=0.3,
            turn_efficiency=0.55,
        ),
    )
}
