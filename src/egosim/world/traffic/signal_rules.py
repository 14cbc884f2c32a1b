"""What a light's aspect lets a vehicle do at its stop line, vectorised."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import BoolArray, IntArray
from egosim.world.signals import GREEN, GREEN_LEFT, YELLOW, TrafficSignals
from egosim.world.traffic.lane_graph import TURN_LEFT


@dataclass(frozen=True, eq=False)
class LightsView:
    """Per signal of TrafficSignals.lane_signals (signal k < number of lights is light k
    alone; later ones are heads governing a lane together): the aspect now and facts
    about its heads (flashing, has a left arrow, has a left arrow and no round green)."""

    aspects: IntArray
    flashing: BoolArray
    arrow_head: BoolArray
    arrow_only: BoolArray

    @classmethod
    def of(cls, signals: TrafficSignals) -> LightsView:
        table = signals.lane_signals
        return cls(signals.signal_aspects(), table.flashing, table.arrow, table.arrow_only)


def signal_permissions(
    lights: LightsView, light: IntArray, turn: IntArray
) -> tuple[BoolArray, BoolArray]:
    """(may proceed, shows a yellow to stop for) for vehicles facing lights `light`.

    A dark light (OFF) or a flashing-yellow head stops nobody. A left turn at a head with
    a left arrow goes on the arrow only; every other movement goes on green, except under
    a head with no round green (type 1, over an approach served alone), whose arrow is
    the only go lamp for all its movements. A yellow without a go lamp asks the vehicle
    to stop if it comfortably can.
    """
    aspect = lights.aspects[light]
    dark = (aspect < 0) | lights.flashing[light]
    on_arrow = ((turn == TURN_LEFT) & lights.arrow_head[light]) | lights.arrow_only[light]
    go_lamp = np.where(on_arrow, GREEN_LEFT, GREEN)
    lit = np.where(dark, 0, aspect)
    proceed = dark | ((lit & go_lamp) != 0)
    yellow = ~proceed & ((lit & YELLOW) != 0)
    return proceed, yellow
