"""OpenDRIVE dynamic signal types -> the protocol's trafficLightType codes.

OpenDRIVE names signals by a country's catalogue code (`type` / `subtype`); the German
catalogue (StVO), which most tools write, is read:

| type      | subtype   | head                       | trafficLightType |
|-----------|-----------|----------------------------|------------------|
| 1000001   | any       | red / yellow / green       | 0 R/Y/G          |
| 1000011   | 10 (left) | red / yellow / left arrow  | 1 R/Y/left arrow |
| 1000011   | other     | arrow head (right, straight) | 0 R/Y/G        |
| 1000002, 1000007 | any | pedestrian, bicycle heads | ignored (reported) |

Any other dynamic signal whose type mentions "light" (as some exporters write) is read as
R/Y/G; other dynamic signals are ignored and reported.
"""

from __future__ import annotations

from egosim.world.map.light_type import LightType

THREE_LAMP_HEAD = "1000001"
ARROW_HEAD = "1000011"
LEFT_ARROW_SUBTYPE = "10"


def light_type_of(signal_type: str, subtype: str) -> LightType | None:
    """The trafficLightType of a dynamic signal, None when it is not a vehicle light."""
    if signal_type == THREE_LAMP_HEAD:
        return LightType.RYG
    if signal_type == ARROW_HEAD:
        return LightType.RYG_LEFT if subtype == LEFT_ARROW_SUBTYPE else LightType.RYG
    if "light" in signal_type.lower():
        return LightType.RYG
    return None
