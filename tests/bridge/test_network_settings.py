"""The network settings file overrides the protocol table like MORAI's Network Settings tab."""

from __future__ import annotations

import pytest

from egosim.bridge import simulation_context
from egosim.bridge.bindings import HANDLERS
from egosim.bridge.protocol.network import default_network_settings, parse_network_settings
from egosim.bridge.protocol.table import EGO_INPUT_ROWS, ROWS, Direction
from egosim.bridge.scene.scenarios import apply_network_settings
from egosim.cli import main
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.yamltext import YamlFileError
from tests.contract import load_contract

DOCUMENT_NAMES = {
    "/ctrl_cmd",
    "/commands/vel",
    "/gv_direct_cmd",
    "/gv_state_cmd",
    "/ghost_ctrl_cmd",
    "/NpcGhost_Topic",
    "/Ego_topic",
    "/Object_topic",
    "/CollisionData",
    "/GetTrafficLightStatus",
    "/SetTrafficLight",
    "/InsnStatus",
    "/InsnControl",
    "/ScenarioLoad",
    "/SaveSensorData",
    "/lamps",
    "/ReplayInfo_topic",
    "/SensorPosControl",
    "/sim/process/state/msg/MoraiSimProcStatus",
    "/ego_setting",
    "/VehicleCollisionData",
    "/Service_MoraiEventCmd",
    "/Service_MoraiMapSpec",
    "/Service_MoraiSL",
    "/Morai_SimProc",
    "/Morai_TLSrv",
    "/Service_MoraiVehicleSpec",
}


def test_table_holds_every_name_of_the_protocol_document() -> None:
    assert {row.name for row in ROWS} >= DOCUMENT_NAMES


def test_every_row_type_exists_in_the_contract() -> None:
    profile = get_profile("26.r1")
    contract = load_contract("26.r1")
    for row in ROWS:
        if row.direction is Direction.SERVICE:
            assert row.type_name in contract["services"]
        else:
            profile.message(row.type_name)


def test_defaults_enable_only_the_morai_command_input() -> None:
    settings = default_network_settings()
    live = [key for key in EGO_INPUT_ROWS.values() if settings.row(key).enabled]
    assert live == ["ctrl_cmd"]


def test_overrides_rename_rerate_and_disable() -> None:
    settings = parse_network_settings(
        "ego_input: GhostCtrlCmd\n"
        "rows:\n"
        "  ego_status: {name: /car/status, rate_hz: 100}\n"
        "  collision: {enabled: false}\n",
        "net.yaml",
    )
    assert settings.row("ego_status").name == "/car/status"
    assert settings.row("ego_status").rate_hz == 100
    assert not settings.row("collision").enabled
    assert settings.row("ghost_ctrl_cmd").enabled
    assert not settings.row("ctrl_cmd").enabled


def test_the_dead_man_timeout_is_off_unless_set() -> None:
    assert default_network_settings().command_timeout_s is None
    assert parse_network_settings("command_timeout_s: null\n", "n.yaml").command_timeout_s is None
    settings = parse_network_settings("command_timeout_s: 0.5\n", "net.yaml")
    assert settings.command_timeout_s == 0.5


@pytest.mark.parametrize(
    ("text", "line", "field"),
    [
        ("rows:\n  ego_status:\n    rate_hz: 0\n", 3, "rows.ego_status.rate_hz"),
        ("rows:\n  nope: {}\n", 2, "rows.nope"),
        ("rows:\n  ego_status: {colour: red}\n", 2, "rows.ego_status.colour"),
        ("rows:\n  ctrl_cmd: {rate_hz: 5}\n", 2, "rows.ctrl_cmd.rate_hz"),
        ("rows:\n  ctrl_cmd:\n    enabled: true\n", 3, "rows.ctrl_cmd.enabled"),
        ("ego_input: Joystick\n", 1, "ego_input"),
        ("ego_input: [MoraiCmdController]\n", 1, "ego_input"),
        ("rows:\n  lamps: {name: 'bad name'}\n", 2, "rows.lamps.name"),
        ("command_timeout_s: 0\n", 1, "command_timeout_s"),
        ("command_timeout_s: -1\n", 1, "command_timeout_s"),
        ("command_timeout_s: .nan\n", 1, "command_timeout_s"),
        ("command_timeout_s: 1.0e+9\n", 1, "command_timeout_s"),
        ("command_timeout_s: yes\n", 1, "command_timeout_s"),
    ],
)
def test_errors_name_file_line_and_field(text: str, line: int, field: str) -> None:
    with pytest.raises(YamlFileError) as error:
        parse_network_settings(text, "net.yaml")
    assert str(error.value).startswith(f"net.yaml:{line}: {field}: ")


def test_syntax_error_names_the_line() -> None:
    with pytest.raises(YamlFileError, match=r"^net\.yaml:2: not valid YAML"):
        parse_network_settings("rows:\n  a: b: c\n", "net.yaml")


def test_topics_command_prints_the_effective_table(
    tmp_path, capsys: pytest.CaptureFixture[str]
) -> None:
    network = tmp_path / "net.yaml"
    network.write_text("rows:\n  object_status: {name: /objects, rate_hz: 5}\n")
    assert main(["topics", "--network", str(network)]) == 0
    lines = capsys.readouterr().out.splitlines()
    row = next(line.split() for line in lines if line.startswith("object_status"))
    assert row[2:] == ["/objects", "morai_msgs/ObjectStatusList", "5", "Hz", "yes"]


def test_topics_command_reports_a_bad_file(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    network = tmp_path / "net.yaml"
    network.write_text("ego_input: 3\n")
    assert main(["topics", "--network", str(network)]) == 1
    assert "net.yaml:1: ego_input" in capsys.readouterr().err


def test_every_row_of_the_table_is_served() -> None:
    assert [row.key for row in ROWS if row.key not in HANDLERS] == []
    kinds = {
        # Rows with an opener publish on topics of their own (one per camera).
        Direction.PUBLISH: {**HANDLERS.publishers, **HANDLERS.openers},
        Direction.SUBSCRIBE: HANDLERS.subscribers,
        Direction.SERVICE: HANDLERS.services,
    }
    assert all(row.key in kinds[row.direction] for row in ROWS)


def test_every_handler_takes_its_row_s_type() -> None:
    profile = get_profile("26.r1")
    taken = {
        row.key: (row.type_name, HANDLERS.subscribers[row.key].takes(profile).name)
        for row in ROWS
        if row.direction is Direction.SUBSCRIBE
    } | {
        row.key: (f"{row.type_name}Request", HANDLERS.services[row.key].takes(profile).name)
        for row in ROWS
        if row.direction is Direction.SERVICE
    }
    assert {key: names for key, names in taken.items() if names[0] != names[1]} == {}


def test_live_settings_keep_the_cameras_on_the_camera_row_s_topic() -> None:
    context = simulation_context(World(build_builtin_map("straight")))
    scenario = parse_scenario(
        "map: straight\nnetwork:\n  rows:\n    camera: {name: /front/compressed}\n"
        "  sensors:\n    cameras:\n      - {}\n",
        "live.yaml",
    )
    apply_network_settings(context, scenario)
    assert context.sensors.camera_topics == ("/front/compressed",)
