"""MGeo single crosswalks -> crosswalks pedestrians cross.

A record of singlecrosswalk_set.json is one painted crossing: its `idx`, its outline
`points` and its `sign_type`, a Korean road-marking code: 5321 (crosswalk) and 533
(raised crosswalk) are read; other codes, such as 534 (bicycle crossing), are reported
and left out, and a record without one is read as a crosswalk. The crossing is squared to
the lane nearest its centre (see egosim.world.map.crossings).
"""

from __future__ import annotations

import numpy as np

from egosim.world.map.crossings import crossing
from egosim.world.map.lanes import Crosswalk, LaneMap
from egosim.world.map.mgeo.records import Record, unique_by_idx

SINGLECROSSWALK_SET = "singlecrosswalk_set.json"
PEDESTRIAN_CROSSING_SIGNS = frozenset({"5321", "533"})


def read_crosswalks(items: list[Record], lane_map: LaneMap, notes: list[str]) -> list[Crosswalk]:
    outlines = {}
    for idx, record in unique_by_idx(items).items():
        sign = record.text("sign_type")
        if sign is not None and sign not in PEDESTRIAN_CROSSING_SIGNS:
            notes.append(f"{SINGLECROSSWALK_SET}: {idx}: sign_type {sign} is no crosswalk")
            continue
        outlines[idx] = record.points("points")[:, :2]
    if not outlines:
        return []
    centres = np.array([outline.mean(axis=0) for outline in outlines.values()])
    headings = lane_map.project_many(centres).heading
    crosswalks = []
    for (idx, outline), heading in zip(outlines.items(), headings, strict=True):
        walk = crossing(idx, outline, float(heading), lane_map.intersections.values())
        if walk is None:
            notes.append(f"{SINGLECROSSWALK_SET}: {idx}: crosses no road")
            continue
        crosswalks.append(walk)
    return crosswalks
