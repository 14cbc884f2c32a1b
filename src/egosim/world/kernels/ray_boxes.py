"""Rays against upright boxes (sensors/raycast.py's cast_boxes) as one compiled loop over
the (ray, box) pairs the broad phase's bearing intervals give: the bounding-cone test,
the slab test and the nearest hit per ray."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import maximum, minimum


@kernel
def nearest_box_hits(
    directions: FloatArray,
    sorted_rays: IntArray,
    interval_box: IntArray,
    first: IntArray,
    stop: IntArray,
    offset: FloatArray,
    tangent_length: FloatArray,
    box_frame: FloatArray,
    half_size: FloatArray,
    distance: FloatArray,
    cos_incidence: FloatArray,
) -> None:
    """For each interval k, box interval_box[k] against rays sorted_rays[first[k]:stop[k]]:
    raycast._in_bounding_cone, then raycast._slab_entry; distance and cos_incidence take
    each ray's nearest entry in place (on equal distances, the later pair's cos).

    offset (N, 3): box centres from the origin; box_frame rows: cos yaw, sin yaw, then the
    origin in each box's frame (x, y, z); half_size (3, N); directions (3, rays).
    """
    for k in range(interval_box.shape[0]):
        b = interval_box[k]
        cos_yaw, sin_yaw = box_frame[0, b], box_frame[1, b]
        for position in range(first[k], stop[k]):
            ray = sorted_rays[position]
            east, north, up = directions[0, ray], directions[1, ray], directions[2, ray]
            along = east * offset[b, 0] + north * offset[b, 1] + up * offset[b, 2]
            if not along >= tangent_length[b]:
                continue
            entry, exit_, entry_cos = -np.inf, np.inf, 0.0
            for axis in range(3):
                if axis == 0:
                    direction = cos_yaw * east + sin_yaw * north
                elif axis == 1:
                    direction = -sin_yaw * east + cos_yaw * north
                else:
                    direction = up
                start, half = box_frame[2 + axis, b], half_size[axis, b]
                if direction == 0.0:
                    # A ray parallel to a slab is inside it for all t, or for none.
                    inside = abs(start) <= half
                    near = -np.inf if inside else np.inf
                    far = np.inf if inside else -np.inf
                else:
                    inverse = 1.0 / direction
                    to_low_face = (-half - start) * inverse
                    to_high_face = (half - start) * inverse
                    near = minimum(to_low_face, to_high_face)
                    far = maximum(to_low_face, to_high_face)
                if near > entry:
                    entry, entry_cos = near, abs(direction)
                exit_ = minimum(exit_, far)
            if entry <= exit_ and entry > 0.0:
                if entry < distance[ray]:
                    distance[ray], cos_incidence[ray] = entry, entry_cos
                elif entry == distance[ray]:
                    cos_incidence[ray] = entry_cos
