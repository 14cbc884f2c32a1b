"""A scenario's positions moved from the frame its file states into the map's frame.

A MORAI scenario says where its coordinates are measured from (its map's east and north
offsets in a UTM zone). When that is not the origin of the map the world runs, every
position is carried over through latitude and longitude, and every heading turned by the
grid convergence between the two frames; heights stay as they are. A map whose
georeference is assumed (it names none) takes the positions as they are.
"""

from __future__ import annotations

import math
from dataclasses import replace

from egosim.world.map.georef import GeoReference
from egosim.world.scenario.model import PoseStart, Scenario, Start

SAME_ORIGIN_M = 1e-3
"""Origins closer than this are the same frame: nothing moves."""


def same_frame(a: GeoReference, b: GeoReference) -> bool:
    return (
        (a.utm_zone, a.northern, a.projection, a.ellipsoid)
        == (b.utm_zone, b.northern, b.projection, b.ellipsoid)
        and abs(a.origin_east - b.origin_east) < SAME_ORIGIN_M
        and abs(a.origin_north - b.origin_north) < SAME_ORIGIN_M
    )


class _Move:
    """Points and headings of the frame `origin` in the frame `target`."""

    def __init__(self, origin: GeoReference, target: GeoReference) -> None:
        self.origin, self.target = origin, target

    def point(self, x: float, y: float) -> tuple[float, float]:
        lat, lon, _ = self.origin.local_to_geodetic(x, y, 0.0)
        east, north, _ = self.target.geodetic_to_local(lat, lon, 0.0)
        return east, north

    def pose(self, pose: PoseStart) -> PoseStart:
        x, y = self.point(pose.x, pose.y)
        ahead = self.point(pose.x + math.cos(pose.heading), pose.y + math.sin(pose.heading))
        return PoseStart(x, y, pose.z, math.atan2(ahead[1] - y, ahead[0] - x))

    def start(self, start: Start) -> Start:
        return self.pose(start) if isinstance(start, PoseStart) else start


def in_map_frame(scenario: Scenario, georef: GeoReference) -> tuple[Scenario, tuple[str, ...]]:
    """`scenario` with its positions in the frame of a map georeferenced by `georef`, and
    the line to report when they had to move."""
    origin = scenario.origin
    if origin is None or georef.assumed or same_frame(origin, georef):
        return scenario, ()
    move = _Move(origin, georef)
    ego = scenario.ego
    moved = replace(
        scenario,
        ego=None if ego is None else replace(ego, start=move.start(ego.start)),
        npcs=tuple(replace(npc, start=move.start(npc.start)) for npc in scenario.npcs),
        pedestrians=tuple(
            replace(
                walker,
                waypoints=None
                if walker.waypoints is None
                else tuple(move.point(x, y) for x, y in walker.waypoints),
                wake_point=None if walker.wake_point is None else move.point(*walker.wake_point),
            )
            for walker in scenario.pedestrians
        ),
        obstacles=tuple(replace(o, pose=move.pose(o.pose)) for o in scenario.obstacles),
        origin=georef,
    )
    x, y = move.point(0.0, 0.0)
    note = (
        f"{scenario.source.label}: the file's positions are measured from "
        f"({origin.origin_east:.3f}, {origin.origin_north:.3f}), the map's from "
        f"({georef.origin_east:.3f}, {georef.origin_north:.3f}): they are moved into the "
        f"map's frame (the file's (0, 0) is the map's ({x:.3f}, {y:.3f}))"
    )
    return moved, (note,)
