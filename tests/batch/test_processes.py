"""A case's processes start with the signal handling of a process started from a shell,
whatever their supervisor's: Ray's workers block SIGINT, a shell's background job ignores
it, and Python itself ignores SIGPIPE and SIGXFSZ. The SIGINT that stops a case reaches
its processes either way."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
from pathlib import Path

SUPERVISOR = textwrap.dedent(
    """
    import signal, sys, threading
    from pathlib import Path
    from egosim.batch.processes import GroupProcess

    # As a Ray worker's task thread and a background job: SIGINT blocked and ignored.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
    folder = Path(sys.argv[1])
    status = GroupProcess(["grep", "^Sig", "/proc/self/status"], folder / "status.log")
    status.popen.wait()
    status.log.join(5.0)
    # A shell that traps SIGINT, then waits: stopped by SIGINT, not by the SIGKILL after.
    ready = threading.Event()
    trap = "trap 'echo stopped by SIGINT; exit 0' INT; echo ready; while :; do sleep 0.1; done"
    sleeper = GroupProcess(
        ["/bin/sh", "-c", trap], folder / "trap.log", on_line=lambda line: ready.set()
    )
    assert ready.wait(30), "the shell did not start within 30 s"
    print(sleeper.stop(signal.SIGINT, 10.0))
    """
)


def mask(status: str, field: str) -> int:
    (line,) = [line for line in status.splitlines() if line.startswith(f"{field}:")]
    return int(line.split()[1], 16)


def bit(number: int) -> int:
    return 1 << (number - 1)


def test_a_case_process_starts_with_default_signals_and_stops_on_sigint(tmp_path: Path) -> None:
    supervisor = subprocess.run(
        [sys.executable, "-c", SUPERVISOR, str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert supervisor.returncode == 0, supervisor.stderr
    status = (tmp_path / "status.log").read_text()
    for number in (signal.SIGINT, signal.SIGTERM, signal.SIGPIPE, signal.SIGXFSZ):
        assert not mask(status, "SigBlk") & bit(number), (number, status)
        assert not mask(status, "SigIgn") & bit(number), (number, status)
    assert supervisor.stdout.split() == ["0"]  # the trap's exit status
    assert "stopped by SIGINT" in (tmp_path / "trap.log").read_text()
