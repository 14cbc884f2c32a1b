"""Recording already-serialised messages into a ROS 1 bag without blocking the caller."""

from __future__ import annotations

import logging
import os
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType

from rosbags.interfaces import Connection
from rosbags.rosbag1 import Writer, WriterError
from rosbags.typesys.msg import normalize_msgtype

from .dropping_queue import DroppingQueue
from .errors import RecorderError
from .recordings import start_recording, stop_recording

log = logging.getLogger(__name__)

# As `rosbag record`: chunks of 768 KiB, the unit that reaches the disk whole.
DEFAULT_CHUNK_SIZE = 768 * 1024
# Queued messages between the simulation loop and the disk: about 10 minutes of
# every egosim topic at its default rate, or 256 MiB of payload, whichever first.
DEFAULT_QUEUE_LIMIT = 100_000
DEFAULT_QUEUE_BYTES = 256 * 1024 * 1024
# A quiet bag (few, small messages) still reaches the disk this often.
# A process killed with SIGKILL loses at most the messages of this long (and of the
# queue not yet taken, which the writer takes at least as often).
DEFAULT_FLUSH_INTERVAL_S = 0.05


@dataclass(frozen=True)
class ConnectionHandle:
    """What `BagRecorder.add_connection` returns and `BagRecorder.write` takes."""

    index: int
    topic: str


@dataclass(frozen=True)
class _ConnectionSpec:
    topic: str
    type_name: str
    md5sum: str
    definition: str
    callerid: str
    latching: bool


@dataclass(frozen=True)
class RecorderStats:
    """Counters of one recording."""

    written: int  # messages handed to the bag file
    flushed: int  # of those, messages in chunks already on disk (survive a crash)
    dropped: int  # messages refused because the queue was full
    chunks: int  # chunks flushed to disk


class BagRecorder:
    """Appends serialised messages to a new bag from a writer thread.

    `write` only queues the bytes, so the simulation loop never waits for the
    disk; when the queue is full the message is dropped and counted. Every
    chunk is flushed to disk as it fills, and the open chunk at least every
    `flush_interval` s, so a killed process loses at most that much; the
    resulting unindexed bag is repaired by `repair_bag`.
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        *,
        chunk_size: int = DEFAULT_CHUNK_SIZE,
        queue_limit: int = DEFAULT_QUEUE_LIMIT,
        queue_bytes: int = DEFAULT_QUEUE_BYTES,
        flush_interval: float = DEFAULT_FLUSH_INTERVAL_S,
    ) -> None:
        self.path = Path(path)
        self.flush_interval = flush_interval
        try:
            self._writer = Writer(self.path)
            self._writer.chunk_threshold = chunk_size
            self._writer.open()
        except (OSError, WriterError) as exc:
            raise RecorderError(f"cannot create bag {self.path}: {exc}") from exc
        # The header must be on disk before any chunk, or a crash leaves no bag at all.
        self._sync()
        self._specs: list[_ConnectionSpec] = []
        self._connections: dict[int, Connection] = {}
        self._queue: DroppingQueue[tuple[int, int, bytes]] = DroppingQueue(queue_limit, queue_bytes)
        self._written = 0
        self._flushed = 0
        self._chunks = 0
        self._reported_drops = 0
        self._failure: BaseException | None = None
        self._closed = False
        self._finishing = threading.Lock()
        self._finished = False
        start_recording(self.path)
        self._thread = threading.Thread(
            target=self._drain, name=f"bag-writer:{self.path.name}", daemon=True
        )
        self._thread.start()

    def add_connection(
        self,
        topic: str,
        type_name: str,
        md5sum: str,
        definition: str,
        callerid: str = "/egosim",
        latching: bool = False,
    ) -> ConnectionHandle:
        """Declare a topic; its connection record is written with its first message."""
        if self._closed:
            raise RecorderError(f"recorder of {self.path} is closed")
        # Appending to a list is atomic; the writer thread only reads entries
        # for handles it has already been given, so no lock is needed.
        self._specs.append(
            _ConnectionSpec(topic, type_name, md5sum, definition, callerid, latching)
        )
        return ConnectionHandle(len(self._specs) - 1, topic)

    def write(self, handle: ConnectionHandle, stamp_ns: int, data: bytes) -> bool:
        """Queue one serialised message received at `stamp_ns`; False if it was dropped.

        After a writer failure every message is dropped; `close` raises the failure.
        """
        if self._closed:
            raise RecorderError(f"recorder of {self.path} is closed")
        return self._queue.offer((handle.index, stamp_ns, data), len(data))

    @property
    def stats(self) -> RecorderStats:
        return RecorderStats(self._written, self._flushed, self._queue.dropped, self._chunks)

    def close(self, timeout: float | None = None) -> RecorderStats:
        """Write what is queued, the index and the header; raises if the writer failed, or
        has not finished within `timeout` s (None: however long it takes).

        Any thread may close, several at once (a forced exit closes while the main thread
        may be closing too): each returns once the bag is complete."""
        self._closed = True
        self._queue.close()
        self._thread.join(timeout)
        if self._thread.is_alive():
            raise RecorderError(f"{self.path}: the writer did not finish within {timeout} s")
        with self._finishing:
            if not self._finished:
                self._finished = True
                stop_recording(self.path)
                self._report_drops()
        if self._failure is not None:
            raise RecorderError(f"recording {self.path} failed: {self._failure!r}") from (
                self._failure
            )
        return self.stats

    def __enter__(self) -> BagRecorder:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    def _drain(self) -> None:
        last_flush = time.monotonic()
        try:
            while True:
                items, closing = self._queue.take_all(self.flush_interval)
                for index, stamp_ns, data in items:
                    self._write_one(index, stamp_ns, data)
                if time.monotonic() - last_flush >= self.flush_interval:
                    self._flush_open_chunk()
                    self._report_drops()
                    last_flush = time.monotonic()
                if closing:
                    break
            self._writer.close()
            self._chunks = sum(chunk.pos != -1 for chunk in self._writer.chunks)
            self._flushed = self._written
        except BaseException as exc:  # the thread must record why the bag stopped
            log.exception("bag writer for %s failed; recording stopped", self.path)
            self._failure = exc
            self._queue.close()
            self._writer.abort()

    def _write_one(self, index: int, stamp_ns: int, data: bytes) -> None:
        connection = self._connections.get(index)
        if connection is None:
            spec = self._specs[index]
            connection = self._writer.add_connection(
                spec.topic,
                normalize_msgtype(spec.type_name),
                msgdef=spec.definition,
                md5sum=spec.md5sum,
                callerid=spec.callerid,
                latching=int(spec.latching),
            )
            self._connections[index] = connection
        chunks_before = self._closed_chunks()
        self._writer.write(connection, stamp_ns, data)
        self._written += 1
        if self._closed_chunks() != chunks_before:
            self._synced_chunk()

    def _flush_open_chunk(self) -> None:
        chunk = self._writer.chunks[-1]
        if chunk.data.tell() > 0:
            self._writer.write_chunk(chunk)
            self._synced_chunk()

    def _synced_chunk(self) -> None:
        """A chunk holding every message written so far has just been written out."""
        self._sync()
        self._chunks = self._closed_chunks()
        self._flushed = self._written

    def _closed_chunks(self) -> int:
        # rosbags' Writer opens a new in-memory chunk each time one is written out.
        return len(self._writer.chunks) - 1

    def _sync(self) -> None:
        bio = self._writer.bio
        assert bio is not None
        bio.flush()
        os.fsync(bio.fileno())

    def _report_drops(self) -> None:
        dropped = self._queue.dropped
        if dropped > self._reported_drops:
            log.warning(
                "%s: %d messages dropped (queue full; %d in total)",
                self.path,
                dropped - self._reported_drops,
                dropped,
            )
            self._reported_drops = dropped
