import pytest
from pyproj import CRS, Transformer
from tests.world.map.mgeo.sample_mgeo import ORIGIN, mgeo_files

from egosim.sensors import GpsModel
from egosim.sensors.frames import Pose
from egosim.world.map.mgeo import build_mgeo_map, read_georeference

KOREA_CENTRAL_BELT = (
    "+proj=tmerc +lat_0=38 +lon_0=127 +k=1 +x_0=200000 +y_0=600000 +ellps=GRS80 +units=m +no_defs"
)


def expected_fix(crs: CRS, origin: tuple[float, float, float], x: float, y: float, z: float):
    to_geodetic = Transformer.from_crs(crs, crs.geodetic_crs, always_xy=True)
    lon, lat = to_geodetic.transform(origin[0] + x, origin[1] + y)
    return lat, lon, origin[2] + z


@pytest.mark.parametrize(("x", "y", "z"), [(0.0, 0.0, 0.0), (1.75, -60.0, 0.5), (80.0, 160.0, 2)])
def test_gps_on_a_utm_map_gives_the_projection_lat_lon(x, y, z):
    lane_map = build_mgeo_map("sample", mgeo_files(), [])
    fix = GpsModel(lane_map.georef).measure(Pose(x=x, y=y, z=z))
    lat, lon, alt = expected_fix(CRS.from_epsg(32652), ORIGIN, x, y, z)
    assert (fix.latitude, fix.longitude) == pytest.approx((lat, lon), abs=1e-9)
    assert fix.altitude == pytest.approx(alt)
    assert (fix.east_offset, fix.north_offset) == (ORIGIN[0], ORIGIN[1])


def test_utm_zone_name_sets_mapspec_fields():
    georef = read_georeference(mgeo_files()["global_info.json"])
    assert (georef.utm_zone, georef.northern) == (52, True)
    assert georef.central_meridian_deg == 129.0
    assert georef.scale_factor == 0.9996


def test_gps_on_a_transverse_mercator_map_gives_the_projection_lat_lon():
    origin = (210_000.0, 550_000.0, 20.0)
    files = mgeo_files()
    files["global_info.json"] = {
        "global_coordinate_system": KOREA_CENTRAL_BELT,
        "local_origin_in_global": list(origin),
    }
    lane_map = build_mgeo_map("sample", files, [])
    fix = GpsModel(lane_map.georef).measure(Pose(x=30.0, y=-40.0, z=1.0))
    lat, lon, alt = expected_fix(CRS.from_proj4(KOREA_CENTRAL_BELT), origin, 30.0, -40.0, 1.0)
    assert (fix.latitude, fix.longitude) == pytest.approx((lat, lon), abs=1e-9)
    assert fix.altitude == pytest.approx(alt)
    georef = lane_map.georef
    assert (georef.central_meridian_deg, georef.central_latitude_deg) == (127.0, 38.0)
    assert (georef.scale_factor, georef.false_easting, georef.false_northing) == (
        1.0,
        200_000.0,
        600_000.0,
    )
    # The UTM zone MapSpec reports is the one holding the origin (127° E: zone 52).
    assert georef.utm_zone == 52
