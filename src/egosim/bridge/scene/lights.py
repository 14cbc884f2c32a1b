"""Traffic lights and intersections: status out, overrides in, MoraiTLInfo on request.

The world keeps a light's aspect in GetTrafficLightStatus codes (1 red, 4 yellow,
16 green, 32 green-left, OR-combined; -1 off). MoraiTLInfo's table writes its codes
as 0x0001, 0x0100, 0x0001 0000, 0x0010 0000: binary digits, as its int16 field
shows (0x10000 would not fit), so they are the same values; the conversion below
is where a differing release would differ.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from ...world.signals import OFF, SignalError
from ..context import MAP_FRAME, BridgeContext
from ..protocol.table import Row

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

log = logging.getLogger(__name__)


def tl_info_status(aspect: int) -> int:
    """A world aspect in MoraiTLInfo.status codes."""
    return aspect


def publish_traffic_light_status(context: BridgeContext, row: Row) -> bytes | None:
    """/GetTrafficLightStatus: the light governing the lane ahead of the ego, else the
    nearest; its bytes (trafficLightIndex, trafficLightType, trafficLightStatus)."""
    light = context.world.ego_traffic_light(context.session.camera_index)
    if light is None:
        return None
    pack = context.profile.message("morai_msgs/GetTrafficLightStatus").flat().pack
    # header: seq and stamp written by the outlet
    return pack(0, 0, 0, MAP_FRAME, light.light_id, light.light_type, light.aspect)


def publish_intersection_status(context: BridgeContext, row: Row) -> list[bytes]:
    """/InsnStatus: one message per signalised intersection, in index order, each period;
    their bytes, for the outlet to stamp."""
    pack = context.profile.message("morai_msgs/IntersectionStatus").flat().pack
    return [
        # header: seq and stamp written by the outlet
        pack(0, 0, 0, MAP_FRAME, status.intersection_id, status.phase_index, status.elapsed_s)
        for status in sorted(
            context.world.signals.intersection_statuses(), key=lambda s: s.intersection_id
        )
    ]


def on_set_traffic_light(
    context: BridgeContext, row: Row, request: morai_26_r1.SetTrafficLight
) -> None:
    """/SetTrafficLight: hold a light's aspect until its intersection is controlled."""
    try:
        context.world.signals.set_light(request.trafficLightIndex, int(request.trafficLightStatus))
    except SignalError as error:
        log.warning("%s ignored: %s", row.name, error)


def on_intersection_control(
    context: BridgeContext, row: Row, request: morai_26_r1.IntersectionControl
) -> None:
    """/InsnControl: jump an intersection to a phase (intersection_status) and a time in it."""
    try:
        context.world.signals.control_intersection(
            int(request.intersection_index),
            int(request.intersection_status),
            float(request.intersection_status_time),
        )
    except SignalError as error:
        log.warning("%s ignored: %s", row.name, error)


def serve_tl_info(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiTLInfoSrvRequest
) -> morai_26_r1.MoraiTLInfoSrvResponse:
    """/Morai_TLSrv: the state of any light of the map; an unknown index reads off (-1)."""
    light_id = request.request.idx
    try:
        aspect = context.world.signals.light(light_id).aspect
    except SignalError as error:
        log.warning("%s: %s", row.name, error)
        aspect = OFF
    return context.profile.message("morai_msgs/MoraiTLInfoSrvResponse").new(
        response=context.profile.message("morai_msgs/MoraiTLInfo").new(
            header=context.header(), idx=light_id, status=tl_info_status(aspect)
        )
    )
