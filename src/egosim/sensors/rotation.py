"""Rotations as used across the sensors: ROS convention, angles in rad.

Roll, pitch and yaw are the fixed-axis x-y-z angles of REP 103, i.e. the
rotation taking body vectors into the parent frame is Rz(yaw) Ry(pitch) Rx(roll).
Quaternions are (x, y, z, w), as in geometry_msgs/Quaternion.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

Matrix3 = npt.NDArray[np.float64]
Quaternion = tuple[float, float, float, float]


def rotation_matrix(roll: float, pitch: float, yaw: float) -> Matrix3:
    """Rz(yaw) @ Ry(pitch) @ Rx(roll): child-frame vectors into the parent frame."""
    cr, sr = _cos_sin(roll)
    cp, sp = _cos_sin(pitch)
    cy, sy = _cos_sin(yaw)
    # The products on plain floats: the same IEEE operations as on numpy scalars,
    # without their per-operation overhead.
    return np.array(
        (
            cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr,
        )
    ).reshape(3, 3)  # fmt: skip


def _cos_sin(angle: float) -> tuple[float, float]:
    """libm's cosine and sine: numpy's own for float64 (the compiled kernels rely on the
    same), without its per-call overhead."""
    try:
        return math.cos(angle), math.sin(angle)
    except ValueError:  # an infinite angle: numpy's NaN (and warning), as before
        return float(np.cos(angle)), float(np.sin(angle))


def quaternion_from_matrix(rotation: Matrix3) -> Quaternion:
    """Unit quaternion (x, y, z, w) with w >= 0 of a proper rotation matrix."""
    m = rotation.tolist()  # plain floats: the arithmetic below is the same, only cheaper
    # Branch on the largest diagonal term so the square root never nears zero.
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0.0:
        s = 2.0 * math.sqrt(1.0 + trace)
        q = (
            (m[2][1] - m[1][2]) / s,
            (m[0][2] - m[2][0]) / s,
            (m[1][0] - m[0][1]) / s,
            0.25 * s,
        )
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2])
        q = (
            0.25 * s,
            (m[0][1] + m[1][0]) / s,
            (m[0][2] + m[2][0]) / s,
            (m[2][1] - m[1][2]) / s,
        )
    elif m[1][1] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2])
        q = (
            (m[0][1] + m[1][0]) / s,
            0.25 * s,
            (m[1][2] + m[2][1]) / s,
            (m[0][2] - m[2][0]) / s,
        )
    else:
        s = 2.0 * math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1])
        q = (
            (m[0][2] + m[2][0]) / s,
            (m[1][2] + m[2][1]) / s,
            0.25 * s,
            (m[1][0] - m[0][1]) / s,
        )
    sign = -1.0 if q[3] < 0.0 else 1.0
    x, y, z, w = q
    # Added left to right, not by sum(): Python 3.12's sum() compensates float rounding.
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    return (sign * x / norm, sign * y / norm, sign * z / norm, sign * w / norm)


def quaternion_from_euler(roll: float, pitch: float, yaw: float) -> Quaternion:
    """Quaternion (x, y, z, w) of rotation_matrix(roll, pitch, yaw)."""
    return quaternion_from_matrix(rotation_matrix(roll, pitch, yaw))
