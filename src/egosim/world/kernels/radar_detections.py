"""The radar's detections (sensors/radar.py) in compiled passes around the calls that stay
numpy's on both paths: the rotation into the sensor frame (a BLAS product), the
arctangents, the range rate's einsum and the amplitude's log10."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import maximum
from egosim.world.kernels.sorting import lexsort_argsort


@kernel
def shown_centres(
    unique_ids: IntArray,
    hidden_ids: IntArray,
    positions: FloatArray,
    sizes: FloatArray,
    origin: FloatArray,
    shown: IntArray,
    from_origin: FloatArray,
) -> int:
    """The objects whose id is none of `hidden_ids` into `shown`, in table order, and
    their box centres (footprint centre, half the height up) from `origin` into
    from_origin (N, 3); their count."""
    count = 0
    for k in range(unique_ids.shape[0]):
        hidden = False
        for hidden_id in hidden_ids:
            hidden = hidden or unique_ids[k] == hidden_id
        if hidden:
            continue
        shown[count] = k
        # + 0.0 as numpy adds the centre's zero offsets (it turns -0.0 into 0.0).
        from_origin[count, 0] = (positions[k, 0] + 0.0) - origin[0]
        from_origin[count, 1] = (positions[k, 1] + 0.0) - origin[1]
        from_origin[count, 2] = (positions[k, 2] + sizes[k, 2] / 2.0) - origin[2]
        count += 1
    return count


@kernel
def nearest_in_view(
    local: FloatArray,
    azimuth: FloatArray,
    elevation: FloatArray,
    min_range: float,
    max_range: float,
    half_azimuth: float,
    half_elevation: float,
    max_detections: int,
    distance: FloatArray,
) -> IntArray:
    """The rows of `local` (N, 3, sensor frame) inside the ranges and the field of view,
    nearest first (ties in row order), at most max_detections; every row's distance
    into `distance`."""
    inside = np.empty(local.shape[0], dtype=np.int64)
    count = 0
    for k in range(local.shape[0]):
        x, y, z = local[k, 0], local[k, 1], local[k, 2]
        distance[k] = np.sqrt((x * x + y * y) + z * z)
        if (
            distance[k] >= min_range
            and distance[k] <= max_range
            and abs(azimuth[k]) <= half_azimuth
            and abs(elevation[k]) <= half_elevation
        ):
            inside[count] = k
            count += 1
    inside = inside[:count]
    # np.argsort(kind="stable")'s order: by distance, then row (no NaN is inside).
    nearest: IntArray = inside[lexsort_argsort(np.zeros(count, dtype=np.int64), distance[inside])]
    return nearest[:max_detections]


@kernel
def lines_of_sight(
    order: IntArray,
    shown: IntArray,
    from_origin: FloatArray,
    distance: FloatArray,
    velocities: FloatArray,
    sensor_velocity: FloatArray,
    sight: FloatArray,
    relative_velocity: FloatArray,
) -> bool:
    """Per detection (row order[k] of the shown objects): the unit line of sight into
    sight[k] and the object's velocity relative to the sensor into relative_velocity[k].
    False, and nothing written, if a detection lies at the sensor itself (distance 0,
    a gate from 0 m): numpy divides by it without an error, this does not."""
    for k in range(order.shape[0]):
        if distance[order[k]] == 0.0:
            return False
    for k in range(order.shape[0]):
        row = order[k]
        for axis in range(3):
            sight[k, axis] = from_origin[row, axis] / distance[row]
            relative_velocity[k, axis] = velocities[shown[row], axis] - sensor_velocity[axis]
    return True


@kernel
def seen_areas(
    objects: IntArray,
    headings: FloatArray,
    sizes: FloatArray,
    sight_heading: FloatArray,
    area: FloatArray,
) -> None:
    """Each of `objects`' box area seen along its line of sight (radar.py's amplitude
    before its log), at least 1e-6 m²."""
    for k in range(objects.shape[0]):
        angle = headings[objects[k]] - sight_heading[k]
        length, width, height = sizes[objects[k], 0], sizes[objects[k], 1], sizes[objects[k], 2]
        seen = height * (length * abs(np.sin(angle)) + width * abs(np.cos(angle)))
        area[k] = maximum(seen, 1e-6)
