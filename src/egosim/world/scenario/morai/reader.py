"""A MORAI SIM scenario (the JSON document MORAI's scenario editor saves) -> Scenario.

What egosim carries out: the map (`mapInfo.mapName`, its offsets as the frame of the
positions), the ego (model by DataID, pose or link and ratio, gear, speed), NPC vehicles
(model by DataID, start, speed, desired speed by km/h or by share of the lane's limit,
active distance), pedestrians (waypoint path or straight walk, speed, loop, active
distance and its standard point), objects (DataID onto obstacle kinds, scale) and the
traffic lights' phases (`tlList`). Everything else is reported, one line per field name
(`MoraiScenario.notes`); docs/scenarios.md lists each field and what becomes of it.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass

from egosim.json_value import JsonObject, JsonValue
from egosim.world.map.georef import GeoReference
from egosim.world.scenario.errors import ScenarioError
from egosim.world.scenario.model import (
    EgoSpec,
    LaneStart,
    NpcSpec,
    ObstacleSpec,
    PedestrianSpec,
    PoseStart,
    Scenario,
    SignalsSpec,
    SignalStart,
    Start,
    map_name_of,
)
from egosim.world.scenario.morai.reading import (
    Ignored,
    Reading,
    entries,
    flag,
    integer,
    mapping,
    number,
    switched_on,
    text,
    truthy,
)
from egosim.world.scenario.morai.units import heading_of, mps, unity_to_enu
from egosim.world.traffic.catalogue import DEFAULT_PEDESTRIAN_MODEL, obstacle_for_data_id
from egosim.world.vehicle import DEFAULT_EGO_MODEL, Gear, model_for_data_id
from egosim.yamltext import FieldPath, YamlDocument

ABSOLUTE = "Absolute"
"""initPositionMode of a start given by `pos` and `rot`; any other mode with an
`initLink` starts on that link."""
VELOCITY_BY_LINK, VELOCITY_CUSTOM = 1, 2
"""velocityType: desiredVelocity is a percentage of the lane's limit, or km/h."""
PEDESTRIAN_PATH = "PedPath - {}"
"""waypointDataList pathName of the path of the pedestrian with that UNIQUEID."""
DEFAULT_MOVING_DISTANCE_M = 5.0
DEFAULT_PEDESTRIAN_SPEED_KMH = 10.0
STANDING_STUB_M = 1.0
"""A pedestrian that does not walk stands at the start of a path this long, facing it."""
_SAME_POINT_M = 1e-6

FIELD_NAMES = {"map": "mapInfo.mapName", "start": "initPosition", "lane": "initLink"}
"""The fields placement errors name, as this format calls them."""
_POSITION_COPY = frozenset({"_x", "_y", "_z"})
"""MORAI writes each coordinate again as text for its editor; the numbers are read."""


@dataclass(frozen=True)
class MoraiScenario:
    scenario: Scenario
    notes: tuple[str, ...]
    """What the file asks that egosim does not do, or does its own way: one line per
    field name, listing where."""


def read_morai_scenario(document: str | bytes, label: str = "<scenario>") -> MoraiScenario:
    """The scenario of a MORAI scenario file's text; ScenarioError names the line of a
    JSON syntax error and the JSON path of anything else (every problem at once)."""
    return _Reader(Reading(label), morai_document(document, label)).scenario()


def morai_document(document: str | bytes, label: str = "<scenario>") -> JsonObject:
    """A MORAI scenario file's JSON object, not yet read; ScenarioError names the line and
    column of a syntax error."""
    try:
        data = json.loads(document)
    except json.JSONDecodeError as error:
        raise ScenarioError(label, error.lineno, "", f"column {error.colno}: {error.msg}") from None
    except (UnicodeDecodeError, RecursionError) as error:
        raise ScenarioError(label, None, "", f"not a JSON document: {error}") from None
    if not isinstance(data, dict):
        raise ScenarioError(label, None, "", "a MORAI scenario is a JSON object")
    return data


def _start_fields(initial: bool) -> frozenset[str]:
    return frozenset({"initPositionMode", "pos", "rot", "initLink", "initLinkRatio"}) | (
        {"gear"} if initial else set()
    )


_TOP_READ = frozenset(
    {"version", "egoVehicle", "vehicleList", "pedestrianList", "objectList", "tlList"}
    | {"mapInfo", "waypointDataList"}
)
_TOP_IGNORED = {
    "spawnPointList": Ignored("spawn points make no NPCs in egosim", truthy),
    "pedspawnPointList": Ignored("pedestrian spawn points make no pedestrians", truthy),
    "aiPedstrianList": Ignored("AI pedestrians are not simulated", truthy),
    "shadedAreaList": Ignored("GPS-shaded areas are not simulated", truthy),
    "frictionChangeMaterialList": Ignored("road friction is not simulated", truthy),
    "v2IInfo": Ignored("V2I is not simulated", switched_on("isAlive")),
}
_ENTRY_READ = frozenset({"DataID", "UNIQUEID", "m_eobstacleObjType"})
"""UNIQUEID names an entry's waypoint path (egosim numbers the objects it places itself);
m_eobstacleObjType repeats the kind the list holds."""
_EGO_IGNORED = {
    "v2vUDPSessionInfo": Ignored("V2V is not simulated", switched_on("isInit")),
    "beforeControlMode": Ignored("the control mode is the stack's (EventInfo, --ctrl-mode)"),
    "currentControlMode": Ignored("the control mode is the stack's (EventInfo, --ctrl-mode)"),
}
_SAVED_STATE = Ignored("the saved drivetrain state is not restored; speed is currentVelocity")
_NPC_IGNORED = {
    "isLaneChange": Ignored("egosim's NPCs change lanes only when a scenario says so", truthy),
    "isCloseLoop": Ignored("egosim's NPCs drive no closed loop", truthy),
    "destinationMode": Ignored("egosim's NPCs have no destination: they keep driving"),
    "spawnPointUniqueID": Ignored("spawn points make no NPCs", lambda v: v not in (-1, None)),
    "bias": Ignored("NPCs drive their lane's centre", truthy),
}
_PEDESTRIAN_ANIMATION = Ignored("pedestrians are boxes: no animation")
_PEDESTRIAN_IGNORED = {
    "anim": _PEDESTRIAN_ANIMATION,
    "stateNameHash": _PEDESTRIAN_ANIMATION,
    "stateNormalizedTime": _PEDESTRIAN_ANIMATION,
    "animSpeed": _PEDESTRIAN_ANIMATION,
    "movingDistanceAmount": Ignored("a walk starts at its beginning", truthy),
    "pedestrianBehavior": Ignored("MORAI's pedestrian behaviours are not modelled"),
    "pedestrianType": Ignored("MORAI's pedestrian types are not modelled"),
    "listObjIDForBehavior": Ignored("MORAI's pedestrian behaviours are not modelled", truthy),
    "waypointEventList": Ignored(
        "waypoint events are not run",
        lambda v: (
            isinstance(v, list)
            and any(isinstance(e, dict) and e.get("waypointEventData") for e in v)
        ),
    ),
}
_OBJECT_IGNORED = {
    "isWaypointMode": Ignored("objects stand where they are placed", truthy),
    "moveSpeed": Ignored("objects stand where they are placed", truthy),
    "activeDistance": Ignored("objects stand where they are placed: nothing to activate"),
    "waypointEventList": _PEDESTRIAN_IGNORED["waypointEventList"],
}
_OBJECT_COPIES = frozenset({"initPos", "initRot"})
"""An object's start again, in Unity's axes; `pos` and `rot` are read."""


class _Reader:
    def __init__(self, r: Reading, data: JsonObject) -> None:
        self.r = r
        self.data = data
        self.paths = self._waypoint_paths()
        self.used_paths: set[str] = set()

    def scenario(self) -> MoraiScenario:
        r, data = self.r, self.data
        map_name, origin = self._map_info()
        ego_data = mapping(r, data, "egoVehicle", ())
        ego = None if ego_data is None else self._ego(ego_data, ("egoVehicle",))
        npcs = [self._npc(item, path) for path, item in entries(r, data, "vehicleList")]
        walkers = [
            self._pedestrian(item, path) for path, item in entries(r, data, "pedestrianList")
        ]
        things = [self._object(item, path) for path, item in entries(r, data, "objectList")]
        starts = [self._signal(item, path) for path, item in entries(r, data, "tlList")]
        r.check_fields(data, (), _TOP_READ, _TOP_IGNORED)
        for name, (k, _) in self.paths.items():
            if name not in self.used_paths:
                r.report(("waypointDataList", k, "pathName"), "a path no pedestrian walks: not run")
        r.problems.raise_any()
        scenario = Scenario(
            map_name=map_name_of(map_name),
            map_reference=map_name,
            ego=ego,
            npcs=tuple(n for n in npcs if n is not None),
            pedestrians=tuple(w for w in walkers if w is not None),
            obstacles=tuple(o for o in things if o is not None),
            signals=SignalsSpec(starts=tuple(s for s in starts if s is not None)),
            origin=origin,
            source=YamlDocument(r.label, data, error_type=ScenarioError),
            field_names=FIELD_NAMES,
        )
        return MoraiScenario(scenario, tuple(r.lines()))

    # -- the map --------------------------------------------------------------------

    def _map_info(self) -> tuple[str, GeoReference | None]:
        r = self.r
        path: FieldPath = ("mapInfo",)
        info = mapping(r, self.data, "mapInfo", (), required=True) or {}
        name = text(r, info, "mapName", path, "")
        if "mapInfo" in self.data and not name:
            r.fail((*path, "mapName"), "missing: the scenario names no map")
        system = text(r, info, "scenarioCoordinateSystem", path, "ENU")
        if system != "ENU":
            r.report((*path, "scenarioCoordinateSystem"), f"{system!r}: positions are read as ENU")
        r.check_fields(
            info,
            path,
            frozenset({"mapName", "eastOffset", "northOffset", "globalCoordinateSystem"})
            | {"scenarioCoordinateSystem"},
            {},
        )
        grid = text(r, info, "globalCoordinateSystem", path, "")
        if not grid or "eastOffset" not in info or "northOffset" not in info:
            return name, None
        east = number(r, info, "eastOffset", path)
        north = number(r, info, "northOffset", path)
        if east is None or north is None:
            return name, None
        try:
            return name, GeoReference.from_projection(grid, (east, north, 0.0))
        except ValueError as error:
            r.fail((*path, "globalCoordinateSystem"), str(error))
            return name, None

    def _waypoint_paths(self) -> dict[str, tuple[int, list[tuple[float, float]]]]:
        """pathName -> its place in waypointDataList and its points, ENU (the file keeps
        them in Unity's axes)."""
        r = self.r
        paths: dict[str, tuple[int, list[tuple[float, float]]]] = {}
        for path, item in entries(r, self.data, "waypointDataList"):
            name = text(r, item, "pathName", path, "")
            points: list[tuple[float, float]] = []
            waypoints = item.get("waypointData", [])
            if not isinstance(waypoints, list):
                r.fail((*path, "waypointData"), "expected a list")
                waypoints = []
            for k, waypoint in enumerate(waypoints):
                where = (*path, "waypointData", k)
                if not isinstance(waypoint, dict):
                    r.fail(where, "expected an object")
                    continue
                # A waypoint's rot is the editor's: a walk faces the way it goes.
                pos = mapping(r, waypoint, "pos", where, required=True)
                vector = None if pos is None else self._vector(pos, (*where, "pos"))
                if vector is not None:
                    east, north, _ = unity_to_enu(*vector)
                    points.append((east, north))
            r.check_fields(item, path, frozenset({"pathName", "waypointData"}), {})
            index = path[-1]
            assert isinstance(index, int)  # entries() gives (list name, index)
            paths[name] = (index, points)
        return paths

    # -- shared pieces --------------------------------------------------------------

    def _vector(
        self,
        data: Mapping[str, JsonValue],
        path: FieldPath,
        keys: tuple[str, str, str] = ("x", "y", "z"),
    ) -> tuple[float, float, float] | None:
        values = [number(self.r, data, key, path) for key in keys]
        self.r.check_fields(data, path, frozenset(keys) | _POSITION_COPY, {})
        if any(v is None for v in values):
            return None
        x, y, z = (float(v) for v in values if v is not None)
        return x, y, z

    def _yaw(self, data: Mapping[str, JsonValue], path: FieldPath) -> float:
        """The heading of a `rot` object (rad); roll and pitch come from the road."""
        rot = mapping(self.r, data, "rot", path)
        if rot is None:
            return 0.0
        where = (*path, "rot")
        yaw = number(self.r, rot, "yaw", where, default=0.0) or 0.0
        for key in ("roll", "pitch"):
            angle = number(self.r, rot, key, where, default=0.0) or 0.0
            if abs(math.remainder(angle, 360.0)) > 1e-6:
                self.r.report((*where, key), "not carried out: the road sets roll and pitch")
        self.r.check_fields(rot, where, frozenset({"yaw", "roll", "pitch"}), {})
        return heading_of(yaw)

    def _pose(self, data: Mapping[str, JsonValue], path: FieldPath) -> PoseStart | None:
        pos = mapping(self.r, data, "pos", path, required=True)
        vector = None if pos is None else self._vector(pos, (*path, "pos"))
        heading = self._yaw(data, path)
        if vector is None:
            return None
        x, y, z = vector
        return PoseStart(x, y, z, heading)

    def _start(self, data: Mapping[str, JsonValue], path: FieldPath) -> Start | None:
        """An initPosition: `pos` and `rot`, or a link and the ratio along it."""
        r = self.r
        mode = text(r, data, "initPositionMode", path, ABSOLUTE)
        link = text(r, data, "initLink", path, "")
        if link and (mode != ABSOLUTE or "pos" not in data):
            ratio = number(r, data, "initLinkRatio", path, default=0.0, minimum=0.0)
            if ratio is not None and ratio > 1.0:
                r.fail((*path, "initLinkRatio"), f"{ratio:g} is more than 1 (the link's end)")
                return None
            self._yaw(data, path)
            return None if ratio is None else LaneStart(link, ratio=ratio)
        return self._pose(data, path)

    def _vehicle_model(self, data: Mapping[str, JsonValue], path: FieldPath, default: str) -> str:
        data_id = integer(self.r, data, "DataID", path)
        if data_id is None:
            return default
        model = model_for_data_id(data_id)
        if model is None:
            self.r.report(
                (*path, "DataID"), f"{data_id}: no egosim model for it; drives as {default}"
            )
            return default
        return model.name

    # -- the ego --------------------------------------------------------------------

    def _ego(self, data: Mapping[str, JsonValue], path: FieldPath) -> EgoSpec | None:
        r = self.r
        model = self._vehicle_model(data, path, DEFAULT_EGO_MODEL)
        speed = number(r, data, "currentVelocity", path, default=0.0, minimum=0.0)
        init = mapping(r, data, "initPosition", path, required=True)
        where = (*path, "initPosition")
        start = None if init is None else self._start(init, where)
        gear = None if init is None else self._gear(init, where)
        if init is not None:
            r.check_fields(init, where, _start_fields(True), {"vehicleSaveData": _SAVED_STATE})
        r.check_fields(data, path, _ENTRY_READ | {"initPosition", "currentVelocity"}, _EGO_IGNORED)
        if start is None or speed is None:
            return None
        return EgoSpec(path=path, model=model, start=start, speed=mps(speed), gear=gear)

    def _gear(self, data: Mapping[str, JsonValue], path: FieldPath) -> Gear | None:
        value = integer(self.r, data, "gear", path, default=0)
        if value is None or "gear" not in data:
            return None
        try:
            return Gear(value)
        except ValueError:
            self.r.fail((*path, "gear"), f"{value} is not a gear (1 P, 2 R, 3 N, 4 D)")
            return None

    # -- NPC vehicles ---------------------------------------------------------------

    def _npc(self, data: Mapping[str, JsonValue], path: FieldPath) -> NpcSpec | None:
        r = self.r
        model = self._vehicle_model(data, path, DEFAULT_EGO_MODEL)
        init = mapping(r, data, "initPosition", path, required=True)
        where = (*path, "initPosition")
        start = None if init is None else self._start(init, where)
        if init is not None:
            ignored = {
                "gear": Ignored("NPCs drive themselves"),
                "vehicleSaveData": _SAVED_STATE,
            }
            r.check_fields(init, where, _start_fields(False), ignored)
        speed = number(r, data, "currentVelocity", path, default=0.0, minimum=0.0)
        desired = self._desired_speed(data, path)
        active = number(r, data, "activeDistance", path, default=math.inf, minimum=0.0)
        read = {"initPosition", "currentVelocity", "velocityType", "desiredVelocity"}
        r.check_fields(data, path, _ENTRY_READ | read | {"activeDistance"}, _NPC_IGNORED)
        if start is None or speed is None or desired is None or active is None:
            return None
        target, factor = desired
        return NpcSpec(
            path=path,
            model=model,
            start=start,
            speed=mps(speed),
            target_speed=target,
            speed_factor=factor,
            stalled=target == 0.0 or factor == 0.0,
            active_distance=None if math.isinf(active) else active,
        )

    def _desired_speed(
        self, data: Mapping[str, JsonValue], path: FieldPath
    ) -> tuple[float | None, float] | None:
        """(target speed m/s or None, share of the lane's limit) of velocityType and
        desiredVelocity."""
        r = self.r
        kind = integer(r, data, "velocityType", path, default=VELOCITY_CUSTOM)
        if "velocityType" not in data and "desiredVelocity" not in data:
            return None, 1.0
        desired = number(r, data, "desiredVelocity", path, minimum=0.0)
        if kind is None or desired is None:
            return None
        if kind == VELOCITY_BY_LINK:
            return None, desired / 100.0
        if kind != VELOCITY_CUSTOM:
            r.report(
                (*path, "velocityType"),
                f"{kind} is neither 1 (share of the limit) nor 2 (km/h); desiredVelocity "
                "is read as km/h",
            )
        return mps(desired), 1.0

    # -- pedestrians ----------------------------------------------------------------

    def _pedestrian(self, data: Mapping[str, JsonValue], path: FieldPath) -> PedestrianSpec | None:
        r = self.r
        data_id = integer(r, data, "DataID", path)
        if data_id is not None:
            r.report(
                (*path, "DataID"),
                f"MORAI's pedestrian models are not told apart: walks as "
                f"{DEFAULT_PEDESTRIAN_MODEL}",
            )
        pose = self._pose(data, path)
        speed = number(r, data, "speed", path, default=DEFAULT_PEDESTRIAN_SPEED_KMH, minimum=0.0)
        loop = flag(r, data, "loop", path, False)
        active = flag(r, data, "active", path, True)
        distance = number(r, data, "activeDistance", path, default=math.inf, minimum=0.0)
        moving = number(
            r, data, "movingDistance", path, default=DEFAULT_MOVING_DISTANCE_M, minimum=0.0
        )
        wake = self._standard_point(data, path)
        points = self._walk(data, path, pose, moving)
        read = {"pos", "rot", "speed", "loop", "active", "activeDistance", "movingDistance"}
        read |= {"standardPos", "isWaypointMode", "initPos", "initRot"}
        r.check_fields(data, path, _ENTRY_READ | read, _PEDESTRIAN_IGNORED)
        if pose is None or speed is None or distance is None or points is None:
            return None
        walks = speed > 0.0 and len(points) > 1
        if not walks:
            x, y = points[0]
            heading = pose.heading
            points = [
                (x, y),
                (x + STANDING_STUB_M * math.cos(heading), y + STANDING_STUB_M * math.sin(heading)),
            ]
        return PedestrianSpec(
            path=path,
            model=DEFAULT_PEDESTRIAN_MODEL,
            speed=mps(speed) if walks else 0.0,
            waypoints=tuple(points),
            loop=loop and walks,
            active_distance=None if not active or math.isinf(distance) else distance,
            wake_point=wake,
        )

    def _walk(
        self,
        data: Mapping[str, JsonValue],
        path: FieldPath,
        pose: PoseStart | None,
        moving: float | None,
    ) -> list[tuple[float, float]] | None:
        """The points walked: the waypoint path in waypoint mode, else `movingDistance`
        m straight ahead from `pos`; consecutive repeats dropped."""
        r = self.r
        if pose is None or moving is None:
            return None
        if flag(r, data, "isWaypointMode", path, False):
            unique_id = data.get("UNIQUEID")
            name = PEDESTRIAN_PATH.format(unique_id)
            _, points = self.paths.get(name, (0, None))
            if points is not None:
                self.used_paths.add(name)
                return _distinct(points) if points else [(pose.x, pose.y)]
            r.report(
                (*path, "isWaypointMode"),
                "no waypointDataList path is named after its UNIQUEID "
                f"({PEDESTRIAN_PATH.format('UNIQUEID')!r}): walks movingDistance straight ahead",
            )
        ahead = (pose.x + moving * math.cos(pose.heading), pose.y + moving * math.sin(pose.heading))
        return _distinct([(pose.x, pose.y), ahead])

    def _standard_point(
        self, data: Mapping[str, JsonValue], path: FieldPath
    ) -> tuple[float, float] | None:
        """Where the active distance is measured from (`standardPos`, Unity's axes)."""
        standard = mapping(self.r, data, "standardPos", path)
        vector = None if standard is None else self._vector(standard, (*path, "standardPos"))
        if vector is None:
            return None
        east, north, _ = unity_to_enu(*vector)
        return east, north

    # -- objects --------------------------------------------------------------------

    def _object(self, data: Mapping[str, JsonValue], path: FieldPath) -> ObstacleSpec | None:
        r = self.r
        data_id = integer(r, data, "DataID", path)
        pose = self._pose(data, path)
        scale = mapping(r, data, "scale", path)
        factors = (1.0, 1.0, 1.0) if scale is None else self._vector(scale, (*path, "scale"))
        if factors is not None and min(factors) <= 0.0:
            r.fail((*path, "scale"), f"{factors} has a part that is not above 0")
            factors = None
        r.check_fields(
            data, path, _ENTRY_READ | {"pos", "rot", "scale"} | _OBJECT_COPIES, _OBJECT_IGNORED
        )
        if data_id is None or pose is None or factors is None:
            return None
        model = obstacle_for_data_id(data_id)
        if model is None:
            r.report((*path, "DataID"), f"{data_id}: no egosim obstacle for it; not placed")
            return None
        # Unity's local axes: x across the object, y up, z along it.
        across, up, along = factors
        size = (model.length * along, model.width * across, model.height * up)
        return ObstacleSpec(path=path, model=model.name, pose=pose, size=size)

    # -- traffic lights -------------------------------------------------------------

    def _signal(self, data: Mapping[str, JsonValue], path: FieldPath) -> SignalStart | None:
        r = self.r
        index = integer(r, data, "index", path)
        phase = integer(r, data, "state", path)
        elapsed = number(r, data, "deltaTime", path, default=0.0, minimum=0.0)
        r.check_fields(data, path, frozenset({"index", "state", "deltaTime"}), {})
        for key, value in (("index", index), ("state", phase)):
            if value is not None and value < 0:
                r.fail((*path, key), f"{value} is negative")
                return None
        if index is None or phase is None or elapsed is None:
            return None
        return SignalStart(path=path, index=index, phase=phase, elapsed_s=elapsed)


def _distinct(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    kept = points[:1]
    for point in points[1:]:
        if math.dist(point, kept[-1]) > _SAME_POINT_M:
            kept.append(point)
    return kept


__all__ = ["MoraiScenario", "morai_document", "read_morai_scenario"]
