"""/clock: rosgraph_msgs/Clock with the simulation time, after every step.

Published with `--clock sim` and `--clock sync`, where the simulator sets
/use_sim_time and stamps headers with the simulation time; nothing is published
in real time, where nodes use their wall clocks.
"""

from __future__ import annotations

from ..msgs.typed import standard
from .context import BridgeContext
from .protocol.messages import time_msg
from .protocol.table import Row


def publish_clock(context: BridgeContext, row: Row) -> standard.Clock | None:
    if not context.clock.publishes_clock:
        return None
    profile = context.profile
    return profile.message("rosgraph_msgs/Clock").new(clock=time_msg(profile, context.stamp_ns()))
