"""ReplaySession follows MoraiSimProcHandle commands and reports MoraiSimProcStatus codes."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

from egosim.msgs import get_profile
from egosim.replay import CommandResult, Mode, PlaybackStatus, ReplaySession
from tests.replay.drive import DURATION_S, ego_position

PLAY, PAUSE, STOP = 1, 2, 32
LOAD, TARGET, START, SPEED = 0x0001, 0x0010, 0x0100, 0x1000
EGO, NPC, PEDESTRIAN = 0x0001, 0x0010, 0x0100


@dataclass
class Handle:
    """The fields of MoraiSimProcHandle."""

    sim_process_status: int = 0
    replay_option: int = 0
    rosbag_file_name: str = ""
    replay_target_option: int = 0
    replay_speed: int = 0
    start_time: int = 0


@pytest.fixture
def session(data_root: Path) -> ReplaySession:
    return ReplaySession([data_root])


@pytest.fixture
def playing(session: ReplaySession) -> ReplaySession:
    assert play(session) is CommandResult.SUCCESS
    return session


def play(session: ReplaySession, **fields: object) -> CommandResult:
    command = Handle(PLAY, LOAD, "drive.bag")
    for name, value in fields.items():
        setattr(command, name, value)
    return session.handle(command, received_ns=1)


def advance(session: ReplaySession, seconds: float, step: float = 0.02) -> None:
    for _ in range(round(seconds / step)):
        session.advance(step)


def test_initial_status(session: ReplaySession) -> None:
    status = session.status()
    assert status.latest_command_time_ns == 0
    assert status.command_result is CommandResult.INITIAL == 0x00
    assert status.current_mode is Mode.SIMULATION == 0x01
    assert status.current_status is PlaybackStatus.RUNNING == 0x01
    assert session.frame() is None


def test_load_enters_replay_paused_at_start(session: ReplaySession) -> None:
    result = session.handle(Handle(0, LOAD, "drive.bag"), received_ns=42)
    assert result is CommandResult.SUCCESS == 0x01
    status = session.status()
    assert status.latest_command_time_ns == 42
    assert (status.current_mode, status.current_status) == (Mode.REPLAY, PlaybackStatus.PAUSED)
    advance(session, 1.0)
    assert session.playback_time == 0.0


def test_play_at_1x_follows_sim_time(playing: ReplaySession) -> None:
    advance(playing, 2.0)
    assert playing.playback_time == pytest.approx(2.0)
    frame = playing.frame()
    assert frame is not None and frame.ego is not None
    assert frame.ego.position == pytest.approx(ego_position(2.0), abs=0.01)
    assert playing.status().current_status is PlaybackStatus.RUNNING


def test_play_at_4x(session: ReplaySession) -> None:
    assert play(session, replay_option=LOAD | SPEED, replay_speed=4) is CommandResult.SUCCESS
    advance(session, 1.5)
    assert session.playback_time == pytest.approx(6.0)


def test_speed_changes_while_playing(playing: ReplaySession) -> None:
    advance(playing, 1.0)
    assert playing.handle(Handle(0, SPEED, replay_speed=2), received_ns=2) is CommandResult.SUCCESS
    advance(playing, 1.0)
    assert playing.playback_time == pytest.approx(3.0)


def test_pause_holds_and_play_resumes(playing: ReplaySession) -> None:
    advance(playing, 1.0)
    assert playing.handle(Handle(PAUSE), received_ns=2) is CommandResult.SUCCESS
    assert playing.status().current_status is PlaybackStatus.PAUSED == 0x10
    held = playing.frame()
    advance(playing, 3.0)
    assert playing.playback_time == pytest.approx(1.0)
    assert playing.frame() == held
    assert playing.handle(Handle(PLAY), received_ns=3) is CommandResult.SUCCESS
    advance(playing, 1.0)
    assert playing.playback_time == pytest.approx(2.0)


def test_end_of_bag_pauses_there(playing: ReplaySession) -> None:
    advance(playing, DURATION_S + 1.0)
    status = playing.status()
    assert status.current_status is PlaybackStatus.AT_END == 0x20
    assert status.current_mode is Mode.REPLAY
    assert playing.playback_time == DURATION_S
    # Play again starts over from the start time.
    assert playing.handle(Handle(PLAY), received_ns=2) is CommandResult.SUCCESS
    assert playing.playback_time == 0.0
    assert playing.status().current_status is PlaybackStatus.RUNNING


def test_stop_returns_to_simulation(playing: ReplaySession) -> None:
    advance(playing, 1.0)
    assert playing.handle(Handle(STOP), received_ns=2) is CommandResult.SUCCESS
    status = playing.status()
    assert (status.current_mode, status.current_status) == (Mode.SIMULATION, PlaybackStatus.RUNNING)
    assert playing.frame() is None
    advance(playing, 1.0)
    # The bag stays loaded: play replays it from the start.
    assert playing.handle(Handle(PLAY), received_ns=3) is CommandResult.SUCCESS
    assert playing.status().current_mode is Mode.REPLAY
    assert playing.playback_time == 0.0


def test_start_time_seeks(session: ReplaySession) -> None:
    result = play(session, replay_option=LOAD | START, start_time=7_500)
    assert result is CommandResult.SUCCESS
    assert session.playback_time == 7.5
    frame = session.frame()
    assert frame is not None and frame.ego is not None
    assert frame.ego.position == pytest.approx(ego_position(7.5), abs=0.01)
    advance(session, 3.0)
    assert session.status().current_status is PlaybackStatus.AT_END
    session.handle(Handle(PLAY), received_ns=2)
    assert session.playback_time == 7.5


@pytest.mark.parametrize(
    ("target", "ego", "npcs", "pedestrians"),
    [
        (EGO, True, False, False),
        (NPC, False, True, False),
        (PEDESTRIAN, False, False, True),
        (EGO | PEDESTRIAN, True, False, True),
        (EGO | NPC | PEDESTRIAN, True, True, True),
        (0b0010, False, True, False),  # the binary-digit reading of "NPC vehicle"
        (0b0101, True, False, True),
    ],
)
def test_target_option_filters_frames(
    session: ReplaySession, target: int, ego: bool, npcs: bool, pedestrians: bool
) -> None:
    result = play(session, replay_option=LOAD | TARGET, replay_target_option=target)
    assert result is CommandResult.SUCCESS
    advance(session, 1.0)
    frame = session.frame()
    assert frame is not None
    assert (frame.ego is not None) is ego
    assert (frame.control is not None) is ego
    assert bool(frame.npcs) is npcs
    assert bool(frame.pedestrians) is pedestrians


def test_binary_reading_of_replay_option(session: ReplaySession) -> None:
    """1 load, 2 target, 4 start time, 8 speed."""
    command = Handle(PLAY, 1 | 2 | 4 | 8, "drive.bag", EGO, replay_speed=2, start_time=1_000)
    assert session.handle(command, received_ns=1) is CommandResult.SUCCESS
    assert (session.playback_time, session.speed) == (1.0, 2)
    frame = session.frame()
    assert frame is not None and frame.npcs == () and frame.ego is not None


@pytest.mark.parametrize(
    "name", ["absent.bag", "corrupt.bag", "../outside.bag", "/etc/passwd", "escape.bag"]
)
def test_bad_bag_fails_to_load_and_session_stays_usable(
    session: ReplaySession, data_root: Path, name: str
) -> None:
    (data_root / "corrupt.bag").write_bytes(b"#ROSBAG V2.0\n" + bytes(64))
    (data_root.parent / "outside.bag").write_bytes((data_root / "drive.bag").read_bytes())
    (data_root / "escape.bag").symlink_to(data_root.parent / "outside.bag")
    assert play(session, rosbag_file_name=name) is CommandResult.BAG_LOAD_FAILED == 0x20
    status = session.status()
    assert status.command_result is CommandResult.BAG_LOAD_FAILED
    assert (status.current_mode, session.timeline) == (Mode.SIMULATION, None)
    assert play(session) is CommandResult.SUCCESS
    assert session.status().current_mode is Mode.REPLAY


@pytest.mark.parametrize("name", ["net.bag", "../outside.bag"])
def test_a_bag_outside_the_data_roots_is_logged_with_the_roots_and_the_way_out(
    session: ReplaySession, data_root: Path, name: str, caplog: pytest.LogCaptureFixture
) -> None:
    """The README's replay of a bag recorded elsewhere: the client sees result false and
    command_result 0x20; the log says where the simulator looked and how to change it."""
    (data_root.parent / "outside.bag").write_bytes((data_root / "drive.bag").read_bytes())
    assert play(session, rosbag_file_name=name) is CommandResult.BAG_LOAD_FAILED
    (record,) = [r for r in caplog.records if "cannot load rosbag" in r.getMessage()]
    assert str(data_root) in record.getMessage()
    assert "egosim run --data-root DIR" in record.getMessage()


def test_failed_load_keeps_the_bag_playing(playing: ReplaySession) -> None:
    advance(playing, 1.0)
    assert play(playing, rosbag_file_name="absent.bag") is CommandResult.BAG_LOAD_FAILED
    advance(playing, 1.0)
    assert playing.playback_time == pytest.approx(2.0)


@pytest.mark.parametrize("speed", [0, -2])
def test_non_positive_speed_is_rejected(playing: ReplaySession, speed: int) -> None:
    command = Handle(0, SPEED, replay_speed=speed)
    assert playing.handle(command, received_ns=2) is CommandResult.COMMAND_FAILED == 0x10
    advance(playing, 1.0)
    assert playing.playback_time == pytest.approx(1.0)


def test_loaded_but_failed(session: ReplaySession) -> None:
    result = play(session, replay_option=LOAD | SPEED, replay_speed=0)
    assert result is CommandResult.LOADED_BUT_FAILED == 0x30
    status = session.status()
    assert (status.current_mode, status.current_status) == (Mode.REPLAY, PlaybackStatus.PAUSED)


@pytest.mark.parametrize(
    "command",
    [
        Handle(PLAY),  # nothing loaded
        Handle(PAUSE),
        Handle(0, START, start_time=1_000),
        Handle(7),  # no such process status
        Handle(0, 0x0020),  # no such option bit
        Handle(0, -0x8000),  # int16 with its top bit set
    ],
)
def test_invalid_command_without_bag_fails(session: ReplaySession, command: Handle) -> None:
    assert session.handle(command, received_ns=5) is CommandResult.COMMAND_FAILED
    status = session.status()
    assert status.latest_command_time_ns == 5
    assert status.current_mode is Mode.SIMULATION


@pytest.mark.parametrize(
    "command",
    [
        Handle(0, START, start_time=-1),
        Handle(0, START, start_time=int(DURATION_S * 1000) + 1),
        Handle(0, TARGET, replay_target_option=0),
        Handle(0, TARGET, replay_target_option=0x1000),
    ],
)
def test_invalid_settings_change_nothing(playing: ReplaySession, command: Handle) -> None:
    advance(playing, 1.0)
    before = (playing.playback_time, playing.targets, playing.speed)
    assert playing.handle(command, received_ns=2) is CommandResult.COMMAND_FAILED
    assert (playing.playback_time, playing.targets, playing.speed) == before


def test_time_only_moves_forward(playing: ReplaySession) -> None:
    with pytest.raises(ValueError):
        playing.advance(-0.1)


def test_accepts_a_deserialised_message(session: ReplaySession) -> None:
    handle_type = get_profile("26.r1").message("morai_msgs/MoraiSimProcHandle")
    message = handle_type.deserialize(
        handle_type.serialize(
            handle_type.new(
                sim_process_status=PLAY, replay_option=LOAD, rosbag_file_name="drive.bag"
            )
        )
    )
    assert session.handle(message, received_ns=9) is CommandResult.SUCCESS
    assert session.status().current_status is PlaybackStatus.RUNNING
