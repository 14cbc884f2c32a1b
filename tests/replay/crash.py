"""Recording in a child process that is killed with SIGKILL before it closes its bag."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[2]
PEER = Path(__file__).parent / "peers" / "killed_recorder.py"


def record_and_kill(path: Path, count: int, chunk_size: int, flush_interval: float) -> Any:
    """Run the recorder in a child, SIGKILL it once it reports; its last RecorderStats."""
    child = subprocess.Popen(
        [sys.executable, str(PEER), str(path), str(count), str(chunk_size), str(flush_interval)],
        stdout=subprocess.PIPE,
        text=True,
        cwd=REPO,
        env={**os.environ, "PYTHONPATH": str(REPO)},
    )
    try:
        assert child.stdout is not None
        stats = json.loads(child.stdout.readline())
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait()
    assert child.returncode == -signal.SIGKILL
    return stats
