"""What a camera's label images mean: semantic classes, their colours, instance colours.

Semantic image: every pixel has the colour of its class (SEMANTIC_COLORS; Cityscapes'
palette where Cityscapes has the class). Instance image: a pixel of an object (vehicle,
pedestrian, obstacle) carries the object's `unique_id` as R + 256 G + 65536 B; anything
else is black (0 is no object's id).
"""

from __future__ import annotations

from enum import IntEnum

import numpy as np
import numpy.typing as npt


class SemanticClass(IntEnum):
    SKY = 0
    ROAD = 1
    LANE_MARKING = 2
    STOP_LINE = 3
    CROSSWALK = 4
    SIDEWALK = 5
    TERRAIN = 6
    VEHICLE = 7
    PEDESTRIAN = 8
    OBSTACLE = 9
    TRAFFIC_LIGHT = 10
    POLE = 11


SEMANTIC_COLORS: dict[SemanticClass, tuple[int, int, int]] = {
    SemanticClass.SKY: (70, 130, 180),
    SemanticClass.ROAD: (128, 64, 128),
    SemanticClass.LANE_MARKING: (157, 234, 50),
    SemanticClass.STOP_LINE: (255, 255, 0),
    SemanticClass.CROSSWALK: (0, 255, 255),
    SemanticClass.SIDEWALK: (244, 35, 232),
    SemanticClass.TERRAIN: (152, 251, 152),
    SemanticClass.VEHICLE: (0, 0, 142),
    SemanticClass.PEDESTRIAN: (220, 20, 60),
    SemanticClass.OBSTACLE: (190, 153, 153),
    SemanticClass.TRAFFIC_LIGHT: (250, 170, 30),
    SemanticClass.POLE: (153, 153, 153),
}

SEMANTIC_PALETTE = np.array([SEMANTIC_COLORS[c] for c in sorted(SEMANTIC_COLORS)], dtype=np.uint8)
"""(classes, 3): row k is the colour of SemanticClass(k)."""

MAX_INSTANCE_ID = 2**24 - 1


def instance_colors(unique_ids: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """(N, 3) colours of ids 0..2^24-1 (higher ids wrap)."""
    ids = np.asarray(unique_ids, dtype=np.int64) & MAX_INSTANCE_ID
    return np.stack([ids & 0xFF, (ids >> 8) & 0xFF, (ids >> 16) & 0xFF], axis=-1).astype(np.uint8)


def decode_instances(image: npt.NDArray[np.uint8]) -> npt.NDArray[np.int64]:
    """The unique_id of every pixel of an instance image (H, W, 3) -> (H, W)."""
    channels = image.astype(np.int64)
    ids: npt.NDArray[np.int64] = (
        channels[..., 0] + (channels[..., 1] << 8) + (channels[..., 2] << 16)
    )
    return ids


def decode_semantic(image: npt.NDArray[np.uint8]) -> npt.NDArray[np.int64]:
    """The SemanticClass of every pixel of a semantic image (H, W, 3); -1 where none."""
    key = decode_instances(image)
    palette_key = decode_instances(SEMANTIC_PALETTE[None, :, :])[0]
    result = np.full(key.shape, -1, dtype=np.int64)
    for label, colour_key in enumerate(palette_key):
        result[key == colour_key] = label
    return result
