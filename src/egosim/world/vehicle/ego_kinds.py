"""The one place that decides what kind of vehicle an ego is: by its model's kind.

Road-vehicle models make a steered Vehicle; ground vehicle models make a
SkidSteerVehicle. Both offer command / set_gear / teleport / step / status.
"""

from __future__ import annotations

from egosim.world.vehicle.catalogue import VEHICLE_CATALOGUE, VehicleModel
from egosim.world.vehicle.errors import UnknownVehicleModelError
from egosim.world.vehicle.ground_catalogue import GROUND_VEHICLE_CATALOGUE, GroundVehicleModel
from egosim.world.vehicle.skid_steer import SkidSteerVehicle
from egosim.world.vehicle.vehicle import Pose, Vehicle

EgoModel = VehicleModel | GroundVehicleModel
EgoVehicle = Vehicle | SkidSteerVehicle

EGO_MODELS: dict[str, EgoModel] = {**VEHICLE_CATALOGUE, **GROUND_VEHICLE_CATALOGUE}
"""Every model an ego may be: the road vehicles and the ground vehicles."""


def ego_model(name: str) -> EgoModel:
    """The ego model called `name`; UnknownVehicleModelError names the known ones."""
    try:
        return EGO_MODELS[name]
    except KeyError:
        raise UnknownVehicleModelError(name, sorted(EGO_MODELS)) from None


def ego_vehicle(
    model: EgoModel, pose: Pose | None = None, command_timeout: float | None = None
) -> EgoVehicle:
    """A vehicle of `model`, of the kind the model is, with this dead-man timeout (s;
    None: the last command holds)."""
    if isinstance(model, GroundVehicleModel):
        return SkidSteerVehicle(model, pose, command_timeout=command_timeout)
    return Vehicle(model, pose, command_timeout=command_timeout)
