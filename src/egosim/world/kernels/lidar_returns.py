"""A LiDAR scan's returns (sensors/lidar.py) in one compiled pass over the beams: the
ground hit (raycast.cast_ground), the nearer of it and the box hit (raycast.cast_rays),
the range gate, the points in the sensor frame and the intensity's factors but the
atmospheric one, whose exp stays numpy's on both paths; then the intensities."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.kernels import kernel


@kernel
def lidar_returns(
    height: float,
    directions: FloatArray,
    box_distance: FloatArray,
    box_cos: FloatArray,
    beam_axes: FloatArray,
    min_range: float,
    max_range: float,
    ground_factor: float,
    object_factor: float,
    extinction_factor: float,
    points: np.ndarray,
    lit: FloatArray,
    exponent: FloatArray,
) -> int:
    """The returned beams' points (x, y, z in points[:, :3], float32), in beam order, and
    per point the intensity's scale * reflectivity * |cos| (lit) and the exponent of its
    extinction term (exponent); their count.

    height: the origin's z above the ground plane; directions (3, N) in the map frame;
    box_distance, box_cos: raycast.cast_boxes per beam; beam_axes (3, N) the beams in the
    sensor frame; ground_factor, object_factor: scale * reflectivity of each surface;
    extinction_factor: -2 * extinction per metre.
    """
    count = 0
    falls_to_ground = height > 0.0
    for beam in range(directions.shape[1]):
        rise = directions[2, beam]
        distance = np.inf
        if falls_to_ground and rise < 0.0:
            distance = -height / rise
        cos_incidence = abs(rise)
        factor = ground_factor
        if box_distance[beam] < distance:
            distance, cos_incidence, factor = box_distance[beam], box_cos[beam], object_factor
        if not (distance >= min_range and distance <= max_range):
            continue
        for axis in range(3):
            points[count, axis] = np.float32(beam_axes[axis, beam] * distance)
        lit[count] = factor * cos_incidence
        exponent[count] = extinction_factor * distance
        count += 1
    return count


@kernel
def lidar_intensities(points: np.ndarray, lit: FloatArray, extinction: FloatArray) -> None:
    """points[k, 3] (float32) = lit[k] * extinction[k], for each of the points
    (extinction: numpy's exp of lidar_returns' exponents)."""
    for k in range(extinction.shape[0]):
        points[k, 3] = np.float32(lit[k] * extinction[k])
