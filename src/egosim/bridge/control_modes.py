"""What EventInfo.ctrl_mode means for an ego (bridge/events.py and MultiEgoSetting set it).

3 external: the ego obeys its command input (the default). 1 keyboard and 2 gamepad:
a headless simulator has no human input, so the ego gets no command at all and holds
its brake. 4 auto: MORAI's internal controller drives, here the lane-following
autopilot of world.traffic.autopilot, commanded before every step. Commands hold
until the next one, so a change of mode drops the command the old input left in
force: the ego brakes until its new input commands it.
"""

from __future__ import annotations

import logging

from ..world import Ego
from ..world.traffic import LightsView
from ..world.traffic.autopilot import LaneAutopilot
from ..world.traffic.road_users import lane_occupants_of
from ..world.vehicle import Vehicle
from .codes import ControlMode
from .context import BridgeContext

log = logging.getLogger(__name__)


def switch_ctrl_mode(context: BridgeContext, ego: Ego, mode: ControlMode, by: str) -> None:
    """Put `ego` in control mode `mode` as `by` (a row's name, "the view") asks; a change
    releases the command in force, and is logged."""
    settings = context.settings_of(ego.unique_id)
    if settings.ctrl_mode is not mode:
        log.info(
            "ego %d: control mode %s -> %s (%s)",
            ego.unique_id,
            settings.ctrl_mode.name.lower(),
            mode.name.lower(),
            by,
        )
        settings.ctrl_mode = mode
        ego.vehicle.release_command()


def drive_autopilots(context: BridgeContext) -> None:
    """Command every road-vehicle ego in auto mode for the coming step (loop thread).

    An ego's autopilot is made when it enters auto mode and dropped when it leaves, so
    it plans afresh from wherever the ego is when auto mode is chosen again.
    """
    world = context.world
    auto = [
        ego
        for ego in world.egos
        if context.settings_of(ego.unique_id).ctrl_mode is ControlMode.AUTO
        and isinstance(ego.vehicle, Vehicle)
    ]
    driven = {ego.unique_id for ego in auto}
    autopilots = context.session.autopilots
    for unique_id in set(autopilots) - driven:
        del autopilots[unique_id]
    if not auto:
        return
    lights = LightsView.of(world.signals)
    objects = world.objects()
    for ego in auto:
        autopilot = autopilots.get(ego.unique_id)
        if autopilot is None:
            autopilot = autopilots[ego.unique_id] = LaneAutopilot(world.npcs.graph)
        others = lane_occupants_of(objects, world.map, but=ego.unique_id)
        vehicle = ego.vehicle
        vehicle.command(autopilot.command(vehicle.model, vehicle.status(), lights, others))
