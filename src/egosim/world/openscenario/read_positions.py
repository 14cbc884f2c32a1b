"""<Position>, <Trajectory> and <Route> elements -> position, trajectory and route
objects (positions.py, trajectories.py, routes.py)."""

from __future__ import annotations

import math
from typing import Protocol

from egosim.world.openscenario.positions import (
    GeoPosition,
    LanePosition,
    Orientation,
    Position,
    RelativeLanePosition,
    RelativeObjectPosition,
    RelativeRoadPosition,
    RelativeWorldPosition,
    RoadPosition,
    RoutePosition,
    TrajectoryPosition,
    WorldPosition,
)
from egosim.world.openscenario.reading import Element
from egosim.world.openscenario.routes import Route
from egosim.world.openscenario.trajectories import (
    Clothoid,
    ClothoidSegment,
    ClothoidSpline,
    ControlPoint,
    Nurbs,
    Polyline,
    Shape,
    Trajectory,
    Vertex,
)


class CatalogResolver(Protocol):
    def entry(self, reference: Element) -> Element:
        """The catalogue entry a <CatalogReference> names, in its own scope."""
        ...


def orientation(element: Element) -> Orientation:
    node = element.child("Orientation")
    if node is None:
        return Orientation()
    kind = node.choice("type", ("relative", "absolute"), "relative")
    return Orientation(kind, node.number("h", 0.0))


def position(element: Element, catalogs: CatalogResolver) -> Position:
    """The position inside a <Position> (or any element holding one position choice)."""
    choice = element.only_child()
    if choice is None:
        raise element.node.error("holds no position")
    tag, node = choice.tag, choice.node
    if tag == "WorldPosition":
        return WorldPosition(
            node,
            choice.number("x"),
            choice.number("y"),
            choice.number("z", 0.0),
            choice.number("h", 0.0),
        )
    if tag == "RelativeWorldPosition":
        return RelativeWorldPosition(
            node,
            choice.text("entityRef"),
            choice.number("dx"),
            choice.number("dy"),
            choice.number("dz", 0.0),
            orientation(choice),
        )
    if tag == "RelativeObjectPosition":
        return RelativeObjectPosition(
            node,
            choice.text("entityRef"),
            choice.number("dx"),
            choice.number("dy"),
            choice.number("dz", 0.0),
            orientation(choice),
        )
    if tag == "RoadPosition":
        return RoadPosition(
            node,
            choice.text("roadId"),
            choice.number("s"),
            choice.number("t", 0.0),
            orientation(choice),
        )
    if tag == "RelativeRoadPosition":
        return RelativeRoadPosition(
            node,
            choice.text("entityRef"),
            choice.number("ds"),
            choice.number("dt", 0.0),
            orientation(choice),
        )
    if tag == "LanePosition":
        return LanePosition(
            node,
            choice.text("roadId"),
            choice.integer("laneId"),
            choice.number("s"),
            choice.number("offset", 0.0),
            orientation(choice),
        )
    if tag == "RelativeLanePosition":
        return RelativeLanePosition(
            node,
            choice.text("entityRef"),
            choice.integer("dLane"),
            choice.optional_number("ds"),
            choice.optional_number("dsLane"),
            choice.number("offset", 0.0),
            orientation(choice),
        )
    if tag == "GeoPosition":
        if choice.has("latitudeDeg"):
            latitude, longitude = choice.number("latitudeDeg"), choice.number("longitudeDeg")
        else:
            latitude = math.degrees(choice.number("latitude"))
            longitude = math.degrees(choice.number("longitude"))
        height = choice.number("altitude", choice.number("height", 0.0))
        return GeoPosition(node, latitude, longitude, height, orientation(choice))
    if tag == "TrajectoryPosition":
        return TrajectoryPosition(
            node,
            trajectory_ref(choice.require("TrajectoryRef"), catalogs),
            choice.number("s"),
            choice.number("t", 0.0),
            orientation(choice),
        )
    if tag == "RoutePosition":
        route = route_ref(choice.require("RouteRef"), catalogs)
        where = choice.require("InRoutePosition").only_child()
        if where is None:
            raise node.error("needs an <InRoutePosition> choice")
        if where.tag == "FromCurrentEntity":
            return RoutePosition(node, route, "entity", entity=where.text("entityRef"))
        if where.tag == "FromRoadCoordinates":
            return RoutePosition(
                node,
                route,
                "road",
                path_s=where.number("pathS"),
                t=where.number("t", 0.0),
                orientation=orientation(choice),
            )
        if where.tag == "FromLaneCoordinates":
            return RoutePosition(
                node,
                route,
                "lane",
                path_s=where.number("pathS"),
                lane=where.integer("laneId"),
                lane_offset=where.number("laneOffset", 0.0),
                orientation=orientation(choice),
            )
        raise where.node.error("is not an InRoutePosition choice")
    raise node.error("is not a supported position")


def trajectory_ref(element: Element, catalogs: CatalogResolver) -> Trajectory:
    """A <TrajectoryRef> (1.1+), or the parent of an inline <Trajectory> or a
    <CatalogReference> to one."""
    inline = element.child("Trajectory")
    if inline is not None:
        return trajectory(inline, catalogs)
    reference = element.child("CatalogReference")
    if reference is not None:
        return trajectory(catalogs.entry(reference), catalogs)
    nested = element.child("TrajectoryRef")
    if nested is not None:
        return trajectory_ref(nested, catalogs)
    raise element.node.error("names no trajectory")


def trajectory(element: Element, catalogs: CatalogResolver) -> Trajectory:
    shape_node = element.require("Shape").only_child()
    if shape_node is None:
        raise element.node.error("has an empty <Shape>")
    return Trajectory(
        element.node,
        element.text("name", ""),
        element.boolean("closed", False),
        _shape(shape_node, catalogs),
    )


def _shape(shape: Element, catalogs: CatalogResolver) -> Shape:
    if shape.tag == "Polyline":
        vertices = []
        for vertex in shape.children("Vertex"):
            vertices.append(
                Vertex(
                    position(vertex.require("Position"), catalogs), vertex.optional_number("time")
                )
            )
        if not vertices:
            raise shape.node.error("has no <Vertex>")
        return Polyline(tuple(vertices))
    if shape.tag == "Clothoid":
        start = shape.child("Position")
        rate = shape.optional_number("curvaturePrime")
        if rate is None:
            rate = shape.number("curvatureDot", 0.0)
        return Clothoid(
            shape.number("curvature"),
            rate,
            shape.number("length"),
            shape.optional_number("startTime"),
            shape.optional_number("stopTime"),
            None if start is None else position(start, catalogs),
        )
    if shape.tag == "ClothoidSpline":
        segments = []
        for segment in shape.children("ClothoidSplineSegment"):
            start = segment.child("PositionStart")
            segments.append(
                ClothoidSegment(
                    segment.number("curvatureStart"),
                    segment.number("curvatureEnd"),
                    segment.number("length"),
                    segment.number("hOffset", 0.0),
                    segment.optional_number("timeStart"),
                    None if start is None else position(start, catalogs),
                )
            )
        if not segments:
            raise shape.node.error("has no <ClothoidSplineSegment>")
        return ClothoidSpline(tuple(segments), shape.optional_number("timeEnd"))
    if shape.tag == "Nurbs":
        points = [
            ControlPoint(
                position(point.require("Position"), catalogs),
                point.number("weight", 1.0),
                point.optional_number("time"),
            )
            for point in shape.children("ControlPoint")
        ]
        knots = tuple(knot.number("value") for knot in shape.children("Knot"))
        order = shape.integer("order")
        if order < 1 or len(knots) != len(points) + order:
            raise shape.node.error(
                f"order {order} with {len(points)} control points needs {len(points) + order} "
                f"knots, it has {len(knots)}"
            )
        return Nurbs(order, tuple(points), knots)
    raise shape.node.error("is not a trajectory shape")


def route_ref(element: Element, catalogs: CatalogResolver) -> Route:
    inline = element.child("Route")
    if inline is not None:
        return route(inline, catalogs)
    reference = element.child("CatalogReference")
    if reference is not None:
        return route(catalogs.entry(reference), catalogs)
    raise element.node.error("names no route")


def route(element: Element, catalogs: CatalogResolver) -> Route:
    waypoints = tuple(
        position(waypoint.require("Position"), catalogs)
        for waypoint in element.children("Waypoint")
    )
    if len(waypoints) < 2:
        raise element.node.error("needs at least two <Waypoint>s")
    return Route(
        element.node, element.text("name", ""), element.boolean("closed", False), waypoints
    )
