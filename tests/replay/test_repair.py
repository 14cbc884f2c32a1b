"""A recorder killed mid-recording leaves a bag that opens with every complete chunk."""

from __future__ import annotations

import os
import shutil
from pathlib import Path
from typing import Any

import pytest
from rosbags.rosbag1 import Reader

from egosim.replay import BagError, BagRecorder, BagTimeline, needs_repair, repair_bag
from tests.replay.crash import record_and_kill
from tests.replay.drive import EGO, ego_position, stamp


def ego_positions(path: Path) -> list[tuple[int, float]]:
    with Reader(path) as reader:
        return [(t, EGO.deserialize(data).position.x) for _, t, data in reader.messages()]


@pytest.fixture(scope="module")
def killed_bag(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Any]:
    """A bag of 2000 ego messages in 16 KiB chunks whose recorder was killed before closing."""
    path = tmp_path_factory.mktemp("killed") / "killed.bag"
    stats = record_and_kill(path, 2000, 16 * 1024, flush_interval=3600.0)
    return path, stats


def test_killed_bag_keeps_every_complete_chunk(
    killed_bag: tuple[Path, Any], tmp_path: Path
) -> None:
    original, stats = killed_bag
    bag = shutil.copy(original, tmp_path / "killed.bag")
    assert needs_repair(bag)
    report = repair_bag(bag)
    assert report.repaired
    assert report.chunks == stats["chunks"]
    assert report.messages == stats["flushed"]
    assert report.connections == 1
    assert not needs_repair(bag)
    # The survivors are the first messages, in order and intact.
    positions = ego_positions(bag)
    assert [t for t, _ in positions] == [stamp(k / 50) for k in range(stats["flushed"])]
    for k, (_, x) in enumerate(positions):
        assert x == pytest.approx(ego_position(k / 50)[0], abs=1e-9)


def test_timeline_repairs_on_open(killed_bag: tuple[Path, Any], tmp_path: Path) -> None:
    original, stats = killed_bag
    bag = shutil.copy(original, tmp_path / "killed.bag")
    timeline = BagTimeline.open(bag)
    assert not needs_repair(bag)
    assert timeline.ego is not None
    assert len(timeline.ego) == stats["flushed"]
    assert timeline.duration == pytest.approx((stats["flushed"] - 1) / 50)


def test_truncated_trailing_chunk_is_dropped(killed_bag: tuple[Path, Any], tmp_path: Path) -> None:
    original, stats = killed_bag
    reference = shutil.copy(original, tmp_path / "reference.bag")
    repair_bag(reference)
    with Reader(reference) as reader:
        last_chunk = reader.chunk_infos[-1]
    in_last_chunk = sum(last_chunk.connection_counts.values())
    cut = shutil.copy(original, tmp_path / "cut.bag")
    os.truncate(cut, last_chunk.pos + 100)  # the process died writing that chunk
    report = repair_bag(cut)
    assert report.chunks == stats["chunks"] - 1
    assert report.messages == stats["flushed"] - in_last_chunk
    assert report.truncated_bytes == 100
    assert len(ego_positions(cut)) == report.messages


def chunk_positions(killed: Path, scratch: Path) -> list[int]:
    reference = shutil.copy(killed, scratch / "reference.bag")
    repair_bag(reference)
    with Reader(reference) as reader:
        return [info.pos for info in reader.chunk_infos]


@pytest.mark.parametrize(
    ("chunk", "damage"),
    [
        (0, lambda data, pos: data.find(b"op=", pos) + 3),  # the first chunk's op
        (3, lambda data, pos: data.find(b"size=", pos) + 5),  # a middle chunk's size
        (1, lambda data, pos: pos + 1),  # the length of a chunk's header
    ],
)
def test_a_damaged_bag_is_refused_and_left_as_it_is(
    killed_bag: tuple[Path, Any], tmp_path: Path, chunk: int, damage: Any
) -> None:
    original, _ = killed_bag
    data = bytearray(Path(original).read_bytes())
    data[damage(data, chunk_positions(original, tmp_path)[chunk])] ^= 0xFF
    bag = tmp_path / "damaged.bag"
    bag.write_bytes(data)
    with pytest.raises(BagError, match="damaged"):
        repair_bag(bag)
    with pytest.raises(BagError, match="damaged"):
        BagTimeline.open(bag)
    assert bag.read_bytes() == data


def test_quiet_bag_reaches_disk_by_periodic_flush(tmp_path: Path) -> None:
    """Five messages never fill a chunk; the periodic flush still puts them on disk."""
    bag = tmp_path / "quiet.bag"
    stats = record_and_kill(bag, 5, 768 * 1024, flush_interval=0.05)
    assert stats["flushed"] == 5
    report = repair_bag(bag)
    assert report.messages == 5
    assert len(ego_positions(bag)) == 5


def test_indexed_bag_is_left_alone(recorded_drive: Path, tmp_path: Path) -> None:
    bag = shutil.copy(recorded_drive, tmp_path / "drive.bag")
    before = Path(bag).read_bytes()
    assert not repair_bag(bag).repaired
    assert Path(bag).read_bytes() == before


def test_not_a_bag_is_refused(tmp_path: Path) -> None:
    junk = tmp_path / "junk.bag"
    junk.write_bytes(b"#ROSBAG V1.2\n" + bytes(100))
    with pytest.raises(BagError):
        repair_bag(junk)


def test_bag_being_recorded_is_not_touched(tmp_path: Path) -> None:
    with BagRecorder(tmp_path / "live.bag") as recorder:
        handle = recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition)
        recorder.write(handle, stamp(0.0), EGO.serialize(EGO.new()))
        with pytest.raises(BagError):
            repair_bag(tmp_path / "live.bag")
        with pytest.raises(BagError):
            BagTimeline.open(tmp_path / "live.bag")


@pytest.mark.parametrize("offset", [0, 1, 2])
def test_a_bag_header_whose_names_are_not_text_is_refused(
    recorded_drive: Path, tmp_path: Path, offset: int
) -> None:
    data = bytearray(Path(recorded_drive).read_bytes())
    # Past the magic line, the header length and the first field's length: its name.
    data[len(b"#ROSBAG V2.0\n") + 8 + offset] ^= 0xFF
    bag = tmp_path / "garbled.bag"
    bag.write_bytes(data)
    with pytest.raises(BagError):
        BagTimeline.open(bag)
