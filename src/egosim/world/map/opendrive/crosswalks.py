"""OpenDRIVE crosswalk objects -> crosswalks: the line a pedestrian walks across the road.

The outline is the object's <cornerRoad> points, else its <cornerLocal> points, else its
length × width box around its origin. Pedestrians cross square to the road: the line
runs through the outline's centre along the road's normal at the object, over the
outline's extent that way; the crosswalk is as wide as the outline is long along the road.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from egosim.world.map.lanes import Crosswalk, IntersectionSite
from egosim.world.map.opendrive.document import CrosswalkRecord, Road
from egosim.world.map.opendrive.reference_line import lateral_points, reference_poses

FloatArray = npt.NDArray[np.float64]

# A crosswalk belongs to the signalised intersection whose centre is nearest, within this.
MAX_INTERSECTION_DISTANCE_M = 40.0
# Shorter lines cross nothing a pedestrian could walk.
MIN_CROSSING_M = 0.5


def road_crosswalks(
    road: Road, intersections: list[IntersectionSite], notes: list[str]
) -> list[Crosswalk]:
    crosswalks = []
    for record in road.crosswalks:
        origin = reference_poses(road, np.array([record.s]))
        outline = _outline(road, record, origin)
        if outline is None:
            notes.append(f"road {road.id}: crosswalk {record.id} has no outline or size")
            continue
        heading = origin[0, 3]
        across = np.array([-np.sin(heading), np.cos(heading)])
        along = np.array([np.cos(heading), np.sin(heading)])
        centre = outline.mean(axis=0)
        reach = (outline - centre) @ across
        extent = (outline - centre) @ along
        start, end = centre + reach.min() * across, centre + reach.max() * across
        width = float(extent.max() - extent.min())
        if reach.max() - reach.min() < MIN_CROSSING_M or width <= 0.0:
            notes.append(f"road {road.id}: crosswalk {record.id} crosses no road")
            continue
        crosswalks.append(
            Crosswalk(
                id=f"{road.id}_{record.id}",
                start=(float(start[0]), float(start[1])),
                end=(float(end[0]), float(end[1])),
                width=width,
                intersection_id=_nearest_intersection(centre, intersections),
            )
        )
    return crosswalks


def _outline(road: Road, record: CrosswalkRecord, origin: FloatArray) -> FloatArray | None:
    """(K, 2) outline points in the map frame; `origin` is the reference-line pose (1, 4)
    at the object's s."""
    if record.road_corners:
        s, t = np.array(record.road_corners).T
        return lateral_points(reference_poses(road, s), t)
    if record.local_corners:
        uv = np.array(record.local_corners)
    elif record.length > 0.0 and record.width > 0.0:
        u, v = record.length / 2.0, record.width / 2.0
        uv = np.array([(-u, -v), (u, -v), (u, v), (-u, v)])
    else:
        return None
    yaw = origin[0, 3] + record.hdg
    u_axis = np.array([np.cos(yaw), np.sin(yaw)])
    v_axis = np.array([-np.sin(yaw), np.cos(yaw)])
    return lateral_points(origin, record.t) + uv[:, :1] * u_axis + uv[:, 1:] * v_axis


def _nearest_intersection(point: FloatArray, intersections: list[IntersectionSite]) -> int | None:
    if not intersections:
        return None
    distance, number = min(
        (float(np.hypot(*(np.array(site.center) - point))), site.id) for site in intersections
    )
    return number if distance <= MAX_INTERSECTION_DISTANCE_M else None
