"""MORAI SIM scenario documents the tests write, in the layout MORAI's editor saves: numbers
as MORAI writes them (rotations as text), each coordinate again as text, Unity's axes for
waypoint paths."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

TOWN_ORIGIN = (313000.0, 4161000.0)
"""Where the built-in maps and the shipped MGeo sample sit in UTM zone 52N."""


def vector(x: float, y: float, z: float) -> dict[str, Any]:
    return {"x": x, "y": y, "z": z, "_x": f"{x:,.3f}", "_y": f"{y:,.3f}", "_z": f"{z:,.3f}"}


def rotation(yaw_deg: float, roll_deg: float = 0.0, pitch_deg: float = 0.0) -> dict[str, str]:
    return {"roll": f"{roll_deg:.3f}", "pitch": f"{pitch_deg:.3f}", "yaw": f"{yaw_deg:.3f}"}


def unity(east: float, north: float, up: float = 0.0) -> dict[str, Any]:
    """An ENU point written in Unity's axes (x = -east, y = up, z = -north)."""
    return vector(-east, up, -north)


def at_pose(x: float, y: float, yaw_deg: float, z: float = 0.0) -> dict[str, Any]:
    return {
        "initPositionMode": "Absolute",
        "pos": vector(x, y, z),
        "rot": rotation(yaw_deg),
        "initLink": "",
        "initLinkRatio": 0,
    }


def on_link(link: str, ratio: float) -> dict[str, Any]:
    return {
        "initPositionMode": "Link",
        "pos": vector(0.0, 0.0, 0.0),
        "rot": rotation(0.0),
        "initLink": link,
        "initLinkRatio": ratio,
    }


def ego(init: dict[str, Any], data_id: int = 20200003, gear: int = 4, kmh: float = 0.0) -> dict:
    return {
        "DataID": data_id,
        "UNIQUEID": -1,
        "m_eobstacleObjType": 0,
        "initPosition": {**init, "gear": gear},
        "currentVelocity": kmh,
    }


def npc(
    init: dict[str, Any],
    uid: int,
    data_id: int = 30100010,
    desired_kmh: float = 30.0,
    velocity_type: int = 2,
    kmh: float = 0.0,
    active_distance: float = 999.0,
    **extra: Any,
) -> dict[str, Any]:
    return {
        "DataID": data_id,
        "UNIQUEID": uid,
        "m_eobstacleObjType": 1,
        "initPosition": {**init, "gear": 4},
        "velocityType": velocity_type,
        "desiredVelocity": desired_kmh,
        "currentVelocity": kmh,
        "isCloseLoop": False,
        "isLaneChange": False,
        "activeDistance": active_distance,
        **extra,
    }


def pedestrian(
    x: float,
    y: float,
    yaw_deg: float,
    uid: int,
    kmh: float = 5.0,
    active_distance: float = 999.0,
    waypoints: bool = False,
    moving_m: float = 5.0,
    loop: bool = False,
    standard: tuple[float, float] | None = None,
    **extra: Any,
) -> dict[str, Any]:
    return {
        "DataID": 50100001,
        "UNIQUEID": uid,
        "m_eobstacleObjType": 2,
        "pos": vector(x, y, 0.0),
        "rot": rotation(yaw_deg),
        "activeDistance": active_distance,
        "speed": kmh,
        "active": True,
        "loop": loop,
        "initPos": unity(x, y),
        "movingDistance": moving_m,
        "standardPos": unity(*(standard or (x, y))),
        "isWaypointMode": waypoints,
        **extra,
    }


def path(uid: int, *points: tuple[float, float]) -> dict[str, Any]:
    """A pedestrian's waypoint path through ENU `points`, as MORAI stores it."""
    return {
        "pathName": f"PedPath - {uid}",
        "waypointData": [{"pos": unity(x, y), "rot": rotation(0.0)} for x, y in points],
    }


def thing(
    x: float, y: float, yaw_deg: float, uid: int, data_id: int, scale: float = 1.0
) -> dict[str, Any]:
    return {
        "DataID": data_id,
        "UNIQUEID": uid,
        "m_eobstacleObjType": 4,
        "pos": vector(x, y, 0.0),
        "rot": rotation(yaw_deg),
        "scale": vector(scale, scale, scale),
    }


def scenario(
    map_name: str,
    ego_entry: dict[str, Any] | None = None,
    vehicles: tuple[dict[str, Any], ...] = (),
    pedestrians: tuple[dict[str, Any], ...] = (),
    objects: tuple[dict[str, Any], ...] = (),
    lights: tuple[dict[str, Any], ...] = (),
    paths: tuple[dict[str, Any], ...] = (),
    origin: tuple[float, float] = TOWN_ORIGIN,
) -> dict[str, Any]:
    document: dict[str, Any] = {"version": 1.0}
    if ego_entry is not None:
        document["egoVehicle"] = ego_entry
    document |= {
        "vehicleList": list(vehicles),
        "pedestrianList": list(pedestrians),
        "objectList": list(objects),
        "spawnPointList": [],
        "tlList": list(lights),
        "mapInfo": {
            "mapName": map_name,
            "eastOffset": origin[0],
            "northOffset": origin[1],
            "globalCoordinateSystem": "UTM52N",
            "scenarioCoordinateSystem": "ENU",
        },
        "waypointDataList": list(paths),
    }
    return document


def text(document: dict[str, Any]) -> str:
    return json.dumps(document, indent=2)


def write(folder: Path, name: str, document: dict[str, Any]) -> Path:
    path = folder / name
    path.write_text(text(document), encoding="utf-8")
    return path
