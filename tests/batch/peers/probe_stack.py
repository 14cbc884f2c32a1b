"""A stand-in stack in MORAI's synchronous mode that either changes all it can of the
simulator and then crashes, or writes down what a new case finds.

`probe_stack.py meddle`: sets parameters, starts sync mode with a 20 ms tick, adds an
object, puts the ego in reverse with its hazard lamps on and its autopilot driving, steps
30 frames at full throttle and exits with status 3 (leaving its connections open).

`probe_stack.py observe`: writes `observed.json` in its case folder: the master's
parameters, topics and services (as the graph's nodes name them), the ego's control mode,
gear and lamps, and the md5 of every WaitForTick reply of 40 frames (from the default tick,
at half throttle); then exits 0.

Either writes the simulator's process id to `simulator.pid` in its case folder.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import xmlrpc.client
from pathlib import Path
from typing import Any

from egosim.msgs import get_profile
from egosim.ros1 import Node

PROFILE = get_profile("26.r1")
USER = "probe_stack"
SERVICES = {
    "/SyncModeCmd": "MoraiSyncModeCmdSrv",
    "/SyncModeWaitForTick": "MoraiWaitForTickSrv",
    "/SyncModeCtrlCmd": "MoraiSyncModeCtrlCmdSrv",
    "/SyncModeAddObject": "MoraiSyncModeAddObjectSrv",
    "/Service_MoraiEventCmd": "MoraiEventCmdSrv",
}
CTRL_MODE, GEAR, LAMPS = 0x01, 0x02, 0x04
AUTO, REVERSE, HAZARD = 4, 2, 1


class Services:
    def __init__(self, node: Node) -> None:
        self._proxies = {}
        for name, srv in SERVICES.items():
            kind = PROFILE.service(f"morai_msgs/{srv}")
            proxy = node.service_proxy(name, kind, persistent=True)
            proxy.wait_for_service(30.0)
            self._proxies[name] = (proxy, kind)

    def call_raw(self, service: str, message: str, **fields: Any) -> bytes:
        proxy, kind = self._proxies[service]
        request = kind.request.new(request=PROFILE.message(f"morai_msgs/{message}").new(**fields))
        return bytes(proxy.call(kind.request.serialize(request)))

    def call(self, service: str, message: str, **fields: Any) -> Any:
        _, kind = self._proxies[service]
        return kind.response.deserialize(self.call_raw(service, message, **fields)).response


def command(throttle: float) -> Any:
    return PROFILE.message("morai_msgs/CtrlCmd").new(longlCmdType=1, accel=throttle)


def step(services: Services, first: int, frames: int, throttle: float) -> list[str]:
    """Step `frames` frames after `first`; the md5 of each reply."""
    replies = []
    for frame in range(first + 1, first + frames + 1):
        services.call("/SyncModeCtrlCmd", "SyncModeCtrlCmd", frame=frame, command=command(throttle))
        reply = services.call_raw("/SyncModeWaitForTick", "WaitForTick", user_id=USER, frame=frame)
        replies.append(hashlib.md5(reply).hexdigest())
    return replies


def meddle(node: Node, services: Services) -> int:
    node.set_param("/left_over", {"from": "an earlier case"})
    node.set_param("~private_left_over", 1)
    started = services.call(
        "/SyncModeCmd", "SyncModeCmd", user_id=USER, start_sync_mode=True, time_step=20
    )
    frame = int(started.frame)
    position = PROFILE.message("geometry_msgs/Vector3").new(x=30.0, y=0.0, z=0.0)
    services.call(
        "/SyncModeAddObject",
        "SyncModeAddObject",
        name="2016_Kia_Niro(HEV)",
        position=position,
        heading=0.0,
        frame=frame + 1,
    )
    lamps = PROFILE.message("morai_msgs/Lamps").new(emergencySignal=HAZARD)
    services.call(
        "/Service_MoraiEventCmd",
        "EventInfo",
        option=CTRL_MODE | GEAR | LAMPS,
        ctrl_mode=AUTO,
        gear=REVERSE,
        lamps=lamps,
    )
    step(services, frame, 30, 1.0)
    return 3


def observe(services: Services) -> int:
    master = xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"])
    _, _, params = master.getParamNames("/probe_stack")
    _, _, (publishers, subscribers, servers) = master.getSystemState("/probe_stack")
    _, _, types = master.getTopicTypes("/probe_stack")
    ego = services.call("/Service_MoraiEventCmd", "EventInfo", option=0)
    started = services.call(
        "/SyncModeCmd", "SyncModeCmd", user_id=USER, start_sync_mode=True, time_step=0
    )
    observed = {
        "params": sorted(params),
        "graph": {
            kind: sorted([name, sorted(nodes)] for name, nodes in entries)
            for kind, entries in (("publishers", publishers), ("subscribers", subscribers))
        },
        "services": sorted(name for name, _ in servers),
        "types": sorted(types),
        "ego": {"ctrl_mode": ego.ctrl_mode, "gear": ego.gear, "lamps": str(ego.lamps)},
        "sync_start": {"frame": int(started.frame), "time_step": int(started.time_step)},
        "replies": step(services, int(started.frame), 40, 0.5),
    }
    Path(os.environ["EGOSIM_CASE_DIR"], "observed.json").write_text(json.dumps(observed))
    return 0


def write_simulator_pid() -> None:
    """The simulator's process id (its node's getPid), in simulator.pid of the case folder."""
    master = xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"])
    _, _, uri = master.lookupNode(f"/{USER}", "/egosim")
    _, _, pid = xmlrpc.client.ServerProxy(uri).getPid(f"/{USER}")
    Path(os.environ["EGOSIM_CASE_DIR"], "simulator.pid").write_text(str(pid))


def main() -> int:
    node = Node(USER, rosout_logger=None, embedded_master="never")
    services = Services(node)
    write_simulator_pid()
    if sys.argv[1] == "meddle":
        return meddle(node, services)  # exits with its connections open, as a crash does
    status = observe(services)
    node.shutdown("done")
    return status


if __name__ == "__main__":
    sys.exit(main())
