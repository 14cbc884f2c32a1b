"""BagRecorder: what it writes reads back with rosbags, and it never makes the caller wait."""

from __future__ import annotations

import threading
from pathlib import Path

import pytest
from rosbags.rosbag1 import Reader

from egosim.replay import BagRecorder, RecorderError, needs_repair
from egosim.replay import recorder as recorder_module
from tests.replay.drive import CONTROL, EGO, OBJECTS, drive_messages, expected_counts, stamp

TYPES = {"/Ego_topic": EGO, "/Object_topic": OBJECTS, "/ctrl_cmd": CONTROL}


def test_drive_reads_back_with_rosbags(recorded_drive: Path) -> None:
    with Reader(recorded_drive) as reader:
        connections = {c.topic: c for c in reader.connections}
        assert set(connections) == set(TYPES)
        for topic, kind in TYPES.items():
            connection = connections[topic]
            assert connection.msgtype == kind.store_name
            assert connection.digest == kind.md5sum
            assert connection.msgdef.data == kind.definition
            assert connection.ext.callerid == "/egosim"
            assert connection.ext.latching == 0
            assert connection.msgcount == expected_counts()[topic]
        assert reader.start_time == stamp(0.0)
        assert reader.end_time == stamp(10.0) + 1  # rosbags reports the end exclusive


def test_payload_bytes_and_receive_times_are_kept(recorded_drive: Path) -> None:
    written = [(topic, stamp(t), data) for t, topic, _, data in drive_messages()]
    with Reader(recorded_drive) as reader:
        read = [(c.topic, t, bytes(data)) for c, t, data in reader.messages()]
    assert sorted(read) == sorted(written)


def test_small_chunks_each_reach_the_bag(tmp_path: Path) -> None:
    with BagRecorder(tmp_path / "chunked.bag", chunk_size=4096) as recorder:
        handle = recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition)
        data = EGO.serialize(EGO.new())
        for k in range(1000):
            recorder.write(handle, stamp(k / 50), data)
    stats = recorder.stats
    assert stats.written == 1000
    assert stats.dropped == 0
    with Reader(tmp_path / "chunked.bag") as reader:
        assert len(reader.chunk_infos) == stats.chunks
        assert stats.chunks >= 1000 * len(data) // 4096
        assert reader.message_count == 1000
    assert not needs_repair(tmp_path / "chunked.bag")


def test_latched_connection_is_marked(tmp_path: Path) -> None:
    with BagRecorder(tmp_path / "latched.bag") as recorder:
        handle = recorder.add_connection(
            "/map", EGO.name, EGO.md5sum, EGO.definition, callerid="/egosim/map", latching=True
        )
        recorder.write(handle, stamp(0.0), EGO.serialize(EGO.new()))
    with Reader(tmp_path / "latched.bag") as reader:
        (connection,) = reader.connections
        assert connection.ext.latching == 1
        assert connection.ext.callerid == "/egosim/map"


def test_writes_never_wait_for_a_stalled_disk(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A writer stuck on the disk: write() still returns, and what does not fit is counted."""
    disk_free = threading.Event()
    stalled_write = recorder_module.Writer.write

    def stalled(self: object, *args: object) -> None:
        disk_free.wait()
        stalled_write(self, *args)

    monkeypatch.setattr(recorder_module.Writer, "write", stalled)
    queue_limit, sent = 10, 200
    recorder = BagRecorder(tmp_path / "stalled.bag", queue_limit=queue_limit)
    handle = recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition)
    data = EGO.serialize(EGO.new())
    accepted = [recorder.write(handle, stamp(k / 50), data) for k in range(sent)]
    # At most the queue plus the one message the writer holds got through.
    assert accepted.count(True) <= queue_limit + 1
    assert recorder.stats.dropped == accepted.count(False) >= sent - queue_limit - 1
    disk_free.set()
    stats = recorder.close()
    assert stats.written == accepted.count(True)
    assert stats.written + stats.dropped == sent
    with Reader(tmp_path / "stalled.bag") as reader:
        assert reader.message_count == stats.written


def test_byte_bound_drops_oversized_bursts(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    disk_free = threading.Event()
    stalled_write = recorder_module.Writer.write
    monkeypatch.setattr(
        recorder_module.Writer,
        "write",
        lambda self, *args: (disk_free.wait(), stalled_write(self, *args)),
    )
    recorder = BagRecorder(tmp_path / "burst.bag", queue_bytes=1000)
    handle = recorder.add_connection("/points", EGO.name, EGO.md5sum, EGO.definition)
    assert not recorder.write(handle, stamp(0.0), bytes(1001))
    assert recorder.stats.dropped == 1
    disk_free.set()
    recorder.close()


def test_closed_recorder_refuses_writes(tmp_path: Path) -> None:
    recorder = BagRecorder(tmp_path / "closed.bag")
    handle = recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition)
    recorder.close()
    with pytest.raises(RecorderError):
        recorder.write(handle, stamp(0.0), b"")
    with pytest.raises(RecorderError):
        recorder.add_connection("/ctrl_cmd", CONTROL.name, CONTROL.md5sum, CONTROL.definition)


def test_existing_file_is_not_overwritten(recorded_drive: Path) -> None:
    size = recorded_drive.stat().st_size
    with pytest.raises(RecorderError):
        BagRecorder(recorded_drive)
    assert recorded_drive.stat().st_size == size
