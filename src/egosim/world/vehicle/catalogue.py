"""Vehicle models: dimensions, mass properties, tyres, powertrain and brakes.

Every quantity is SI (m, kg, kg·m², N/rad, rad, rad/s, N·m, W, m/s², m²). Where
each number comes from (published specification or engineering estimate) is
listed in docs/vehicle.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from egosim.world.vehicle.body import VehicleBody
from egosim.world.vehicle.errors import UnknownVehicleModelError

GRAVITY = 9.80665
"""Standard gravity, m/s²."""


@dataclass(frozen=True)
class VehicleModel(VehicleBody):
    """A car's physical description; the centre of gravity (CG) is the body origin."""

    yaw_inertia: float
    """Moment of inertia about the vertical axis through the CG, kg·m²."""
    cg_to_front_axle: float
    """a: CG to front axle, m."""
    cg_to_rear_axle: float
    """b: CG to rear axle, m (a + b = wheelbase)."""
    cg_height: float
    """CG height above the road, m."""
    cornering_stiffness_front: float
    """Front axle (both wheels) lateral force per slip angle, N/rad."""
    cornering_stiffness_rear: float
    """Rear axle (both wheels) lateral force per slip angle, N/rad."""
    max_steer_front: float
    """Largest front road-wheel angle, rad."""
    max_steer_rear: float
    """Largest rear road-wheel angle, rad; 0 when the rear wheels do not steer."""
    max_steer_rate: float
    """Fastest road-wheel angle change of the steering actuator, rad/s."""
    max_drive_torque: float
    """Largest total drive torque at the wheels, N·m."""
    max_power: float
    """Largest drive power at the wheels, W."""
    max_brake_decel: float
    """Deceleration full brake achieves on a dry level road, m/s²."""
    drag_area: float
    """Drag coefficient times frontal area (Cd·A), m²."""
    rolling_resistance_coeff: float
    """Rolling resistance force per normal force, dimensionless."""
    wheel_radius: float
    """Loaded tyre radius, m."""
    max_reverse_speed: float
    """Speed the powertrain stops pushing at in reverse, m/s."""
    max_speed: float = math.inf
    """Speed the powertrain stops pushing at going forwards (a governed top speed), m/s;
    inf: none, power and drag alone set the top speed."""

    @property
    def max_drive_force(self) -> float:
        """Largest tractive force the drive torque gives at the tyre contact, N."""
        return self.max_drive_torque / self.wheel_radius

    @property
    def max_brake_force(self) -> float:
        """Braking force of a fully pressed pedal, N."""
        return self.mass * self.max_brake_decel

    @property
    def bounding_box_center_offset(self) -> float:
        """Centre of the bounding box ahead of the CG along body x, m (negative: behind)."""
        return self.length / 2.0 - self.rear_overhang - self.cg_to_rear_axle

    @property
    def box_centre_ahead_of_reference(self) -> float:
        """Centre of the bounding box ahead of the reference point (MORAI's vehicle origin,
        the midpoint of the rear axle) along body x, m."""
        return self.length / 2.0 - self.rear_overhang


def _estimated_model(
    *,
    name: str,
    length: float,
    width: float,
    height: float,
    wheelbase: float,
    front_overhang: float,
    track_width: float,
    mass: float,
    front_axle_load_fraction: float,
    cg_height: float,
    max_drive_torque: float,
    max_power: float,
    max_brake_decel: float,
    drag_area: float,
    rolling_resistance_coeff: float,
    wheel_radius: float,
    max_reverse_speed: float,
    min_turning_radius: float | None = None,
    max_steer_front: float | None = None,
    max_speed: float = math.inf,
    cornering_coeff_front: float = 8.0,
    cornering_coeff_rear: float = 12.0,
    max_steer_rate: float = 0.6,
    yaw_dynamic_index: float = 1.0,
) -> VehicleModel:
    """A model whose unpublished quantities follow from the published ones.

    The CG position follows from the static axle loads (the front axle carries
    b/L of the weight). Yaw inertia is k·m·a·b with the yaw dynamic index k,
    close to 1 for passenger cars and larger for vehicles with long overhangs.
    Axle cornering stiffness is a cornering coefficient (N/rad per N of axle
    load) times the static axle load; a higher rear coefficient gives the mild
    understeer production cars are tuned for.
    The largest front wheel angle is the published one (`max_steer_front`), else the
    one that puts the outer front wheel on the published kerb-to-kerb turning circle.
    """
    if max_steer_front is None:
        if min_turning_radius is None:
            raise ValueError(f"{name}: give max_steer_front or min_turning_radius")
        max_steer_front = math.atan(wheelbase / (min_turning_radius - track_width / 2.0))
    cg_to_rear_axle = front_axle_load_fraction * wheelbase
    cg_to_front_axle = wheelbase - cg_to_rear_axle
    weight = mass * GRAVITY
    return VehicleModel(
        name=name,
        length=length,
        width=width,
        height=height,
        wheelbase=wheelbase,
        front_overhang=front_overhang,
        rear_overhang=length - wheelbase - front_overhang,
        track_width=track_width,
        mass=mass,
        yaw_inertia=yaw_dynamic_index * mass * cg_to_front_axle * cg_to_rear_axle,
        cg_to_front_axle=cg_to_front_axle,
        cg_to_rear_axle=cg_to_rear_axle,
        cg_height=cg_height,
        cornering_stiffness_front=cornering_coeff_front * weight * front_axle_load_fraction,
        cornering_stiffness_rear=cornering_coeff_rear * weight * (1.0 - front_axle_load_fraction),
        max_steer_front=max_steer_front,
        max_steer_rear=0.0,
        max_steer_rate=max_steer_rate,
        max_drive_torque=max_drive_torque,
        max_power=max_power,
        max_brake_decel=max_brake_decel,
        drag_area=drag_area,
        rolling_resistance_coeff=rolling_resistance_coeff,
        wheel_radius=wheel_radius,
        max_reverse_speed=max_reverse_speed,
        max_speed=max_speed,
    )


DEFAULT_EGO_MODEL = "2016_Kia_Niro(HEV)"

_REVERSE_SPEED_LIMIT_CAR = 20.0 / 3.6

VEHICLE_CATALOGUE: dict[str, VehicleModel] = {
    model.name: model
    for model in (
        _estimated_model(
            name="2016_Kia_Niro(HEV)",
            length=4.355,
            width=1.805,
            height=1.535,
            wheelbase=2.700,
            front_overhang=0.870,
            track_width=1.555,
            mass=1500.0,
            front_axle_load_fraction=0.60,
            cg_height=0.55,
            min_turning_radius=5.3,
            max_drive_torque=1700.0,
            max_power=90e3,
            max_brake_decel=9.0,
            drag_area=0.29 * 2.33,
            rolling_resistance_coeff=0.009,
            wheel_radius=0.326,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
        ),
        _estimated_model(
            name="2016_Hyundai_Ioniq",
            length=4.470,
            width=1.820,
            height=1.450,
            wheelbase=2.700,
            front_overhang=0.880,
            track_width=1.555,
            mass=1400.0,
            front_axle_load_fraction=0.60,
            cg_height=0.52,
            min_turning_radius=5.3,
            max_drive_torque=1700.0,
            max_power=90e3,
            max_brake_decel=9.0,
            drag_area=0.24 * 2.25,
            rolling_resistance_coeff=0.008,
            wheel_radius=0.316,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
        ),
        _estimated_model(
            name="2015_Kia_K5",
            length=4.855,
            width=1.860,
            height=1.465,
            wheelbase=2.805,
            front_overhang=0.965,
            track_width=1.600,
            mass=1500.0,
            front_axle_load_fraction=0.61,
            cg_height=0.53,
            min_turning_radius=5.45,
            max_drive_torque=1800.0,
            max_power=110e3,
            max_brake_decel=9.0,
            drag_area=0.27 * 2.30,
            rolling_resistance_coeff=0.010,
            wheel_radius=0.334,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
        ),
        _estimated_model(
            name="2014_Kia_K7",
            length=4.970,
            width=1.850,
            height=1.475,
            wheelbase=2.845,
            front_overhang=0.980,
            track_width=1.600,
            mass=1650.0,
            front_axle_load_fraction=0.61,
            cg_height=0.54,
            min_turning_radius=5.6,
            max_drive_torque=2000.0,
            max_power=160e3,
            max_brake_decel=9.0,
            drag_area=0.28 * 2.35,
            rolling_resistance_coeff=0.010,
            wheel_radius=0.338,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
        ),
        _estimated_model(
            name="2017_Hyundai_Grandeur",
            length=4.930,
            width=1.865,
            height=1.470,
            wheelbase=2.845,
            front_overhang=0.970,
            track_width=1.600,
            mass=1600.0,
            front_axle_load_fraction=0.61,
            cg_height=0.54,
            min_turning_radius=5.6,
            max_drive_torque=2000.0,
            max_power=150e3,
            max_brake_decel=9.0,
            drag_area=0.28 * 2.35,
            rolling_resistance_coeff=0.010,
            wheel_radius=0.338,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
        ),
        _estimated_model(
            name="2019_Hyundai_Sonata",
            length=4.900,
            width=1.860,
            height=1.445,
            wheelbase=2.840,
            front_overhang=0.950,
            track_width=1.610,
            mass=1470.0,
            front_axle_load_fraction=0.60,
            cg_height=0.52,
            min_turning_radius=5.5,
            max_drive_torque=1800.0,
            max_power=105e3,
            max_brake_decel=9.0,
            drag_area=0.27 * 2.28,
            rolling_resistance_coeff=0.010,
            wheel_radius=0.334,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
        ),
        _estimated_model(
            name="2019_Hyundai_Universe",
            length=12.000,
            width=2.495,
            height=3.350,
            wheelbase=6.120,
            front_overhang=2.400,
            track_width=2.040,
            mass=13000.0,
            front_axle_load_fraction=0.33,
            cg_height=1.30,
            min_turning_radius=11.0,
            max_drive_torque=10000.0,
            max_power=260e3,
            max_brake_decel=6.5,
            drag_area=0.65 * 7.5,
            rolling_resistance_coeff=0.007,
            wheel_radius=0.510,
            max_reverse_speed=10.0 / 3.6,
            cornering_coeff_front=6.0,
            cornering_coeff_rear=7.0,
            max_steer_rate=0.4,
            yaw_dynamic_index=1.5,
        ),
        _estimated_model(
            name="2023_Hyundai_Ioniq5",
            length=4.635,
            width=1.890,
            height=1.605,
            wheelbase=3.000,
            front_overhang=0.845,
            track_width=1.628,
            mass=1910.0,
            front_axle_load_fraction=0.51,
            cg_height=0.52,
            max_steer_front=math.radians(40.0),
            max_drive_torque=3000.0,
            max_power=150e3,
            max_brake_decel=9.0,
            drag_area=0.288 * 2.60,
            rolling_resistance_coeff=0.009,
            wheel_radius=0.360,
            max_reverse_speed=_REVERSE_SPEED_LIMIT_CAR,
            max_speed=185.0 / 3.6,
        ),
        _estimated_model(
            name="ERP42",
            length=2.020,
            width=1.160,
            height=0.860,
            wheelbase=1.040,
            front_overhang=0.490,
            track_width=0.985,
            mass=210.0,
            front_axle_load_fraction=0.50,
            cg_height=0.40,
            max_steer_front=math.radians(28.0),
            max_drive_torque=110.0,
            max_power=3.0e3,
            max_brake_decel=5.0,
            drag_area=0.80 * 1.00,
            rolling_resistance_coeff=0.015,
            wheel_radius=0.280,
            max_reverse_speed=10.0 / 3.6,
            max_speed=25.0 / 3.6,
        ),
    )
}


MORAI_VEHICLE_DATA_IDS: dict[int, str] = {
    20200003: "2016_Kia_Niro(HEV)",
    30100010: "2016_Hyundai_Ioniq",
    30200003: "2016_Kia_Niro(HEV)",
}
"""MORAI SIM's vehicle `DataID`s (what its scenario files and ego settings name a model
by) -> catalogue model names: 2xxxxxxx ego vehicles, 3xxxxxxx NPC vehicles. Only the ids
public MORAI material shows are here; docs/vehicle.md says where each comes from."""


def model_for_data_id(data_id: int) -> VehicleModel | None:
    """The catalogue model MORAI's vehicle `data_id` stands for; None for an id the table
    does not hold (the caller picks a default and says so)."""
    name = MORAI_VEHICLE_DATA_IDS.get(data_id)
    return None if name is None else VEHICLE_CATALOGUE[name]


def vehicle_model(name: str) -> VehicleModel:
    """The catalogue model called `name`; UnknownVehicleModelError names the known ones."""
    try:
        return VEHICLE_CATALOGUE[name]
    except KeyError:
        raise UnknownVehicleModelError(name, sorted(VEHICLE_CATALOGUE)) from None
