"""Sizes of the pedestrian and obstacle models (vehicles use the vehicle catalogue)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class BoxModel:
    """A named object of fixed size: length (along its heading), width, height, m."""

    name: str
    length: float
    width: float
    height: float
    mass_kg: float | None = None
    """An obstacle a vehicle can push aside has a mass; None: immovable."""


PEDESTRIAN_MODELS: dict[str, BoxModel] = {
    m.name: m
    for m in (
        BoxModel("Pedestrian_Adult_Male", 0.35, 0.55, 1.75),
        BoxModel("Pedestrian_Adult_Female", 0.33, 0.50, 1.62),
        BoxModel("Pedestrian_Child", 0.25, 0.40, 1.20),
    )
}
DEFAULT_PEDESTRIAN_MODEL = "Pedestrian_Adult_Male"

OBSTACLE_MODELS: dict[str, BoxModel] = {
    m.name: m
    for m in (
        # A traffic cone, an empty plastic drum and a cardboard box get pushed along; a
        # (concrete or water-filled) barrier does not give.
        BoxModel("Cone", 0.40, 0.40, 0.70, mass_kg=4.0),
        BoxModel("Barrier", 0.50, 2.00, 1.00),
        BoxModel("Drum", 0.60, 0.60, 0.90, mass_kg=15.0),
        BoxModel("Box", 1.00, 1.00, 1.00, mass_kg=10.0),
    )
}
DEFAULT_OBSTACLE_MODEL = "Cone"
