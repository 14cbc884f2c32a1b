"""A sampled path in the map plane: stations, points, headings and (optionally) the time
each point is due; what trajectories and routes are followed along."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import FloatArray


@dataclass(frozen=True, eq=False)
class SampledPath:
    """Points (N, 3) with stations s (N,) from 0, headings (N,) and times (N,) (NaN:
    untimed)."""

    points: FloatArray
    s: FloatArray
    headings: FloatArray
    times: FloatArray

    @classmethod
    def through(
        cls,
        points: FloatArray,
        times: FloatArray | None = None,
        headings: FloatArray | None = None,
    ) -> SampledPath:
        """The polyline through `points`; headings from its segments unless given."""
        points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
        steps = np.hypot(*np.diff(points[:, :2], axis=0).T)
        keep = np.concatenate(([True], steps > 1e-9))
        points = points[keep]
        if times is not None:
            times = np.asarray(times, dtype=np.float64)[keep]
        if headings is not None:
            headings = np.asarray(headings, dtype=np.float64)[keep]
        s = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(points[:, :2], axis=0).T))))
        if headings is None:
            if len(points) > 1:
                segment = np.arctan2(np.diff(points[:, 1]), np.diff(points[:, 0]))
                headings = np.append(segment, segment[-1])
            else:
                headings = np.zeros(len(points))
        return cls(points, s, headings, np.full(len(points), np.nan) if times is None else times)

    @property
    def length(self) -> float:
        return float(self.s[-1])

    @property
    def timed(self) -> bool:
        return bool(np.all(np.isfinite(self.times))) and len(self.times) > 1

    def pose_at(self, s: float) -> tuple[float, float, float, float]:
        """x, y, z, heading at station s (clamped); the heading of the segment there."""
        s = min(max(s, 0.0), self.length)
        if len(self.s) == 1:
            x, y, z = self.points[0]
            return float(x), float(y), float(z), float(self.headings[0])
        j = int(np.clip(np.searchsorted(self.s, s, side="right") - 1, 0, len(self.s) - 2))
        span = self.s[j + 1] - self.s[j]
        f = (s - self.s[j]) / span if span > 0 else 0.0
        x, y, z = self.points[j] + f * (self.points[j + 1] - self.points[j])
        h0, h1 = self.headings[j], self.headings[j + 1]
        heading = h0 + f * math.remainder(float(h1 - h0), math.tau)
        return float(x), float(y), float(z), float(heading)

    def offset_pose(self, s: float, t: float) -> tuple[float, float, float, float]:
        x, y, z, h = self.pose_at(s)
        return x - t * math.sin(h), y + t * math.cos(h), z, h

    def station_at_time(self, time: float) -> float:
        """Station due at path time `time` (clamped to the timed span)."""
        return float(np.interp(time, self.times, self.s))

    def project(self, x: float, y: float) -> float:
        """Station of the path point nearest (x, y)."""
        if len(self.s) == 1:
            return 0.0
        a, b = self.points[:-1, :2], self.points[1:, :2]
        d = b - a
        lengths = np.einsum("ij,ij->i", d, d)
        f = np.clip(
            np.einsum("ij,ij->i", np.array([x, y]) - a, d) / np.maximum(lengths, 1e-12), 0, 1
        )
        nearest = a + f[:, None] * d
        k = int(np.argmin(np.hypot(*(nearest - [x, y]).T)))
        return float(self.s[k] + f[k] * math.sqrt(lengths[k]))
