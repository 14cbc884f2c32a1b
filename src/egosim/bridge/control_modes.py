"""What EventInfo.ctrl_mode means for an ego (its EgoSession sets it, for EventInfo,
MultiEgoSetting and the live view alike).

3 external: the ego obeys its command input (the default). 1 keyboard and 2 gamepad:
a headless simulator has no human input, so the ego gets no command at all and holds
its brake (the live view's keyboard driving is the exception: it drives an ego in
keyboard mode). 4 auto: MORAI's internal controller drives, here the lane-following
autopilot of world.traffic.autopilot, commanded before every step (with an OpenSCENARIO
storyboard running, the storyboard drives the main ego instead: bridge/scene/storyboard.py).
Commands hold until the next one, so a change of mode drops the command the old input
left in force: the ego brakes until its new input commands it.
"""

from __future__ import annotations

from ..world.traffic import LightsView
from ..world.traffic.road_users import lane_occupants_of
from ..world.vehicle import Vehicle
from .context import BridgeContext
from .ego_session import EgoSession
from .protocol.codes import ControlMode


def drive_autopilots(context: BridgeContext) -> None:
    """Command every road-vehicle ego in auto mode for the coming step (loop thread)."""
    world = context.world
    # With a storyboard running, the scenario drives the main ego in auto mode.
    scripted = world.egos[0].unique_id if world.storyboard is not None else None
    auto: list[tuple[EgoSession, Vehicle]] = []
    for ego in world.egos:
        session = context.ego_session(ego)
        if (
            session.ctrl_mode is ControlMode.AUTO
            and isinstance(ego.vehicle, Vehicle)
            and ego.unique_id != scripted
        ):
            auto.append((session, ego.vehicle))
    if not auto:
        return
    lights = LightsView.of(world.signals)
    objects = world.objects()
    for session, vehicle in auto:
        autopilot = session.autopilot_on(world.npcs.graph)
        others = lane_occupants_of(objects, world.map, but=session.ego.unique_id)
        vehicle.command(autopilot.command(vehicle.model, vehicle.status(), lights, others))
