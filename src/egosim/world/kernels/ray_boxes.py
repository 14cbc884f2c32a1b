"""Rays against upright boxes (sensors/raycast.py's cast_boxes) as compiled loops: the
rays split by whether they rise, their bearings enveloped over blocks, and one loop over
the (ray, box) pairs of each box's bearing interval: the bounding-cone test, the slab
test and the nearest hit per ray."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import BoolArray, FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import maximum, minimum


@kernel
def boxes_in_reach(
    origin: FloatArray,
    centres: FloatArray,
    sizes: FloatArray,
    yaws: FloatArray,
    max_range: float,
    exclude_index: int,
    candidates: IntArray,
    box_frame: FloatArray,
    half_size: FloatArray,
    towards: FloatArray,
    sine: FloatArray,
    surrounds: BoolArray,
    top_above: BoolArray,
) -> int:
    """What raycast.cast_boxes works out of the boxes before the rays: the candidates
    (_boxes_in_range: within reach, not `exclude_index`; -1 for none) in box order, their
    count returned; of every box, box_frame (5, N: _box_frames) and half_size (3, N); of
    each candidate k, as _sectors and _box_groups compute them: towards[k] its footprint
    centre from the origin (x, y), sine[k] the sine of its sector's half width (before
    the arcsin), whether its footprint circle surrounds the origin and whether its top
    is above it."""
    count = 0
    for b in range(yaws.shape[0]):
        east, north, up = (
            centres[b, 0] - origin[0],
            centres[b, 1] - origin[1],
            centres[b, 2] - origin[2],
        )
        length, width, height = sizes[b, 0], sizes[b, 1], sizes[b, 2]
        cos_yaw, sin_yaw = np.cos(yaws[b]), np.sin(yaws[b])
        box_frame[0, b], box_frame[1, b] = cos_yaw, sin_yaw
        # The origin in the box's frame: Rz(-yaw) of origin - centre (not -(centre -
        # origin): a zero difference would change sign).
        back_x, back_y = origin[0] - centres[b, 0], origin[1] - centres[b, 1]
        box_frame[2, b] = cos_yaw * back_x + sin_yaw * back_y
        box_frame[3, b] = -sin_yaw * back_x + cos_yaw * back_y
        box_frame[4, b] = origin[2] - centres[b, 2]
        half_size[0, b], half_size[1, b], half_size[2, b] = 0.5 * length, 0.5 * width, 0.5 * height
        bounding_radius = 0.5 * np.sqrt((length * length + width * width) + height * height)
        centre_distance = np.sqrt((east * east + north * north) + up * up)
        if not centre_distance - bounding_radius <= max_range or b == exclude_index:
            continue
        candidates[count] = b
        towards[count, 0], towards[count, 1] = east, north
        horizontal_distance = np.hypot(east, north)
        footprint_radius = 0.5 * np.hypot(length, width)
        surrounds[count] = horizontal_distance <= footprint_radius
        sine[count] = minimum(footprint_radius / maximum(horizontal_distance, 1e-12), 1.0)
        top_above[count] = 0.5 * height - (origin[2] - centres[b, 2]) > 0.0
        count += 1
    return count


@kernel
def sector_intervals(
    candidates: IntArray,
    member: BoolArray,
    surrounds: BoolArray,
    centre_bearing: FloatArray,
    half_width: FloatArray,
    interval_box: IntArray,
    interval_low: FloatArray,
    interval_high: FloatArray,
) -> int:
    """raycast._sectors of the candidates that are `member`s: the bearing intervals of
    their sectors in candidate order, then the second halves of sectors crossing +-pi
    (below -pi, then above pi); their count."""
    count = 0
    for wrapped in range(3):
        for k in range(candidates.shape[0]):
            if not member[k]:
                continue
            low, high = centre_bearing[k] - half_width[k], centre_bearing[k] + half_width[k]
            if surrounds[k]:
                low, high = -np.pi, np.pi
            if wrapped == 0:
                low, high = maximum(low, -np.pi), minimum(high, np.pi)
            elif wrapped == 1:
                if not low < -np.pi:
                    continue
                low, high = low + 2 * np.pi, np.pi
            else:
                if not high > np.pi:
                    continue
                low, high = -np.pi, high - 2 * np.pi
            interval_box[count], interval_low[count], interval_high[count] = (
                candidates[k],
                low,
                high,
            )
            count += 1
    return count


@kernel
def split_by_rise(
    directions: FloatArray, rising: IntArray, others: IntArray, horizontal: FloatArray
) -> int:
    """The rays (3, N) whose z is > 0 into `rising`, the others into `others`, each in ray
    order as np.flatnonzero(z > 0) and np.flatnonzero(~(z > 0)) give them, and their
    horizontal components: x and y of rising[k] into horizontal[0:2, k], of others[k]
    into horizontal[2:4, k]. The count of rising rays (`others` holds N minus that)."""
    risen = fallen = 0
    for ray in range(directions.shape[1]):
        east, north = directions[0, ray], directions[1, ray]
        if directions[2, ray] > 0.0:
            rising[risen], horizontal[0, risen], horizontal[1, risen] = ray, east, north
            risen += 1
        else:
            others[fallen], horizontal[2, fallen], horizontal[3, fallen] = ray, east, north
            fallen += 1
    return risen


RAYS_PER_BLOCK = 8
"""About a LiDAR's channels: the rays of one azimuth, of nearly one bearing."""
BLOCKS_PER_SPAN = 8


@kernel
def bearing_envelopes(bearing: FloatArray, block: FloatArray, span: FloatArray) -> None:
    """The least and greatest of `bearing` (rad) over each block of RAYS_PER_BLOCK
    consecutive rays into block[0, k] and block[1, k], and over each span of
    BLOCKS_PER_SPAN blocks into span[0, j] and span[1, j] (NaN is in none: a block of
    NaN has the empty envelope inf, -inf)."""
    count = bearing.shape[0]
    for k in range(block.shape[1]):
        least, greatest = np.inf, -np.inf
        for position in range(k * RAYS_PER_BLOCK, min((k + 1) * RAYS_PER_BLOCK, count)):
            # Comparisons, not min and max: a NaN bearing changes neither.
            if bearing[position] < least:  # noqa: PLR1730
                least = bearing[position]
            if bearing[position] > greatest:  # noqa: PLR1730
                greatest = bearing[position]
        block[0, k], block[1, k] = least, greatest
    for j in range(span.shape[1]):
        least, greatest = np.inf, -np.inf
        for k in range(j * BLOCKS_PER_SPAN, min((j + 1) * BLOCKS_PER_SPAN, block.shape[1])):
            least, greatest = min(least, block[0, k]), max(greatest, block[1, k])
        span[0, j], span[1, j] = least, greatest


@kernel
def nearest_box_hits(
    directions: FloatArray,
    rays: IntArray,
    bearing: FloatArray,
    block: FloatArray,
    span: FloatArray,
    interval_box: IntArray,
    interval_low: FloatArray,
    interval_high: FloatArray,
    offset: FloatArray,
    tangent_length: FloatArray,
    box_frame: FloatArray,
    half_size: FloatArray,
    distance: FloatArray,
    cos_incidence: FloatArray,
) -> None:
    """For each interval k, box interval_box[k] against the rays whose bearing lies in
    [interval_low[k], interval_high[k]] (found through bearing_envelopes' blocks and
    spans): raycast's _in_bounding_cone, then _slab_entry; distance and cos_incidence
    take each ray's nearest entry in place (on equal distances, the later interval's
    cos). A ray meets the intervals in their order, as through raycast's sorted rays:
    the order of the rays within one interval changes nothing, each is a ray of its own.

    offset (N, 3): box centres from the origin; box_frame rows: cos yaw, sin yaw, then the
    origin in each box's frame (x, y, z); half_size (3, N); directions (3, rays).
    """
    for k in range(interval_box.shape[0]):
        b, low, high = interval_box[k], interval_low[k], interval_high[k]
        cos_yaw, sin_yaw = box_frame[0, b], box_frame[1, b]
        for j in range(span.shape[1]):
            if span[1, j] < low or span[0, j] > high:
                continue
            for kb in range(j * BLOCKS_PER_SPAN, min((j + 1) * BLOCKS_PER_SPAN, block.shape[1])):
                if block[1, kb] < low or block[0, kb] > high:
                    continue
                for position in range(
                    kb * RAYS_PER_BLOCK, min((kb + 1) * RAYS_PER_BLOCK, bearing.shape[0])
                ):
                    if not (bearing[position] >= low and bearing[position] <= high):
                        continue
                    ray = rays[position]
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
