"""BagTimeline reproduces the recorded drive at and between its messages."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from rosbags.rosbag1 import Writer

from egosim.msgs import PROFILES, get_profile
from egosim.replay import (
    BagError,
    BagTimeline,
    MissingTopicsError,
    ReplayTopics,
    UnsupportedReleaseError,
)
from egosim.replay.releases import RELEASE_NAMES
from tests.replay.drive import (
    CONTROL,
    DURATION_S,
    EGO,
    EGO_HZ,
    MOVING_OBJECTS,
    OBJECTS_HZ,
    START_NS,
    control_velocity_kmh,
    ego_heading,
    ego_message,
    ego_pedal,
    ego_position,
    stamp,
)

CM = 0.01


@pytest.fixture(scope="module")
def timeline(recorded_drive: Path) -> BagTimeline:
    return BagTimeline.open(recorded_drive)


def angle_between(a: float, b: float) -> float:
    return abs(math.remainder(a - b, 2 * math.pi))


def test_extent(timeline: BagTimeline) -> None:
    assert timeline.profile == "26.r1"
    assert timeline.start_ns == START_NS
    assert timeline.end_ns == stamp(DURATION_S)
    assert timeline.duration == DURATION_S


@pytest.mark.parametrize("k", [0, 1, 130, 131, 250, 499, 500])
def test_ego_at_message_times(timeline: BagTimeline, k: int) -> None:
    t = k / EGO_HZ
    ego = timeline.sample(t).ego
    assert ego is not None
    assert math.dist(ego.position, ego_position(t)) < CM
    assert angle_between(ego.heading, ego_heading(t)) < 1e-9
    assert ego.accel_pedal == pytest.approx(ego_pedal(t), abs=1e-6)
    assert ego.velocity == (10.0, 0.0, 0.0)
    assert ego.unique_id == -1


@pytest.mark.parametrize("t", [0.011, 2.605, 2.61, 5.555, 9.999])
def test_ego_between_messages(timeline: BagTimeline, t: float) -> None:
    """Positions interpolate linearly (chord error far below 1 cm at 50 Hz)."""
    ego = timeline.sample(t).ego
    assert ego is not None
    assert math.dist(ego.position, ego_position(t)) < CM
    assert angle_between(ego.heading, ego_heading(t)) < 1e-9


def test_heading_interpolates_across_180_degrees(timeline: BagTimeline) -> None:
    """Between 179.x and -179.x deg the heading goes the short way, through 180."""
    crossing = (math.pi - math.radians(150.0)) / (10.0 / 50.0)  # when the heading is 180 deg
    k = int(crossing * EGO_HZ)
    before, after = timeline.sample(k / EGO_HZ).ego, timeline.sample((k + 1) / EGO_HZ).ego
    assert before is not None and after is not None
    assert before.heading > 3.0 and after.heading < -3.0
    middle = timeline.sample((k + 0.5) / EGO_HZ).ego
    assert middle is not None
    assert abs(middle.heading) > 3.1
    assert angle_between(middle.heading, ego_heading((k + 0.5) / EGO_HZ)) < 1e-9


def test_sampling_holds_at_the_ends(timeline: BagTimeline) -> None:
    assert timeline.sample(-5.0) == timeline.sample(0.0)
    assert timeline.sample(DURATION_S + 5.0) == timeline.sample(DURATION_S)
    assert timeline.sample(-5.0).time == 0.0


@pytest.mark.parametrize("t", [0.0, 0.05, 0.0725, 3.31, 4.94])
def test_objects_follow_their_tracks(timeline: BagTimeline, t: float) -> None:
    frame = timeline.sample(t)
    listed = {obj.unique_id: obj for obj in (*frame.npcs, *frame.pedestrians)}
    assert sorted(listed) == [11, 12, 13, 21]
    assert [obj.unique_id for obj in frame.pedestrians] == [21]
    assert all(obj.type == 1 for obj in frame.npcs)
    for moving in MOVING_OBJECTS:
        obj = listed[moving.unique_id]
        assert math.dist(obj.position, moving.position(t)) < CM
        assert obj.velocity[:2] == pytest.approx(moving.velocity, abs=1e-9)
        assert obj.heading == pytest.approx(math.atan2(moving.velocity[1], moving.velocity[0]))
        assert obj.name == f"object#{moving.unique_id}"
        assert obj.size == (1.8, 4.5, 1.5)


def test_object_missing_from_the_next_list_is_held(timeline: BagTimeline) -> None:
    """Object 13 is last listed at 4.95 s: between lists it stays where that list put it."""
    last_listed = 4.95
    t = last_listed + 0.5 / OBJECTS_HZ
    (obj,) = [o for o in timeline.sample(t).npcs if o.unique_id == 13]
    vanishing = next(m for m in MOVING_OBJECTS if m.unique_id == 13)
    assert math.dist(obj.position, vanishing.position(last_listed)) < 1e-9
    assert 13 not in [o.unique_id for o in timeline.sample(5.0).npcs]


def test_control_is_the_latest_command(timeline: BagTimeline) -> None:
    control = timeline.sample(3.37).control
    assert control is not None
    assert control.longitudinal_mode == 2
    assert control.velocity == pytest.approx(control_velocity_kmh(3.3) / 3.6)
    assert control.front_steer == 0.05


def test_topic_names_are_configurable(tmp_path: Path) -> None:
    bag = tmp_path / "renamed.bag"
    with Writer(bag) as writer:
        ego = writer.add_connection(
            "/sim/ego", EGO.store_name, msgdef=EGO.definition, md5sum=EGO.md5sum
        )
        for k in range(3):
            writer.write(ego, stamp(k), EGO.serialize(ego_message(k, k)))
    with pytest.raises(MissingTopicsError):
        BagTimeline.open(bag)
    timeline = BagTimeline.open(bag, topics=ReplayTopics(ego="/sim/ego"))
    assert timeline.duration == 2.0
    assert timeline.objects is None and timeline.control is None
    frame = timeline.sample(1.0)
    assert frame.npcs == () and frame.control is None


def test_zero_header_stamps_fall_back_to_receive_time(tmp_path: Path) -> None:
    """Unstamped messages go on the header clock via the stamped ones' offset."""
    bag = tmp_path / "mixed.bag"
    offset_ns = 5 * 10**9  # header clock runs 5 s ahead of the receive clock
    with Writer(bag) as writer:
        ego = writer.add_connection(
            "/Ego_topic", EGO.store_name, msgdef=EGO.definition, md5sum=EGO.md5sum
        )
        ctrl = writer.add_connection(
            "/ctrl_cmd", CONTROL.store_name, msgdef=CONTROL.definition, md5sum=CONTROL.md5sum
        )
        for k in range(5):
            message = ego_message(k, k)
            if k == 2:
                message.header.stamp.sec = message.header.stamp.nanosec = 0
            writer.write(ego, stamp(k) - offset_ns, EGO.serialize(message))
        writer.write(ctrl, stamp(2.5) - offset_ns, CONTROL.serialize(CONTROL.new(velocity=36.0)))
    timeline = BagTimeline.open(bag)
    assert timeline.start_ns == stamp(0)
    assert timeline.ego is not None and timeline.control is not None
    assert timeline.ego.times.tolist() == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert timeline.control.times.tolist() == [2.5]
    assert timeline.sample(2.4).control is None
    assert timeline.sample(2.5).control is not None


@pytest.mark.parametrize("release", ["24.r2", "2021.08"])
def test_a_bag_of_an_older_release_replays_its_steering(tmp_path: Path, release: str) -> None:
    """Before 26.r1 the front steer is EgoVehicleStatus.wheel_angle (deg) and
    CtrlCmd.steering (rad), and neither message has a rear steer."""
    profile = get_profile(release)
    ego_type, control_type = (
        profile.message("morai_msgs/EgoVehicleStatus"),
        profile.message("morai_msgs/CtrlCmd"),
    )
    bag = tmp_path / "older.bag"
    with Writer(bag) as writer:
        ego = writer.add_connection(
            "/Ego_topic", ego_type.store_name, msgdef=ego_type.definition, md5sum=ego_type.md5sum
        )
        ctrl = writer.add_connection(
            "/ctrl_cmd",
            control_type.store_name,
            msgdef=control_type.definition,
            md5sum=control_type.md5sum,
        )
        status = ego_type.new(wheel_angle=10.0)
        status.header.stamp.sec = 1
        writer.write(ego, stamp(0), ego_type.serialize(status))
        writer.write(ctrl, stamp(0), control_type.serialize(control_type.new(steering=0.2)))
    timeline = BagTimeline.open(bag)
    frame = timeline.sample(0.0)
    assert timeline.profile == release
    assert frame.ego is not None and frame.control is not None
    assert frame.ego.front_steer == pytest.approx(math.radians(10.0))
    assert frame.ego.rear_steer == 0.0
    assert (frame.control.front_steer, frame.control.rear_steer) == (pytest.approx(0.2), 0.0)


def test_every_release_egosim_speaks_can_be_replayed() -> None:
    assert RELEASE_NAMES == PROFILES


def test_other_release_is_reported_clearly(tmp_path: Path) -> None:
    bag = tmp_path / "other.bag"
    with Writer(bag) as writer:
        ego = writer.add_connection(
            "/Ego_topic", EGO.store_name, msgdef=EGO.definition, md5sum="0" * 32
        )
        writer.write(ego, stamp(0), EGO.serialize(ego_message(0, 0)))
    with pytest.raises(UnsupportedReleaseError, match=f"{'0' * 32}.*26.r1.*{EGO.md5sum}"):
        BagTimeline.open(bag)


def test_wrong_type_on_a_replay_topic_is_refused(tmp_path: Path) -> None:
    bag = tmp_path / "wrong.bag"
    with Writer(bag) as writer:
        ctrl = writer.add_connection(
            "/Ego_topic", CONTROL.store_name, msgdef=CONTROL.definition, md5sum=CONTROL.md5sum
        )
        writer.write(ctrl, stamp(0), CONTROL.serialize(CONTROL.new()))
    with pytest.raises(BagError, match="CtrlCmd"):
        BagTimeline.open(bag)


def test_corrupt_payload_is_a_bag_error(tmp_path: Path) -> None:
    bag = tmp_path / "corrupt.bag"
    with Writer(bag) as writer:
        ego = writer.add_connection(
            "/Ego_topic", EGO.store_name, msgdef=EGO.definition, md5sum=EGO.md5sum
        )
        writer.write(ego, stamp(0), b"\x01\x02")
    with pytest.raises(BagError):
        BagTimeline.open(bag)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        BagTimeline.open(tmp_path / "absent.bag")
