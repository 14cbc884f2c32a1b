"""What one sync-mode service call costs: wall time per `/SyncModeCtrlCmd` round trip
(a call that does not tick) and the CPU it takes in the client and in the simulator.

Starts `egosim run --clock sync` as a subprocess (nothing subscribed), starts sync mode
and sends `--calls` CtrlCmds for the next frame over one persistent connection. The
simulator's CPU comes from /proc (user and kernel time), so this runs on Linux only.

Usage: .venv/bin/python benchmarks/sync_service_call.py [--calls 3000]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

from sync_mode import control_request, simulator_client, start_sync_mode

from egosim.msgs import get_profile


def cpu_seconds(pid: int) -> tuple[float, float]:
    """(user, kernel) CPU seconds of process `pid` so far."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    return int(fields[11]) / ticks, int(fields[12]) / ticks


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=3000)
    args = parser.parse_args()

    profile = get_profile("26.r1")
    with simulator_client("sync_call_benchmark") as (node, simulator):
        frame = start_sync_mode(node, profile)
        control = profile.service("morai_msgs/MoraiSyncModeCtrlCmdSrv")
        proxy = node.service_proxy("/SyncModeCtrlCmd", control, persistent=True)
        request = control_request(profile, control, frame + 1)
        proxy.call(request)
        user_before, kernel_before = cpu_seconds(simulator.pid)
        client_before = time.process_time()
        began = time.perf_counter()
        for _ in range(args.calls):
            proxy.call(request)
        wall = time.perf_counter() - began
        client = time.process_time() - client_before
        user_after, kernel_after = cpu_seconds(simulator.pid)
    per_call = 1e6 / args.calls
    print(
        f"{args.calls} calls: {wall * per_call:.0f} us per call; CPU per call: client "
        f"{client * per_call:.0f} us, simulator {(user_after - user_before) * per_call:.0f}"
        f" us user + {(kernel_after - kernel_before) * per_call:.0f} us kernel"
    )


if __name__ == "__main__":
    main()
