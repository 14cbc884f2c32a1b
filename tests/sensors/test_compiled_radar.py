"""The compiled radar (world/kernels/radar_detections.py) against the numpy path: random
traffic around a moving, turning carrier gives bit-identical detections, an object at
the sensor itself included."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from egosim.sensors import MountPose, Pose
from egosim.sensors.radar import RadarConfig, RadarDetections, RadarModel, RadarNoise
from egosim.world import kernels
from egosim.world.traffic.objects import ObjectTable

pytestmark = pytest.mark.skipif(
    not kernels.AVAILABLE, reason="no compiled path: numba missing or EGOSIM_COMPILED=0"
)

FIELDS = ("unique_ids", "positions", "azimuths", "range_rates", "amplitudes")


def traffic(rng: np.random.Generator, count: int) -> ObjectTable:
    """The carrier (id 1) at the origin, then cars and pedestrians within 160 m, some at
    equal distances (ties), some behind, above or below the field of view."""
    distance = rng.uniform(0.2, 160.0, count)
    bearing = rng.uniform(-np.pi, np.pi, count)
    sizes = rng.choice([(4.5, 1.9, 1.6), (0.6, 0.6, 1.8), (12.0, 2.5, 3.8)], count)
    positions = np.c_[
        distance * np.cos(bearing), distance * np.sin(bearing), rng.normal(0, 2, count)
    ]
    # A quarter share one position and one height: equal distances, kept in table order.
    positions[: count // 4] = positions[0]
    sizes[: count // 4] = sizes[0]
    return ObjectTable(
        unique_ids=np.r_[1, np.arange(2, count + 2)].astype(np.int64),
        object_types=np.ones(count + 1, np.int64),
        names=("",) * (count + 1),
        positions=np.r_[[[0.0, 0.0, 0.0]], positions],
        headings=rng.uniform(-np.pi, np.pi, count + 1),
        velocities=rng.normal(0.0, 8.0, (count + 1, 3)),
        accelerations=np.zeros((count + 1, 3)),
        sizes=np.r_[[(4.5, 1.9, 1.6)], sizes],
    )


def detected(model: RadarModel, table: ObjectTable, pose: Pose, seed: int) -> RadarDetections:
    rng = np.random.default_rng(seed)
    return model.detect(pose, (3.0, -1.0, 0.0), 0.2, table, hidden_ids=(1,), rng=rng)


@pytest.mark.parametrize(
    "config",
    [
        RadarConfig(),
        RadarConfig(
            horizontal_fov_deg=360.0,
            min_range_m=0.0,
            max_detections=7,
            mount=MountPose(x=3.6, y=0.4, z=0.3, yaw=0.4, pitch=0.05),
            noise=RadarNoise(range_std_m=0.3, azimuth_std_rad=0.02, range_rate_std_m_s=0.1),
        ),
    ],
)
def test_compiled_and_numpy_detections_are_identical(
    config: RadarConfig, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(4)
    model = RadarModel(config)
    seen = 0
    for k in range(20):
        table = traffic(rng, int(rng.integers(1, 120)))
        pose = Pose(x=float(rng.normal()), y=float(rng.normal()), yaw=float(rng.uniform(-3, 3)))
        monkeypatch.setattr(kernels, "ACTIVE", True)
        compiled = detected(model, table, pose, k)
        monkeypatch.setattr(kernels, "ACTIVE", False)
        plain = detected(model, table, pose, k)
        for name in FIELDS:
            assert getattr(compiled, name).tobytes() == getattr(plain, name).tobytes(), name
        seen += len(compiled)
    assert seen > 100


def test_an_object_at_the_sensor_itself_is_detected_as_numpy_detects_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Gated from 0 m, an object whose centre is the sensor's origin is a detection at
    distance 0: numpy's division gives NaN there, and the compiled path must not fail."""
    model = RadarModel(RadarConfig(min_range_m=0.0))
    mount = model.config.mount
    table = ObjectTable(
        unique_ids=np.array([5, 6], np.int64),
        object_types=np.ones(2, np.int64),
        names=("", ""),
        # The first box's centre (half its 0.4 m up) is the radar's origin.
        positions=np.array([[mount.x, mount.y, mount.z - 0.2], [20.0, 1.0, 0.0]]),
        headings=np.zeros(2),
        velocities=np.ones((2, 3)),
        accelerations=np.zeros((2, 3)),
        sizes=np.array([[4.5, 1.8, 0.4], [4.5, 1.8, 1.5]]),
    )
    results = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # numpy's 0 / 0
        for compiled in (True, False):
            monkeypatch.setattr(kernels, "ACTIVE", compiled)
            results.append(model.detect(Pose(), (0.0, 0.0, 0.0), 0.0, table))
    compiled_detections, plain = results
    assert compiled_detections.unique_ids.tolist() == [5, 6]
    assert np.isnan(compiled_detections.range_rates[0])
    for name in FIELDS:
        assert getattr(compiled_detections, name).tobytes() == getattr(plain, name).tobytes()
