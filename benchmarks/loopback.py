"""Loopback addresses for benchmarks that start their own ROS masters, and the simulator
started on one."""

from __future__ import annotations

import os
import socket
import subprocess
import sys


def free_port() -> int:
    """A TCP port nothing listens on at 127.0.0.1 right now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def start_simulator(*args: str, master_uri: str | None = None) -> subprocess.Popen[str]:
    """`egosim run ARGS` (no view, warnings only) on `master_uri` (default: a free
    loopback port), once it has printed that it is ready."""
    uri = master_uri or f"http://127.0.0.1:{free_port()}/"
    env = dict(os.environ, ROS_MASTER_URI=uri, ROS_IP="127.0.0.1")
    process = subprocess.Popen(
        [sys.executable, "-m", "egosim", "run", "--no-view", "--log-level", "WARNING", *args],
        env=env,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert process.stdout is not None
    for line in process.stdout:
        if line.strip() == "egosim: ready":
            return process
    raise RuntimeError("egosim exited before it was ready")
