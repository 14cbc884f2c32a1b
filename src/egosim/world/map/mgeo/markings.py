"""MGeo lane boundaries -> the road markings painted on them.

A record of lane_boundary_set.json is one painted boundary: its `points`, `lane_color`
(white, yellow, blue; a list gives one colour per line), `lane_shape` (one word per
line, left to right: "Solid" or "Broken"; ["Solid", "Solid"] is a double line, and
"Solid Broken" in one string is read the same way), `lane_width` (m, one line's painted
width), `dash_interval_L1` / `dash_interval_L2` (m of paint, then of gap) and
`double_line_interval` (m between the two lines). `lane_type` 530 (the Korean code of
a stop line) marks a stop line. A record whose colour is none of these, or whose shape
has no known word, is reported and left out (boundaries that are not painted).
"""

from __future__ import annotations

from egosim.json_value import JsonValue
from egosim.world.map.errors import MapGeometryError
from egosim.world.map.markings import (
    DASH_GAP_M,
    DASH_LENGTH_M,
    DOUBLE_GAP_M,
    LANE_LINE_WIDTH_M,
    LineStyle,
    MarkingColor,
    MarkingKind,
    RoadMarking,
)
from egosim.world.map.mgeo.records import Record, unique_by_idx

LANE_BOUNDARY_SET = "lane_boundary_set.json"
STOP_LINE_TYPE = "530"
SHAPES = {"solid": LineStyle.SOLID, "broken": LineStyle.DASHED, "dashed": LineStyle.DASHED}
COLORS = {color.value: color for color in MarkingColor}


def read_markings(items: list[Record], notes: list[str]) -> list[RoadMarking]:
    markings = []
    for idx, record in unique_by_idx(items).items():
        color = _first(record.data.get("lane_color"))
        lines = tuple(SHAPES.get(word.lower()) for word in _words(record.data.get("lane_shape")))
        if str(color).lower() not in COLORS or not lines or None in lines:
            notes.append(
                f"{LANE_BOUNDARY_SET}: {idx}: lane_color {record.data.get('lane_color')!r} / "
                f"lane_shape {record.data.get('lane_shape')!r} is no painted line"
            )
            continue
        kind = (
            MarkingKind.STOP_LINE
            if str(_first(record.data.get("lane_type"))) == STOP_LINE_TYPE
            else MarkingKind.LANE_LINE
        )
        try:
            marking = RoadMarking(
                idx,
                record.points("points"),
                COLORS[str(color).lower()],
                lines,  # type: ignore[arg-type]
                kind=kind,
                width_m=_positive(record, "lane_width", LANE_LINE_WIDTH_M),
                dash_length_m=_positive(record, "dash_interval_L1", DASH_LENGTH_M),
                dash_gap_m=_positive(record, "dash_interval_L2", DASH_GAP_M),
                double_gap_m=_positive(record, "double_line_interval", DOUBLE_GAP_M),
            )
        except MapGeometryError as error:
            notes.append(f"{LANE_BOUNDARY_SET}: {idx}: {error}; not drawn")
            continue
        markings.append(marking)
    return markings


def _first(value: JsonValue) -> JsonValue:
    return value[0] if isinstance(value, list) and value else value


def _words(value: JsonValue) -> list[str]:
    if isinstance(value, str):
        return value.split()
    if isinstance(value, list):
        return [word for item in value if isinstance(item, str) for word in item.split()]
    return []


def _positive(record: Record, key: str, default: float) -> float:
    value = record.number(key)
    return value if value is not None and value > 0.0 else default
