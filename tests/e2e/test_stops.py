"""How `egosim run` stops, as a process among real ROS peers: the sequence that
once ignored Ctrl-C (autopilot, a replay, back to ctrl_mode 3, recording, a page on the
view) stopped by SIGINT, SIGTERM or Debian's `rosnode kill`; a second signal, or a clean
stop that cannot finish, ends the process within the bound with the bag indexed."""

from __future__ import annotations

import os
import pty
import random
import re
import select
import shutil
import signal
import sys
import time
import xmlrpc.client
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.conftest import RosProcess, free_port
from tests.debian_ros import require_ros
from tests.e2e.conftest import Simulator
from tests.e2e.driver import RospyDriver
from tests.e2e.test_replay import LOAD, PLAY, SET_SPEED, sim_proc
from tests.replay.drive import record_drive
from tests.stop_stress import (
    REPLAY_BAG,
    STOP_BOUND_S,
    PageWatcher,
    bag_problem,
    provide_replay_bag,
    rosbag_says_indexed,
    rosnode_kill,
)
from tests.waiting import until

pytestmark = pytest.mark.ros

EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
STUCK = Path(__file__).parent / "peers" / "stuck_egosim.py"
REPO = Path(__file__).parents[2]
EXIT_STOP_FORCED = 4  # egosim.app.exit_codes, as a shell sees it


def start_stuck(spawn_ros: Callable[..., RosProcess], bag: Path) -> RosProcess:
    """`egosim run --record BAG` whose loop got stuck after a few ticks (peers/stuck_egosim.py)."""
    require_ros()
    process = spawn_ros(
        [sys.executable, str(STUCK), "run", "--record", str(bag), "--no-view"],
        master_uri=f"http://127.0.0.1:{free_port()}/",
        ROS_IP="127.0.0.1",
    )
    process.expect(r"^egosim: ready$")
    process.expect(r"^stuck$")
    return process


def view_socket(simulator: Simulator) -> str:
    """The websocket of the view the simulator announced."""
    for line in simulator.process.output:
        if match := re.match(r"^egosim: view at http(\S+)$", line):
            return f"ws{match.group(1)}ws"
    raise AssertionError(f"no view announced: {simulator.process.output}")


def timed_exit(process: RosProcess, since: float) -> tuple[int, float]:
    """The exit status and the seconds from `since` to the exit (waiting generously)."""
    status = process.wait(timeout=60)
    return status, time.monotonic() - since


def autopilot_replay_and_back(client: RospyDriver) -> None:
    """Autopilot, a replay, then back to the external controller: the sequence after which a
    stop once never came."""
    event = {"option": 1, "ctrl_mode": 4}
    assert client.call(*EVENT, {"request": event})["response"]["ctrl_mode"] == 4
    assert sim_proc(
        client, sim_process_status=PLAY, replay_option=LOAD | SET_SPEED,
        rosbag_file_name=REPLAY_BAG, replay_speed=2,
    )  # fmt: skip
    event["ctrl_mode"] = 3
    assert client.call(*EVENT, {"request": event})["response"]["ctrl_mode"] == 3


@pytest.mark.parametrize("how", ["SIGINT", "rosnode kill"])  # SIGTERM: tests/app
def test_the_stop_that_never_came_is_prompt_clean_and_leaves_an_indexed_bag(
    egosim: Callable[..., Simulator],
    rospy_client: Callable[..., RospyDriver],
    ros_env: dict[str, str],
    tmp_path: Path,
    how: str,
) -> None:
    data_root = tmp_path / "data"
    data_root.mkdir()
    provide_replay_bag(data_root, record_drive(tmp_path / "drive.bag"))
    bag = data_root / "drive_record.bag"
    simulator = egosim("--record", str(bag), "--view-port", "0")
    page = PageWatcher(view_socket(simulator), random.Random(29))
    try:
        autopilot_replay_and_back(rospy_client(simulator))
        if how == "rosnode kill":
            rosnode_kill(simulator.master_uri, ros_env)  # returns once egosim has answered
            since = time.monotonic()
        else:
            since = time.monotonic()
            simulator.process.popen.send_signal(getattr(signal, how))
        status, seconds = timed_exit(simulator.process, since)
    finally:
        page.close()
    stderr = simulator.process.stderr_text()
    assert status == 0, stderr[-3000:]
    assert seconds <= STOP_BOUND_S, f"{how}: stopped after {seconds:.2f} s"
    reason = "requested by /rosnode" if how == "rosnode kill" else how
    assert f"stopping: {reason}" in stderr
    assert bag_problem(bag) is None
    assert rosbag_says_indexed(bag)


def test_a_second_signal_ends_a_stuck_stop_at_once_with_the_bag_indexed(
    spawn_ros: Callable[..., RosProcess], tmp_path: Path
) -> None:
    bag = tmp_path / "stuck.bag"
    process = start_stuck(spawn_ros, bag)
    process.popen.send_signal(signal.SIGINT)
    # The first asks for a clean stop, which cannot come (the loop is stuck); the second
    # comes well before the first's deadline.
    time.sleep(0.2)
    since = time.monotonic()
    process.popen.send_signal(signal.SIGINT)
    status, seconds = timed_exit(process, since)
    assert status == 128 + signal.SIGINT, process.stderr_text()[-3000:]
    assert seconds <= STOP_BOUND_S
    assert "SIGINT again: exiting now, without a clean stop" in process.stderr_text()
    assert bag_problem(bag) is None
    assert rosbag_says_indexed(bag)


def test_a_clean_stop_that_cannot_finish_is_forced_within_the_bound(
    spawn_ros: Callable[..., RosProcess], tmp_path: Path
) -> None:
    bag = tmp_path / "stuck.bag"
    process = start_stuck(spawn_ros, bag)
    since = time.monotonic()
    process.popen.send_signal(signal.SIGTERM)
    status, seconds = timed_exit(process, since)
    stderr = process.stderr_text()
    assert status == EXIT_STOP_FORCED, stderr[-3000:]
    assert seconds <= STOP_BOUND_S
    assert "the stop (SIGTERM) did not finish within 1.4 s; exiting now" in stderr
    # Where the main thread was held: the stuck tick of peers/stuck_egosim.py.
    assert re.search(r'stuck_egosim\.py", line \d+ in tick', stderr)
    assert bag_problem(bag) is None
    assert rosbag_says_indexed(bag)


def test_egosim_record_stops_on_rosnode_kill_with_its_bag_closed(
    egosim: Callable[..., Simulator],
    spawn_ros: Callable[..., RosProcess],
    ros_env: dict[str, str],
    tmp_path: Path,
) -> None:
    simulator = egosim("--no-view")
    bag = tmp_path / "net.bag"
    recorder = spawn_ros(
        [sys.executable, "-m", "egosim", "record", str(bag), "--topics", "/Ego_topic"],
        master_uri=simulator.master_uri,
        ROS_IP="127.0.0.1",
    )
    rosnode_kill(simulator.master_uri, ros_env, _recorder_node(simulator.master_uri, recorder))
    status, seconds = timed_exit(recorder, time.monotonic())
    assert status == 0, recorder.stderr_text()[-3000:]
    assert seconds <= STOP_BOUND_S
    assert "stopping: requested by /rosnode" in recorder.stderr_text()
    assert bag_problem(bag) is None


def _recorder_node(master_uri: str, recorder: RosProcess) -> str:
    """The name `egosim record` subscribes under (egosim_record_<ns>), once it has."""

    def subscribed() -> str | None:
        _, _, (_, subscribers, _) = xmlrpc.client.ServerProxy(master_uri).getSystemState("/t")
        names = [n for topic, nodes in subscribers if topic == "/Ego_topic" for n in nodes]
        recording = "recording 1 topics" in recorder.stderr_text()
        return (
            next((n for n in names if n.startswith("/egosim_record_")), None) if recording else None
        )

    return until(subscribed, "egosim record to subscribe to /Ego_topic")


def test_ctrl_c_in_a_terminal_stops_make_run_cleanly_and_make_reports_130(
    ros_env: dict[str, str], tmp_path: Path
) -> None:
    """The quick start's stop as a user makes it: Ctrl-C typed in the terminal reaches make
    and egosim alike. egosim stops cleanly with its bag closed; make ends with the
    interrupt (130 in a shell), as the README says."""
    require_ros()
    if shutil.which("make") is None:
        pytest.skip("make is not installed")
    bag = tmp_path / "make_run.bag"
    env = {**ros_env, "ROS_MASTER_URI": f"http://127.0.0.1:{free_port()}/", "ROS_IP": "127.0.0.1"}
    args = f"--no-view --record {bag}"
    pid, terminal = pty.fork()
    if pid == 0:  # the child: make on the terminal's side, as typed in a shell
        os.chdir(REPO)
        os.execvpe("make", ["make", "run", f"ARGS={args}"], env)
    output = _read_until(terminal, b"egosim: ready")
    since = time.monotonic()
    os.write(terminal, b"\x03")  # Ctrl-C: the terminal sends SIGINT to its foreground job
    output += _read_until(terminal, None)
    _, status = os.waitpid(pid, 0)
    seconds = time.monotonic() - since
    os.close(terminal)
    text = output.decode(errors="replace")
    assert os.waitstatus_to_exitcode(status) == -signal.SIGINT, text[-3000:]  # 130 in a shell
    assert seconds <= STOP_BOUND_S
    assert "stopping: SIGINT" in text
    assert f"bag {bag} closed" in text
    assert bag_problem(bag) is None


def _read_until(terminal: int, mark: bytes | None, timeout: float = 120.0) -> bytes:
    """What the terminal shows until `mark` appears (None: until it closes)."""
    seen = b""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        ready, _, _ = select.select([terminal], [], [], 0.5)
        if not ready:
            continue
        try:
            chunk = os.read(terminal, 4096)
        except OSError:  # the other side closed
            return seen
        if not chunk:
            return seen
        seen += chunk
        if mark is not None and mark in seen:
            return seen
    raise AssertionError(f"the terminal never showed {mark!r}: {seen[-3000:]!r}")
