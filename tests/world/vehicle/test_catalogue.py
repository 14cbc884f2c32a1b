from __future__ import annotations

import math

import pytest

from egosim.world.vehicle import (
    DEFAULT_EGO_MODEL,
    VEHICLE_CATALOGUE,
    UnknownVehicleModelError,
    vehicle_model,
)


def test_default_ego_is_the_published_kia_niro() -> None:
    niro = vehicle_model(DEFAULT_EGO_MODEL)
    assert DEFAULT_EGO_MODEL == "2016_Kia_Niro(HEV)"
    assert (niro.length, niro.width, niro.height) == (4.355, 1.805, 1.535)
    assert niro.wheelbase == 2.700
    assert niro.front_overhang == 0.870
    assert niro.rear_overhang == pytest.approx(0.785)


@pytest.mark.parametrize("model", VEHICLE_CATALOGUE.values(), ids=VEHICLE_CATALOGUE)
def test_every_model_is_geometrically_consistent(model) -> None:
    assert model.front_overhang + model.wheelbase + model.rear_overhang == pytest.approx(
        model.length
    )
    assert model.cg_to_front_axle + model.cg_to_rear_axle == pytest.approx(model.wheelbase)
    assert 0.0 < model.cg_to_front_axle < model.wheelbase
    assert model.track_width < model.width
    assert 0.0 < model.max_steer_front < math.pi / 2
    # Production vehicles understeer: b·Cr > a·Cf.
    assert (
        model.cg_to_rear_axle * model.cornering_stiffness_rear
        > model.cg_to_front_axle * model.cornering_stiffness_front
    )


def test_catalogue_has_cars_and_a_heavy_vehicle() -> None:
    for name in ("2015_Kia_K5", "2014_Kia_K7", "2016_Hyundai_Ioniq", "2017_Hyundai_Grandeur"):
        assert name in VEHICLE_CATALOGUE
    assert any(model.mass > 10_000 for model in VEHICLE_CATALOGUE.values())


def test_unknown_model_names_the_known_ones() -> None:
    with pytest.raises(UnknownVehicleModelError) as raised:
        vehicle_model("1908_Ford_Model_T")
    message = str(raised.value)
    assert "1908_Ford_Model_T" in message
    assert all(name in message for name in VEHICLE_CATALOGUE)
    assert isinstance(raised.value, LookupError)
