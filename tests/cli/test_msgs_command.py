"""`egosim msgs` lists and shows types like rosmsg/rossrv do."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from egosim.cli import main
from egosim.msgs import PROFILES
from tests.contract import load_contract


def listing(capsys: pytest.CaptureFixture[str], *args: str) -> dict[str, tuple[str, str]]:
    assert main(["msgs", *args]) == 0
    rows = [line.split() for line in capsys.readouterr().out.splitlines()]
    return {name: (md5, kind) for md5, kind, name in rows}


@pytest.mark.parametrize("profile", PROFILES)
def test_lists_every_contract_type_with_its_md5(
    capsys: pytest.CaptureFixture[str], profile: str
) -> None:
    rows = listing(capsys, "--profile", profile)
    contract = load_contract(profile)
    for name, message in contract["messages"].items():
        assert rows[name] == (message["md5sum"], "msg")
    for name, service in contract["services"].items():
        assert rows[name] == (service["md5sum"], "srv")
    assert rows["sensor_msgs/Imu"][1] == "msg"


def test_shows_one_definition(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "morai_msgs/CtrlCmd"]) == 0
    out = capsys.readouterr().out
    assert "b36ceb480d187645a32b95c2be82bf56" in out
    assert "float64 front_steer" in out


def test_older_release_shows_its_own_definition(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "--profile", "24.r2", "morai_msgs/CtrlCmd"]) == 0
    out = capsys.readouterr().out
    assert "718f1a493f1a335da59a19f673d82bb4" in out
    assert "float64 steering" in out


def test_md5_only(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "--md5", "morai_msgs/MoraiEventCmdSrv"]) == 0
    assert capsys.readouterr().out.strip() == "12515282709d0774401eb06049aedb82"


def test_unknown_type_is_a_one_line_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "nope/Nothing"]) == 1
    assert "nope/Nothing" in capsys.readouterr().err


def test_console_script_runs() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "egosim", "msgs", "--md5", "morai_msgs/CtrlCmd"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert result.stdout.strip() == "b36ceb480d187645a32b95c2be82bf56"


def test_short_name_resolves_to_its_package(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "CtrlCmd"]) == 0
    short = capsys.readouterr().out
    assert main(["msgs", "morai_msgs/CtrlCmd"]) == 0
    assert short == capsys.readouterr().out
    assert short.startswith("# morai_msgs/CtrlCmd  md5sum: b36ceb480d187645a32b95c2be82bf56")


def test_unknown_short_name_is_one_line_listing_candidates(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["msgs", "ctrlcmd"]) == 1
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1
    assert "morai_msgs/CtrlCmd" in lines[0]
    assert "morai_msgs/SyncModeCtrlCmd" in lines[0]
    assert "Traceback" not in captured.err


def test_service_shows_request_and_response_fields(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "MoraiScenarioLoadSrv"]) == 0
    body = capsys.readouterr().out.splitlines()[1:]
    separator = body.index("---")
    assert body[: separator + 1] == [
        "morai_msgs/ScenarioLoad request",
        "  string file_name",
        "  bool load_network_connection_data",
        "  bool delete_all",
        "  bool load_ego_vehicle_data",
        "  bool load_surrounding_vehicle_data",
        "  bool load_pedestrian_data",
        "  bool load_obstacle_data",
        "  bool set_pause",
        "---",
    ]
    assert body[separator + 1 :] == ["morai_msgs/MoraiSrvResponse response", "  bool result"]


def test_nested_types_expand_beneath_their_field(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["msgs", "NavSatFix"]) == 0
    body = capsys.readouterr().out.splitlines()
    assert body[1] == "uint8 COVARIANCE_TYPE_UNKNOWN=0"
    assert "std_msgs/Header header" in body
    assert body[body.index("std_msgs/Header header") + 2] == "  time stamp"
    assert "  int8 STATUS_NO_FIX=-1" in body
    assert "float64[9] position_covariance" in body


def test_export_writes_a_catkin_package(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    target = tmp_path / "src" / "morai_msgs"
    assert main(["msgs", "--export", str(target), "--profile", "2021.08"]) == 0
    assert "wrote morai_msgs 2021.08" in capsys.readouterr().out
    assert (target / "package.xml").is_file()
    assert (target / "msg" / "CtrlCmd.msg").is_file()
    assert (target / "srv" / "MoraiEventCmdSrv.srv").is_file()


def test_export_into_an_unwritable_place_is_a_one_line_error(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    assert main(["msgs", "--export", str(blocker / "morai_msgs")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("egosim msgs: cannot write") and len(err.splitlines()) == 1


def test_export_python_without_genpy_says_what_to_install(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    # egosim's own interpreter has no genpy: the message names the fix.
    assert main(["msgs", "--export-python", str(tmp_path), "--ros-python", sys.executable]) == 1
    err = capsys.readouterr().err
    assert "python3-genpy" in err and len(err.splitlines()) == 1
