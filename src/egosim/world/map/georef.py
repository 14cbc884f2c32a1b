"""Georeference of a map's local ENU frame: local = UTM(zone) - origin (or another projection)."""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass
from functools import lru_cache
from typing import TypeAlias, TypeVar, overload

import numpy as np
from numpy.typing import ArrayLike
from pyproj import CRS, Transformer, get_ellps_map
from pyproj.exceptions import CRSError

from egosim.world.arrays import FloatArray

Coordinate = TypeVar("Coordinate", float, FloatArray)

UTM_SCALE_FACTOR = 0.9996
UTM_FALSE_EASTING = 500_000.0
UTM_FALSE_NORTHING_SOUTH = 10_000_000.0
_UTM_ZONE_NAME = re.compile(r"UTM\s*(\d{1,2})\s*([NS])", re.IGNORECASE)


@dataclass(frozen=True)
class GeoReference:
    """Ties the map's local frame (x east, y north, z up, metres) to UTM.

    A local point (x, y, z) has UTM coordinates
    (origin_east + x, origin_north + y) and ellipsoidal height origin_up + z.

    `projection` (a PROJ definition such as "+proj=tmerc ...") replaces UTM for maps drawn in
    another grid; origin_east / origin_north are then coordinates in that grid, `utm_zone`
    stays the UTM zone of the origin, and the MapSpec parameters come from the projection.
    """

    utm_zone: int
    northern: bool
    origin_east: float
    origin_north: float
    origin_up: float
    ellipsoid: str = "WGS84"
    projection: str | None = None
    assumed: bool = False
    """The map names no georeference: egosim placed it where the built-in maps are, so its
    latitudes and longitudes are invented (see `assumed_georeference`)."""

    def __post_init__(self) -> None:
        if not 1 <= self.utm_zone <= 60:
            raise ValueError(f"UTM zone must be in 1..60, got {self.utm_zone}")

    @classmethod
    def from_projection(cls, definition: str, origin: tuple[float, float, float]) -> GeoReference:
        """The georeference of a local frame whose origin sits at `origin` in a projection.

        `definition` is a UTM zone name ("UTM52N", "UTM 33S") or anything pyproj reads (a
        PROJ string, "EPSG:5186", WKT). UTM definitions give a plain UTM georeference;
        others keep the definition. Raises ValueError for a definition pyproj cannot read.
        """
        east, north, up = (float(v) for v in origin)
        zone_name = _UTM_ZONE_NAME.fullmatch(definition.strip())
        if zone_name:
            zone, hemisphere = zone_name.groups()
            return cls(int(zone), hemisphere.upper() == "N", east, north, up)
        try:
            crs = CRS.from_user_input(definition)
        except CRSError as error:
            raise ValueError(f"unknown projection {definition!r}") from error
        if crs.utm_zone is not None:
            zone, hemisphere = int(crs.utm_zone[:-1]), crs.utm_zone[-1]
            return cls(zone, hemisphere == "N", east, north, up, _ellipsoid_name(definition))
        lon, lat = _projection_to_geodetic(definition).transform(east, north)
        zone = int((lon + 180.0) // 6.0) % 60 + 1
        return cls(zone, lat >= 0.0, east, north, up, _ellipsoid_name(definition), definition)

    @property
    def central_meridian_deg(self) -> float:
        if self.projection is not None:
            return _projection_parameter(self.projection, "lon_0", 0.0)
        return -183.0 + 6.0 * self.utm_zone

    @property
    def central_latitude_deg(self) -> float:
        if self.projection is not None:
            return _projection_parameter(self.projection, "lat_0", 0.0)
        return 0.0

    @property
    def scale_factor(self) -> float:
        if self.projection is not None:
            return _projection_parameter(self.projection, "k_0", 1.0)
        return UTM_SCALE_FACTOR

    @property
    def false_easting(self) -> float:
        if self.projection is not None:
            return _projection_parameter(self.projection, "x_0", 0.0)
        return UTM_FALSE_EASTING

    @property
    def false_northing(self) -> float:
        if self.projection is not None:
            return _projection_parameter(self.projection, "y_0", 0.0)
        return 0.0 if self.northern else UTM_FALSE_NORTHING_SOUTH

    @property
    def _to_geodetic(self) -> Transformer:
        if self.projection is not None:
            return _projection_to_geodetic(self.projection)
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


@overload
def _like_input(
    sample: float, values: tuple[ArrayLike, ArrayLike, ArrayLike]
) -> tuple[float, float, float]: ...


@overload
def _like_input(
    sample: FloatArray, values: tuple[ArrayLike, ArrayLike, ArrayLike]
) -> tuple[FloatArray, FloatArray, FloatArray]: ...


def _like_input(
    sample: float | FloatArray, values: tuple[ArrayLike, ArrayLike, ArrayLike]
) -> tuple[float, float, float] | tuple[FloatArray, FloatArray, FloatArray]:
    """Scalars in, Python floats out; arrays in, float64 arrays out (`values` are pyproj's
    and numpy's results)."""
    first, second, third = (np.asarray(value, dtype=np.float64) for value in values)
    if np.ndim(sample) == 0:
        return float(first), float(second), float(third)
    return first, second, third


@lru_cache(maxsize=16)
def _utm_to_geodetic(zone: int, northern: bool, ellipsoid: str) -> Transformer:
    utm = CRS.from_dict(
        {"proj": "utm", "zone": zone, "south": not northern, "ellps": ellipsoid, "units": "m"}
    )
    return Transformer.from_crs(utm, utm.geodetic_crs, always_xy=True)


@lru_cache(maxsize=16)
def _projection_to_geodetic(projection: str) -> Transformer:
    crs = CRS.from_user_input(projection)
    return Transformer.from_crs(crs, crs.geodetic_crs, always_xy=True)


ProjValue: TypeAlias = str | int | float | bool | None
"""A value of a PROJ parameter (`+k_0=0.9996`; a bare `+no_defs` is None)."""


@lru_cache(maxsize=16)
def _projection_dict(projection: str) -> dict[str, ProjValue]:
    with warnings.catch_warnings():
        # to_dict goes through a PROJ string; its lossy-conversion warning is about datums.
        warnings.simplefilter("ignore", UserWarning)
        return CRS.from_user_input(projection).to_dict()


def _ellipsoid_name(projection: str) -> str:
    """The PROJ name of the projection's ellipsoid (as MapSpec and `+ellps` spell it)."""
    parameters = _projection_dict(projection)
    for name in (parameters.get("ellps"), parameters.get("datum")):
        if name in get_ellps_map():
            return str(name)
    return "WGS84"


def _projection_parameter(projection: str, name: str, default: float) -> float:
    parameters = _projection_dict(projection)
    # PROJ spells the scale factor k_0 or k.
    value = parameters.get(name, parameters.get("k") if name == "k_0" else None)
    return default if value is None else float(value)
