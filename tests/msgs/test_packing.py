"""The precompiled serialisers give rosbags' bytes for every type of every release, and
leave whatever they do not take as it is to the generic serialiser."""

from __future__ import annotations

import random

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
        for name in sorted(get_profile(release).store.fielddefs)
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
