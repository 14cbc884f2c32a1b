"""A crosswalk's walking line from its painted outline, for every map format.

Pedestrians cross square to the road: the line runs through the outline's centre along
the road's normal there, over the outline's extent that way; the crosswalk is as wide as
the outline reaches along the road. It waits for the lights of the signalised
intersection whose centre is nearest, within MAX_INTERSECTION_DISTANCE_M.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.lanes import Crosswalk, IntersectionSite

MAX_INTERSECTION_DISTANCE_M = 40.0
# Shorter lines cross nothing a pedestrian could walk.
MIN_CROSSING_M = 0.5


def crossing(
    crosswalk_id: str,
    outline: FloatArray,
    road_heading: float,
    intersections: Iterable[IntersectionSite],
) -> Crosswalk | None:
    """The crosswalk painted as `outline` ((K, 2) map points, closed or not) on a road
    running along `road_heading` (rad); None when it reaches across no road."""
    if len(outline) > 1 and np.array_equal(outline[0], outline[-1]):
        outline = outline[:-1]  # a closing point would pull the centre towards itself
    across = np.array([-np.sin(road_heading), np.cos(road_heading)])
    along = np.array([np.cos(road_heading), np.sin(road_heading)])
    centre = outline.mean(axis=0)
    reach = (outline - centre) @ across
    extent = (outline - centre) @ along
    width = float(extent.max() - extent.min())
    if reach.max() - reach.min() < MIN_CROSSING_M or width <= 0.0:
        return None
    start, end = centre + reach.min() * across, centre + reach.max() * across
    return Crosswalk(
        id=crosswalk_id,
        start=(float(start[0]), float(start[1])),
        end=(float(end[0]), float(end[1])),
        width=width,
        intersection_id=_nearest_intersection(centre, intersections),
    )


def _nearest_intersection(
    point: FloatArray, intersections: Iterable[IntersectionSite]
) -> int | None:
    distances = [(float(np.hypot(*(np.array(s.center) - point))), s.id) for s in intersections]
    if not distances:
        return None
    distance, number = min(distances)
    return number if distance <= MAX_INTERSECTION_DISTANCE_M else None
