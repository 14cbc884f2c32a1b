"""A publishing row's message now, as its subscribers read it."""

from __future__ import annotations

from typing import Any

from egosim.bridge import HANDLERS, BridgeContext


def built(context: BridgeContext, key: str) -> Any:
    """What the publishing row `key` sends now, as a message (several: a list): a row
    that writes its own bytes is read from them, as a subscriber reads them."""
    row = context.row(key)
    message_type = context.profile.message(row.type_name)
    message = HANDLERS.publishers[key](context, row)

    def read(one: Any) -> Any:
        return message_type.deserialize(one) if isinstance(one, bytes) else one

    return [read(one) for one in message] if isinstance(message, list) else read(message)
