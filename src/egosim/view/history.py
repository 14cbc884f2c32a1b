"""The last minute of what the page plots, kept by the server so a page opened late sees
it at once (its plots and trails then start full, not empty).

Every SPACING_S of simulation time the view's stage (loop thread) takes one sample of
each ego: the plotted fields of its frame entry (speed, steering, pedals, lane offset)
and its position (the trail). Each ego's samples are a ring of HISTORY_S / SPACING_S + 1
entries, so memory is bounded whatever the run's length; the check on the ticks between
samples is one comparison. A browser gets the whole of it once, when it connects (server
thread), as a "history" message; the frames after it extend it on the page.
"""

from __future__ import annotations

import math
import threading
from collections import deque
from typing import Literal, get_args

import numpy as np

from ..bridge import BridgeContext
from .messages import HistoryMessage, HistorySeries
from .snapshot import ego_entries

HISTORY_S = 60.0
SPACING_S = 0.1
PlottedField = Literal["x", "y", "speed", "steer", "accel_pedal", "brake_pedal", "lane_offset"]
FIELDS: tuple[PlottedField, ...] = get_args(PlottedField)
"""What is kept of an ego's frame entry, besides the time."""

Sample = tuple[float, ...]
"""(t, *FIELDS)."""


class PlotHistory:
    def __init__(self, span_s: float = HISTORY_S, spacing_s: float = SPACING_S) -> None:
        self.span_s = span_s
        self.spacing_s = spacing_s
        self._capacity = math.floor(span_s / spacing_s + 1e-9) + 1
        self._lock = threading.Lock()
        self._egos: dict[int, deque[Sample]] = {}
        self._next_s = -math.inf
        self._last_s = -math.inf

    def record(self, context: BridgeContext) -> None:
        """After a tick (loop thread): a sample of every ego when one is due."""
        now = context.world.sim_time
        if self._last_s <= now < self._next_s:
            return
        entries = ego_entries(context)
        with self._lock:
            if now < self._last_s:  # time went back: what is kept is of another run
                self._egos.clear()
            self._last_s = now
            self._next_s = now + self.spacing_s - 1e-9
            egos: dict[int, deque[Sample]] = {}
            for entry in entries:
                ring = self._egos.get(entry["id"])
                if ring is None:
                    ring = deque(maxlen=self._capacity)
                ring.append((now, *(float(entry[name]) for name in FIELDS)))
                egos[entry["id"]] = ring
            self._egos = egos  # egos that are gone are forgotten

    def message(self) -> HistoryMessage:
        """Everything kept, as a "history" message (any thread; `encode` makes its JSON)."""
        with self._lock:
            kept = {unique_id: list(ring) for unique_id, ring in self._egos.items()}
        egos: list[HistorySeries] = []
        for unique_id, samples in kept.items():
            columns = np.array(samples, dtype=np.float64).reshape(-1, len(FIELDS) + 1).T
            egos.append({"id": unique_id, **dict(zip(("t", *FIELDS), columns, strict=True))})
        return {
            "type": "history",
            "span_s": self.span_s,
            "spacing_s": self.spacing_s,
            "egos": egos,
        }
