"""MapSpec and VehicleSpec: the static descriptions a client asks for once."""

from __future__ import annotations

from typing import Any

from ..msgs import Profile
from ..world.map.georef import GeoReference
from ..world.vehicle import VehicleModel
from .messages import vector3
from .units import deg

UTM_PLANE_COORDINATE_SYSTEM = 0  # MapSpec.plane_coordinate_system: 0 UTM, 1 TM


def map_spec(profile: Profile, georef: GeoReference) -> Any:
    """morai_msgs/MapSpec: the UTM projection and local origin of the loaded map."""
    return profile.message("morai_msgs/MapSpec").new(
        plane_coordinate_system=UTM_PLANE_COORDINATE_SYSTEM,
        utm_num=georef.utm_zone,
        utm_offset=vector3(profile, (georef.origin_east, georef.origin_north, georef.origin_up)),
        ellipse=georef.ellipsoid,
        central_latitude=georef.central_latitude_deg,
        central_meridian=georef.central_meridian_deg,
        scale_factor=georef.scale_factor,
        false_easting=georef.false_easting,
        false_northing=georef.false_northing,
    )


def vehicle_spec(profile: Profile, model: VehicleModel | None) -> Any:
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
