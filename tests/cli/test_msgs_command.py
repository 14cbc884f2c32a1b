"""`egosim msgs` lists and shows types like rosmsg/rossrv do."""

from __future__ import annotations

import subprocess
import sys

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
