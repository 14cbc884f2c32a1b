"""A stand-in stack: joins the case's ROS graph (subscribes /Ego_topic, any type), then
behaves as told: `exit CODE AFTER_S` (exits once a status stamped AFTER_S s of simulation
time has come) or `hang` (never ends, ignores SIGINT)."""

from __future__ import annotations

import signal
import struct
import sys
import threading
import time
from collections.abc import Mapping
from dataclasses import dataclass

from egosim.ros1 import Node


@dataclass(frozen=True)
class AnyType:
    name: str = "*"
    md5sum: str = "*"
    definition: str = ""


def main() -> int:
    node = Node("stand_in_stack", rosout_logger=None, embedded_master="never")
    late_enough = threading.Event()
    after_s = float(sys.argv[3]) if sys.argv[1] == "exit" else float("inf")

    def on_status(data: bytes, header: Mapping[str, str]) -> None:
        # std_msgs/Header first: seq, stamp.secs, stamp.nsecs (little-endian uint32).
        _, secs, nsecs = struct.unpack_from("<III", data)
        if secs + nsecs * 1e-9 >= after_s:
            late_enough.set()

    node.subscribe("/Ego_topic", AnyType(), on_status)
    if sys.argv[1] == "hang":
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        while True:
            time.sleep(1.0)
    late_enough.wait(600)
    node.shutdown("done")
    return int(sys.argv[2])


if __name__ == "__main__":
    sys.exit(main())
