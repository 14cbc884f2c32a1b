"""The compiled box cast (world/kernels/ray_boxes.py) against the numpy path: LiDAR
scans of random traffic, the sensor among the boxes, give bit-identical points."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.sensors import LidarConfig, LidarModel, ObstacleBoxes, Pose
from egosim.world import kernels

pytestmark = pytest.mark.skipif(
    not kernels.AVAILABLE, reason="no compiled path: numba missing or EGOSIM_COMPILED=0"
)


def traffic(rng: np.random.Generator, count: int) -> ObstacleBoxes:
    """The ego's box first, then cars, cones and trucks within 60 m, some touching it,
    some straddling the bearing of +-180 degrees, some above the sensor."""
    distance = rng.uniform(1.0, 60.0, count)
    bearing = rng.uniform(-np.pi, np.pi, count)
    bearing[: count // 5] = np.pi - rng.uniform(0.0, 0.05, count // 5)
    sizes = rng.choice([(4.5, 1.9, 1.6), (0.4, 0.4, 0.7), (12.0, 2.5, 3.8)], count)
    centres = np.c_[distance * np.cos(bearing), distance * np.sin(bearing), sizes[:, 2] / 2.0]
    return ObstacleBoxes(
        np.r_[[[0.0, 0.0, 0.8]], centres],
        np.r_[[(4.5, 1.9, 1.6)], sizes],
        np.r_[0.0, rng.uniform(-np.pi, np.pi, count)],
    )


def test_compiled_and_numpy_scans_give_identical_points(monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(11)
    model = LidarModel(LidarConfig())
    hits = 0
    for _ in range(12):
        scene = traffic(rng, int(rng.integers(1, 80)))
        pose = Pose(x=float(rng.normal()), y=float(rng.normal()), yaw=float(rng.uniform(-3, 3)))
        scans = []
        for compiled in (True, False):
            monkeypatch.setattr(kernels, "ACTIVE", compiled)
            scans.append(model.scan(pose, scene, exclude_index=0))
        assert scans[0].tobytes() == scans[1].tobytes()
        hits += int(np.count_nonzero(scans[0][:, 2] > -1.0))
    assert hits > 1000  # the boxes were seen, not only the ground


@pytest.mark.parametrize(
    ("config", "pose"),
    [
        # Tilted on a slope, the points' ranges gated close in.
        (LidarConfig(min_range_m=6.0, max_range_m=40.0), Pose(roll=0.04, pitch=-0.09, yaw=2.9)),
        # Below the ground plane: no ground returns, only boxes.
        (LidarConfig(channels=8), Pose(z=-3.0, yaw=-1.2)),
        # Steep beams and a coarse spin, no range gate to speak of.
        (
            LidarConfig(
                channels=32, min_elevation_deg=-60.0, max_elevation_deg=30.0,
                horizontal_resolution_deg=1.0, min_range_m=0.0,
            ),
            Pose(pitch=0.3, yaw=0.5),
        ),
    ],
)  # fmt: skip
def test_compiled_and_numpy_returns_agree_on_slopes_gates_and_heights(
    monkeypatch: pytest.MonkeyPatch, config: LidarConfig, pose: Pose
) -> None:
    model = LidarModel(config)
    scene = traffic(np.random.default_rng(5), 60)
    scans = []
    for compiled in (True, False):
        monkeypatch.setattr(kernels, "ACTIVE", compiled)
        scans.append(model.scan(pose, scene, exclude_index=0))
    assert len(scans[0]) > 100
    assert scans[0].tobytes() == scans[1].tobytes()
