"""The ego vehicle: catalogue models, single-track dynamics, pedals and control commands.

Public API:
    Vehicle, Pose, RoadSurface, VehicleStatus   create, command, step and read a vehicle
    ControlCommand, LongitudinalMode, CommandVerdict, CommandGate   CtrlCmd semantics
    Gear                                        P/R/N/D
    VehicleModel, VEHICLE_CATALOGUE, DEFAULT_EGO_MODEL, vehicle_model   the catalogue
    Wheels, WheelStatus                         per-wheel outputs
    VehicleError, UnknownVehicleModelError
"""

from egosim.world.vehicle.catalogue import (
    DEFAULT_EGO_MODEL,
    VEHICLE_CATALOGUE,
    VehicleModel,
    vehicle_model,
)
from egosim.world.vehicle.control import (
    DEFAULT_COMMAND_TIMEOUT,
    CommandGate,
    CommandVerdict,
    ControlCommand,
    LongitudinalMode,
)
from egosim.world.vehicle.errors import UnknownVehicleModelError, VehicleError
from egosim.world.vehicle.gear import Gear
from egosim.world.vehicle.vehicle import Pose, RoadSurface, Vehicle, VehicleStatus
from egosim.world.vehicle.wheels import Wheels, WheelStatus

__all__ = [
    "DEFAULT_COMMAND_TIMEOUT",
    "DEFAULT_EGO_MODEL",
    "VEHICLE_CATALOGUE",
    "CommandGate",
    "CommandVerdict",
    "ControlCommand",
    "Gear",
    "LongitudinalMode",
    "Pose",
    "RoadSurface",
    "UnknownVehicleModelError",
    "Vehicle",
    "VehicleError",
    "VehicleModel",
    "VehicleStatus",
    "WheelStatus",
    "Wheels",
    "vehicle_model",
]
