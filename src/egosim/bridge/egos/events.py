"""One-shot vehicle events: MoraiEventCmdSrv and the /lamps topic.

EventInfo.option is an int8 bit mask; the document writes its bits as 0x0001
ctrl_mode, 0x0010 gear, 0x0100 lamps, 0x1000 set_pause. An int8 can only hold the
binary reading of that notation (1, 2, 4, 8), so that is what egosim reads; the hex
reading of gear (0x10 = 16) fits as well and is accepted for gear, as no other bit
claims 16.
"""

from __future__ import annotations

import logging
from dataclasses import replace
from typing import TYPE_CHECKING

from ...world.vehicle import Gear
from ..context import BridgeContext
from ..ego_session import Lamps
from ..protocol.codes import ControlMode
from ..protocol.table import Row

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

log = logging.getLogger(__name__)

OPTION_CTRL_MODE = 0x01
OPTION_GEAR = 0x02 | 0x10
OPTION_LAMPS = 0x04
OPTION_SET_PAUSE = 0x08
GEAR_NO_CHANGE = -1


def lamps_from(lamps: Lamps, message: morai_26_r1.Lamps, source: str) -> Lamps:
    """`lamps` as a morai_msgs/Lamps received on `source` (a row's name) sets them; a
    value out of range leaves its lamp as it was."""
    if message.turnSignal in (0, 1, 2):
        lamps = replace(lamps, turn_signal=int(message.turnSignal))
    else:
        log.warning("%s: turnSignal %s is not 0, 1 or 2; ignored", source, message.turnSignal)
    if message.emergencySignal in (0, 1):
        lamps = replace(lamps, emergency=int(message.emergencySignal))
    else:
        log.warning(
            "%s: emergencySignal %s is not 0 or 1; ignored", source, message.emergencySignal
        )
    return lamps


def on_lamps(context: BridgeContext, row: Row, message: morai_26_r1.Lamps) -> None:
    """/lamps: the main ego's turn and emergency lamps."""
    session = context.ego_session(context.world.egos[0])
    session.set_lamps(lamps_from(session.lamps, message, row.name))


def serve_event_cmd(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiEventCmdSrvRequest
) -> morai_26_r1.MoraiEventCmdSrvResponse:
    """/Service_MoraiEventCmd: apply the selected parts; answer with the resulting state."""
    event = request.request
    ego = context.world.egos[0]
    session = context.ego_session(ego)
    option = int(event.option) & 0xFF
    if option & OPTION_CTRL_MODE:
        try:
            mode = ControlMode(int(event.ctrl_mode))
        except ValueError:
            log.warning("%s: ctrl_mode %s is not 1..4; ignored", row.name, event.ctrl_mode)
        else:
            session.set_ctrl_mode(mode, by=row.name)
    if option & OPTION_GEAR and event.gear != GEAR_NO_CHANGE:
        try:
            ego.vehicle.set_gear(Gear(int(event.gear)))
        except ValueError:
            log.warning("%s: gear %s is not -1 or 1..4; ignored", row.name, event.gear)
    if option & OPTION_LAMPS:
        session.set_lamps(lamps_from(session.lamps, event.lamps, row.name))
    if option & OPTION_SET_PAUSE:
        context.world.paused = bool(event.set_pause)
    profile = context.profile
    lamps = profile.message("morai_msgs/Lamps").new(
        header=context.header(),
        turnSignal=session.lamps.turn_signal,
        emergencySignal=session.lamps.emergency,
    )
    state = profile.message("morai_msgs/EventInfo").new(
        option=event.option,
        ctrl_mode=int(session.ctrl_mode),
        gear=int(ego.vehicle.gear),
        lamps=lamps,
        set_pause=context.world.paused,
    )
    return profile.message("morai_msgs/MoraiEventCmdSrvResponse").new(response=state)
