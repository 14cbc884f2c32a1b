"""roscpp nodes (built here with g++ against Debian's ros-core-dev) and egosim, both ways,
through egosim's embedded master."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from tests.ros1.helpers import STRING, string_bytes, string_text, wait_until

pytestmark = [pytest.mark.ros, pytest.mark.roscpp]

SOURCES = Path(__file__).parent / "roscpp"


def _build_flags() -> list[str] | str:
    """Compiler flags for roscpp and std_msgs, or why they are unavailable."""
    compiler = shutil.which("g++")
    if compiler is None:
        return "no C++ compiler (g++) installed"
    if shutil.which("pkg-config") is None:
        return "pkg-config is not installed"
    flags = subprocess.run(
        ["pkg-config", "--cflags", "--libs", "roscpp", "std_msgs"],
        capture_output=True,
        text=True,
        check=False,
    )
    if flags.returncode != 0 or not Path("/usr/include/ros/ros.h").exists():
        return f"roscpp development files not found (apt-get install ros-core-dev): {flags.stderr}"
    return flags.stdout.split()


@pytest.fixture(scope="module")
def roscpp_programs(tmp_path_factory) -> dict[str, Path]:
    flags = _build_flags()
    if isinstance(flags, str):
        pytest.skip(flags)
    out = tmp_path_factory.mktemp("roscpp")
    programs = {}
    for name in ("talker", "listener"):
        binary = out / name
        build = subprocess.run(
            ["g++", "-O1", "-o", str(binary), str(SOURCES / f"{name}.cpp"), *flags],
            capture_output=True,
            text=True,
            check=False,
        )
        assert build.returncode == 0, build.stderr
        programs[name] = binary
    return programs


def test_egosim_publisher_to_roscpp_listener(
    embedded_master, spawn_ros, make_node, roscpp_programs
):
    node = make_node("egosim", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    listener = spawn_ros([str(roscpp_programs["listener"])], embedded_master.uri)
    listener.expect("subscribed")
    wait_until(lambda: pub.num_subscribers == 1)
    for i in range(3):
        pub.publish(string_bytes(f"from egosim {i}"))
    for i in range(3):
        assert listener.expect("^heard ").string == f"heard from egosim {i} from /egosim"


def test_roscpp_talker_to_egosim_subscriber(embedded_master, spawn_ros, make_node, roscpp_programs):
    node = make_node("egosim", master_uri=embedded_master.uri)
    received: list[tuple[str, str]] = []
    node.subscribe(
        "/chatter",
        STRING,
        lambda data, header: received.append((string_text(data), header["callerid"])),
    )
    spawn_ros([str(roscpp_programs["talker"])], embedded_master.uri)
    wait_until(lambda: len(received) >= 3)
    first = int(received[0][0].split()[1])
    assert received[:3] == [(f"cpp {first + k}", "/cpp_talker") for k in range(3)]
