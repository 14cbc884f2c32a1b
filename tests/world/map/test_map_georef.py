import numpy as np
import pytest
from pyproj import Transformer

from egosim.world.map.builtin_origin import BUILTIN_GEOREF, assumed_georeference
from egosim.world.map.georef import GeoReference

KOREA = GeoReference(
    utm_zone=52, northern=True, origin_east=313_000.0, origin_north=4_161_000.0, origin_up=0.0
)


def test_origin_on_central_meridian_lies_at_129_east() -> None:
    ref = GeoReference(52, True, origin_east=500_000.0, origin_north=4_161_000.0, origin_up=12.0)
    lat, lon, alt = ref.local_to_geodetic(0.0, 0.0, 0.0)
    assert lon == pytest.approx(129.0, abs=1e-9)
    assert ref.central_meridian_deg == 129.0
    assert 37.0 < lat < 38.0
    assert alt == 12.0


def test_equator_northing_zero() -> None:
    ref = GeoReference(31, True, origin_east=500_000.0, origin_north=0.0, origin_up=0.0)
    lat, lon, _ = ref.local_to_geodetic(0.0, 0.0, 0.0)
    assert lat == pytest.approx(0.0, abs=1e-9)
    assert lon == pytest.approx(3.0, abs=1e-9)


def test_southern_false_northing() -> None:
    ref = GeoReference(56, False, origin_east=500_000.0, origin_north=10_000_000.0, origin_up=0.0)
    assert ref.false_northing == 10_000_000.0
    lat, lon, _ = ref.local_to_geodetic(0.0, -100_000.0, 0.0)
    assert lat < 0.0
    assert lon == pytest.approx(153.0, abs=1e-9)


def test_round_trip_within_a_millimetre() -> None:
    rng = np.random.default_rng(3)
    xyz = rng.uniform(-5000.0, 5000.0, size=(3, 200))
    back = KOREA.geodetic_to_local(*KOREA.local_to_geodetic(*xyz))
    assert np.max(np.abs(np.asarray(back) - xyz)) < 1e-3


def test_scalar_round_trip_returns_floats() -> None:
    lat, lon, alt = KOREA.local_to_geodetic(120.5, -40.25, 3.0)
    x, y, z = KOREA.geodetic_to_local(lat, lon, alt)
    assert all(isinstance(v, float) for v in (lat, lon, alt, x, y, z))
    assert (x, y, z) == pytest.approx((120.5, -40.25, 3.0), abs=1e-3)


def test_one_km_north_is_about_one_km_of_latitude() -> None:
    lat0, _, _ = KOREA.local_to_geodetic(0.0, 0.0, 0.0)
    lat1, _, _ = KOREA.local_to_geodetic(0.0, 1000.0, 0.0)
    # a degree of latitude is ~111 km at 37.6°N; the UTM scale is within 0.1 % of 1
    assert (lat1 - lat0) * 111_000.0 == pytest.approx(1000.0, rel=5e-3)


def test_mapspec_constants() -> None:
    assert KOREA.scale_factor == 0.9996
    assert KOREA.false_easting == 500_000.0
    assert KOREA.false_northing == 0.0
    assert KOREA.ellipsoid == "WGS84"


def test_zone_out_of_range_rejected() -> None:
    with pytest.raises(ValueError):
        GeoReference(61, True, 0.0, 0.0, 0.0)


def test_an_assumed_georeference_keeps_what_morai_stacks_compute_from_gps() -> None:
    georef = assumed_georeference()
    assert georef.assumed and not BUILTIN_GEOREF.assumed
    # A MORAI stack projects GPS to UTM 52N and subtracts MapSpec's offset.
    to_utm = Transformer.from_crs("EPSG:4326", "EPSG:32652", always_xy=True)
    lat, lon, _ = georef.local_to_geodetic(120.0, -35.0, 0.0)
    east, north = to_utm.transform(lon, lat)
    assert (georef.utm_zone, georef.northern) == (52, True)
    assert (east - georef.origin_east, north - georef.origin_north) == pytest.approx(
        (120.0, -35.0), abs=1e-6
    )
