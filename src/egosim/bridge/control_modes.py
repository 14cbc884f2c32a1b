"""What EventInfo.ctrl_mode means for an ego (bridge/events.py and MultiEgoSetting set it).

3 external: the ego obeys its command input (the default). 1 keyboard and 2 gamepad:
a headless simulator has no human input, so the ego gets no command at all and holds
its brake. 4 auto: MORAI's internal controller drives, here the lane-following
autopilot of world.traffic.autopilot, commanded before every step (with an OpenSCENARIO
storyboard running, the storyboard drives the main ego instead: bridge/storyboard.py). Commands hold
until the next one, so a change of mode drops the command the old input left in
force: the ego brakes until its new input commands it.
"""

from __future__ import annotations

from ..world import Ego
from ..world.traffic import LightsView
from ..world.traffic.autopilot import LaneAutopilot
from ..world.traffic.road_users import lane_occupants_of
from ..world.vehicle import Vehicle
from .codes import ControlMode
from .context import BridgeContext


def switch_ctrl_mode(context: BridgeContext, ego: Ego, mode: ControlMode) -> None:
    """Put `ego` in control mode `mode`; a change releases the command in force."""
    settings = context.settings_of(ego.unique_id)
    if settings.ctrl_mode is not mode:
        settings.ctrl_mode = mode
        ego.vehicle.release_command()


def drive_autopilots(context: BridgeContext) -> None:
    """Command every road-vehicle ego in auto mode for the coming step (loop thread).

    An ego's autopilot is made when it enters auto mode and dropped when it leaves, so
    it plans afresh from wherever the ego is when auto mode is chosen again.
    """
    world = context.world
    # With a storyboard running, the scenario drives the main ego in auto mode.
    scripted = world.egos[0].unique_id if world.storyboard is not None else None
    auto = [
        ego
        for ego in world.egos
        if context.settings_of(ego.unique_id).ctrl_mode is ControlMode.AUTO
        and isinstance(ego.vehicle, Vehicle)
        and ego.unique_id != scripted
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
