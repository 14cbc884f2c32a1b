"""Gaussian measurement noise shared by the sensor models."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from egosim.sensors.errors import MissingRandomGeneratorError, SensorConfigError


def require_non_negative(name: str, values: Sequence[float]) -> None:
    if np.any(np.asarray(values) < 0.0):
        raise SensorConfigError(f"{name} must be >= 0, got {values}")


def gaussian(
    std: npt.NDArray[np.float64], rng: np.random.Generator | None, sensor: str
) -> npt.NDArray[np.float64]:
    """One zero-mean sample per entry of `std`; exact zeros when there is no noise.

    Draws nothing when every std is zero, so a noiseless sensor needs no
    generator and leaves the caller's generator untouched.
    """
    if not np.any(std):
        return np.zeros_like(std)
    if rng is None:
        raise MissingRandomGeneratorError(f"{sensor} has noise configured; pass a numpy Generator")
    return rng.normal(0.0, 1.0, size=std.shape) * std
