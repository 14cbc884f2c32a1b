"""Scenario text or data -> Scenario, validated against scenario.schema.json."""

from __future__ import annotations

import json
import math
from functools import cache
from importlib import resources
from typing import cast

import jsonschema

from egosim.json_value import JsonObject, JsonValue
from egosim.world.scenario.errors import ScenarioError
from egosim.world.scenario.model import (
    EgoSpec,
    LaneChangeSpec,
    LaneStart,
    NpcSpec,
    ObstacleSpec,
    PedestrianSpec,
    PoseStart,
    Scenario,
    SignalsSpec,
    Start,
    map_name_of,
)
from egosim.world.signals import IntersectionProgram, PhaseTiming
from egosim.world.traffic.catalogue import DEFAULT_OBSTACLE_MODEL, DEFAULT_PEDESTRIAN_MODEL
from egosim.world.vehicle import DEFAULT_EGO_MODEL
from egosim.yamltext import (
    FieldPath,
    Problems,
    YamlDocument,
    YamlFileError,
    as_list,
    as_number,
    as_object,
    as_text,
    flag_at,
    integer_at,
    list_at,
    number_at,
    object_at,
    objects_at,
    optional_number_at,
    optional_text_at,
    parse_yaml,
    text_at,
)

DEFAULT_NPC_MODEL = DEFAULT_EGO_MODEL
DEFAULT_WALK_SPEED_MPS = 1.3
_TIMING_FIELDS = ("green_s", "left_s", "yellow_s", "all_red_s", "flash_s")


@cache
def scenario_schema() -> JsonObject:
    """The JSON Schema of the scenario format."""
    text = resources.files(__package__).joinpath("scenario.schema.json").read_text("utf-8")
    return as_object(json.loads(text))


def parse_scenario(document: JsonValue, label: str = "<scenario>") -> Scenario:
    """A Scenario from YAML text (a string) or already-parsed data; `label` names it in
    errors."""
    if isinstance(document, str):
        source = parse_yaml(document, label, ScenarioError)
    else:
        source = YamlDocument(label, document, error_type=ScenarioError)
    _validate(source)
    return _build(source)


def _validate(source: YamlDocument) -> None:
    """Every schema violation of the file, each at its own line, at once."""
    validator = jsonschema.Draft202012Validator(scenario_schema())
    errors: list[YamlFileError] = []
    for violation in validator.iter_errors(source.data):
        error = _telling(violation)
        path = tuple(error.absolute_path)
        if error.validator == "additionalProperties" and isinstance(error.instance, dict):
            # Point at each unexpected key rather than at the mapping holding it.
            schema = error.schema
            allowed = set(schema.get("properties", {})) if isinstance(schema, dict) else set()
            unexpected = [key for key in error.instance if key not in allowed]
            errors += [source.error((*path, k), f"unknown field {k!r}") for k in unexpected]
            if unexpected:
                continue
        errors.append(source.error(path, error.message))
    if errors:
        raise ScenarioError.of_all(errors)


def _telling(violation: jsonschema.ValidationError) -> jsonschema.ValidationError:
    """The error to show for a violation. A oneOf (a start is a pose or a lane start)
    holds each branch's errors: those of a branch whose fields the entry uses (one with
    no unknown-field error) tell the user what is wrong with what they wrote."""
    if violation.validator == "oneOf" and violation.context:
        branches: dict[object, list[jsonschema.ValidationError]] = {}
        for error in violation.context:
            branches.setdefault(error.relative_schema_path[0], []).append(error)
        meant = [
            errors
            for errors in branches.values()
            if not any(e.validator == "additionalProperties" for e in errors)
        ]
        if len(meant) == 1:
            return cast(jsonschema.ValidationError, jsonschema.exceptions.best_match(meant[0]))
    return cast(jsonschema.ValidationError, jsonschema.exceptions.best_match([violation]))


def _build(source: YamlDocument) -> Scenario:
    data = as_object(source.data)
    ego = object_at(data, "ego")
    return Scenario(
        map_name=map_name_of(text_at(data, "map")),
        seed=integer_at(data, "seed", 0),
        ego=None if ego is None else _ego(ego, ("ego",)),
        npcs=tuple(_npc(n, ("npcs", k)) for k, n in enumerate(objects_at(data, "npcs"))),
        pedestrians=tuple(
            _pedestrian(p, ("pedestrians", k))
            for k, p in enumerate(objects_at(data, "pedestrians"))
        ),
        obstacles=tuple(
            _obstacle(o, ("obstacles", k)) for k, o in enumerate(objects_at(data, "obstacles"))
        ),
        signals=_signals(source, object_at(data, "signals") or {}),
        network=object_at(data, "network"),
        map_reference=text_at(data, "map"),
        source=source,
    )


def _pose(data: JsonObject) -> PoseStart:
    return PoseStart(
        x=number_at(data, "x"),
        y=number_at(data, "y"),
        z=number_at(data, "z", 0.0),
        heading=math.radians(number_at(data, "heading_deg", 0.0)),
    )


def _start(data: JsonObject) -> Start:
    if "lane" in data:
        return LaneStart(
            text_at(data, "lane"), number_at(data, "s", 0.0), number_at(data, "lateral", 0.0)
        )
    return _pose(data)


def _ego(data: JsonObject, path: FieldPath) -> EgoSpec:
    return EgoSpec(
        path=path,
        model=text_at(data, "model", DEFAULT_EGO_MODEL),
        start=_start(as_object(data["start"])),
        speed=number_at(data, "speed_mps", 0.0),
    )


def _npc(data: JsonObject, path: FieldPath) -> NpcSpec:
    change = object_at(data, "lane_change")
    return NpcSpec(
        path=path,
        model=text_at(data, "model", DEFAULT_NPC_MODEL),
        start=_start(as_object(data["start"])),
        speed=number_at(data, "speed_mps", 0.0),
        target_speed=optional_number_at(data, "target_speed_mps"),
        speed_factor=number_at(data, "speed_factor", 1.0),
        route=tuple(as_text(lane) for lane in list_at(data, "route")),
        start_delay_s=number_at(data, "start_delay_s", 0.0),
        stalled=flag_at(data, "stalled", False),
        lane_change=None if change is None else _lane_change(change),
    )


def _lane_change(data: JsonObject) -> LaneChangeSpec:
    return LaneChangeSpec(
        lane=text_at(data, "lane"),
        after_s=number_at(data, "after_s", 0.0),
        duration_s=number_at(data, "duration_s", LaneChangeSpec.duration_s),
    )


def _pedestrian(data: JsonObject, path: FieldPath) -> PedestrianSpec:
    waypoints = data.get("waypoints")
    return PedestrianSpec(
        path=path,
        model=text_at(data, "model", DEFAULT_PEDESTRIAN_MODEL),
        speed=number_at(data, "speed_mps", DEFAULT_WALK_SPEED_MPS),
        start_s=number_at(data, "start_s", 0.0),
        sidewalk=optional_text_at(data, "sidewalk"),
        crosswalk=optional_text_at(data, "crosswalk"),
        waypoints=None if waypoints is None else tuple(_point(p) for p in as_list(waypoints)),
        loop=flag_at(data, "loop", True),
    )


def _point(value: JsonValue) -> tuple[float, float]:
    x, y = as_list(value)
    return as_number(x), as_number(y)


def _obstacle(data: JsonObject, path: FieldPath) -> ObstacleSpec:
    size = object_at(data, "size")
    return ObstacleSpec(
        path=path,
        model=text_at(data, "model", DEFAULT_OBSTACLE_MODEL),
        pose=_pose(as_object(data["pose"])),
        size=None
        if size is None
        else (number_at(size, "length"), number_at(size, "width"), number_at(size, "height")),
    )


def _timing(data: JsonObject, base: PhaseTiming) -> PhaseTiming:
    values = {name: number_at(data, name) for name in _TIMING_FIELDS if name in data}
    return PhaseTiming(**{**{n: getattr(base, n) for n in _TIMING_FIELDS}, **values})


def _signals(source: YamlDocument, data: JsonObject) -> SignalsSpec:
    default = _timing(object_at(data, "default") or {}, PhaseTiming())
    programs: dict[int, IntersectionProgram] = {}
    paths: dict[int, FieldPath] = {}
    problems = Problems()
    for k, entry in enumerate(objects_at(data, "intersections")):
        path = ("signals", "intersections", k)
        number = integer_at(entry, "id")
        if number in programs:
            problems.add(source.error((*path, "id"), f"intersection {entry['id']} is listed twice"))
            continue
        programs[number] = IntersectionProgram(
            timing=_timing(entry, default),
            initial_phase=integer_at(entry, "initial_phase", 0),
            initial_elapsed_s=number_at(entry, "initial_elapsed_s", 0.0),
        )
        paths[number] = path
    problems.raise_any()
    return SignalsSpec(default, programs, paths)
