"""Rays against the ground plane z = 0 and yaw-oriented boxes, all in the map frame.

Boxes are intersected with the slab method in each box's own frame. A broad
phase keeps the work proportional to the beams that can reach a box: boxes
beyond range are dropped, each remaining box only sees the beams whose
horizontal bearing falls inside the sector its footprint circle subtends, and
of those only the beams inside the cone its bounding sphere subtends.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum

import numpy as np
import numpy.typing as npt

from egosim.sensors.errors import SensorConfigError
from egosim.world import kernels
from egosim.world.arrays import FloatArray
from egosim.world.kernels.ray_boxes import (
    BLOCKS_PER_SPAN,
    RAYS_PER_BLOCK,
    bearing_envelopes,
    boxes_in_reach,
    nearest_box_hits,
    sector_intervals,
    split_by_rise,
)

IndexArray = npt.NDArray[np.intp]
RayGroup = tuple[IndexArray, FloatArray, FloatArray]
"""Rays by index, and their x and y components."""


class Surface(IntEnum):
    NONE = 0
    GROUND = 1
    OBJECT = 2


@dataclass(frozen=True)
class ObstacleBoxes:
    """N upright boxes in the map frame.

    centres (N, 3) m: the box's geometric centre, so it spans z +- height / 2.
    sizes (N, 3) m: length (along its heading), width, height.
    yaws (N,) rad: heading of the length axis, counter-clockwise from east.
    """

    centres: FloatArray
    sizes: FloatArray
    yaws: FloatArray

    def __post_init__(self) -> None:
        centres = np.asarray(self.centres, dtype=np.float64).reshape(-1, 3)
        sizes = np.asarray(self.sizes, dtype=np.float64).reshape(-1, 3)
        yaws = np.asarray(self.yaws, dtype=np.float64).reshape(-1)
        if not len(centres) == len(sizes) == len(yaws):
            raise SensorConfigError(
                f"boxes need as many centres, sizes and yaws: "
                f"{len(centres)}, {len(sizes)}, {len(yaws)}"
            )
        if np.any(sizes <= 0.0):
            raise SensorConfigError("box sizes must be > 0")
        object.__setattr__(self, "centres", centres)
        object.__setattr__(self, "sizes", sizes)
        object.__setattr__(self, "yaws", yaws)

    @classmethod
    def empty(cls) -> ObstacleBoxes:
        return cls(np.empty((0, 3)), np.empty((0, 3)), np.empty(0))

    def __len__(self) -> int:
        return len(self.yaws)


@dataclass(frozen=True)
class RayHits:
    """Nearest hit per ray: distance (inf if none), surface, |cos| of incidence."""

    distance: FloatArray
    surface: npt.NDArray[np.int8]
    cos_incidence: FloatArray


@dataclass(frozen=True)
class BearingBlocks:
    """Rays with their horizontal bearings (rad) and the envelopes of those bearings over
    blocks of consecutive rays and spans of blocks (kernels/ray_boxes.py's
    bearing_envelopes): where the rays of a bearing interval can be."""

    rays: IndexArray
    bearing: FloatArray
    block: FloatArray
    span: FloatArray


class RayFan:
    """Unit rays from one origin, one axis per row (3, N), and what the compiled box cast
    needs of them, worked out when first asked for and then kept: the rising and the
    other rays, each group with its bearings and their envelopes. A LiDAR keeps its fan
    while its beams keep their rotation (a vehicle standing, or holding its heading)."""

    def __init__(self, axes: FloatArray) -> None:
        self.axes = axes
        self.count = axes.shape[1]
        self._groups: tuple[RayGroup, RayGroup] | None = None
        self._blocks: dict[bool, BearingBlocks] = {}

    def blocks(self, rising: bool) -> BearingBlocks:
        """The rising rays (z > 0) or the others, with their bearings' envelopes."""
        blocks = self._blocks.get(rising)
        if blocks is None:
            rays, east, north = self._group(rising)
            # raycast's numpy path takes the same arctangents of the same components.
            bearing = np.arctan2(north, east)
            block_count = -(-len(rays) // RAYS_PER_BLOCK)
            blocks = BearingBlocks(
                rays,
                bearing,
                np.empty((2, block_count)),
                np.empty((2, -(-block_count // BLOCKS_PER_SPAN))),
            )
            bearing_envelopes(bearing, blocks.block, blocks.span)
            self._blocks[rising] = blocks
        return blocks

    def _group(self, rising: bool) -> RayGroup:
        """The rising rays or the others, and their x and y components (contiguous)."""
        if self._groups is None:
            rising_rays, other_rays = np.empty(self.count, np.intp), np.empty(self.count, np.intp)
            horizontal = np.empty((4, self.count))
            risen = split_by_rise(self.axes, rising_rays, other_rays, horizontal)
            self._groups = (
                (other_rays[: self.count - risen], *horizontal[2:, : self.count - risen]),
                (rising_rays[:risen], *horizontal[:2, :risen]),
            )
        return self._groups[rising]


def cast_ground(origin: FloatArray, directions: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Distance along unit `directions` to the plane z = 0 (inf if not reached), and |cos|."""
    rise = directions[:, 2]
    distance = np.full(len(directions), np.inf)
    if origin[2] > 0.0:
        # Only falling beams reach the plane; -height / rise is height / -rise to the bit.
        np.divide(-origin[2], rise, out=distance, where=rise < 0.0)
    return distance, np.abs(rise)


def cast_rays(
    origin: FloatArray,
    directions: FloatArray,
    boxes: ObstacleBoxes,
    max_range: float,
    exclude_index: int | None = None,
) -> RayHits:
    """Nearest of ground and box hits for rays from `origin` along unit `directions`."""
    distance, cos_incidence = cast_ground(origin, directions)
    box_distance, box_cos = cast_boxes(origin, directions, boxes, max_range, exclude_index)
    surface = np.full(len(directions), Surface.GROUND, dtype=np.int8)
    # Few beams meet a box: update those rather than choosing between whole arrays.
    box_first = np.flatnonzero(box_distance < distance)
    distance[box_first] = box_distance[box_first]
    cos_incidence[box_first] = box_cos[box_first]
    surface[box_first] = Surface.OBJECT
    missed = np.isinf(distance)
    np.copyto(surface, Surface.NONE, where=missed)
    np.copyto(cos_incidence, 0.0, where=missed)
    return RayHits(distance, surface, cos_incidence)


def cast_boxes(
    origin: FloatArray,
    directions: FloatArray,
    boxes: ObstacleBoxes,
    max_range: float,
    exclude_index: int | None = None,
) -> tuple[FloatArray, FloatArray]:
    """Distance to the nearest box entry per ray (inf if none) and |cos| of incidence.

    A ray starting inside a box does not see that box.
    """
    if kernels.ACTIVE:
        # One row per axis: a LiDAR's rotated beams already are, so nothing is copied.
        fan = RayFan(np.ascontiguousarray(directions.T))
        return cast_fan(origin, fan, boxes, max_range, exclude_index)
    distance = np.full(len(directions), np.inf)
    cos_incidence = np.zeros(len(directions))
    candidates = _boxes_in_range(origin, boxes, max_range, exclude_index)
    if len(candidates) == 0 or len(directions) == 0:
        return distance, cos_incidence
    ray_index, box_index = _pairs_in_sector(origin, directions, boxes, candidates)
    pair_direction = directions[ray_index]
    in_cone = _in_bounding_cone(origin, boxes, pair_direction, box_index)
    ray_index, box_index, pair_direction = (
        ray_index[in_cone],
        box_index[in_cone],
        pair_direction[in_cone],
    )
    pair_distance, pair_cos, hit = _slab_entry(origin, boxes, pair_direction, box_index)
    ray_index, pair_distance, pair_cos = ray_index[hit], pair_distance[hit], pair_cos[hit]

    np.minimum.at(distance, ray_index, pair_distance)
    nearest = pair_distance == distance[ray_index]
    cos_incidence[ray_index[nearest]] = pair_cos[nearest]
    return distance, cos_incidence


def cast_fan(
    origin: FloatArray,
    fan: RayFan,
    boxes: ObstacleBoxes,
    max_range: float,
    exclude_index: int | None = None,
) -> tuple[FloatArray, FloatArray]:
    """cast_boxes for the rays of `fan`, through the compiled kernels (the broad phase's
    bearing intervals, then one loop over their rays); `fan` keeps its rays' bearings."""
    distance = np.full(fan.count, np.inf)
    cos_incidence = np.zeros(fan.count)
    count = len(boxes)
    if count == 0 or fan.count == 0:
        return distance, cos_incidence
    candidates = np.empty(count, np.intp)
    frames, half_size = np.empty((5, count)), np.empty((3, count))
    towards, sine = np.empty((count, 2)), np.empty(count)
    surrounds, top_above = np.empty(count, np.bool_), np.empty(count, np.bool_)
    reached = boxes_in_reach(
        origin, boxes.centres, boxes.sizes, boxes.yaws, max_range,
        -1 if exclude_index is None else range(count)[exclude_index],
        candidates, frames, half_size, towards, sine, surrounds, top_above,
    )  # fmt: skip
    if reached == 0:
        return distance, cos_incidence
    candidates, towards = candidates[:reached], towards[:reached]
    # _sectors' arctangent and arcsine, numpy's on both paths.
    centre_bearing = np.arctan2(towards[:, 1], towards[:, 0])
    half_width = np.arcsin(sine[:reached])
    offset, tangent_length = _cone_tangents(origin, boxes)
    boxes_of, lows, highs = (
        np.empty(3 * reached, np.intp),
        np.empty(3 * reached),
        np.empty(3 * reached),
    )
    everyone = np.ones(reached, np.bool_)
    # _box_groups: the falling and level rays meet every candidate, the rising ones only
    # those whose top is above the origin.
    for rising, member in ((False, everyone), (True, top_above[:reached])):
        if rising and not member.any():
            break
        blocks = fan.blocks(rising)
        spans = sector_intervals(
            candidates, member, surrounds[:reached], centre_bearing, half_width,
            boxes_of, lows, highs,
        )  # fmt: skip
        nearest_box_hits(
            fan.axes, blocks.rays, blocks.bearing, blocks.block, blocks.span,
            boxes_of[:spans], lows[:spans], highs[:spans], offset, tangent_length,
            frames, half_size, distance, cos_incidence,
        )  # fmt: skip
    return distance, cos_incidence


def _boxes_in_range(
    origin: FloatArray, boxes: ObstacleBoxes, max_range: float, exclude_index: int | None
) -> IndexArray:
    bounding_radius = 0.5 * np.linalg.norm(boxes.sizes, axis=1)
    centre_distance = np.linalg.norm(boxes.centres - origin, axis=1)
    keep = centre_distance - bounding_radius <= max_range
    if exclude_index is not None:
        keep[exclude_index] = False
    return np.flatnonzero(keep)


def _pairs_in_sector(
    origin: FloatArray, directions: FloatArray, boxes: ObstacleBoxes, candidates: IndexArray
) -> tuple[IndexArray, IndexArray]:
    """(ray, box) pairs whose horizontal bearing lies in the box footprint's sector.

    A ray whose horizontal projection misses the footprint's circumscribed
    circle misses the box, so this never drops a hit. A vertical ray can only
    hit a box whose circle contains the origin; those boxes take every ray.

    A rising ray misses every box whose top is not above the origin (the slab test
    puts that box's top face behind it), so such boxes only take the other rays;
    with the sensor above the traffic, that halves the work. Each ray's pairs keep
    the order of its boxes.
    """
    pairs = [
        _sector_pairs(origin, directions, rays, boxes, group)
        for rays, group in _ray_groups(origin, directions, boxes, candidates)
    ]
    if len(pairs) == 1:
        return pairs[0]
    return np.concatenate([p[0] for p in pairs]), np.concatenate([p[1] for p in pairs])


def _ray_groups(
    origin: FloatArray, directions: FloatArray, boxes: ObstacleBoxes, candidates: IndexArray
) -> list[tuple[IndexArray, IndexArray]]:
    """(rays, boxes they may meet): the falling and level rays with every candidate, then
    the rising rays with the boxes whose top is above the origin, if any."""
    rising = directions[:, 2] > 0.0
    return [
        (np.flatnonzero(rising if rises else ~rising), group)
        for rises, group in _box_groups(origin, boxes, candidates)
    ]


def _box_groups(
    origin: FloatArray, boxes: ObstacleBoxes, candidates: IndexArray
) -> list[tuple[bool, IndexArray]]:
    """(whether the rays rise, the candidates they may meet): _ray_groups' groups."""
    # The top face's offset exactly as _slab_entry computes it.
    top_above = 0.5 * boxes.sizes[candidates, 2] - (origin[2] - boxes.centres[candidates, 2]) > 0.0
    groups = [(False, candidates)]
    if top_above.any():
        groups.append((True, candidates[top_above]))
    return groups


def _sector_pairs(
    origin: FloatArray,
    directions: FloatArray,
    rays: IndexArray,
    boxes: ObstacleBoxes,
    candidates: IndexArray,
) -> tuple[IndexArray, IndexArray]:
    """_pairs_in_sector among `rays` and `candidates`."""
    sorted_rays, interval_box, first, stop = _sector_intervals(
        origin, directions, rays, boxes, candidates
    )
    counts = np.maximum(stop - first, 0)
    box_index = np.repeat(interval_box, counts)
    interval_start = np.repeat(first - (np.cumsum(counts) - counts), counts)
    return sorted_rays[interval_start + np.arange(counts.sum())], box_index


def _sector_intervals(
    origin: FloatArray,
    directions: FloatArray,
    rays: IndexArray,
    boxes: ObstacleBoxes,
    candidates: IndexArray,
) -> tuple[IndexArray, IndexArray, IndexArray, IndexArray]:
    """`rays` sorted by bearing, and per bearing interval of a box's sector (_sectors): its
    box and the range first:stop of the sorted rays inside it."""
    bearing = _bearings(directions, rays)
    by_bearing = np.argsort(bearing, kind="stable")
    sorted_bearing = bearing[by_bearing]
    interval_box, interval_low, interval_high = _sectors(origin, boxes, candidates)
    first = np.searchsorted(sorted_bearing, interval_low, side="left")
    stop = np.searchsorted(sorted_bearing, interval_high, side="right")
    return rays[by_bearing], interval_box, first, stop


def _bearings(directions: FloatArray, rays: IndexArray) -> FloatArray:
    """The horizontal bearing (rad, -pi..pi) of each of `rays`."""
    # take() gathers from a column of the LiDAR's transposed beams twice as fast as [rays, k].
    return np.arctan2(directions[:, 1].take(rays), directions[:, 0].take(rays))


def _sectors(
    origin: FloatArray, boxes: ObstacleBoxes, candidates: IndexArray
) -> tuple[IndexArray, FloatArray, FloatArray]:
    """The bearing intervals of the boxes' sectors, in the order of `candidates`, then the
    second halves of sectors crossing +-pi: each interval's box, low and high end (rad)."""
    offset = boxes.centres[candidates, :2] - origin[:2]
    horizontal_distance = np.hypot(offset[:, 0], offset[:, 1])
    footprint_radius = 0.5 * np.hypot(boxes.sizes[candidates, 0], boxes.sizes[candidates, 1])
    surrounds = horizontal_distance <= footprint_radius
    centre_bearing = np.arctan2(offset[:, 1], offset[:, 0])
    half_width = np.arcsin(
        np.minimum(footprint_radius / np.maximum(horizontal_distance, 1e-12), 1.0)
    )
    low = np.where(surrounds, -np.pi, centre_bearing - half_width)
    high = np.where(surrounds, np.pi, centre_bearing + half_width)

    # A sector crossing +-pi is split into two intervals inside [-pi, pi].
    wraps_low = low < -np.pi
    wraps_high = high > np.pi
    interval_box = np.concatenate([candidates, candidates[wraps_low], candidates[wraps_high]])
    interval_low = np.concatenate(
        [np.maximum(low, -np.pi), low[wraps_low] + 2 * np.pi, np.full(wraps_high.sum(), -np.pi)]
    )
    interval_high = np.concatenate(
        [np.minimum(high, np.pi), np.full(wraps_low.sum(), np.pi), high[wraps_high] - 2 * np.pi]
    )
    return interval_box, interval_low, interval_high


def _in_bounding_cone(
    origin: FloatArray, boxes: ObstacleBoxes, pair_direction: FloatArray, box_index: IndexArray
) -> npt.NDArray[np.bool_]:
    """Whether each pair's ray meets the box's bounding sphere (or starts inside it)."""
    offset, tangent_length = _cone_tangents(origin, boxes)
    towards = offset[box_index]
    # Summed left to right, as the compiled cast does (einsum's order depends on size).
    along = (
        pair_direction[:, 0] * towards[:, 0] + pair_direction[:, 1] * towards[:, 1]
    ) + pair_direction[:, 2] * towards[:, 2]
    in_cone: npt.NDArray[np.bool_] = along >= tangent_length[box_index]
    return in_cone


def _cone_tangents(origin: FloatArray, boxes: ObstacleBoxes) -> tuple[FloatArray, FloatArray]:
    """Each box's centre from the origin (N, 3), and the length of a tangent from the
    origin to its bounding sphere (-inf when the origin is inside it)."""
    offset = boxes.centres - origin
    radius_sq: FloatArray = 0.25 * np.einsum("ij,ij->i", boxes.sizes, boxes.sizes)
    distance_sq: FloatArray = np.einsum("ij,ij->i", offset, offset)
    tangent_length = np.sqrt(np.maximum(distance_sq - radius_sq, 0.0))
    # Rays into a sphere the origin is inside of always pass.
    tangent_length[distance_sq <= radius_sq] = -np.inf
    return offset, tangent_length


def _box_frames(
    origin: FloatArray, boxes: ObstacleBoxes
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Each box's cos and sin of yaw, and the origin in each box's frame (3, N)."""
    cos_yaw, sin_yaw = np.cos(boxes.yaws), np.sin(boxes.yaws)
    offset = origin - boxes.centres
    # Rz(-yaw) takes map vectors into each box's frame.
    box_origin = np.stack(
        [
            cos_yaw * offset[:, 0] + sin_yaw * offset[:, 1],
            -sin_yaw * offset[:, 0] + cos_yaw * offset[:, 1],
            offset[:, 2],
        ]
    )
    return cos_yaw, sin_yaw, box_origin


def _slab_entry(
    origin: FloatArray, boxes: ObstacleBoxes, pair_direction: FloatArray, box_index: IndexArray
) -> tuple[FloatArray, FloatArray, npt.NDArray[np.bool_]]:
    """Entry distance, |cos| at the entry face and whether each (ray, box) pair hits.

    Works one box axis at a time on flat arrays: the ray's parameter interval
    inside each pair of parallel faces, intersected over the three axes.
    """
    cos_yaw, sin_yaw, box_origin = _box_frames(origin, boxes)
    pair_cos, pair_sin = cos_yaw[box_index], sin_yaw[box_index]
    east, north, up = pair_direction.T
    local_direction = (pair_cos * east + pair_sin * north, -pair_sin * east + pair_cos * north, up)
    half_size = 0.5 * boxes.sizes.T

    count = len(box_index)
    entry = np.full(count, -np.inf)
    exit_ = np.full(count, np.inf)
    entry_cos = np.zeros(count)
    for axis, direction in enumerate(local_direction):
        start = box_origin[axis][box_index]
        half = half_size[axis][box_index]
        with np.errstate(divide="ignore", invalid="ignore"):
            inverse = 1.0 / direction
            to_low_face = (-half - start) * inverse
            to_high_face = (half - start) * inverse
        near = np.minimum(to_low_face, to_high_face)
        far = np.maximum(to_low_face, to_high_face)
        parallel = direction == 0.0
        if parallel.any():
            # A ray parallel to a slab is inside it for all t, or for none.
            inside = np.abs(start[parallel]) <= half[parallel]
            near[parallel] = np.where(inside, -np.inf, np.inf)
            far[parallel] = np.where(inside, np.inf, -np.inf)
        later = near > entry
        entry[later] = near[later]
        entry_cos[later] = np.abs(direction[later])
        np.minimum(exit_, far, out=exit_)
    hit = (entry <= exit_) & (entry > 0.0)
    return entry, entry_cos, hit
