"""A stand-in stack in MORAI's synchronous mode that notes which master and graph it meets,
from its start to its end, and lingers after its drive as a slow stack's shutdown does.

As it starts it adds a line to `starts` in its case folder and asks its master
(ROS_MASTER_URI) for /run_id and the graph's nodes (before it looks for the simulator).
It steps the world at the physics step until the simulator goes away (thinking THINK_S
over each frame, as a stack does), then keeps asking every 20 ms for LINGER_S (SIGINT,
which the batch sends once the drive is over, is ignored from the drive's start; before
it, SIGINT ends the stack at once). It writes `met.json`
in its case folder: every /run_id and node it met (or that its master did not answer),
and the wall times of its start, of the drive's end and of its own end.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import time
import xmlrpc.client
from pathlib import Path
from typing import Any

from egosim.msgs import get_profile
from egosim.ros1 import Node, ServiceError

PROFILE = get_profile("26.r1")
USER = "lingering_stack"
LINGER_S = 1.0
ASK_EVERY_S = 0.02
THINK_S = 0.01
UNANSWERED = "unanswered"


class Met:
    def __init__(self) -> None:
        self.master = xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"])
        self.run_ids: set[str] = set()
        self.nodes: set[str] = set()

    def ask(self) -> list[str]:
        """The graph's nodes now (noting them and the run id)."""
        try:
            _, _, run_id = self.master.getParam(f"/{USER}", "/run_id")
            _, _, state = self.master.getSystemState(f"/{USER}")
        except OSError:
            self.run_ids.add(UNANSWERED)
            return []
        self.run_ids.add(run_id)
        nodes = sorted({node for column in state for _, names in column for node in names})
        self.nodes.update(nodes)
        return nodes


def call(proxy: Any, kind: Any, message: str, **fields: Any) -> Any:
    request = kind.request.new(request=PROFILE.message(f"morai_msgs/{message}").new(**fields))
    return kind.response.deserialize(proxy.call(kind.request.serialize(request))).response


def drive(node: Node) -> None:
    """Step frame after frame until the simulator ends the drive."""
    proxies = {}
    for name, srv in (
        ("/SyncModeCmd", "MoraiSyncModeCmdSrv"),
        ("/SyncModeWaitForTick", "MoraiWaitForTickSrv"),
    ):
        kind = PROFILE.service(f"morai_msgs/{srv}")
        proxy = node.service_proxy(name, kind, persistent=True)
        proxy.wait_for_service(30.0)
        proxies[name] = (proxy, kind)
    started = call(
        *proxies["/SyncModeCmd"], "SyncModeCmd", user_id=USER, start_sync_mode=True, time_step=0
    )
    frame = int(started.frame)
    # Told to stop (SIGINT) as its drive ends, before it has seen the simulator go, it
    # still notes the end and lingers, as a slow stack's shutdown does.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        while True:
            frame += 1
            call(*proxies["/SyncModeWaitForTick"], "WaitForTick", user_id=USER, frame=frame)
            time.sleep(THINK_S)
    except ServiceError:
        return  # the drive is over: the simulator has gone


def main() -> int:
    began = time.time()
    with Path(os.environ["EGOSIM_CASE_DIR"], "starts").open("a") as starts:
        starts.write(f"{os.getpid()}\n")
    met = Met()
    first_nodes = met.ask()
    node = Node(USER, rosout_logger=None, embedded_master="never")
    drive(node)
    drive_over = time.time()
    while time.time() < drive_over + LINGER_S:
        met.ask()
        time.sleep(ASK_EVERY_S)
    node.shutdown("done")
    record = {
        "run_ids": sorted(met.run_ids),
        "nodes": sorted(met.nodes),
        "first_nodes": first_nodes,
        "began": began,
        "drive_over": drive_over,
        "ended": time.time(),
    }
    Path(os.environ["EGOSIM_CASE_DIR"], "met.json").write_text(json.dumps(record))
    return 0


if __name__ == "__main__":
    sys.exit(main())
