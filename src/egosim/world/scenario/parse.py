"""Scenario text or data -> Scenario, validated against scenario.schema.json."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from functools import cache
from importlib import resources
from typing import Any, cast

import jsonschema

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
from egosim.yamltext import FieldPath, Problems, YamlDocument, YamlFileError, parse_yaml

DEFAULT_NPC_MODEL = DEFAULT_EGO_MODEL
DEFAULT_WALK_SPEED_MPS = 1.3
_TIMING_FIELDS = ("green_s", "left_s", "yellow_s", "all_red_s", "flash_s")


@cache
def scenario_schema() -> dict[str, Any]:
    """The JSON Schema of the scenario format."""
    text = resources.files(__package__).joinpath("scenario.schema.json").read_text("utf-8")
    return cast(dict[str, Any], json.loads(text))


def parse_scenario(document: str | Mapping[str, Any], label: str = "<scenario>") -> Scenario:
    """A Scenario from YAML text (or already-parsed data); `label` names it in errors."""
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
    data = source.data
    ego = data.get("ego")
    return Scenario(
        map_name=map_name_of(data["map"]),
        seed=data.get("seed", 0),
        ego=None if ego is None else _ego(ego, ("ego",)),
        npcs=tuple(_npc(n, ("npcs", k)) for k, n in enumerate(data.get("npcs", ()))),
        pedestrians=tuple(
            _pedestrian(p, ("pedestrians", k)) for k, p in enumerate(data.get("pedestrians", ()))
        ),
        obstacles=tuple(
            _obstacle(o, ("obstacles", k)) for k, o in enumerate(data.get("obstacles", ()))
        ),
        signals=_signals(source, data.get("signals", {})),
        network=data.get("network"),
        map_reference=data["map"],
        source=source,
    )


def _pose(data: Mapping[str, Any]) -> PoseStart:
    return PoseStart(
        x=float(data["x"]),
        y=float(data["y"]),
        z=float(data.get("z", 0.0)),
        heading=math.radians(float(data.get("heading_deg", 0.0))),
    )


def _start(data: Mapping[str, Any]) -> Start:
    if "lane" in data:
        return LaneStart(data["lane"], float(data.get("s", 0.0)), float(data.get("lateral", 0.0)))
    return _pose(data)


def _ego(data: Mapping[str, Any], path: FieldPath) -> EgoSpec:
    return EgoSpec(
        path=path,
        model=data.get("model", DEFAULT_EGO_MODEL),
        start=_start(data["start"]),
        speed=float(data.get("speed_mps", 0.0)),
    )


def _npc(data: Mapping[str, Any], path: FieldPath) -> NpcSpec:
    target = data.get("target_speed_mps")
    change = data.get("lane_change")
    return NpcSpec(
        path=path,
        model=data.get("model", DEFAULT_NPC_MODEL),
        start=_start(data["start"]),
        speed=float(data.get("speed_mps", 0.0)),
        target_speed=None if target is None else float(target),
        speed_factor=float(data.get("speed_factor", 1.0)),
        route=tuple(data.get("route", ())),
        start_delay_s=float(data.get("start_delay_s", 0.0)),
        stalled=bool(data.get("stalled", False)),
        lane_change=None if change is None else _lane_change(change),
    )


def _lane_change(data: Mapping[str, Any]) -> LaneChangeSpec:
    return LaneChangeSpec(
        lane=data["lane"],
        after_s=float(data.get("after_s", 0.0)),
        duration_s=float(data.get("duration_s", LaneChangeSpec.duration_s)),
    )


def _pedestrian(data: Mapping[str, Any], path: FieldPath) -> PedestrianSpec:
    waypoints = data.get("waypoints")
    return PedestrianSpec(
        path=path,
        model=data.get("model", DEFAULT_PEDESTRIAN_MODEL),
        speed=float(data.get("speed_mps", DEFAULT_WALK_SPEED_MPS)),
        start_s=float(data.get("start_s", 0.0)),
        sidewalk=data.get("sidewalk"),
        crosswalk=data.get("crosswalk"),
        waypoints=None if waypoints is None else tuple((float(x), float(y)) for x, y in waypoints),
        loop=bool(data.get("loop", True)),
    )


def _obstacle(data: Mapping[str, Any], path: FieldPath) -> ObstacleSpec:
    size = data.get("size")
    return ObstacleSpec(
        path=path,
        model=data.get("model", DEFAULT_OBSTACLE_MODEL),
        pose=_pose(data["pose"]),
        size=None
        if size is None
        else (float(size["length"]), float(size["width"]), float(size["height"])),
    )


def _timing(data: Mapping[str, Any], base: PhaseTiming) -> PhaseTiming:
    values = {name: float(data[name]) for name in _TIMING_FIELDS if name in data}
    return PhaseTiming(**{**{n: getattr(base, n) for n in _TIMING_FIELDS}, **values})


def _signals(source: YamlDocument, data: Mapping[str, Any]) -> SignalsSpec:
    default = _timing(data.get("default", {}), PhaseTiming())
    programs: dict[int, IntersectionProgram] = {}
    paths: dict[int, FieldPath] = {}
    problems = Problems()
    for k, entry in enumerate(data.get("intersections", ())):
        path = ("signals", "intersections", k)
        if entry["id"] in programs:
            problems.add(source.error((*path, "id"), f"intersection {entry['id']} is listed twice"))
            continue
        programs[entry["id"]] = IntersectionProgram(
            timing=_timing(entry, default),
            initial_phase=entry.get("initial_phase", 0),
            initial_elapsed_s=float(entry.get("initial_elapsed_s", 0.0)),
        )
        paths[entry["id"]] = path
    problems.raise_any()
    return SignalsSpec(default, programs, paths)
