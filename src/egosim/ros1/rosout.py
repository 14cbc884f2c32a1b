"""Python logging to the /rosout topic (rosgraph_msgs/Log), as every ROS node does."""

from __future__ import annotations

import dataclasses
import logging
import threading
from functools import cache
from typing import TYPE_CHECKING

from egosim.msgs import DEFAULT_PROFILE, get_profile

from .errors import NodeShutdownError
from .publication import Publisher

if TYPE_CHECKING:
    from egosim.msgs.typed import standard

ROSOUT_TOPIC = "/rosout"
_LEVELS = ((logging.CRITICAL, 16), (logging.ERROR, 8), (logging.WARNING, 4), (logging.INFO, 2))
_DEBUG = 1


@cache
def log_type() -> standard.LogType:
    return get_profile(DEFAULT_PROFILE).message("rosgraph_msgs/Log")


@cache
def _header_type() -> standard.HeaderType:
    return get_profile(DEFAULT_PROFILE).message("std_msgs/Header")


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
        if getattr(self._busy, "active", False):
            return
        self._busy.active = True
        try:
            self._publisher.publish(self.serialize(record))
        except NodeShutdownError:
            pass  # a record logged while the node shuts down has nowhere to go
        except Exception:
            self.handleError(record)
        finally:
            self._busy.active = False

    def serialize(self, record: logging.LogRecord) -> bytes:
        self._seq += 1
        seconds = int(record.created)
        header = _header_type().new(seq=self._seq, frame_id="")
        header.stamp = dataclasses.replace(
            header.stamp, sec=seconds, nanosec=int((record.created - seconds) * 1e9)
        )
        log = log_type()
        return log.serialize(
            log.new(
                header=header,
                level=_ros_level(record.levelno),
                name=self._node_name,
                msg=record.getMessage(),
                file=record.pathname,
                function=record.funcName or "",
                line=record.lineno,
            )
        )
