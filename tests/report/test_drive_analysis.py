"""A recorded drive read back and set against its map: series in SI, lane errors, red
lights run and collisions (a bag written as egosim records one, no ROS needed)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from egosim.cli import main
from egosim.msgs import get_profile
from egosim.replay import BagRecorder
from egosim.report import best_fitting_map, lane_errors, read_drive, red_lights_run
from egosim.report.page import drive_events
from egosim.world.map import BUILTIN_MAP_NAMES, build_builtin_map

P26, P2021 = get_profile("26.r1"), get_profile("2021.08")
START_NS = 1_800_000_000 * 10**9
EGO_HZ = 50
LIGHT_HZ = 10
SPEED_MPS = 10.0
OFFSET_M = 0.3  # left of R1_E_1's centre line (the lane runs east along y = -271.75)
HEADING_RAD = 0.02
START_X = -200.0
STOP_LINE_X = -109.5  # R1_E_1's stop line, under TL2_W
DURATION_S = 12.0
COLLISION_S = 11.0


def _vector(profile: Any, x: float, y: float, z: float = 0.0) -> Any:
    return profile.message("geometry_msgs/Vector3").make(x=x, y=y, z=z)


def _header(profile: Any, type_name: str, t: float) -> Any:
    header = profile.message(type_name).new().header
    header.stamp.sec, header.stamp.nanosec = divmod(START_NS + round(t * 1e9), 10**9)
    return header


def ego_x(t: float, speed: float = SPEED_MPS) -> float:
    return START_X + speed * t


def write_drive(
    path: Path, light_aspect: int, ego_hz: int = EGO_HZ, speed: float = SPEED_MPS
) -> Path:
    """The drive east along R1_E_1 through TL2_W's stop line, /Ego_topic at `ego_hz`, the
    light's status at 10 Hz, /CollisionData at half the ego's rate (a cone hit at 11 s)."""
    ego = P26.message("morai_msgs/EgoVehicleStatus")
    light = P26.message("morai_msgs/GetTrafficLightStatus")
    with BagRecorder(path) as recorder:
        handles = {
            (topic, profile.name): recorder.add_connection(
                topic, kind.name, kind.md5sum, kind.definition
            )
            for topic, profile, kind in (
                ("/Ego_topic", P26, ego),
                ("/GetTrafficLightStatus", P26, light),
                ("/CollisionData", P26, P26.message("morai_msgs/CollisionData")),
                # A 2021.08 client was served too: its connection holds the same collisions.
                ("/CollisionData", P2021, P2021.message("morai_msgs/CollisionData")),
            )
        }
        messages = []
        for k in range(int(DURATION_S * LIGHT_HZ) + 1):
            t = k / LIGHT_HZ
            status = light.new(
                header=_header(P26, light.name, t),
                trafficLightIndex="TL2_W",
                trafficLightType=2,
                trafficLightStatus=light_aspect,
            )
            messages.append(
                (t, handles["/GetTrafficLightStatus", "26.r1"], light.serialize(status))
            )
        for k in range(int(DURATION_S * ego_hz) + 1):
            t = k / ego_hz
            message = ego.new(
                header=_header(P26, ego.name, t),
                position=_vector(P26, ego_x(t, speed), -271.75 + OFFSET_M),
                velocity=_vector(P26, speed, 0.0),
                heading=math.degrees(HEADING_RAD),
                accel=0.25,
                brake=0.0,
                front_steer_angle=1.5,
            )
            messages.append((t, handles["/Ego_topic", "26.r1"], ego.serialize(message)))
            if k % 2 == 0:
                for profile in (P26, P2021):
                    kind = profile.message("morai_msgs/CollisionData")
                    hit = abs(t - COLLISION_S) < 1e-9
                    objects = [
                        profile.message("morai_msgs/ObjectStatus").new(
                            unique_id=7,
                            type=2,
                            name="Cone",
                            position=_vector(profile, ego_x(t, speed) + 2.0, -271.75),
                        )
                    ]
                    collision = kind.new(
                        header=_header(profile, kind.name, t),
                        collision_object=objects if hit else [],
                    )
                    handle = handles["/CollisionData", profile.name]
                    messages.append((t, handle, kind.serialize(collision)))
        for t, handle, data in sorted(messages, key=lambda m: m[0]):
            recorder.write(handle, START_NS + round(t * 1e9), data)
    return path


@pytest.fixture(scope="module")
def town():
    return build_builtin_map("town")


@pytest.fixture(scope="module")
def red_drive(tmp_path_factory: pytest.TempPathFactory):
    return read_drive(write_drive(tmp_path_factory.mktemp("bags") / "red.bag", light_aspect=1))


def test_series_are_the_recorded_values_in_si(red_drive) -> None:
    n = int(DURATION_S * EGO_HZ) + 1
    t = np.arange(n) / EGO_HZ
    assert np.allclose(red_drive.times_s, t)
    assert np.allclose(red_drive.x, START_X + SPEED_MPS * t)
    assert np.allclose(red_drive.speed_mps, SPEED_MPS)
    assert np.allclose(red_drive.heading, HEADING_RAD)
    assert np.allclose(red_drive.front_steer_rad, math.radians(1.5))
    assert np.allclose(red_drive.accel_pedal, 0.25)


def test_lane_errors_against_the_lane_driven(town, red_drive) -> None:
    errors = lane_errors(town, red_drive)
    on_road = red_drive.x < -114.0  # before the junction connectors begin at x = -104
    assert set(np.array(errors.lane_ids)[on_road]) == {"R1_E_1"}
    assert np.allclose(errors.lateral_m[on_road], OFFSET_M)
    assert np.allclose(errors.heading_error_rad[on_road], HEADING_RAD)


def test_a_red_light_run_once_at_the_stop_line(town, red_drive) -> None:
    (run,) = red_lights_run(town, red_drive, lane_errors(town, red_drive))
    crossing_s = (STOP_LINE_X - START_X) / SPEED_MPS
    assert run.time_s == pytest.approx(crossing_s, abs=1.0 / EGO_HZ)
    assert (run.x, run.y) == pytest.approx((STOP_LINE_X, -271.75))
    assert "TL2_W" in run.detail


def test_a_red_light_run_between_sparse_samples(town, tmp_path: Path) -> None:
    # At 45 m/s and 1 Hz: 0.5 m before the line, then 44.5 m past it, beyond the junction.
    speed = 45.0
    drive = read_drive(write_drive(tmp_path / "sparse.bag", 1, ego_hz=1, speed=speed))
    (run,) = red_lights_run(town, drive, lane_errors(town, drive))
    assert run.time_s == pytest.approx((STOP_LINE_X - START_X) / speed, abs=1e-6)
    assert (run.x, run.y) == pytest.approx((STOP_LINE_X, -271.75))


def test_green_is_no_violation(town, tmp_path: Path) -> None:
    drive = read_drive(write_drive(tmp_path / "green.bag", light_aspect=16))
    assert red_lights_run(town, drive, lane_errors(town, drive)) == []


def test_each_collision_counts_once_across_releases(town, red_drive) -> None:
    (collision,) = red_drive.collisions
    assert collision.time_s == pytest.approx(COLLISION_S)
    assert (collision.x, collision.name, collision.unique_id) == (
        pytest.approx(ego_x(COLLISION_S) + 2.0),
        "Cone",
        7,
    )
    events = drive_events(
        red_drive, town, red_lights_run(town, red_drive, lane_errors(town, red_drive))
    )
    assert [(e.kind, e.label) for e in events] == [
        ("red_light", "red light TL2_W"),
        ("collision", "hit Cone"),
    ]


def test_the_map_a_drive_was_on_is_found(red_drive) -> None:
    maps = [build_builtin_map(name) for name in BUILTIN_MAP_NAMES]
    assert best_fitting_map(red_drive.xy, maps).name == "town"


def test_report_command_errors_are_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    not_a_bag = tmp_path / "notes.bag"
    not_a_bag.write_text("not a bag\n")
    for bag, expected in (
        (tmp_path / "missing.bag", "no bag at"),
        (not_a_bag, "is not a ROS 1 v2.0 bag"),
    ):
        assert main(["report", str(bag), "-o", str(tmp_path / "r.html")]) == 2
        (line,) = capsys.readouterr().err.splitlines()
        assert line.startswith("egosim report: ") and expected in line
    bag = write_drive(tmp_path / "drive.bag", light_aspect=1)
    assert main(["report", str(bag), "-o", str(tmp_path / "none" / "r.html")]) == 2
    assert capsys.readouterr().err.strip() == f"egosim report: no folder {tmp_path / 'none'}"
    assert main(["report", str(bag), "-o", str(tmp_path / "r.html"), "--map", "nowhere"]) == 2
    assert "nowhere: no such file or folder" in capsys.readouterr().err


def test_report_command_on_a_named_map(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bag = write_drive(tmp_path / "drive.bag", light_aspect=1)
    page = tmp_path / "drive.html"
    assert main(["report", str(bag), "-o", str(page), "--map", "town"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out == [
        "map: town",
        f"wrote {page}",
        f"wrote {tmp_path / 'drive_trajectory.png'}",
        f"wrote {tmp_path / 'drive_series.png'}",
    ]
    text = page.read_text()
    assert "red lights run: 1" in text and "collisions: 1" in text
    assert "<td>red_light</td>" in text and "<td>collision</td>" in text
