"""OpenDRIVE crosswalk objects -> crosswalks: the line a pedestrian walks across the road.

The outline is the object's <cornerRoad> points, else its <cornerLocal> points, else its
length × width box around its origin; the road's heading at the object's s squares the
crossing (see egosim.world.map.crossings).
"""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.crossings import crossing
from egosim.world.map.lanes import Crosswalk, IntersectionSite
from egosim.world.map.opendrive.document import CrosswalkRecord, Road
from egosim.world.map.opendrive.reference_line import lateral_points, reference_poses


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
        walk = crossing(f"{road.id}_{record.id}", outline, origin[0, 3], intersections)
        if walk is None:
            notes.append(f"road {road.id}: crosswalk {record.id} crosses no road")
            continue
        crosswalks.append(walk)
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
    corners: FloatArray = lateral_points(origin, record.t) + uv[:, :1] * u_axis + uv[:, 1:] * v_axis
    return corners
