"""`egosim run` starts, announces itself, and stops cleanly (issue: Foundation)."""

from __future__ import annotations

import signal
import socket
import subprocess
import sys
import xmlrpc.client
from pathlib import Path

import pytest

from tests.conftest import free_port

pytestmark = pytest.mark.ros


def system_state(master_uri: str) -> list[list[list]]:
    code, _, state = xmlrpc.client.ServerProxy(master_uri).getSystemState("/test")
    assert code == 1
    return state


def egosim_entries(state: list[list[list]]) -> list[str]:
    return [name for group in state for name, nodes in group if "/egosim" in nodes]


@pytest.mark.parametrize("stop_signal", [signal.SIGINT, signal.SIGTERM])
def test_stops_cleanly_and_unregisters_everything(
    rosmaster, spawn_ros, tmp_path: Path, stop_signal: signal.Signals
) -> None:
    process = spawn_ros(
        [sys.executable, "-m", "egosim", "run", "--data-root", str(tmp_path)],
        master_uri=rosmaster,
        ROS_IP="127.0.0.1",
    )
    process.expect(r"^egosim: ready$")
    registered = egosim_entries(system_state(rosmaster))
    assert {"/Ego_topic", "/ctrl_cmd", "/Service_MoraiEventCmd"} <= set(registered)
    process.popen.send_signal(stop_signal)
    assert process.wait(timeout=10) == 0
    assert egosim_entries(system_state(rosmaster)) == []
    code, _, _ = xmlrpc.client.ServerProxy(rosmaster).lookupNode("/test", "/egosim")
    assert code != 1


def test_embedded_master_serves_until_stopped(egosim) -> None:
    simulator = egosim()
    assert "/Ego_topic" in egosim_entries(system_state(simulator.master_uri))
    simulator.process.popen.send_signal(signal.SIGINT)
    assert simulator.process.wait(timeout=10) == 0
    with pytest.raises(OSError):
        system_state(simulator.master_uri)


def run_expecting_failure(args: list[str], env_master: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "egosim", "run", *args],
        env={"ROS_MASTER_URI": env_master, "PATH": "/usr/bin:/bin", "HOME": "/tmp"},
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )


def test_port_taken_is_a_one_line_startup_error() -> None:
    with socket.socket() as blocker:
        blocker.bind(("127.0.0.1", 0))
        blocker.listen()
        port = blocker.getsockname()[1]
        result = run_expecting_failure([], f"http://127.0.0.1:{port}/")
    assert result.returncode != 0
    assert "egosim: ready" not in result.stdout
    assert result.stderr.strip().splitlines()[-1].startswith("egosim: ")


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["--map", "atlantis"], "atlantis"),
        (["--scenario", "/nonexistent/scenario.yaml"], "/nonexistent/scenario.yaml"),
    ],
)
def test_bad_file_is_a_one_line_startup_error(args: list[str], expected: str) -> None:
    result = run_expecting_failure(args, f"http://127.0.0.1:{free_port()}/")
    assert result.returncode != 0
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith("egosim: ") and expected in last
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize(
    ("option", "content", "expected"),
    [
        ("--network", b"ego_input: \xff\xfe\n", "not UTF-8 text"),
        ("--network", b"sensors:\n  lidar:\n    channels: 1000000000\n", "must be <= 256"),
        ("--scenario", b"map: town\nnpcs: " + b"[" * 20000 + b"]" * 20000, "nested deeper"),
        ("--network", b"rows: " + b"[" * 20000 + b"]" * 20000, "nested deeper"),
    ],
)
def test_unusable_settings_and_scenarios_are_one_line_errors(
    tmp_path: Path, option: str, content: bytes, expected: str
) -> None:
    path = tmp_path / "file.yaml"
    path.write_bytes(content)
    result = run_expecting_failure([option, str(path)], f"http://127.0.0.1:{free_port()}/")
    assert result.returncode == 2
    assert result.stderr.strip().count("\n") == 0, result.stderr[-2000:]
    assert result.stderr.startswith("egosim: ") and expected in result.stderr


def test_rtf_needs_the_sim_clock() -> None:
    result = run_expecting_failure(["--rtf", "4"], f"http://127.0.0.1:{free_port()}/")
    assert result.returncode == 2
    assert result.stderr.strip() == "egosim: --rtf needs --clock sim"


def test_invalid_scenario_names_file_line_and_field(tmp_path: Path) -> None:
    scenario = tmp_path / "bad.yaml"
    scenario.write_text("map: town\nnpcs:\n  - model: 2016_Kia_Niro(HEV)\n    speed: fast\n")
    master = f"http://127.0.0.1:{free_port()}/"
    result = run_expecting_failure(["--scenario", str(scenario)], master)
    assert result.returncode != 0
    last = result.stderr.strip().splitlines()[-1]
    assert f"{scenario}:" in last
    assert "Traceback" not in result.stderr


def test_duration_stops_by_itself(egosim) -> None:
    simulator = egosim("--clock", "sim", "--rtf", "0", "--duration", "5")
    assert simulator.process.wait(timeout=60) == 0


def test_an_openscenario_run_ends_with_its_storyboard(egosim) -> None:
    gallery = Path(__file__).parents[2] / "examples" / "openscenario"
    simulator = egosim(
        "--scenario",
        str(gallery / "braking_target.xosc"),
        "--ctrl-mode",
        "auto",
        "--clock",
        "sim",
        "--rtf",
        "0",
        "--no-view",
    )
    # The scenario drives the ego into the braking target: the evaluation fails, the
    # storyboard ends, and so does the run (well before its 20 s time-out).
    assert simulator.process.wait(timeout=60) == 0
    log = simulator.process.stderr_text()
    assert "scenario ended at t=" in log and "evaluation failure" in log
