"""PCD v0.7 encoding."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.sensors import LidarModel, Pose, encode_pcd
from egosim.sensors.errors import SensorError

HEADER_LINES = 11


def split_pcd(data: bytes) -> tuple[dict[str, str], np.ndarray]:
    lines = data.split(b"\n", HEADER_LINES)
    header = dict(
        line.decode("ascii").split(" ", 1)
        for line in lines[:HEADER_LINES]
        if not line.startswith(b"#")
    )
    return header, np.frombuffer(lines[HEADER_LINES], dtype="<f4").reshape(-1, 4)


def test_header_describes_float32_xyz_intensity() -> None:
    points = LidarModel().scan(Pose())
    header, _ = split_pcd(encode_pcd(points))
    assert header == {
        "VERSION": "0.7",
        "FIELDS": "x y z intensity",
        "SIZE": "4 4 4 4",
        "TYPE": "F F F F",
        "COUNT": "1 1 1 1",
        "WIDTH": str(len(points)),
        "HEIGHT": "1",
        "VIEWPOINT": "0 0 0 1 0 0 0",
        "POINTS": str(len(points)),
        "DATA": "binary",
    }


def test_data_round_trips() -> None:
    points = LidarModel().scan(Pose())
    _, decoded = split_pcd(encode_pcd(points))
    np.testing.assert_array_equal(decoded, points)


def test_empty_cloud_encodes() -> None:
    header, decoded = split_pcd(encode_pcd(np.empty((0, 4), dtype=np.float32)))
    assert header["POINTS"] == "0"
    assert decoded.shape == (0, 4)


def test_wrong_shape_is_refused() -> None:
    with pytest.raises(SensorError):
        encode_pcd(np.zeros((5, 3)))
