"""A small MGeo map as parsed JSON: a signalised four-way junction, a curve, a lane change.

The junction is centred on the local origin; its box reaches BOX_M from the centre on each
axis and every arm runs ARM_M further out. Arms carry one 3.5 m lane each way (right-hand
traffic), the west arm two incoming lanes with a lane-change link between them. The north
arm's outgoing lane continues as a right-hand quarter circle of radius CURVE_RADIUS_M
centred at CURVE_CENTER. Coordinates: UTM zone 52N, local origin at ORIGIN.
"""

from __future__ import annotations

import math

import numpy as np

from egosim.world.map.polyline import arc, connector_curve

BOX_M = 10.0
ARM_M = 100.0
LANE_M = 3.5
CURVE_RADIUS_M = 50.0
CURVE_CENTER = (LANE_M / 2 + CURVE_RADIUS_M, BOX_M + ARM_M)
ORIGIN = (313_000.0, 4_161_000.0, 10.0)
ARMS = {"E": (1.0, 0.0), "N": (0.0, 1.0), "W": (-1.0, 0.0), "S": (0.0, -1.0)}
LEFT_ARROW_HEAD = ["red", "yellow", "left", "straight"]
PLAIN_HEAD = ["red", "yellow", "straight"]


def _xyz(points: np.ndarray) -> list[list[float]]:
    return [[float(x), float(y), 0.0] for x, y in points[:, :2]]


class _Writer:
    def __init__(self) -> None:
        self.nodes: list[dict] = []
        self.links: list[dict] = []

    def node(self, idx: str, point: np.ndarray, stop_line: bool = False, junction: bool = False):
        self.nodes.append(
            {
                "idx": idx,
                "point": [float(point[0]), float(point[1]), 0.0],
                "node_type": 1,
                "junction": ["J1"] if junction else [],
                "on_stop_line": stop_line,
            }
        )

    def link(self, idx: str, start: str, end: str, points: np.ndarray, **extra) -> None:
        self.links.append(
            {
                "idx": idx,
                "from_node_idx": start,
                "to_node_idx": end,
                "points": _xyz(points),
                "max_speed": 50,
                "link_type": "1",
                "road_id": idx[:3],
                "ego_lane": 1,
                "can_move_left_lane": False,
                "can_move_right_lane": False,
                "left_lane_change_dst_link_idx": None,
                "right_lane_change_dst_link_idx": None,
                "lane_ch_link_path": [],
                "related_signal": [],
                "width_start": LANE_M,
                "width_end": LANE_M,
                "force_width_start": False,
                "force_width_end": False,
                **extra,
            }
        )


def _frame(arm: str) -> tuple[np.ndarray, np.ndarray]:
    outward = np.array(ARMS[arm])
    return outward, np.array([-outward[1], outward[0]])


def incoming_line(arm: str, lane: int = 1) -> np.ndarray:
    """Centreline of incoming lane `lane` (1 = inner) of an arm, from far end to stop line."""
    d, n = _frame(arm)
    offset = (lane - 0.5) * LANE_M * n
    return np.array([(BOX_M + ARM_M) * d + offset, BOX_M * d + offset])


def outgoing_line(arm: str) -> np.ndarray:
    d, n = _frame(arm)
    offset = -0.5 * LANE_M * n
    return np.array([BOX_M * d + offset, (BOX_M + ARM_M) * d + offset])


def _heading(line: np.ndarray) -> float:
    dx, dy = line[-1] - line[-2]
    return math.atan2(dy, dx)


def mgeo_files() -> dict[str, object]:
    """{file name: parsed JSON} of the sample map."""
    w = _Writer()
    for arm in ARMS:
        inner, out = incoming_line(arm), outgoing_line(arm)
        w.node(f"N_{arm}_in_start", inner[0])
        w.node(f"N_{arm}_in_end", inner[1], stop_line=True, junction=True)
        w.node(f"N_{arm}_out_start", out[0], junction=True)
        w.node(f"N_{arm}_out_end", out[1])
        w.link(f"L_{arm}_in", f"N_{arm}_in_start", f"N_{arm}_in_end", inner)
        w.link(f"L_{arm}_out", f"N_{arm}_out_start", f"N_{arm}_out_end", out)
    outer = incoming_line("W", 2)
    w.node("N_W_in2_start", outer[0])
    w.node("N_W_in2_end", outer[1], stop_line=True, junction=True)
    w.link("L_W_in2", "N_W_in2_start", "N_W_in2_end", outer)
    for link in w.links:
        if link["idx"] == "L_W_in":
            link.update(can_move_right_lane=True, right_lane_change_dst_link_idx="L_W_in2")
    w.links[-1].update(can_move_left_lane=True, left_lane_change_dst_link_idx="L_W_in")
    w.link(
        "LC_W_2_1",
        "N_W_in2_start",
        "N_W_in_end",
        np.array([outer[0], incoming_line("W")[1]]),
        lane_ch_link_path=["L_W_in2", "L_W_in"],
    )
    for source in ARMS:
        for target in ARMS:
            if source != target:
                _connector(w, f"C_{source}{target}", source, 1, target)
    _connector(w, "C_WE2", "W", 2, "E")
    curve = arc(CURVE_CENTER, CURVE_RADIUS_M, math.pi, -math.pi / 2, step=0.5)
    w.node("N_curve_end", curve[-1])
    w.link("L_N_curve", "N_N_out_end", "N_curve_end", curve, max_speed=30)
    return {
        "global_info.json": {
            "maj_ver": 2,
            "min_ver": 1,
            "global_coordinate_system": "UTM52N",
            "local_origin_in_global": list(ORIGIN),
            "traffic_dir": "RHT",
            "country": "KR",
            "lane_change_link_included": True,
        },
        "node_set.json": w.nodes,
        "link_set.json": w.links,
        "traffic_light_set.json": _lights(),
        "synced_traffic_light_set.json": [
            {
                "idx": "SL_NS",
                "link_id_list": ["L_N_in", "L_S_in"],
                "point": [0.0, 0.0, 5.0],
                "intersection_controller_id": "IntTL1",
                "signal_id_list": ["TL_N", "TL_S"],
            },
            {
                "idx": "SL_EW",
                "link_id_list": ["L_E_in", "L_W_in"],
                "point": [0.0, 0.0, 5.0],
                "intersection_controller_id": "IntTL1",
                "signal_id_list": ["TL_E", "TL_W"],
            },
        ],
        "intersection_controller_set.json": [
            {"idx": "IntTL1", "synced_signal_id_list": ["SL_NS", "SL_EW"], "point": [0, 0, 0]}
        ],
    }


def _connector(w: _Writer, idx: str, source: str, lane: int, target: str) -> None:
    a, b = incoming_line(source, lane), outgoing_line(target)
    start_node = "N_W_in2_end" if lane == 2 else f"N_{source}_in_end"
    curve = connector_curve(a[-1], _heading(a), b[0], _heading(b))
    w.link(idx, start_node, f"N_{target}_out_start", curve)


def _lights() -> list[dict]:
    lights = []
    for arm in ARMS:
        d, n = _frame(arm)
        spot = BOX_M * d + 2.5 * LANE_M * n
        governed = [f"L_{arm}_in"]
        if arm == "W":
            governed.append("L_W_in2")
        if arm == "E":
            # Listed past the stop line: the light governs the lane arriving at it.
            governed = ["C_EN", "C_EW", "C_ES"]
        lights.append(
            {
                "idx": f"TL_{arm}",
                "link_id_list": governed,
                "point": [float(spot[0]), float(spot[1]), 5.0],
                "type": "car",
                "sub_type": LEFT_ARROW_HEAD if arm in "NS" else PLAIN_HEAD,
                "orientation": "+0",
            }
        )
    lights.append(
        {
            "idx": "PL_S",
            "link_id_list": [],
            "point": [12.0, -12.0, 3.0],
            "type": "pedestrian",
            "sub_type": ["red", "green"],
        }
    )
    return lights


TWIN_LATERAL_M = 0.0
"""A twin head hangs over the middle of the road at its arm's stop line."""


def mgeo_files_with_twin_heads() -> dict[str, object]:
    """The sample map with a second head over each approach, as K-City has: `TL_<arm>2`
    governs the same links as `TL_<arm>`, shows the other lamp set (a round-green head
    beside each left-arrow head and the reverse) and is synced with it."""
    files = mgeo_files()
    lights: list[dict] = files["traffic_light_set.json"]  # type: ignore[assignment]
    for light in [light for light in lights if light["type"] == "car"]:
        arm = light["idx"][-1]
        d, n = _frame(arm)
        spot = BOX_M * d + TWIN_LATERAL_M * n
        twin_lamps = PLAIN_HEAD if light["sub_type"] == LEFT_ARROW_HEAD else LEFT_ARROW_HEAD
        lights.append(
            {
                **light,
                "idx": f"{light['idx']}2",
                "point": [float(spot[0]), float(spot[1]), 5.5],
                "sub_type": twin_lamps,
            }
        )
    for synced in files["synced_traffic_light_set.json"]:  # type: ignore[attr-defined]
        synced["signal_id_list"] = [
            head for light in synced["signal_id_list"] for head in (light, f"{light}2")
        ]
    return files
