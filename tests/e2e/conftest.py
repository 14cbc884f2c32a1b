"""End-to-end fixtures: `egosim run` as a subprocess and real rospy clients.

`module_egosim` starts simulators that live for a whole test module: for tests that only
ask (services, handshakes) and leave nothing that another test of the module would see,
so that they need not pay a simulator start each.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.conftest import RosProcess, free_port, ros_environment, ros_spawner
from tests.debian_ros import require_ros
from tests.e2e.driver import RospyDriver


@dataclass
class Simulator:
    process: RosProcess
    master_uri: str
    data_root: Path


def simulator_starter(
    spawn: Callable[..., RosProcess], directory: Path
) -> Callable[..., Simulator]:
    """`start(*args)` starts `egosim run` on a free master port and waits for ready."""

    def start(*args: str) -> Simulator:
        require_ros()
        uri = f"http://127.0.0.1:{free_port()}/"
        data_root = directory / "data"
        data_root.mkdir(exist_ok=True)
        process = spawn(
            [sys.executable, "-m", "egosim", "run", "--data-root", str(data_root), *args],
            master_uri=uri,
            ROS_IP="127.0.0.1",
        )
        process.expect(r"^egosim: ready$")
        return Simulator(process, uri, data_root)

    return start


@pytest.fixture
def egosim(spawn_ros: Callable[..., RosProcess], tmp_path: Path) -> Callable[..., Simulator]:
    """`egosim(*args)` starts `egosim run` on a free master port and waits for ready."""
    return simulator_starter(spawn_ros, tmp_path)


@pytest.fixture(scope="module")
def module_egosim(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Callable[..., Simulator]]:
    """`module_egosim(*args)`: as `egosim`, the simulator stopped after the module's tests."""
    directory = tmp_path_factory.mktemp("module_egosim")
    with ros_spawner(directory, ros_environment(directory)) as spawn:
        yield simulator_starter(spawn, directory)


@pytest.fixture
def rospy_client(ros_env: dict[str, str], tmp_path: Path) -> Iterator[Callable[..., RospyDriver]]:
    """`rospy_client(simulator, profile="26.r1")`: a rospy node with contract classes."""
    drivers: list[RospyDriver] = []

    def connect(simulator: Simulator, profile: str = "26.r1") -> RospyDriver:
        name = f"client{len(drivers)}"
        env = dict(ros_env, ROS_MASTER_URI=simulator.master_uri, ROS_IP="127.0.0.1")
        driver = RospyDriver(env, tmp_path / f"{name}.stderr", profile, name)
        drivers.append(driver)
        return driver

    try:
        yield connect
    finally:
        for driver in drivers:
            driver.close()
