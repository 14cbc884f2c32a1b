"""Where the built-in maps sit on Earth."""

from egosim.world.map.georef import GeoReference

# A local origin in Seoul, Korea (about 37.58 N, 126.89 E), UTM zone 52N, at sea level.
BUILTIN_GEOREF = GeoReference(
    utm_zone=52, northern=True, origin_east=313_000.0, origin_north=4_161_000.0, origin_up=0.0
)
