"""A painted road marking: a line or double line along a polyline (see markings.py for
where a map's markings come from)."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.errors import MapGeometryError

LANE_LINE_WIDTH_M = 0.15
STOP_LINE_WIDTH_M = 0.45
DASH_LENGTH_M = 3.0
DASH_GAP_M = 5.0
DOUBLE_GAP_M = 0.15


class MarkingColor(Enum):
    WHITE = "white"
    YELLOW = "yellow"
    BLUE = "blue"


class LineStyle(Enum):
    SOLID = "solid"
    DASHED = "dashed"


class MarkingKind(Enum):
    LANE_LINE = "lane_line"
    STOP_LINE = "stop_line"


@dataclass(frozen=True, eq=False)
class RoadMarking:
    """One painted line (or double line) along `points` (N >= 2, 3), map frame, m.

    `lines` lists each line's style from left to right of the direction of `points`:
    one entry for a single line, two for a double line.
    """

    id: str
    points: FloatArray
    color: MarkingColor
    lines: tuple[LineStyle, ...]
    kind: MarkingKind = MarkingKind.LANE_LINE
    width_m: float = LANE_LINE_WIDTH_M
    dash_length_m: float = DASH_LENGTH_M
    dash_gap_m: float = DASH_GAP_M
    double_gap_m: float = DOUBLE_GAP_M

    def __post_init__(self) -> None:
        points = np.asarray(self.points, dtype=np.float64)
        if points.ndim != 2 or len(points) < 2 or points.shape[1] != 3:
            raise MapGeometryError(f"marking {self.id}: points must be (N >= 2, 3)")
        if not np.all(np.isfinite(points)):
            raise MapGeometryError(f"marking {self.id}: points are not finite")
        # A point repeating the one before it has no direction to paint along.
        step = np.hypot(*np.diff(points[:, :2], axis=0).T)
        points = points[np.concatenate(([True], step > 1e-6))]
        if len(points) < 2:
            raise MapGeometryError(f"marking {self.id}: its points do not span a line")
        if not self.lines or self.width_m <= 0.0 or self.dash_length_m <= 0.0:
            raise MapGeometryError(f"marking {self.id}: needs a line and positive sizes")
        if self.dash_gap_m < 0.0 or self.double_gap_m < 0.0:
            raise MapGeometryError(f"marking {self.id}: gaps must be >= 0")
        points.flags.writeable = False
        object.__setattr__(self, "points", points)
