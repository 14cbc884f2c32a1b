"""Recording egosim's topics into a ROS 1 bag: from inside the simulator (`egosim run
--record`, through the bridge's taps) or as a separate node (`egosim record`).

Both hand over bytes already on the wire with the type, md5sum and full
definition of their connection, so Debian's `rosbag info`/`rosbag play` and
rqt_bag read the result, and a replay can decode it.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

from ..bridge.core import Tap
from ..replay import BagRecorder, ConnectionHandle, RecorderError, RecorderStats
from ..ros1 import ANY_TYPE, MessageCallback, MessageTypeInfo, Node, TopicType
from .signals import StopControl

log = logging.getLogger(__name__)

RECORDER_NODE_NAME = "egosim_record"


class BagExistsError(RecorderError):
    """Recording would overwrite a file."""


def open_recorder(path: Path) -> BagRecorder:
    """A recorder writing a new bag at `path`; an existing file is never overwritten."""
    if path.exists():
        raise BagExistsError(f"{path} already exists; choose a new bag name")
    return BagRecorder(path)


class TopicRecorder:
    """Writes messages of any number of topics, from any thread, into one bag.

    One bag connection per (topic, md5sum), declared with the first message.
    Messages arriving after `close` (a late callback of a closing node) are ignored.
    """

    def __init__(self, recorder: BagRecorder) -> None:
        self.recorder = recorder
        self._lock = threading.Lock()
        self._connections: dict[tuple[str, str], ConnectionHandle] = {}
        self._closed = False
        self._reported = False

    def record(
        self,
        topic: str,
        message_type: MessageTypeInfo,
        data: bytes,
        stamp_ns: int,
        *,
        callerid: str = "/egosim",
        latching: bool = False,
    ) -> None:
        with self._lock:
            if self._closed:
                return
            key = (topic, message_type.md5sum)
            handle = self._connections.get(key)
            if handle is None:
                handle = self.recorder.add_connection(
                    topic,
                    message_type.name,
                    message_type.md5sum,
                    message_type.definition,
                    callerid=callerid,
                    latching=latching,
                )
                self._connections[key] = handle
            self.recorder.write(handle, stamp_ns, data)

    def tap(self) -> Tap:
        """A bridge tap recording every message egosim sends or receives at its header time."""

        def record(topic: str, message_type: MessageTypeInfo, data: bytes, stamp_ns: int) -> None:
            self.record(topic, message_type, data, stamp_ns)

        return record

    def __enter__(self) -> TopicRecorder:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def close(self, timeout: float | None = None) -> RecorderStats:
        """Close the bag (see BagRecorder.close); from any thread, also more than once."""
        # A forced exit closes from another thread while the main thread may hold the
        # lock, even be stuck holding it: the lock is waited for only so long.
        held = self._lock.acquire(timeout=-1 if timeout is None else timeout)
        self._closed = True
        if held:
            self._lock.release()
        stats = self.recorder.close(timeout)
        if not self._reported:
            self._reported = True
            log.info(
                "bag %s closed: %d messages on %d connections, %d dropped",
                self.recorder.path,
                stats.written,
                len(self._connections),
                stats.dropped,
            )
        return stats


def record_from_network(
    recorder: TopicRecorder,
    topics: Sequence[str],
    control: StopControl,
    duration: float | None = None,
    ros_argv: Sequence[str] = (),
) -> None:
    """Subscribe to `topics` (any type) on the running ROS graph and record what arrives,
    stamped with the wall clock at reception as `rosbag record` does, until a stop is
    asked for (a signal, `rosnode kill`) or `duration` s have passed. Raises the
    transport's errors when there is no master."""
    node = Node(
        f"{RECORDER_NODE_NAME}_{time.time_ns()}",
        list(ros_argv),
        embedded_master="never",
        rosout_logger=None,
    )
    node.on_shutdown_request(control.request)
    try:
        for topic in topics:
            node.subscribe(topic, ANY_TYPE, _recording_callback(recorder, node.resolve_name(topic)))
        log.info("recording %d topics into %s", len(topics), recorder.recorder.path)
        if not control.stop.wait(duration):
            control.request(f"--duration {duration:g} s recorded")
        control.stopping()
        log.info("stopping: %s", control.reason)
    finally:
        node.shutdown(control.reason or "recording finished")


def _recording_callback(recorder: TopicRecorder, topic: str) -> MessageCallback:
    def received(data: bytes, header: Mapping[str, str]) -> None:
        # The publisher's connection header names the type it actually sends.
        wire_type = TopicType(
            header.get("type", ""), header.get("md5sum", ""), header.get("message_definition", "")
        )
        recorder.record(
            topic,
            wire_type,
            data,
            time.time_ns(),
            callerid=header.get("callerid", ""),
            latching=header.get("latching") == "1",
        )

    return received
