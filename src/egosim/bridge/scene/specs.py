"""MapSpec and VehicleSpec: the static descriptions a client asks for once."""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

import numpy as np

from ...world import World
from ...world.map.georef import GeoReference
from ...world.traffic import ObjectType
from ...world.vehicle import VEHICLE_CATALOGUE, GroundVehicleModel, VehicleModel
from ..context import BridgeContext
from ..protocol.messages import vector3
from ..protocol.table import Row
from ..protocol.units import deg

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1
    from ..protocol.releases import CanonicalProfile

log = logging.getLogger(__name__)

# MapSpec.plane_coordinate_system.
UTM_PLANE_COORDINATE_SYSTEM = 0
TM_PLANE_COORDINATE_SYSTEM = 1


def map_spec(profile: CanonicalProfile, georef: GeoReference) -> morai_26_r1.MapSpec:
    """morai_msgs/MapSpec: the projection and local origin of the loaded map; a map drawn
    in a grid other than UTM (such as Korea's EPSG:5186) is a TM one."""
    return profile.message("morai_msgs/MapSpec").new(
        plane_coordinate_system=UTM_PLANE_COORDINATE_SYSTEM
        if georef.projection is None
        else TM_PLANE_COORDINATE_SYSTEM,
        utm_num=georef.utm_zone,
        utm_offset=vector3(profile, (georef.origin_east, georef.origin_north, georef.origin_up)),
        ellipse=georef.ellipsoid,
        central_latitude=georef.central_latitude_deg,
        central_meridian=georef.central_meridian_deg,
        scale_factor=georef.scale_factor,
        false_easting=georef.false_easting,
        false_northing=georef.false_northing,
    )


def vehicle_spec(
    profile: CanonicalProfile, model: VehicleModel | GroundVehicleModel | None
) -> morai_26_r1.VehicleSpec:
    """morai_msgs/VehicleSpec of a model; all zeros for none (an unknown unique_id)."""
    spec = profile.message("morai_msgs/VehicleSpec")
    if model is None:
        return spec.new()
    return spec.new(
        size=vector3(profile, (model.length, model.width, model.height)),
        wheel_base=model.wheelbase,
        max_steering=deg(model.max_steer_front),
        overhang=model.front_overhang,
        rear_overhang=model.rear_overhang,
    )


def serve_map_spec(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiMapSpecSrvRequest
) -> morai_26_r1.MoraiMapSpecSrvResponse:
    """/Service_MoraiMapSpec: the loaded map's georeference."""
    return context.profile.message("morai_msgs/MoraiMapSpecSrvResponse").new(
        response=map_spec(context.profile, context.world.map.georef)
    )


def serve_vehicle_spec(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiVehicleSpecSrvRequest
) -> morai_26_r1.MoraiVehicleSpecSrvResponse:
    """/Service_MoraiVehicleSpec: any vehicle by unique_id; all zeros for an unknown id."""
    unique_id = int(request.request.unique_id)
    model = vehicle_model_of(context.world, unique_id)
    if model is None:
        log.warning("%s: no vehicle with unique_id %d", row.name, unique_id)
    return context.profile.message("morai_msgs/MoraiVehicleSpecSrvResponse").new(
        response=vehicle_spec(context.profile, model)
    )


def vehicle_model_of(world: World, unique_id: int) -> VehicleModel | GroundVehicleModel | None:
    """The catalogue model of the vehicle `unique_id` in the scene: an ego, or an NPC as
    shown (simulated, ghost or replayed); None for anything else or a model the catalogue
    does not hold."""
    for ego in world.egos:
        if ego.unique_id == unique_id:
            return ego.vehicle.model
    shown = world.objects()
    npcs = np.flatnonzero(
        (shown.unique_ids == unique_id) & (shown.object_types == ObjectType.NPC_VEHICLE)
    )
    return VEHICLE_CATALOGUE.get(shown.names[int(npcs[0])]) if len(npcs) else None
