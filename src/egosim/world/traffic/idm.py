"""The Intelligent Driver Model (Treiber, Hennecke, Helbing 2000), vectorised."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import FloatArray


@dataclass(frozen=True)
class IntelligentDriverModel:
    """Car-following acceleration from own speed, desired speed, gap and approach rate.

    a = a_max [1 - (v / v0)^delta - (s* / s)^2],  s* = s0 + max(0, v T + v dv / (2 sqrt(a_max b)))
    with s the bumper-to-bumper gap and dv = v - v_leader. In equilibrium behind a leader
    at speed v the gap is (s0 + v T) / sqrt(1 - (v / v0)^delta); on a free road the speed
    tends to v0.
    """

    time_headway_s: float = 1.5
    min_gap_m: float = 2.0
    max_accel_mps2: float = 1.5
    comfortable_decel_mps2: float = 2.0
    delta: float = 4.0
    max_decel_mps2: float = 9.0
    """Emergency braking limit the result is clamped to (about a dry road's grip), m/s²."""

    def desired_gap(self, v: FloatArray, dv: FloatArray) -> FloatArray:
        """s*, m."""
        brake_term = v * dv / (2.0 * np.sqrt(self.max_accel_mps2 * self.comfortable_decel_mps2))
        gap: FloatArray = self.min_gap_m + np.maximum(0.0, v * self.time_headway_s + brake_term)
        return gap

    def acceleration(
        self, v: FloatArray, v0: FloatArray, gap: FloatArray, dv: FloatArray
    ) -> FloatArray:
        """m/s² for speeds v, v0 (m/s), gaps (m; inf for a free road) and dv (m/s)."""
        free = 1.0 - self.speed_term(v / v0)
        # A free road's infinite gap divides to exactly 0: no interaction.
        interaction = (self.desired_gap(v, dv) / np.maximum(gap, 1e-3)) ** 2
        accel = self.max_accel_mps2 * (free - interaction)
        return np.clip(accel, -self.max_decel_mps2, self.max_accel_mps2)

    def speed_term(self, ratio: FloatArray) -> FloatArray:
        """ratio ** delta; for an integer delta a product left to right, as the compiled
        step computes it (kernels/npc_motion.py: numpy's float power may differ from it
        in the last bit on some CPUs)."""
        if not self.integer_delta():
            power: FloatArray = ratio**self.delta
            return power
        result = np.ones_like(ratio)
        for k in range(int(self.delta)):
            result = ratio if k == 0 else result * ratio
        return result

    def integer_delta(self) -> bool:
        """delta is a whole number >= 0 (the compiled step handles only those)."""
        return float(self.delta).is_integer() and self.delta >= 0

    def equilibrium_gap(self, v: float, v0: float) -> float:
        """Gap (m) at which a = 0 behind a leader at the same speed v < v0."""
        return float(
            (self.min_gap_m + v * self.time_headway_s) / np.sqrt(1.0 - (v / v0) ** self.delta)
        )

    def can_stop_within(self, v: FloatArray, distance: FloatArray) -> npt.NDArray[np.bool_]:
        """True where v (m/s) can be brought to rest within distance (m) at comfortable decel."""
        return v * v <= 2.0 * self.comfortable_decel_mps2 * distance
