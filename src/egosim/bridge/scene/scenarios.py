"""Scenario loading by topic (/ScenarioLoad) and service (/Service_MoraiSL).

ScenarioLoad.file_name comes from the network, so it resolves only inside the
configured scenario roots (a bare name may omit the .yaml, .xosc or .json extension, as
MORAI SIM's own scenario names do), must be a regular file (a named pipe would never
finish), and is read and parsed on the transport's thread (`prepare_scenario`), so the
simulation loop never waits on a user's file; the loop only applies the parsed scenario.
An OpenSCENARIO file's catalogue directories must lie inside the roots too; its map must
be the one running.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Generic, Protocol, TypeVar

from ...datapaths import PathOutsideRootsError, resolve_in_roots
from ...scenario_files import SCENARIO_SUFFIXES, read_scenario_file
from ...world.scenario import Scenario, ScenarioError, ScenarioLoadOptions, ScenarioLoadReport
from ...yamltext import YamlFileError
from ..context import BridgeContext
from ..protocol.network import network_settings_of, section_of
from ..protocol.table import Row
from ..sensors.sensor_rig import sensor_rig_of
from .storyboard import scenario_drives_ego

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

    ScenarioLoadFields = morai_26_r1.ScenarioLoad | morai_26_r1.SyncModeScenarioLoad
    """A scenario-loading request: the topic's message or the sync-mode service's, which
    share the fields read here."""

log = logging.getLogger(__name__)


class ScenarioRequestError(Exception):
    """A ScenarioLoad request that cannot be honoured; the message says why."""


Load = TypeVar("Load", bound="ScenarioLoadFields")
Load_co = TypeVar("Load_co", bound="ScenarioLoadFields", covariant=True)


class LoadingRequest(Protocol[Load_co]):
    """A scenario-loading service's request (MoraiScenarioLoadSrv's, MoraiSyncModeSLSrv's)."""

    @property
    def request(self) -> Load_co: ...


@dataclass(frozen=True)
class ScenarioRequest(Generic[Load]):
    """A ScenarioLoad request with its file read and parsed, or why that failed."""

    request: Load
    """The ScenarioLoad (or SyncModeScenarioLoad) message."""
    scenario: Scenario | None
    error: str = ""


def scenario_path(name: str, roots: tuple[Path, ...]) -> Path:
    for suffix in SCENARIO_SUFFIXES:
        try:
            return resolve_in_roots(name + suffix, roots)
        except FileNotFoundError:
            continue
    raise FileNotFoundError(f"no scenario {name!r} in {[str(root) for root in roots]}")


def load_options(request: ScenarioLoadFields) -> ScenarioLoadOptions:
    return ScenarioLoadOptions(
        delete_all=bool(request.delete_all),
        load_network_connection_data=bool(request.load_network_connection_data),
        load_ego_vehicle_data=bool(request.load_ego_vehicle_data),
        load_surrounding_vehicle_data=bool(request.load_surrounding_vehicle_data),
        load_pedestrian_data=bool(request.load_pedestrian_data),
        load_object_data=bool(request.load_obstacle_data),
        set_pause=bool(request.set_pause),
    )


def read_scenario(request: Load, roots: tuple[Path, ...]) -> ScenarioRequest[Load]:
    """Resolve, read and parse the file a ScenarioLoad names (any thread)."""
    try:
        path = scenario_path(request.file_name, roots)
        return ScenarioRequest(request, read_scenario_file(path, roots=roots))
    except (PathOutsideRootsError, OSError, UnicodeDecodeError, ScenarioError) as error:
        return ScenarioRequest(request, None, f"scenario {request.file_name!r} not loaded: {error}")


def prepare_scenario(
    context: BridgeContext, row: Row, message: morai_26_r1.ScenarioLoad
) -> ScenarioRequest[morai_26_r1.ScenarioLoad]:
    """The /ScenarioLoad topic's message, read (transport thread)."""
    return read_scenario(message, context.data_roots)


def prepare_scenario_service(
    context: BridgeContext, row: Row, request: LoadingRequest[Load]
) -> ScenarioRequest[Load]:
    """A scenario-loading service's request (its `request` field), read (transport thread)."""
    return read_scenario(request.request, context.data_roots)


def load_requested_scenario(context: BridgeContext, prepared: ScenarioRequest[Load]) -> None:
    """Apply a read ScenarioLoad request to the world, or raise ScenarioRequestError."""
    if prepared.scenario is None:
        raise ScenarioRequestError(prepared.error)
    request = prepared.request
    options = replace(load_options(request), scenario_drives_ego=scenario_drives_ego(context))
    try:
        report = context.world.load_scenario(prepared.scenario, options)
    except ScenarioError as error:
        raise ScenarioRequestError(f"scenario {request.file_name!r} not loaded: {error}") from error
    log_scenario_loaded(prepared.scenario, report)
    if report.network_settings is not None:
        apply_network_settings(context, prepared.scenario)


def log_scenario_loaded(scenario: Scenario, report: ScenarioLoadReport, by: str = "") -> None:
    """The line every scenario load leaves on the console, whoever asked (`by`)."""
    log.info(
        "scenario %s loaded%s: ego %s, %d NPCs, %d pedestrians, %d obstacles%s",
        scenario.source.label,
        f" by {by}" if by else "",
        "placed" if report.ego_placed else "kept",
        report.npcs_spawned,
        report.pedestrians_spawned,
        report.obstacles_spawned,
        ", paused" if report.paused else "",
    )
    for note in report.notes:
        log.warning("%s", note)


def apply_network_settings(context: BridgeContext, scenario: Scenario) -> None:
    """A scenario's `network:` section (load_network_connection_data) becomes the table in
    force at once: rows renamed, re-rated, enabled or disabled, the ego input switched,
    the egos' command timeout set, the sensors reconfigured; a section with a mistake
    changes nothing."""
    try:
        settings = network_settings_of(section_of(scenario.source, "network"))
    except YamlFileError as error:
        log.error("scenario network settings not applied: %s", error)
        return
    changes = context.rows.apply_settings(settings) if context.rows is not None else []
    sensors_changed = settings.sensors != context.settings.sensors or (
        settings.row("camera").name != context.settings.row("camera").name
    )
    context.settings = settings
    if settings.command_timeout_s != context.world.command_timeout_s:
        context.world.command_timeout_s = settings.command_timeout_s
        changes.append(f"command timeout {settings.command_timeout_s} s")
    if sensors_changed:
        context.sensors = sensor_rig_of(settings, context.world.map.georef)
        changes.append("sensors reconfigured")
    log.info(
        "scenario network settings applied (ego input %s): %s",
        settings.ego_input,
        "; ".join(changes) or "nothing changed",
    )


def on_scenario_load(
    context: BridgeContext, row: Row, prepared: ScenarioRequest[morai_26_r1.ScenarioLoad]
) -> None:
    try:
        load_requested_scenario(context, prepared)
    except ScenarioRequestError as error:
        log.error("%s: %s", row.name, error)


def serve_scenario_load(
    context: BridgeContext, row: Row, prepared: ScenarioRequest[morai_26_r1.ScenarioLoad]
) -> morai_26_r1.MoraiScenarioLoadSrvResponse:
    """/Service_MoraiSL: MoraiSrvResponse.result true when the scenario was loaded."""
    try:
        load_requested_scenario(context, prepared)
        result = True
    except ScenarioRequestError as error:
        log.error("%s: %s", row.name, error)
        result = False
    return context.profile.message("morai_msgs/MoraiScenarioLoadSrvResponse").new(
        response=context.profile.message("morai_msgs/MoraiSrvResponse").new(result=result)
    )
