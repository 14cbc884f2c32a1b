"""Small scenario files the end-to-end tests write under the simulator's data root."""

from __future__ import annotations

from pathlib import Path

RED_LIGHT_TOWN = """\
map: town
seed: 7
ego:
  model: 2016_Kia_Niro(HEV)
  start: {lane: R1_E_1, s: 10.0}
npcs:
  - model: 2015_Kia_K5
    start: {lane: R2_E_1, s: 20.0}
    target_speed_mps: 10.0
"""

OBSTACLE_AHEAD = """\
map: straight
seed: 1
ego:
  model: 2016_Kia_Niro(HEV)
  start: {lane: R1_E_1, s: 10.0}
obstacles:
  - {model: Barrier, pose: {x: 40.0, y: -1.75, heading_deg: 90.0}}
"""

TWO_NPCS = """\
map: town
seed: 3
ego:
  model: 2016_Kia_Niro(HEV)
  start: {lane: R5_E_1, s: 30.0}
npcs:
  - {model: 2019_Hyundai_Sonata, start: {lane: R5_E_1, s: 80.0}}
  - {model: 2014_Kia_K7, start: {lane: R5_E_2, s: 60.0}}
"""

# The ego's reference point (rear axle, what /Ego_topic reports) stands at x = 100 m, its
# footprint centre 1.39 m ahead. Beside it, objects a little behind and a little ahead
# alternate: by distance from the reported position they come A, B, C, D (and the NPC
# behind before the NPC ahead), by distance from the footprint centre in the other order
# of each pair.
OBJECTS_FORE_AND_AFT = """\
map: straight
seed: 2
ego:
  model: 2016_Kia_Niro(HEV)
  start: {lane: R1_E_1, s: 100.0}
npcs:
  - {model: 2019_Hyundai_Sonata, start: {lane: R1_W_1, s: 904.5}, stalled: true}
  - {model: 2019_Hyundai_Sonata, start: {lane: R1_W_1, s: 894.0}, stalled: true}
obstacles:
  - {model: Cone, pose: {x: 96.0, y: -5.25}}
  - {model: Cone, pose: {x: 105.0, y: -5.25}}
  - {model: Cone, pose: {x: 92.0, y: -5.25}}
  - {model: Cone, pose: {x: 109.5, y: -5.25}}
"""


def write(root: Path, name: str, text: str) -> Path:
    path = root / name
    path.write_text(text)
    return path
