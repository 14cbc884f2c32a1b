"""OpenCV's HSV scale (H 0-180, S and V 0-255), computed independently of the renderer,
and the bands lane and light detectors written for MORAI commonly use."""

from __future__ import annotations

import colorsys

import numpy as np

WHITE_LOW, WHITE_HIGH = (0, 0, 185), (30, 60, 255)
YELLOW_LOW, YELLOW_HIGH = (15, 80, 120), (35, 255, 255)


def hsv(rgb: np.ndarray) -> tuple[float, float, float]:
    h, s, v = colorsys.rgb_to_hsv(*(float(c) / 255.0 for c in rgb))
    return h * 180.0, s * 255.0, v * 255.0


def in_band(rgb: np.ndarray, low: tuple[int, ...], high: tuple[int, ...]) -> bool:
    return all(lo <= c <= hi for c, lo, hi in zip(hsv(rgb), low, high, strict=True))


def is_red(rgb: np.ndarray) -> bool:
    h, s, v = hsv(rgb)
    return (h <= 10 or h >= 170) and s >= 150 and v >= 150
