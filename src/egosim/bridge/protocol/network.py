"""The network settings file: MORAI's Network Settings tab as a YAML override of the table.

ego_input: MoraiCmdController      # or WeBOTCmdController, GVDirectCmd, GVStateCmd,
                                   # GhostCtrlCmd
rows:
  ego_status: {name: /Ego_topic, rate_hz: 100}
  collision: {enabled: false}
sensors:                           # mounts, noise, LiDAR geometry (sensor_settings.py)
  lidar: {channels: 32}
command_timeout_s: 0.5             # dead-man brake after this silence; off when absent
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace

from ...json_value import JsonObject, JsonValue
from ...yamltext import Problems, YamlDocument, YamlFileError, parse_yaml
from .sensor_settings import SensorSettings, parse_sensor_settings
from .table import DEFAULT_EGO_INPUT, EGO_INPUT_ROWS, ROWS, ROWS_BY_KEY, Direction, Row

ROS_NAME = re.compile(r"^[~/]?[A-Za-z][\w/]*$")
ROW_FIELDS = {"name", "rate_hz", "enabled"}
SETTINGS = ("ego_input", "rows", "sensors", "command_timeout_s")
MAX_COMMAND_TIMEOUT_S = 3600.0


@dataclass(frozen=True)
class NetworkSettings:
    """The effective table: every row with its name, rate and on/off decided."""

    ego_input: str
    rows: tuple[Row, ...]
    sensors: SensorSettings = field(default_factory=SensorSettings)
    command_timeout_s: float | None = None
    """Dead-man timeout of the ego commands (s of simulation time without a CtrlCmd or
    SyncModeCtrlCmd before the ego brakes); None: the last command holds."""

    def row(self, key: str) -> Row:
        return next(row for row in self.rows if row.key == key)

    def enabled_rows(self) -> list[Row]:
        return [row for row in self.rows if row.enabled]


def default_network_settings() -> NetworkSettings:
    return settings_for(DEFAULT_EGO_INPUT, {})


def settings_for(ego_input: str, overrides: dict[str, Row]) -> NetworkSettings:
    live_input_row = EGO_INPUT_ROWS[ego_input]
    rows = []
    for row in ROWS:
        row = overrides.get(row.key, row)  # noqa: PLW2901 - the override replaces the default
        if row.key in EGO_INPUT_ROWS.values():
            row = replace(row, enabled=row.key == live_input_row)  # noqa: PLW2901
        rows.append(row)
    return NetworkSettings(ego_input, tuple(rows))


def parse_network_settings(text: str, label: str) -> NetworkSettings:
    """Settings from a YAML text; errors name the file, line and field, all at once."""
    return network_settings_of(parse_yaml(text, label))


def section_of(document: YamlDocument, key: str) -> YamlDocument:
    """The part of `document` under `key` (a scenario's `network:`), as a document of its
    own whose errors still name the file's lines."""
    data = document.data.get(key) if isinstance(document.data, dict) else None
    lines = {path[1:]: line for path, line in document.lines.items() if path[:1] == (key,)}
    return YamlDocument(document.label, data, lines, document.error_type)


def network_settings_of(document: YamlDocument) -> NetworkSettings:
    """Settings from a parsed document; errors name the file, line and field, and every
    problem of the document is reported at once."""
    data = document.data if document.data is not None else {}
    if not isinstance(data, dict):
        raise document.error((), f"expected a mapping with any of {', '.join(SETTINGS)}")
    problems = Problems()
    for key in sorted(set(data) - set(SETTINGS), key=str):
        problems.add(document.error((key,), f"unknown setting (known: {', '.join(SETTINGS)})"))
    ego_input = data.get("ego_input", DEFAULT_EGO_INPUT)
    if not isinstance(ego_input, str) or ego_input not in EGO_INPUT_ROWS:
        problems.add(document.error(("ego_input",), f"must be one of {', '.join(EGO_INPUT_ROWS)}"))
        ego_input = DEFAULT_EGO_INPUT
    rows = data.get("rows") or {}
    overrides: dict[str, Row] = {}
    if not isinstance(rows, dict):
        problems.add(document.error(("rows",), "expected a mapping of row key to settings"))
        rows = {}
    for key, value in rows.items():
        with problems.collecting():
            overrides[key] = _override(document, key, value)
    sensors = SensorSettings()
    with problems.collecting():
        sensors = parse_sensor_settings(document, data.get("sensors"))
    timeout = None
    with problems.collecting():
        timeout = _command_timeout(document, data.get("command_timeout_s"))
    problems.raise_any()
    return replace(settings_for(ego_input, overrides), sensors=sensors, command_timeout_s=timeout)


def _command_timeout(document: YamlDocument, value: JsonValue) -> float | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise document.error(("command_timeout_s",), "expected a number of seconds, or null")
    if not 0.0 < value <= MAX_COMMAND_TIMEOUT_S:
        raise document.error(
            ("command_timeout_s",), f"must be in (0, {MAX_COMMAND_TIMEOUT_S:g}] s, or null (off)"
        )
    return float(value)


def _override(document: YamlDocument, key: str, value: JsonValue) -> Row:
    path = ("rows", str(key))
    if key not in ROWS_BY_KEY:
        raise document.error(path, "unknown row (see `egosim topics` for the keys)")
    if not isinstance(value, dict):
        raise document.error(path, "expected a mapping with name, rate_hz, enabled")
    row = ROWS_BY_KEY[key]
    problems = Problems()
    for field_name in value:
        if field_name not in ROW_FIELDS:
            problems.add(
                document.error((*path, str(field_name)), "unknown field (name, rate_hz, enabled)")
            )
    name = value.get("name", row.name)
    if not isinstance(name, str) or not ROS_NAME.match(name):
        problems.add(document.error((*path, "name"), f"not a valid ROS name: {name!r}"))
        name = row.name
    enabled = value.get("enabled", row.enabled)
    if not isinstance(enabled, bool):
        problems.add(document.error((*path, "enabled"), "expected true or false"))
        enabled = row.enabled
    if key in EGO_INPUT_ROWS.values() and "enabled" in value:
        problems.add(
            document.error((*path, "enabled"), "ego command inputs are chosen by ego_input")
        )
    rate = row.rate_hz
    with problems.collecting():
        rate = _rate(document, path, row, value)
    problems.raise_any()
    return replace(row, name=name, enabled=enabled, rate_hz=rate)


def _rate(
    document: YamlDocument, path: tuple[str, ...], row: Row, value: JsonObject
) -> float | None:
    """The row's rate_hz, if the file sets one, checked."""
    if "rate_hz" not in value:
        return row.rate_hz
    rate = value["rate_hz"]
    if row.direction is not Direction.PUBLISH:
        raise document.error((*path, "rate_hz"), "only publishers have a rate")
    if isinstance(rate, bool) or not isinstance(rate, int | float):
        raise document.error((*path, "rate_hz"), "expected a number of Hz")
    if not (math.isfinite(rate) and 0 < rate <= MAX_RATE_HZ):
        raise document.error((*path, "rate_hz"), f"must be in 0..{MAX_RATE_HZ:g} Hz (above 0)")
    return rate


#: No row publishes faster than this (the physics runs at 100 Hz by default).
MAX_RATE_HZ = 1000.0


def load_network_settings(path: str | None) -> NetworkSettings:
    """The settings of the file at `path`, or the defaults when no file is given."""
    if path is None:
        return default_network_settings()
    with open(path, "rb") as file:
        data = file.read()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise YamlFileError(path, None, "", f"not UTF-8 text ({error.reason})") from None
    return parse_network_settings(text, path)
