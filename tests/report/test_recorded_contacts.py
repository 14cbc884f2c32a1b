"""Collisions as a report counts them from /CollisionData: a contact is listed in
every message while it lasts and counts once; one already listed by the bag's first message
was under way when the recording began and is told apart, not counted."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from egosim.cli import main
from egosim.msgs import get_profile
from egosim.replay import BagRecorder
from egosim.report import read_drive
from egosim.world.collision import REJOIN_S

P26 = get_profile("26.r1")
EGO = P26.message("morai_msgs/EgoVehicleStatus")
COLLISION = P26.message("morai_msgs/CollisionData")
OBJECT = P26.message("morai_msgs/ObjectStatus")
START_NS = 1_800_000_000 * 10**9
RATE_HZ = 20  # the row's default rate
DURATION_S = 6.0
BARRIER, CONE = 11, 12


def _header(type_name: str, t: float) -> Any:
    header = P26.message(type_name).new().header
    header.stamp.sec, header.stamp.nanosec = divmod(START_NS + round(t * 1e9), 10**9)
    return header


def _object(unique_id: int, x: float) -> Any:
    position = P26.message("geometry_msgs/Vector3").make(x=x, y=-1.75, z=0.0)
    name = {BARRIER: "Barrier", CONE: "Cone"}[unique_id]
    return OBJECT.new(unique_id=unique_id, type=2, name=name, position=position)


def write_bag(path: Path, touching: Callable[[float], list[int]]) -> Path:
    """An ego standing still and a CollisionData at 20 Hz listing `touching(t)`."""
    with BagRecorder(path) as recorder:
        ego = recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition)
        hits = recorder.add_connection(
            "/CollisionData", COLLISION.name, COLLISION.md5sum, COLLISION.definition
        )
        for k in range(round(DURATION_S * RATE_HZ) + 1):
            t = k / RATE_HZ
            stamp = START_NS + round(t * 1e9)
            status = EGO.new(header=_header(EGO.name, t))
            recorder.write(ego, stamp, EGO.serialize(status))
            listed = [_object(uid, 40.0 + uid) for uid in touching(t)]
            message = COLLISION.new(header=_header(COLLISION.name, t), collision_object=listed)
            recorder.write(hits, stamp, COLLISION.serialize(message))
    return path


def test_a_lasting_contact_is_one_collision(tmp_path: Path) -> None:
    drive = read_drive(write_bag(tmp_path / "d.bag", lambda t: [BARRIER] if t >= 2.0 else []))
    (collision,) = drive.collisions
    assert (collision.time_s, collision.unique_id, collision.name) == (2.0, BARRIER, "Barrier")
    assert collision.x == pytest.approx(40.0 + BARRIER)
    assert drive.contacts_at_start == ()


def test_touching_again_soon_after_parting_is_the_same_collision(tmp_path: Path) -> None:
    """As the simulator counts them: a bounce (back within REJOIN_S) is one collision, a
    touch after longer apart another."""
    soon, later = 2.0 + REJOIN_S / 2, 4.0 + REJOIN_S * 1.5

    def touching(t: float) -> list[int]:
        return [BARRIER] if 1.0 <= t < 2.0 or soon <= t < 3.0 or t >= later else []

    drive = read_drive(write_bag(tmp_path / "d.bag", touching))
    assert [c.time_s for c in drive.collisions] == pytest.approx([1.0, later])


def test_a_contact_in_the_first_message_was_under_way_before_the_recording(
    tmp_path: Path,
) -> None:
    """The ego rests against a barrier it hit before the bag began, then hits a cone."""
    bag = write_bag(tmp_path / "late.bag", lambda t: [BARRIER] + ([CONE] if t >= 3.0 else []))
    drive = read_drive(bag)
    (under_way,) = drive.contacts_at_start
    assert (under_way.time_s, under_way.unique_id) == (0.0, BARRIER)
    (collision,) = drive.collisions
    assert (collision.time_s, collision.unique_id) == (3.0, CONE)
    page = tmp_path / "report.html"
    assert main(["report", str(bag), "-o", str(page), "--map", "straight"]) == 0
    text = page.read_text()
    assert "collisions: 1 (1 more already under way when the recording began: not counted)" in (
        text
    )
    assert "already touching Barrier (id 11) when the recording began" in text
