"""The vehicle ahead of the ego: gap, time-to-collision and time headway."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from egosim.world.traffic import ObjectTable

LEAD_CORRIDOR_HALF_WIDTH_M = 1.75
"""An object whose centre is this close to the ego's heading line counts as ahead in its
lane (half a standard lane); a straight corridor, so on tight bends it is approximate."""
LEAD_RANGE_M = 150.0
MIN_CLOSING_SPEED_MPS = 1e-3
MIN_HEADWAY_SPEED_MPS = 0.5
"""Below this ego speed the time headway is not defined (standing in a queue)."""


@dataclass(frozen=True)
class LeadGap:
    gap_m: float
    """Bumper to bumper along the ego's heading."""
    closing_speed_mps: float
    """Ego speed minus the lead's speed along the ego's heading (positive: closing)."""
    ego_speed_mps: float

    @property
    def ttc_s(self) -> float | None:
        if self.closing_speed_mps <= MIN_CLOSING_SPEED_MPS:
            return None
        return max(self.gap_m, 0.0) / self.closing_speed_mps

    @property
    def headway_s(self) -> float | None:
        if self.ego_speed_mps < MIN_HEADWAY_SPEED_MPS:
            return None
        return max(self.gap_m, 0.0) / self.ego_speed_mps


def lead_gap(objects: ObjectTable, ego_id: int) -> LeadGap | None:
    """The nearest object (vehicle, pedestrian or obstacle) ahead of ego `ego_id` in its
    corridor, if any."""
    is_ego = objects.unique_ids == ego_id
    if not np.any(is_ego):
        return None
    k = int(np.flatnonzero(is_ego)[0])
    heading = float(objects.headings[k])
    along = np.array([math.cos(heading), math.sin(heading)])
    across = np.array([-along[1], along[0]])
    offset = objects.positions[:, :2] - objects.positions[k, :2]
    forward = offset @ along
    sideways = offset @ across
    gap = forward - objects.sizes[k, 0] / 2.0 - objects.sizes[:, 0] / 2.0
    ahead = (
        ~is_ego
        & (forward > 0.0)
        & (np.abs(sideways) <= LEAD_CORRIDOR_HALF_WIDTH_M)
        & (gap <= LEAD_RANGE_M)
    )
    if not np.any(ahead):
        return None
    lead = int(np.flatnonzero(ahead)[np.argmin(gap[ahead])])
    ego_speed = float(objects.velocities[k, :2] @ along)
    lead_speed = float(objects.velocities[lead, :2] @ along)
    return LeadGap(float(gap[lead]), ego_speed - lead_speed, ego_speed)
