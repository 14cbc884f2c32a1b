"""Scenario loading by topic (/ScenarioLoad) and service (/Service_MoraiSL).

ScenarioLoad.file_name comes from the network, so it resolves only inside the
configured scenario roots (a bare name may omit the .yaml extension).
"""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

from ..datapaths import PathOutsideRootsError, resolve_in_roots
from ..world.scenario import ScenarioError, ScenarioLoadOptions, parse_scenario
from .context import BridgeContext
from .table import Row

log = logging.getLogger(__name__)

SCENARIO_SUFFIXES = ("", ".yaml", ".yml")


class ScenarioRequestError(Exception):
    """A ScenarioLoad request that cannot be honoured; the message says why."""


def scenario_path(name: str, roots: tuple[Path, ...]) -> Path:
    for suffix in SCENARIO_SUFFIXES:
        try:
            return resolve_in_roots(name + suffix, roots)
        except FileNotFoundError:
            continue
    raise FileNotFoundError(f"no scenario {name!r} in {[str(root) for root in roots]}")


def load_options(request: Any) -> ScenarioLoadOptions:
    return ScenarioLoadOptions(
        delete_all=bool(request.delete_all),
        load_network_connection_data=bool(request.load_network_connection_data),
        load_ego_vehicle_data=bool(request.load_ego_vehicle_data),
        load_surrounding_vehicle_data=bool(request.load_surrounding_vehicle_data),
        load_pedestrian_data=bool(request.load_pedestrian_data),
        load_object_data=bool(request.load_obstacle_data),
        set_pause=bool(request.set_pause),
    )


def load_requested_scenario(context: BridgeContext, request: Any) -> None:
    """Apply a ScenarioLoad request to the world, or raise ScenarioRequestError."""
    try:
        path = scenario_path(request.file_name, context.data_roots)
        scenario = parse_scenario(path.read_text(encoding="utf-8"), str(path))
        report = context.world.load_scenario(scenario, load_options(request))
    except (PathOutsideRootsError, OSError, UnicodeDecodeError, ScenarioError) as error:
        raise ScenarioRequestError(f"scenario {request.file_name!r} not loaded: {error}") from error
    log.info(
        "scenario %s loaded: ego %s, %d NPCs, %d pedestrians, %d obstacles%s",
        path,
        "placed" if report.ego_placed else "kept",
        report.npcs_spawned,
        report.pedestrians_spawned,
        report.obstacles_spawned,
        ", paused" if report.paused else "",
    )
    if report.network_settings is not None:
        log.info(
            "scenario network settings (applied at the next start with --network): %s",
            report.network_settings,
        )


def on_scenario_load(context: BridgeContext, row: Row, request: Any) -> None:
    try:
        load_requested_scenario(context, request)
    except ScenarioRequestError as error:
        log.error("%s: %s", row.name, error)


def serve_scenario_load(context: BridgeContext, row: Row, request: Any) -> Any:
    """/Service_MoraiSL: MoraiSrvResponse.result true when the scenario was loaded."""
    try:
        load_requested_scenario(context, request.request)
        result = True
    except ScenarioRequestError as error:
        log.error("%s: %s", row.name, error)
        result = False
    return context.profile.message("morai_msgs/MoraiScenarioLoadSrvResponse").new(
        response=context.profile.message("morai_msgs/MoraiSrvResponse").new(result=result)
    )
