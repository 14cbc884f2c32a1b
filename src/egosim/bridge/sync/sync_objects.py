"""/SyncModeAddObject and /SyncModeRemoveObject: objects in or out at a frame.

AddObject.name is a model of the obstacle catalogue (a static box standing at
`position`) or of the vehicle catalogue (an NPC placed on the lane nearest to
`position`, which then drives); heading is in degrees (ENU, 0 = east,
counter-clockwise), like every MORAI heading. RemoveObject takes out the NPC or
obstacle with that unique_id (egos and pedestrians cannot be removed).
"""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING

from ...world import UnknownObjectModelError
from ..context import BridgeContext
from ..protocol.table import Row
from ..protocol.units import rad
from .sync_mode import at_frame, result_message, service_response

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

log = logging.getLogger(__name__)


def add_requested_object(
    context: BridgeContext, row: Row, request: morai_26_r1.SyncModeAddObject
) -> bool:
    position = (float(request.position.x), float(request.position.y), float(request.position.z))
    heading = float(request.heading)
    if not all(math.isfinite(v) for v in (*position, heading)):
        log.error("%s: %r: position or heading is not finite", row.name, request.name)
        return False
    try:
        unique_id = context.world.add_object(request.name, position, rad(heading))
    except UnknownObjectModelError as error:
        log.error("%s: %s", row.name, error)
        return False
    log.info("%s: %s added as object %d", row.name, request.name, unique_id)
    return True


def remove_requested_object(
    context: BridgeContext, row: Row, request: morai_26_r1.SyncModeRemoveObject
) -> bool:
    if not context.world.remove_object(int(request.unique_id)):
        log.error("%s: no NPC or obstacle %d", row.name, request.unique_id)
        return False
    return True


def serve_add_object(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiSyncModeAddObjectSrvRequest
) -> object:
    add = request.request
    ok = at_frame(context, row, int(add.frame), lambda c: add_requested_object(c, row, add))
    return service_response(context, "MoraiSyncModeAddObjectSrv", result_message(context, ok))


def serve_remove_object(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiSyncModeRemoveObjectSrvRequest
) -> object:
    remove = request.request
    ok = at_frame(
        context, row, int(remove.frame), lambda c: remove_requested_object(c, row, remove)
    )
    return service_response(context, "MoraiSyncModeRemoveObjectSrv", result_message(context, ok))
