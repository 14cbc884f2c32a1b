"""/clock: rosgraph_msgs/Clock with the simulation time, after every step.

Published with `--clock sim` and `--clock sync`, where the simulator sets
/use_sim_time and stamps headers with the simulation time; nothing is published
in real time, where nodes use their wall clocks.
"""

from __future__ import annotations

from .context import BridgeContext
from .protocol.table import Row


def publish_clock(context: BridgeContext, row: Row) -> bytes | None:
    """Its bytes: the stamp's sec and nanosec."""
    if not context.clock.publishes_clock:
        return None
    pack = context.profile.message("rosgraph_msgs/Clock").flat().pack
    return pack(*divmod(context.stamp_ns(), 1_000_000_000))
