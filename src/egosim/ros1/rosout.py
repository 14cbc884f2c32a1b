"""Python logging to the /rosout topic (rosgraph_msgs/Log), as every ROS node does."""

from __future__ import annotations

import logging
import threading
from dataclasses import dataclass
from functools import cache
from typing import Any

from rosbags.typesys import Stores, get_typestore

from .publication import Publisher

ROSOUT_TOPIC = "/rosout"
_LOG_TYPE = "rosgraph_msgs/msg/Log"
_LEVELS = ((logging.CRITICAL, 16), (logging.ERROR, 8), (logging.WARNING, 4), (logging.INFO, 2))
_DEBUG = 1


@dataclass(frozen=True)
class LogType:
    name: str
    md5sum: str
    definition: str


@cache
def _typestore() -> Any:
    return get_typestore(Stores.ROS1_NOETIC)


@cache
def log_type() -> LogType:
    definition, md5sum = _typestore().generate_msgdef(_LOG_TYPE)
    return LogType("rosgraph_msgs/Log", md5sum, definition)


def _ros_level(levelno: int) -> int:
    return next((ros for py, ros in _LEVELS if levelno >= py), _DEBUG)


class RosoutHandler(logging.Handler):
    """Publishes log records on /rosout; records logged while publishing are not re-published."""

    def __init__(self, publisher: Publisher, node_name: str, level: int = logging.INFO) -> None:
        super().__init__(level)
        self._publisher = publisher
        self._node_name = node_name
        self._busy = threading.local()
        self._seq = 0

    def emit(self, record: logging.LogRecord) -> None:
        if getattr(self._busy, "active", False) or self._publisher.num_subscribers == 0:
            return
        self._busy.active = True
        try:
            self._publisher.publish(self.serialize(record))
        except Exception:
            self.handleError(record)
        finally:
            self._busy.active = False

    def serialize(self, record: logging.LogRecord) -> bytes:
        store = _typestore()
        types = store.types
        self._seq += 1
        seconds = int(record.created)
        stamp = types["builtin_interfaces/msg/Time"](
            sec=seconds, nanosec=int((record.created - seconds) * 1e9)
        )
        message = types[_LOG_TYPE](
            header=types["std_msgs/msg/Header"](seq=self._seq, stamp=stamp, frame_id=""),
            level=_ros_level(record.levelno),
            name=self._node_name,
            msg=record.getMessage(),
            file=record.pathname,
            function=record.funcName or "",
            line=record.lineno,
            topics=[],
        )
        return bytes(store.serialize_ros1(message, _LOG_TYPE))
