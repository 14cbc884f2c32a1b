"""GPS fixes against an independent UTM projection (pyproj)."""

from __future__ import annotations

import numpy as np
import pytest
from pyproj import Transformer

from egosim.sensors import GPS_STATUS_FIX, GpsModel, GpsNoise, MountPose, Pose
from egosim.sensors.errors import MissingRandomGeneratorError, SensorConfigError
from egosim.world.map.georef import GeoReference

UTM_52N = "EPSG:32652"
GEOREF = GeoReference(
    utm_zone=52, northern=True, origin_east=302459.942, origin_north=4122635.537, origin_up=28.0
)
TO_UTM = Transformer.from_crs("EPSG:4326", UTM_52N, always_xy=True)


def utm_minus_offset(fix) -> tuple[float, float]:
    east, north = TO_UTM.transform(fix.longitude, fix.latitude)
    return east - fix.east_offset, north - fix.north_offset


def test_utm_of_fix_minus_offsets_is_antenna_position() -> None:
    model = GpsModel(GEOREF, mount=MountPose(x=1.0, y=0.5, z=1.5))
    fix = model.measure(Pose(x=120.0, y=-340.0, z=2.0, yaw=np.pi / 2))
    # Facing north: the mount's forward offset goes north, its left offset west.
    east, north = utm_minus_offset(fix)
    assert east == pytest.approx(120.0 - 0.5, abs=0.01)
    assert north == pytest.approx(-340.0 + 1.0, abs=0.01)
    assert fix.altitude == pytest.approx(28.0 + 2.0 + 1.5, abs=1e-9)
    assert (fix.east_offset, fix.north_offset) == (GEOREF.origin_east, GEOREF.origin_north)
    assert fix.status == GPS_STATUS_FIX


def test_origin_on_central_meridian_has_its_longitude() -> None:
    georef = GeoReference(
        utm_zone=52, northern=True, origin_east=500000.0, origin_north=4_000_000.0, origin_up=0.0
    )
    fix = GpsModel(georef).measure(Pose())
    assert fix.longitude == pytest.approx(129.0, abs=1e-9)
    # Northing 4000 km is about 36.1 deg north on WGS84.
    assert 36.0 < fix.latitude < 36.2


def test_noise_has_configured_spread_and_no_bias() -> None:
    model = GpsModel(GEOREF, noise=GpsNoise(horizontal_std_m=1.0, vertical_std_m=2.0))
    rng = np.random.default_rng(7)
    fixes = [model.measure(Pose(), rng) for _ in range(4000)]
    errors = np.array([(*utm_minus_offset(fix), fix.altitude - 28.0) for fix in fixes])
    np.testing.assert_allclose(errors.mean(axis=0), 0.0, atol=0.1)
    np.testing.assert_allclose(errors.std(axis=0), (1.0, 1.0, 2.0), rtol=0.05)
    assert abs(np.corrcoef(errors[:, 0], errors[:, 1])[0, 1]) < 0.05


def test_same_seed_gives_same_fixes() -> None:
    model = GpsModel(GEOREF, noise=GpsNoise(horizontal_std_m=0.5))
    first = [model.measure(Pose(), np.random.default_rng(3)) for _ in range(2)]
    again = [model.measure(Pose(), np.random.default_rng(3)) for _ in range(2)]
    assert first == again


def test_noisy_gps_needs_a_generator() -> None:
    with pytest.raises(MissingRandomGeneratorError):
        GpsModel(GEOREF, noise=GpsNoise(horizontal_std_m=0.5)).measure(Pose())


def test_negative_noise_is_refused() -> None:
    with pytest.raises(SensorConfigError):
        GpsNoise(vertical_std_m=-1.0)
