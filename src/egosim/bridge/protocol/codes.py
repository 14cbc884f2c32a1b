"""Protocol codes of the bridge's own state (the world's codes, such as Gear and light
types, live with the world)."""

from __future__ import annotations

from enum import IntEnum


class ControlMode(IntEnum):
    """EventInfo.ctrl_mode: who drives an ego (docs/protocol.md, Control modes)."""

    KEYBOARD = 1
    GAMEPAD = 2
    EXTERNAL = 3
    """The ego obeys its command input (/ctrl_cmd, ...): the default."""
    AUTO = 4
    """MORAI's internal controller: egosim's lane-following autopilot."""
