"""What a camera sees that moves: each frame's triangles over a map's static scene.

A frame adds to the static scene (egosim.sensors.camera_scene) the objects (vehicles as
a body and a cabin, pedestrians and obstacles as boxes, each of its real size) and the
lamps of every head, lit in the colour of its aspect; with the view's clip matrix, only
those that may show in it.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera import boxes_in_view
from egosim.sensors.camera_labels import SemanticClass
from egosim.sensors.camera_mesh import Mesh, MeshBuilder, add_boxes
from egosim.sensors.camera_scene import LampGeometry, StaticScene
from egosim.world.arrays import BoolArray, FloatArray
from egosim.world.signals.aspects import GREEN, GREEN_LEFT, OFF, RED, YELLOW
from egosim.world.traffic.objects import ObjectTable, ObjectType

LAMP_OFF = (45, 45, 45)
LAMP_ON = {RED: (255, 30, 20), YELLOW: (255, 190, 0), GREEN: (0, 220, 90), GREEN_LEFT: (0, 220, 90)}
PEDESTRIAN = (190, 110, 80)
OBSTACLE = (230, 120, 30)
VEHICLE_PAINTS = ((200, 30, 30), (40, 70, 160), (220, 220, 215), (30, 30, 30), (120, 125, 130))
# Vehicles: a body of the full footprint this share of the height, a narrower cabin above.
BODY_SHARE = 0.55
CABIN_LENGTH_SHARE = 0.55
CABIN_WIDTH_SHARE = 0.9


def build_frame_mesh(
    scene: StaticScene,
    objects: ObjectTable,
    aspects: npt.ArrayLike,
    hidden_ids: Iterable[int] = (),
    clip_from_scene: FloatArray | None = None,
) -> Mesh:
    """The moving part of a frame: every object but `hidden_ids`, and the lamps; with a
    view's `clip_from_scene`, only the objects and lights that may show in it."""
    builder = MeshBuilder(scene.origin)
    keep = ~np.isin(objects.unique_ids, np.fromiter(hidden_ids, dtype=np.int64))
    shown_lights = np.ones(len(scene.lights), dtype=bool)
    if clip_from_scene is not None:
        # Upright boxes on their footprint centre, yaw-free: the circle round the footprint.
        feet = objects.positions - scene.origin
        reach = np.hypot(objects.sizes[:, 0], objects.sizes[:, 1]) / 2.0
        lower = feet - np.column_stack((reach, reach, np.zeros_like(reach)))
        upper = feet + np.column_stack((reach, reach, objects.sizes[:, 2]))
        keep &= boxes_in_view(lower, upper, clip_from_scene)
        lamps = scene.lamps
        shown_lights = boxes_in_view(
            lamps.lower - scene.origin, lamps.upper - scene.origin, clip_from_scene
        )
    types = objects.object_types[keep]
    ids = objects.unique_ids[keep]
    positions = objects.positions[keep]
    sizes = objects.sizes[keep]
    yaws = objects.headings[keep]
    vehicle = (types == ObjectType.NPC_VEHICLE) | (types == ObjectType.EGO)
    _add_vehicles(builder, positions[vehicle], sizes[vehicle], yaws[vehicle], ids[vehicle])
    for kind, label, colour in (
        (ObjectType.PEDESTRIAN, SemanticClass.PEDESTRIAN, PEDESTRIAN),
        (ObjectType.OBSTACLE, SemanticClass.OBSTACLE, OBSTACLE),
    ):
        rows = types == kind
        centres = positions[rows] + np.column_stack(
            (np.zeros((rows.sum(), 2)), sizes[rows, 2] / 2.0)
        )
        add_boxes(builder, centres, sizes[rows], yaws[rows], colour, label, ids[rows])
    _add_lamps(builder, scene.lamps, aspects, shown_lights)
    return builder.mesh()


def _add_vehicles(
    builder: MeshBuilder,
    feet: FloatArray,
    sizes: FloatArray,
    yaws: FloatArray,
    ids: npt.NDArray[np.int64],
) -> None:
    if len(feet) == 0:
        return
    paints = np.array(VEHICLE_PAINTS, dtype=np.float64)[ids % len(VEHICLE_PAINTS)]
    body = sizes * np.array([1.0, 1.0, BODY_SHARE])
    body_centres = feet + np.column_stack((np.zeros((len(feet), 2)), body[:, 2] / 2.0))
    add_boxes(builder, body_centres, body, yaws, paints, SemanticClass.VEHICLE, ids)
    cabin = sizes * np.array([CABIN_LENGTH_SHARE, CABIN_WIDTH_SHARE, 1.0 - BODY_SHARE])
    cabin_centres = feet + np.column_stack(
        (np.zeros((len(feet), 2)), body[:, 2] + cabin[:, 2] / 2.0)
    )
    glass = paints * 0.45
    add_boxes(builder, cabin_centres, cabin, yaws, glass, SemanticClass.VEHICLE, ids)


def _add_lamps(
    builder: MeshBuilder, lamps: LampGeometry, aspects: npt.ArrayLike, shown: BoolArray
) -> None:
    """The lamps of the lights `shown` (a mask over the scene's lights)."""
    rows = shown[lamps.light_index]
    if not rows.any():
        return
    bits = lamps.lamp_bit[rows]
    aspect = np.asarray(aspects, dtype=np.int64)[lamps.light_index[rows]]
    lit = (aspect != OFF) & ((aspect & bits) != 0)
    colors = np.empty((len(lit), 3))
    colors[:] = LAMP_OFF
    for bit, colour in LAMP_ON.items():
        colors[lit & (bits == bit)] = colour
    builder.add(lamps.triangles[rows], colors, SemanticClass.TRAFFIC_LIGHT)
