"""Pinhole camera: intrinsics, mount, projection, and the matrices a rasteriser needs.

Frames: the camera body frame is placed on base_link by its MountPose and has base_link's
axes (x forward, y left, z up; positive pitch looks down). Its optical frame (REP 103's
`_optical` convention) has the same origin with z forward, x right, y down.

Intrinsics follow OpenCV: square pixels, the principal point at the image centre
((W - 1) / 2, (H - 1) / 2 with integer coordinates at pixel centres), no distortion.
The focal length comes from the field of view along one axis: MORAI SIM (Unity) gives the
vertical field of view, f = H / (2 tan(FOV / 2)); `FovAxis.HORIZONTAL` takes it along the
width instead, f = W / (2 tan(FOV / 2)), as most other simulators do.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

import numpy as np

from egosim.sensors.errors import SensorConfigError
from egosim.sensors.frames import MountPose, sensor_in_map
from egosim.sensors.rotation import Matrix3
from egosim.world.arrays import BoolArray, FloatArray
from egosim.world.vehicle import Pose

DEFAULT_CAMERA_MOUNT = MountPose(x=1.5, y=0.0, z=1.2)
"""Behind the windscreen: 1.5 m ahead of and 1.2 m above the mount origin, m."""

OPTICAL_IN_BODY: Matrix3 = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])
"""Columns: the optical frame's x (right), y (down), z (forward) in the body frame."""

# OpenGL's eye frame (x right, y up, z backward) from the optical frame.
_EYE_FROM_OPTICAL = np.diag([1.0, -1.0, -1.0])


class FovAxis(Enum):
    VERTICAL = "vertical"
    HORIZONTAL = "horizontal"


class CameraMode(Enum):
    RGB = "rgb"
    SEMANTIC = "semantic"
    INSTANCE = "instance"
    DEPTH = "depth"


@dataclass(frozen=True)
class Intrinsics:
    """Pinhole parameters in pixels (OpenCV convention)."""

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float

    @property
    def matrix(self) -> FloatArray:
        """K, 3 x 3."""
        return np.array([[self.fx, 0.0, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class CameraConfig:
    """One camera. Defaults: MORAI's front camera, 640 x 480, 90 deg vertical FOV, 30 Hz."""

    width: int = 640
    height: int = 480
    fov_deg: float = 90.0
    fov_axis: FovAxis = FovAxis.VERTICAL
    rate_hz: float = 30.0
    mount: MountPose = DEFAULT_CAMERA_MOUNT
    mode: CameraMode = CameraMode.RGB
    jpeg_quality: int = 90
    near_m: float = 0.1
    far_m: float = 1000.0

    def __post_init__(self) -> None:
        if not (1 <= self.width <= 8192 and 1 <= self.height <= 8192):
            raise SensorConfigError(
                f"image size must be 1..8192 px, got {self.width}x{self.height}"
            )
        if not 0.0 < self.fov_deg < 180.0:
            raise SensorConfigError(f"fov_deg must be in (0, 180), got {self.fov_deg}")
        if not 0.0 < self.rate_hz <= 1000.0:
            raise SensorConfigError(f"rate_hz must be in (0, 1000], got {self.rate_hz}")
        if not 1 <= self.jpeg_quality <= 100:
            raise SensorConfigError(f"jpeg_quality must be 1..100, got {self.jpeg_quality}")
        if not 0.0 < self.near_m < self.far_m:
            raise SensorConfigError("clip distances must satisfy 0 < near_m < far_m")

    @property
    def focal_length_px(self) -> float:
        span = self.height if self.fov_axis is FovAxis.VERTICAL else self.width
        return span / (2.0 * math.tan(math.radians(self.fov_deg) / 2.0))

    def intrinsics(self) -> Intrinsics:
        f = self.focal_length_px
        return Intrinsics(
            self.width, self.height, f, f, (self.width - 1) / 2.0, (self.height - 1) / 2.0
        )


@dataclass(frozen=True)
class CameraView:
    """Where a camera stands in the map: its optical centre and optical -> map rotation."""

    origin: FloatArray
    optical_to_map: Matrix3

    @classmethod
    def of(cls, vehicle_pose: Pose, mount: MountPose) -> CameraView:
        origin, body_to_map = sensor_in_map(vehicle_pose, mount)
        return cls(origin, body_to_map @ OPTICAL_IN_BODY)

    def to_optical(self, points: FloatArray) -> FloatArray:
        """(N, 3) map points in the optical frame."""
        return (np.asarray(points, dtype=np.float64) - self.origin) @ self.optical_to_map


def project(
    points: FloatArray, view: CameraView, intrinsics: Intrinsics
) -> tuple[FloatArray, FloatArray]:
    """Pixel coordinates (N, 2: u right, v down) and depth along the optical axis (N,, m)
    of map points; points behind the camera get NaN pixels."""
    optical = view.to_optical(points)
    depth = optical[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = intrinsics.fx * optical[:, 0] / depth + intrinsics.cx
        v = intrinsics.fy * optical[:, 1] / depth + intrinsics.cy
    behind = depth <= 0.0
    u[behind] = np.nan
    v[behind] = np.nan
    return np.column_stack((u, v)), depth


def view_matrix(view: CameraView) -> FloatArray:
    """4 x 4: map points (homogeneous) into OpenGL's eye frame."""
    eye_from_map = _EYE_FROM_OPTICAL @ view.optical_to_map.T
    matrix = np.eye(4)
    matrix[:3, :3] = eye_from_map
    matrix[:3, 3] = -eye_from_map @ view.origin
    return matrix


def projection_matrix(intrinsics: Intrinsics, near: float, far: float) -> FloatArray:
    """4 x 4 OpenGL clip matrix whose pixel grid matches `intrinsics` exactly.

    OpenGL's pixel k spans [k, k + 1) in window coordinates while OpenCV's spans
    [k - 0.5, k + 0.5), hence the half-pixel terms; window rows count up from the
    bottom, so v is mirrored.
    """
    w, h = intrinsics.width, intrinsics.height
    matrix = np.zeros((4, 4))
    matrix[0, 0] = 2.0 * intrinsics.fx / w
    matrix[0, 2] = 1.0 - 2.0 * (intrinsics.cx + 0.5) / w
    matrix[1, 1] = 2.0 * intrinsics.fy / h
    matrix[1, 2] = 2.0 * (intrinsics.cy + 0.5) / h - 1.0
    matrix[2, 2] = -(far + near) / (far - near)
    matrix[2, 3] = -2.0 * far * near / (far - near)
    matrix[3, 2] = -1.0
    return matrix


def scene_matrices(
    view: CameraView, intrinsics: Intrinsics, near: float, far: float, scene_origin: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """(eye_from_scene, clip_from_scene), 4 x 4, for points in a scene frame whose origin
    is `scene_origin` in the map."""
    scene_to_map = np.eye(4)
    scene_to_map[:3, 3] = scene_origin
    eye = view_matrix(view) @ scene_to_map
    return eye, projection_matrix(intrinsics, near, far) @ eye


# The 8 corners of a box as choices of (lower or upper) per axis.
_CORNER_PICKS = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], bool)


def boxes_in_view(lower: FloatArray, upper: FloatArray, clip_from_frame: FloatArray) -> BoolArray:
    """(N,) whether each axis-aligned box lower[k]..upper[k] (N, 3) may show through the
    4 x 4 matrix `clip_from_frame` from the boxes' frame to clip space.

    A box is out when all its corners are beyond the same clip plane (x > w, x < -w and
    so on); the test is linear in the point, so it holds behind the camera too. It may
    keep a box that shows nothing, never the reverse.
    """
    corners = np.where(_CORNER_PICKS[None], upper[:, None, :], lower[:, None, :])
    clip = corners @ clip_from_frame[:, :3].T + clip_from_frame[:, 3]
    w = clip[..., 3:4]
    beyond = np.concatenate((clip[..., :3] > w, clip[..., :3] < -w), axis=-1)
    shown: BoolArray = ~np.any(np.all(beyond, axis=1), axis=1)
    return shown
