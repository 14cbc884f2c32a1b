"""Sizes of the pedestrian and obstacle models (vehicles use the vehicle catalogue)."""

from __future__ import annotations

from dataclasses import dataclass

from egosim.world.vehicle.catalogue import VEHICLE_CATALOGUE


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

MORAI_OBSTACLE_DATA_IDS: dict[int, str] = {
    40100001: "Box",
    40100002: "Box",
    40100003: "Box",
    40100004: "Drum",
    40100005: "Cone",
    40100007: "Cone",
    40100008: "2017_Hyundai_Grandeur",
    40100011: "2016_Hyundai_Ioniq",
    40100013: "2019_Hyundai_Sonata",
    40100018: "2015_Kia_K5",
    40100020: "2016_Kia_Niro(HEV)",
    40100027: "Drum",
    40100033: "Barrier",
    40100047: "Barrier",
    40100049: "Barrier",
    40100092: "Box",
    40200086: "Cone",
}
"""MORAI SIM's obstacle `DataID`s (scenario files' `objectList`) -> an obstacle model, or a
vehicle catalogue model for a parked-car object (it stands as an obstacle of that car's
size). docs/vehicle.md says where each comes from."""


def obstacle_for_data_id(data_id: int) -> BoxModel | None:
    """The obstacle MORAI's object `data_id` stands for; a parked car is an immovable box
    of its model's size, named after the model. None for an id the table does not hold."""
    name = MORAI_OBSTACLE_DATA_IDS.get(data_id)
    if name is None:
        return None
    if name in OBSTACLE_MODELS:
        return OBSTACLE_MODELS[name]
    car = VEHICLE_CATALOGUE[name]
    return BoxModel(car.name, car.length, car.width, car.height)
