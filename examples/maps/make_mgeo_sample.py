"""Write egosim's MGeo sample map: one signalised four-way junction with crosswalks.

The main road runs east-west with two lanes each way, the side road north-south with one
lane each way; each arm is 120 m long from the junction centre, 50 km/h. The junction's
four approaches have lights (left-arrow heads where a left turn is possible) run by one
intersection controller, and a crosswalk crosses each arm at the junction's mouth.

The folder shipped with egosim (src/egosim/data/maps/mgeo_sample/) is this script's
output; a test checks that it still is.

Run: .venv/bin/python examples/maps/make_mgeo_sample.py [OUTPUT_FOLDER]
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import numpy as np

from egosim.world.map import LaneMap
from egosim.world.map.builtin_origin import BUILTIN_GEOREF
from egosim.world.map.mgeo import mgeo_files
from egosim.world.map.road_network import JunctionSpec, RoadNetworkBuilder, RoadSpec

NAME = "mgeo_sample"
DEFAULT_FOLDER = Path(__file__).parents[2] / "src" / "egosim" / "data" / "maps" / NAME
ARM_LENGTH_M = 120.0
JUNCTION_RADIUS_M = 14.0
LANE_WIDTH_M = 3.5
SPEED_LIMIT_MPS = 50.0 / 3.6
# Road id, direction of the arm from the centre, lanes leaving / entering the junction.
ARMS = (
    (1, (1.0, 0.0), 2, 2),
    (2, (0.0, 1.0), 1, 1),
    (3, (-1.0, 0.0), 2, 2),
    (4, (0.0, -1.0), 1, 1),
)


def sample_map() -> LaneMap:
    builder = RoadNetworkBuilder(LANE_WIDTH_M)
    builder.add_junction(JunctionSpec(1, (0.0, 0.0), JUNCTION_RADIUS_M))
    for road_id, direction, leaving, entering in ARMS:
        reference = np.array([(0.0, 0.0), np.multiply(direction, ARM_LENGTH_M)])
        builder.add_road(RoadSpec(road_id, reference, leaving, entering, SPEED_LIMIT_MPS, 1))
    return builder.build(NAME, BUILTIN_GEOREF)


def readable_json(content: object) -> str:
    """Indented JSON with each point ([x, y, z]) on one line."""
    text = json.dumps(content, indent=1)
    return re.sub(r"\[\s+([^\[\]{}]*?)\s+\]", _one_line, text) + "\n"


def _one_line(match: re.Match[str]) -> str:
    return "[" + ", ".join(part.strip() for part in match.group(1).split(",")) + "]"


def write(folder: Path) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    for name, content in mgeo_files(sample_map()).items():
        (folder / name).write_text(readable_json(content), encoding="utf-8")


if __name__ == "__main__":
    write(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_FOLDER)
