"""The ego vehicle: catalogue models, single-track dynamics, pedals and control commands.

Public API:
    Vehicle, Pose, RoadSurface, VehicleStatus   create, command, step and read a vehicle
    Motion                                      a status's pose, velocity and acceleration
    ControlCommand, LongitudinalMode, CommandVerdict, CommandGate   CtrlCmd semantics
    Gear                                        P/R/N/D
    VehicleModel, VEHICLE_CATALOGUE, DEFAULT_EGO_MODEL, vehicle_model   the catalogue
    MORAI_VEHICLE_DATA_IDS, model_for_data_id   MORAI's vehicle DataIDs -> catalogue models
    Wheels, WheelStatus                         per-wheel outputs
    SkidSteerVehicle, SideEffortCommand, BodyVelocityCommand   skid-steer ground vehicles
    GroundVehicleModel, GROUND_VEHICLE_CATALOGUE              their catalogue
    EGO_MODELS, ego_model, ego_vehicle, EgoModel, EgoVehicle  an ego of its model's kind
    sensor_mount_origin                         MORAI's sensor mount origin in base_link
    VehicleError, UnknownVehicleModelError
"""

from egosim.world.vehicle.catalogue import (
    DEFAULT_EGO_MODEL,
    MORAI_VEHICLE_DATA_IDS,
    VEHICLE_CATALOGUE,
    VehicleModel,
    model_for_data_id,
    vehicle_model,
)
from egosim.world.vehicle.control import (
    DEFAULT_COMMAND_TIMEOUT,
    CommandGate,
    CommandVerdict,
    ControlCommand,
    LongitudinalMode,
)
from egosim.world.vehicle.ego_kinds import (
    EGO_MODELS,
    EgoModel,
    EgoVehicle,
    ego_model,
    ego_vehicle,
)
from egosim.world.vehicle.errors import UnknownVehicleModelError, VehicleError
from egosim.world.vehicle.gear import Gear
from egosim.world.vehicle.ground_catalogue import GROUND_VEHICLE_CATALOGUE, GroundVehicleModel
from egosim.world.vehicle.mount_origin import sensor_mount_origin
from egosim.world.vehicle.skid_steer import SkidSteerVehicle
from egosim.world.vehicle.skid_steer_commands import BodyVelocityCommand, SideEffortCommand
from egosim.world.vehicle.vehicle import Motion, Pose, RoadSurface, Vehicle, VehicleStatus
from egosim.world.vehicle.wheels import Wheels, WheelStatus

__all__ = [
    "DEFAULT_COMMAND_TIMEOUT",
    "DEFAULT_EGO_MODEL",
    "EGO_MODELS",
    "GROUND_VEHICLE_CATALOGUE",
    "MORAI_VEHICLE_DATA_IDS",
    "VEHICLE_CATALOGUE",
    "BodyVelocityCommand",
    "CommandGate",
    "CommandVerdict",
    "ControlCommand",
    "EgoModel",
    "EgoVehicle",
    "Gear",
    "GroundVehicleModel",
    "LongitudinalMode",
    "Motion",
    "Pose",
    "RoadSurface",
    "SideEffortCommand",
    "SkidSteerVehicle",
    "UnknownVehicleModelError",
    "Vehicle",
    "VehicleError",
    "VehicleModel",
    "VehicleStatus",
    "WheelStatus",
    "Wheels",
    "ego_model",
    "ego_vehicle",
    "model_for_data_id",
    "sensor_mount_origin",
    "vehicle_model",
]
