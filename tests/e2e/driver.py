"""The test side of peers/rospy_driver.py: a real rospy node under the test's control."""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import threading
from pathlib import Path
from typing import Any

from tests.contract import PROTOCOL_DIR
from tests.debian_ros import ROS_PYTHON

PEER = Path(__file__).parent / "peers" / "rospy_driver.py"
REPLY_TIMEOUT_S = 60.0


class DriverError(RuntimeError):
    """The rospy node reported an error for a request."""


class RospyDriver:
    def __init__(self, env: dict[str, str], log_path: Path, profile: str = "26.r1", name="client"):
        self._stderr = log_path.open("wb")
        self.popen = subprocess.Popen(
            [
                ROS_PYTHON,
                str(PEER),
                str(PROTOCOL_DIR / f"morai_msgs-{profile}.json"),
                str(PROTOCOL_DIR / "std_msgs_used.json"),
                name,
            ],
            env=env,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self._stderr,
            text=True,
            start_new_session=True,
        )
        self.log_path = log_path
        self._lock = threading.Lock()
        self._reply()  # "ready"

    def _reply(self) -> Any:
        assert self.popen.stdout is not None
        result: list[str] = []
        reader = threading.Thread(target=lambda: result.append(self.popen.stdout.readline()))
        reader.start()
        reader.join(REPLY_TIMEOUT_S)
        if not result or not result[0]:
            raise DriverError(f"rospy driver gave no reply; stderr: {self.stderr()[-3000:]}")
        reply = json.loads(result[0])
        if not reply["ok"]:
            raise DriverError(f"{reply['error']}\n{reply.get('traceback', '')}")
        return reply["result"]

    def request(self, op: str, **fields: Any) -> Any:
        assert self.popen.stdin is not None
        with self._lock:
            self.popen.stdin.write(json.dumps({"op": op, **fields}) + "\n")
            self.popen.stdin.flush()
            return self._reply()

    def subscribe(self, topic: str, type_name: str, raw: bool = False) -> None:
        """Subscribe; `raw` messages are {"hex": serialized bytes} as received."""
        self.request("subscribe", topic=topic, type=type_name, raw=raw)

    def wait_connected(self, topic: str, count: int = 1, timeout: float = 20.0) -> None:
        """Wait until a subscribed topic has `count` publishers connected."""
        self.request("wait_connected", topic=topic, count=count, timeout=timeout)

    def now(self) -> float:
        """The client's ROS time (s): simulation time when /use_sim_time is set."""
        return self.request("now")

    def messages(
        self, topic: str, since: int = 0, count: int = 1, timeout: float = 20.0
    ) -> list[dict[str, Any]]:
        """Messages received on topic from index `since`, waiting for `count` of them."""
        return self.request("messages", topic=topic, since=since, count=count, timeout=timeout)

    def received(self, topic: str) -> int:
        """How many messages have been received on topic so far (the `since` of the next)."""
        return self.request("received", topic=topic)

    def next_message(self, topic: str, timeout: float = 20.0) -> dict[str, Any]:
        """A message received after this call."""
        seen = self.received(topic)
        received = self.messages(topic, since=seen, count=1, timeout=timeout)
        if not received:
            raise DriverError(f"no message on {topic} within {timeout} s")
        return received[0]

    def publish(self, topic: str, type_name: str, msg: dict[str, Any], **options: Any) -> None:
        self.request("publish", topic=topic, type=type_name, msg=msg, **options)

    def stream(self, topic: str, type_name: str, msg: dict[str, Any], rate: float = 20.0) -> None:
        self.request("stream", topic=topic, type=type_name, msg=msg, rate=rate)

    def stop_stream(self, topic: str) -> None:
        self.request("stop_stream", topic=topic)

    def call(self, service: str, type_name: str, request: dict[str, Any]) -> dict[str, Any]:
        return self.request("call", service=service, type=type_name, request=request)

    def stderr(self) -> str:
        self._stderr.flush()
        return self.log_path.read_text(errors="replace")

    def close(self) -> None:
        with contextlib.suppress(OSError, ValueError):
            assert self.popen.stdin is not None
            self.popen.stdin.close()
        try:
            self.popen.wait(5)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.popen.pid, signal.SIGKILL)
            self.popen.wait()
        self._stderr.close()
        if self.popen.stdout is not None:
            self.popen.stdout.close()
