"""Georeference of a map's local ENU frame: local = UTM(zone) - origin."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TypeVar

import numpy as np
import numpy.typing as npt
from pyproj import CRS, Transformer

Coordinate = TypeVar("Coordinate", float, npt.NDArray[np.float64])

UTM_SCALE_FACTOR = 0.9996
UTM_FALSE_EASTING = 500_000.0
UTM_FALSE_NORTHING_SOUTH = 10_000_000.0


@dataclass(frozen=True)
class GeoReference:
    """Ties the map's local frame (x east, y north, z up, metres) to UTM.

    A local point (x, y, z) has UTM coordinates
    (origin_east + x, origin_north + y) and ellipsoidal height origin_up + z.
    """

    utm_zone: int
    northern: bool
    origin_east: float
    origin_north: float
    origin_up: float
    ellipsoid: str = "WGS84"

    def __post_init__(self) -> None:
        if not 1 <= self.utm_zone <= 60:
            raise ValueError(f"UTM zone must be in 1..60, got {self.utm_zone}")

    @property
    def central_meridian_deg(self) -> float:
        return -183.0 + 6.0 * self.utm_zone

    @property
    def central_latitude_deg(self) -> float:
        return 0.0

    @property
    def scale_factor(self) -> float:
        return UTM_SCALE_FACTOR

    @property
    def false_easting(self) -> float:
        return UTM_FALSE_EASTING

    @property
    def false_northing(self) -> float:
        return 0.0 if self.northern else UTM_FALSE_NORTHING_SOUTH

    @property
    def _to_geodetic(self) -> Transformer:
        return _utm_to_geodetic(self.utm_zone, self.northern, self.ellipsoid)

    def local_to_geodetic(
        self, x: Coordinate, y: Coordinate, z: Coordinate
    ) -> tuple[Coordinate, Coordinate, Coordinate]:
        """Local ENU metres -> (latitude deg, longitude deg, altitude m)."""
        lon, lat = self._to_geodetic.transform(
            np.add(x, self.origin_east), np.add(y, self.origin_north)
        )
        return _like_input(x, (lat, lon, np.add(z, self.origin_up)))

    def geodetic_to_local(
        self, lat_deg: Coordinate, lon_deg: Coordinate, alt_m: Coordinate
    ) -> tuple[Coordinate, Coordinate, Coordinate]:
        """(latitude deg, longitude deg, altitude m) -> local ENU metres."""
        east, north = self._to_geodetic.transform(lon_deg, lat_deg, direction="INVERSE")
        return _like_input(
            lat_deg,
            (
                np.subtract(east, self.origin_east),
                np.subtract(north, self.origin_north),
                np.subtract(alt_m, self.origin_up),
            ),
        )


def _like_input(sample: object, values: tuple) -> tuple:
    """Scalars in, Python floats out; arrays in, float64 arrays out."""
    if np.ndim(sample) == 0:
        return tuple(float(v) for v in values)
    return tuple(np.asarray(v, dtype=np.float64) for v in values)


@lru_cache(maxsize=16)
def _utm_to_geodetic(zone: int, northern: bool, ellipsoid: str) -> Transformer:
    utm = CRS.from_dict(
        {"proj": "utm", "zone": zone, "south": not northern, "ellps": ellipsoid, "units": "m"}
    )
    return Transformer.from_crs(utm, utm.geodetic_crs, always_xy=True)
