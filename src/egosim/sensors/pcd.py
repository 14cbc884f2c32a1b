"""Point Cloud Data (PCD v0.7) encoding of LiDAR points."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from egosim.sensors.errors import SensorError

PCD_FIELDS = ("x", "y", "z", "intensity")


def encode_pcd(points: npt.ArrayLike) -> bytes:
    """A binary PCD v0.7 file of (M, 4) points: x y z intensity, little-endian float32."""
    cloud = np.asarray(points, dtype="<f4")
    if cloud.ndim != 2 or cloud.shape[1] != len(PCD_FIELDS):
        raise SensorError(f"PCD points must have shape (M, 4), got {cloud.shape}")
    count = len(cloud)
    header = (
        "# .PCD v0.7 - Point Cloud Data file format\n"
        "VERSION 0.7\n"
        f"FIELDS {' '.join(PCD_FIELDS)}\n"
        "SIZE 4 4 4 4\n"
        "TYPE F F F F\n"
        "COUNT 1 1 1 1\n"
        f"WIDTH {count}\n"
        "HEIGHT 1\n"
        "VIEWPOINT 0 0 0 1 0 0 0\n"
        f"POINTS {count}\n"
        "DATA binary\n"
    )
    return header.encode("ascii") + np.ascontiguousarray(cloud).tobytes()
