"""The ego is the scenario's car: its bounding box, axles and performance make the
vehicle egosim drives, so contact happens where the scenario's car's front is."""

from __future__ import annotations

import math

import pytest
from tests.world.openscenario.stories import (
    DT,
    init_speed,
    lane,
    scenario,
    start_world,
    step,
    teleport,
    vehicle,
)

from egosim.scenario_files import openscenario_scenario
from egosim.world.openscenario import read_openscenario
from egosim.world.openscenario.ego_model import UnusableFiguresError, scenario_ego_model
from egosim.world.openscenario.entities import EntityDefinition, EntityKind, VehicleFigures
from egosim.world.vehicle import ControlCommand, LongitudinalMode
from egosim.world.vehicle.catalogue import DEFAULT_EGO_MODEL, vehicle_model

# A car of Euro NCAP's catalogue size: 4.358 m long, its box centre 1.349 m ahead of
# the rear axle, so its front is 1.349 + 2.179 = 3.528 m ahead of the reference point.
GOLF = """<ScenarioObject name="Ego"><Vehicle name="golf" vehicleCategory="car" mass="1480">
  <BoundingBox><Center x="1.349" y="0" z="0.788"/>
    <Dimensions width="1.815" length="4.358" height="1.577"/></BoundingBox>
  <Performance maxSpeed="50" maxAcceleration="3" maxDeceleration="6"/>
  <Axles><FrontAxle maxSteering="0.55" wheelDiameter="0.64" trackWidth="1.54" positionX="2.685"
    positionZ="0.32"/>
    <RearAxle maxSteering="0" wheelDiameter="0.64" trackWidth="1.52" positionX="0"
      positionZ="0.32"/></Axles>
</Vehicle></ScenarioObject>"""
FRONT_M = 1.349 + 4.358 / 2.0


def golf_world(drives_ego: bool, speed: float = 10.0, target_s: float = 80.0):  # type: ignore[no-untyped-def]
    text = scenario(
        GOLF + vehicle("Target", length=4.0, centre_x=1.5),
        teleport("Ego", lane(40)) + init_speed("Ego", speed) + teleport("Target", lane(target_s)),
    )
    return start_world(text, drives_ego)


def test_the_ego_takes_the_scenario_cars_size_axles_and_performance() -> None:
    world, _ = golf_world(False)
    model = world.egos[0].vehicle.model
    assert (model.length, model.width, model.height) == (4.358, 1.815, 1.577)
    assert model.wheelbase == pytest.approx(2.685)
    assert model.box_centre_ahead_of_reference == pytest.approx(1.349)
    assert model.front_overhang == pytest.approx(4.358 - 2.685 - (2.179 - 1.349))
    assert (model.track_width, model.wheel_radius, model.max_steer_front) == (1.54, 0.32, 0.55)
    assert (model.mass, model.max_speed, model.max_brake_decel) == (1480, 50, 6)
    assert model.max_drive_force == pytest.approx(1480 * 3)


def test_an_ego_without_axles_keeps_its_own_wheelbase_in_the_scenarios_box() -> None:
    world, _ = golf_world(False)
    no_axles = """<ScenarioObject name="Ego"><Vehicle name="box" vehicleCategory="car">
      <BoundingBox><Center x="1.3" y="0" z="0.7"/><Dimensions width="1.9" length="4.6"
        height="1.4"/></BoundingBox></Vehicle></ScenarioObject>"""
    text = scenario(no_axles, teleport("Ego", lane(40)))
    world.load_scenario(openscenario_scenario(read_openscenario(text, "t.xosc")))
    model = world.egos[0].vehicle.model
    own = vehicle_model(DEFAULT_EGO_MODEL)
    assert (model.length, model.width, model.box_centre_ahead_of_reference) == (4.6, 1.9, 1.3)
    # From egosim's own model (not from the last scenario's car).
    assert (model.wheelbase, model.mass, model.max_brake_decel) == (
        own.wheelbase,
        own.mass,
        own.max_brake_decel,
    )


def test_the_ego_touches_a_standing_target_when_the_scenario_cars_front_reaches_it() -> None:
    # Ego reference at s = 40 doing 10 m/s; the target's box (centre 1.5 m ahead of its
    # reference, 4 m long) spans s = 79.5..83.5.
    world, run = golf_world(True)
    gap = (80.0 - 0.5) - (40.0 + FRONT_M)
    contact_at = gap / 10.0
    for _ in range(round((contact_at + 0.5) / DT)):
        run.step(DT, True)
        world.step(DT)
        if world.ego_collision_log:
            break
    assert world.ego_collision_log, "no contact"
    # The contact is seen within the step it happens in.
    assert world.ego_collision_log[0].time_s == pytest.approx(contact_at, abs=DT + 1e-9)


def test_scripted_entities_are_listed_and_touched_with_the_scenarios_box() -> None:
    world, _ = golf_world(True)
    objects = world.objects()
    (row,) = [k for k, name in enumerate(objects.names) if name == "Target_model"]
    # 4 m long, 2 m wide, 1.4 m high; its centre 1.5 m ahead of its reference at s = 80.
    assert tuple(objects.sizes[row]) == pytest.approx((4.0, 2.0, 1.4))
    assert tuple(objects.positions[row][:2]) == pytest.approx((81.5, -1.75))
    ego = world.egos[0].vehicle.model
    assert (ego.length, ego.width) == (4.358, 1.815)


def test_full_brake_decelerates_at_the_scenarios_max_deceleration() -> None:
    world, run = golf_world(False, speed=20.0, target_s=400.0)
    ego = world.egos[0].vehicle
    step(world, run, 0.1, drives_ego=False)
    ego.command(ControlCommand(mode=LongitudinalMode.PEDALS, brake=1.0))
    step(world, run, 0.5, drives_ego=False)
    v0 = ego.status().velocity[0]
    step(world, run, 1.0, drives_ego=False)
    # Rolling resistance and drag add a little (< 0.3 m/s² at 20 m/s for a car).
    assert v0 - ego.status().velocity[0] == pytest.approx(6.0, abs=0.3)


def test_figures_that_make_no_car_are_refused() -> None:
    base = vehicle_model(DEFAULT_EGO_MODEL)
    box = EntityDefinition("Ego", EntityKind.VEHICLE, "tiny", "car", 2.0, 1.5, 1.4, (1.0, 0, 0.7))
    too_long = VehicleFigures(3.5, 0.0, 0.6, 1.4, 0.5)
    with pytest.raises(UnusableFiguresError, match="do not fit"):
        scenario_ego_model(EntityDefinition(**{**box.__dict__, "figures": too_long}), base)
    with pytest.raises(UnusableFiguresError, match="bounding box"):
        scenario_ego_model(EntityDefinition(**{**box.__dict__, "length": math.nan}), base)
