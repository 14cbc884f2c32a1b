"""The storyboard stage: an OpenSCENARIO scenario's storyboard steps before the world.

In control mode auto (EventInfo ctrl_mode 4) the scenario drives the main ego (its
actions on the ego are MORAI's internal controller then, in place of the lane
autopilot); in external mode the ego's stack drives it. What the storyboard reports
(an element it does not carry out, a position it cannot place) is logged once.
"""

from __future__ import annotations

import logging

from ..context import BridgeContext
from ..protocol.codes import ControlMode

log = logging.getLogger("egosim.openscenario")


def scenario_drives_ego(context: BridgeContext) -> bool:
    main = context.world.egos[0]
    return context.ego_session(main).ctrl_mode is ControlMode.AUTO


def step_storyboard(context: BridgeContext, dt: float) -> None:
    world = context.world
    run = world.storyboard
    if run is None or world.paused:
        return
    for note in run.step(dt, scenario_drives_ego(context)):
        log.warning("%s", note)
