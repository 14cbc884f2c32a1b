"""Where the built-in maps sit on Earth, and maps that name no place of their own."""

import dataclasses

from egosim.world.map.georef import GeoReference

# A local origin in Seoul, Korea (about 37.58 N, 126.89 E), UTM zone 52N, at sea level.
BUILTIN_GEOREF = GeoReference(
    utm_zone=52, northern=True, origin_east=313_000.0, origin_north=4_161_000.0, origin_up=0.0
)


def assumed_georeference() -> GeoReference:
    """The georeference of a map that names none: the built-in maps' UTM zone 52N origin,
    marked assumed. UTM 52N, as MORAI's Korean maps, keeps what MORAI stacks rely on:
    MapSpec names a UTM zone and offset, and UTM(GPS latitude, longitude) minus that offset
    is the map position; only the place on Earth is invented."""
    return dataclasses.replace(BUILTIN_GEOREF, assumed=True)
