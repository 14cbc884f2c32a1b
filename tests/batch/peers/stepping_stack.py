"""A stand-in stack in MORAI's synchronous mode: starts it with a tick of --tick-ms (default
$STEPPING_TICK_MS, else 0: the simulator's physics step) and steps the world frame by
frame, pressing the brake fully in every frame with --brake (all a good stack can do with
a red light too close to stop for).

Without --frames it steps until the simulator goes away. With --frames N it writes
`stepped` in its case folder after N frames and then, as told by its last argument:
`exit CODE` (exits with CODE), `hang` (stops stepping and ignores SIGINT, noting each in
`sigint` in its case folder) or `idle` (stops stepping and exits 0 on SIGINT). The drive it
leaves is N ticks long whenever it ends.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
from pathlib import Path
from typing import Any

from egosim.msgs import get_profile
from egosim.ros1 import Node, ServiceError

PROFILE = get_profile("26.r1")
USER = "stepping_stack"


class Services:
    def __init__(self, node: Node) -> None:
        self._proxies = {}
        for name, srv in (
            ("/SyncModeCmd", "MoraiSyncModeCmdSrv"),
            ("/SyncModeWaitForTick", "MoraiWaitForTickSrv"),
            ("/SyncModeCtrlCmd", "MoraiSyncModeCtrlCmdSrv"),
        ):
            kind = PROFILE.service(f"morai_msgs/{srv}")
            proxy = node.service_proxy(name, kind, persistent=True)
            proxy.wait_for_service(30.0)
            self._proxies[name] = (proxy, kind)

    def call(self, name: str, message: str, **fields: Any) -> Any:
        proxy, kind = self._proxies[name]
        request = kind.request.new(request=PROFILE.message(f"morai_msgs/{message}").new(**fields))
        return kind.response.deserialize(proxy.call(kind.request.serialize(request))).response


def arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    parser.add_argument("--tick-ms", type=int, default=int(os.environ.get("STEPPING_TICK_MS", "0")))
    parser.add_argument("--brake", action="store_true")
    parser.add_argument("--frames", type=int, default=None)
    parser.add_argument("then", nargs="*", default=[])
    return parser.parse_args()


def main() -> int:
    args = arguments()
    node = Node(USER, rosout_logger=None, embedded_master="never")
    services = Services(node)
    started = services.call(
        "/SyncModeCmd", "SyncModeCmd", user_id=USER, start_sync_mode=True, time_step=args.tick_ms
    )
    brake = PROFILE.message("morai_msgs/CtrlCmd").new(longlCmdType=1, brake=1.0)
    frame = int(started.frame)
    try:
        while args.frames is None or frame - started.frame < args.frames:
            frame += 1
            if args.brake:
                services.call("/SyncModeCtrlCmd", "SyncModeCtrlCmd", frame=frame, command=brake)
            services.call("/SyncModeWaitForTick", "WaitForTick", user_id=USER, frame=frame)
    except ServiceError:
        return 0  # the drive is over: the simulator has gone
    Path(os.environ["EGOSIM_CASE_DIR"], "stepped").write_text(str(frame - started.frame))
    if args.then[0] == "exit":
        node.shutdown("done")
        return int(args.then[1])
    interrupted = threading.Event()
    sigint = Path(os.environ["EGOSIM_CASE_DIR"], "sigint")
    ignore = args.then[0] == "hang"
    signal.signal(signal.SIGINT, lambda *_: sigint.touch() if ignore else interrupted.set())
    while not interrupted.wait(0.5):
        pass
    node.shutdown("interrupted")
    return 0


if __name__ == "__main__":
    sys.exit(main())
