"""The precompiled serialisers give rosbags' bytes for every type of every release, and
leave whatever they do not take as it is to the generic serialiser."""

from __future__ import annotations

import random
import struct

import numpy as np
import pytest

from egosim.msgs import PROFILES, MessageType, SerializationError, get_profile
from tests.msgs.test_roundtrip import populated


def generic_bytes(message_type: MessageType, message: object) -> bytes:
    return bytes(message_type.store.serialize_ros1(message, message_type.store_name))


def every_type_of_every_release() -> list[tuple[str, str]]:
    """Every type each release's store holds: morai_msgs, its services' halves, and the
    ROS standard types, those egosim publishes and the rest."""
    return [
        (release, name)
        for release in PROFILES
        for name in sorted(get_profile(release).complete_store().fielddefs)
    ]


@pytest.mark.parametrize(("release", "name"), every_type_of_every_release())
def test_packed_bytes_are_the_generic_serialisers(release: str, name: str) -> None:
    message_type = get_profile(release).message(name)
    messages = [message_type.new()] + [
        populated(message_type, message_type.store_name, random.Random(f"{name}{seed}"))
        for seed in range(3)
    ]
    for message in messages:
        packed = message_type.pack(message)
        assert packed is not None, f"{name} in {release}: the layout refused {message}"
        assert packed == generic_bytes(message_type, message)
        assert message_type.serialize(message) == packed


def test_text_beyond_ascii_is_packed_as_utf8() -> None:
    header = get_profile().message("std_msgs/Header")
    message = header.new(seq=7, frame_id="Kamera-é-日本")
    assert header.pack(message) == generic_bytes(header, message)


def test_empty_sequences_are_packed() -> None:
    cloud = get_profile().message("sensor_msgs/PointCloud2")
    message = cloud.new(fields=[], data=np.zeros(0, np.uint8))
    assert cloud.pack(message) == generic_bytes(cloud, message)


def test_an_array_in_the_other_byte_order_gets_the_generic_bytes() -> None:
    imu = get_profile().message("sensor_msgs/Imu")
    message = imu.new(orientation_covariance=np.arange(9, dtype=">f8"))
    assert imu.pack(message) is None
    assert imu.serialize(message) == generic_bytes(imu, message)


@pytest.mark.parametrize(
    ("name", "values"),
    [
        ("sensor_msgs/Imu", {"orientation_covariance": np.zeros(8)}),  # 9 long on the wire
        ("sensor_msgs/Imu", {"orientation_covariance": [0.0] * 9}),  # not an array
        ("sensor_msgs/PointCloud2", {"data": [1, 2, 3]}),
        ("std_msgs/Header", {"seq": -1}),  # uint32
        ("std_msgs/Header", {"frame_id": b"map"}),  # bytes, not text
    ],
)
def test_what_the_generic_serialiser_refuses_is_still_refused(
    name: str, values: dict[str, object]
) -> None:
    message_type = get_profile().message(name)
    message = message_type.new(**values)
    assert message_type.pack(message) is None
    with pytest.raises(SerializationError, match=name.rpartition("/")[2]):
        message_type.serialize(message)


def leaf_values(message: object, leaves: tuple[str, ...], release: str) -> list[object]:
    """The values a flat packer takes for `message`: each leaf's, a sequence of messages
    as its elements' bytes."""
    values = []
    for path in leaves:
        value = message
        for part in path.split("."):
            value = getattr(value, part)
        if isinstance(value, list) and value and hasattr(type(value[0]), "__msgtype__"):
            element = get_profile(release).message(type(value[0]).__msgtype__)
            value = [element.serialize(item) for item in value]
        values.append(value)
    return values


@pytest.mark.parametrize(("release", "name"), every_type_of_every_release())
def test_flat_and_stamped_packers_give_the_message_s_bytes(release: str, name: str) -> None:
    message_type = get_profile(release).message(name)
    flat = message_type.flat()
    for seed in range(2):
        message = populated(message_type, message_type.store_name, random.Random(f"{name}{seed}"))
        if message_type.pack_stamped is not None:  # a stamp's nanosec is below 1 s
            message.header.stamp.nanosec %= 1_000_000_000  # type: ignore[attr-defined]
        data = generic_bytes(message_type, message)
        assert flat.pack(*leaf_values(message, flat.leaves, release)) == data
        if message_type.pack_stamped is not None:
            header = message.header  # type: ignore[attr-defined]
            stamp = header.stamp.sec * 1_000_000_000 + header.stamp.nanosec
            seq = header.seq
            header.seq, header.stamp.sec, header.stamp.nanosec = 0, 0, 0
            assert message_type.serialize_stamped(message, seq, stamp) == data


def test_a_range_of_leaves_packs_that_part_of_the_message() -> None:
    marker = get_profile().message("visualization_msgs/Marker")
    message = populated(marker, marker.store_name, random.Random(3))
    whole = marker.flat()
    values = dict(zip(whole.leaves, leaf_values(message, whole.leaves, "26.r1"), strict=True))
    parts = [marker.flat(last="ns"), marker.flat("id", "scale.z"), marker.flat("color.r")]
    assert [leaf for part in parts for leaf in part.leaves] == list(whole.leaves)
    packed = b"".join(part.pack(*(values[leaf] for leaf in part.leaves)) for part in parts)
    assert packed == generic_bytes(marker, message)
    with pytest.raises(ValueError, match="no leaf"):
        marker.flat("pose.position")


def test_a_message_given_as_its_bytes_serialises_as_those_bytes() -> None:
    header = get_profile().message("std_msgs/Header")
    data = header.serialize(header.new(seq=3, frame_id="map"))
    assert header.serialize(data) == data


def test_a_flat_packer_refuses_what_the_layout_does_not_take() -> None:
    header = get_profile().message("std_msgs/Header").flat()
    with pytest.raises(struct.error):
        header.pack(-1, 0, 0, "map")  # seq is a uint32
    imu = get_profile().message("sensor_msgs/Imu").flat()
    values = [0] * len(imu.leaves)
    values[imu.leaves.index("header.frame_id")] = "imu"
    with pytest.raises(ValueError):
        imu.pack(*values)  # the covariances are no numpy arrays


def test_a_stamped_message_its_layout_refuses_gets_the_generic_bytes_stamped() -> None:
    imu = get_profile().message("sensor_msgs/Imu")
    message = imu.new(orientation_covariance=np.arange(9, dtype=">f8"))
    stamped = imu.new(
        header=get_profile()
        .message("std_msgs/Header")
        .new(seq=4, stamp=get_profile().message("builtin_interfaces/Time").new(sec=2, nanosec=5)),
        orientation_covariance=np.arange(9, dtype=">f8"),
    )
    assert imu.pack_stamped is not None and imu.pack_stamped(message, 4, 2, 5) is None
    assert imu.serialize_stamped(message, 4, 2_000_000_005) == generic_bytes(imu, stamped)
