"""Solid contacts: closed-form impulses, conserved momentum, no interpenetration, and
what they do in the World (a barrier stops the ego, a heavier NPC pushes it)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.world.traffic.scenes import EGO_OUT_OF_THE_WAY, run, world_from

from egosim.world.collision import Footprints
from egosim.world.contact import (
    PENETRATION_SLOP_M,
    RESTITUTION,
    Bodies,
    ContactModel,
    penetration,
    respond,
)
from egosim.world.vehicle import ControlCommand, LongitudinalMode

CAR_LENGTH_M, CAR_WIDTH_M = 4.5, 1.8


def _cars(centres: list[tuple[float, float]], headings: list[float] | None = None) -> Footprints:
    n = len(centres)
    return Footprints(
        np.array(centres, dtype=np.float64),
        np.zeros(n) if headings is None else np.array(headings, dtype=np.float64),
        np.full(n, CAR_LENGTH_M),
        np.full(n, CAR_WIDTH_M),
    )


def _bodies(centres, velocities, masses, headings=None) -> Bodies:
    inverse = np.array([0.0 if math.isinf(m) else 1.0 / m for m in masses])
    return Bodies(_cars(centres, headings), np.array(velocities, dtype=np.float64), inverse)


@pytest.mark.parametrize("e", [0.0, 0.2, 0.5, 1.0])
def test_equal_masses_in_one_dimension_give_the_textbook_velocities(e: float) -> None:
    v = 10.0
    bodies = _bodies([(0.0, 0.0), (4.4, 0.0)], [(v, 0.0), (0.0, 0.0)], [1500.0, 1500.0])
    response = respond(bodies, np.array([[0, 1]]), ContactModel(restitution=e))
    assert response.velocities[:, 0] == pytest.approx([v * (1 - e) / 2, v * (1 + e) / 2])
    assert response.velocities[:, 1] == pytest.approx([0.0, 0.0])


def test_unequal_masses_in_one_dimension_give_the_textbook_velocities() -> None:
    m1, m2, u1, u2, e = 1500.0, 13000.0, 3.0, -8.0, RESTITUTION
    bodies = _bodies([(0.0, 0.0), (4.4, 0.0)], [(u1, 0.0), (u2, 0.0)], [m1, m2])
    response = respond(bodies, np.array([[0, 1]]))
    v1 = (m1 * u1 + m2 * u2 + m2 * e * (u2 - u1)) / (m1 + m2)
    v2 = (m1 * u1 + m2 * u2 + m1 * e * (u1 - u2)) / (m1 + m2)
    assert response.velocities[:, 0] == pytest.approx([v1, v2])


def test_momentum_is_conserved_and_energy_never_grows() -> None:
    rng = np.random.default_rng(7)
    # A pile-up: eight cars in a row, 0.2 m into each other, random velocities, masses
    # and headings up to 20 deg off the row.
    n = 8
    centres = [(4.3 * k, 0.0) for k in range(n)]
    velocities = rng.normal(0.0, 8.0, (n, 2))
    masses = rng.uniform(900.0, 15000.0, n)
    headings = list(rng.uniform(-0.35, 0.35, n))
    bodies = _bodies(centres, velocities, masses, headings)
    pairs = np.array([[k, k + 1] for k in range(n - 1)])
    response = respond(bodies, pairs)
    before = masses @ velocities
    after = masses @ response.velocities
    assert after == pytest.approx(before, abs=1e-6 * np.abs(before).max())
    energy = lambda v: float(np.sum(masses * np.sum(v * v, axis=1)) / 2)  # noqa: E731
    assert energy(response.velocities) <= energy(velocities) * (1 + 1e-12)


def test_an_immovable_body_reflects_the_approach_speed_times_the_restitution() -> None:
    bodies = _bodies([(0.0, 0.0), (4.3, 0.0)], [(10.0, 0.0), (0.0, 0.0)], [1500.0, math.inf])
    response = respond(bodies, np.array([[0, 1]]))
    assert response.velocities[0] == pytest.approx([-RESTITUTION * 10.0, 0.0])
    assert response.velocities[1] == pytest.approx([0.0, 0.0])
    assert response.moved.tolist() == [True, False]


def test_friction_bounds_the_sliding_impulse() -> None:
    # A glancing blow: sliding 10 m/s along the contact, approaching at 0.4 m/s.
    bodies = _bodies([(0.0, 0.0), (0.0, 1.7)], [(10.0, 0.4), (0.0, 0.0)], [1500.0, math.inf])
    model = ContactModel(friction=0.5)
    response = respond(bodies, np.array([[0, 1]]), model)
    # The normal impulse stops the approach (0.4 m/s is a resting contact: e = 0);
    # friction takes at most mu times that impulse off the sliding speed.
    assert response.velocities[0, 1] == pytest.approx(0.0)
    assert response.velocities[0, 0] == pytest.approx(10.0 - 0.5 * 0.4)


def test_penetration_is_removed_in_proportion_to_inverse_mass() -> None:
    bodies = _bodies([(0.0, 0.0), (4.0, 0.0)], [(0.0, 0.0), (0.0, 0.0)], [1000.0, 3000.0])
    normals, depths = penetration(_cars([(0.0, 0.0)]), _cars([(4.0, 0.0)]))
    assert normals.tolist() == [[1.0, 0.0]]
    assert depths == pytest.approx([0.5])
    response = respond(bodies, np.array([[0, 1]]))
    push = 0.5 - PENETRATION_SLOP_M
    assert response.displacements[:, 0] == pytest.approx([-0.75 * push, 0.25 * push])
    moved = Footprints(
        bodies.footprints.centres + response.displacements,
        bodies.footprints.headings,
        bodies.footprints.lengths,
        bodies.footprints.widths,
    )
    _, left = penetration(_cars([tuple(moved.centres[0])]), _cars([tuple(moved.centres[1])]))
    assert left == pytest.approx([PENETRATION_SLOP_M])


def test_two_immovable_bodies_are_left_alone() -> None:
    bodies = _bodies([(0.0, 0.0), (1.0, 0.0)], [(5.0, 0.0), (0.0, 0.0)], [math.inf, math.inf])
    response = respond(bodies, np.array([[0, 1]]))
    assert not response.moved.any()
    assert response.velocities.tolist() == bodies.velocities.tolist()


# -- in the World ---------------------------------------------------------------------

BARRIER_X = 60.0
BARRIER_HALF_DEPTH_M = 0.25  # a Barrier facing along the lane: 0.5 m deep, 2 m across


def _ego_before_a_barrier(speed_mps: float) -> dict:
    return {
        "map": "straight",
        "ego": {"start": {"lane": "R1_E_1", "s": 20.0}, "speed_mps": speed_mps},
        "obstacles": [{"model": "Barrier", "pose": {"x": BARRIER_X, "y": -1.75, "heading_deg": 0}}],
    }


def _front_overlap(world) -> float:
    """How far the ego's front bumper is into the barrier's face, m (negative: short of it)."""
    table = world.objects()
    ego = int(np.flatnonzero(table.unique_ids == world.egos[0].unique_id)[0])
    front = table.positions[ego, 0] + table.sizes[ego, 0] / 2.0
    return float(front - (BARRIER_X - BARRIER_HALF_DEPTH_M))


@pytest.mark.parametrize("kmh", [20.0, 50.0])
def test_a_head_on_into_a_barrier_ends_at_rest_in_front_of_it(kmh: float) -> None:
    v = kmh / 3.6
    world = world_from(_ego_before_a_barrier(v))
    ego = world.egos[0].vehicle
    ego.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=v))
    deepest, bounced = -math.inf, None
    for _ in range(round(20.0 / world.physics_step_s)):
        world.step()
        deepest = max(deepest, _front_overlap(world))
        if world.ego_collision_log and bounced is None:
            bounced = world.ego_status().velocity[0]
            # The driver brakes after the impact.
            ego.command(ControlCommand(brake=1.0))
    assert len(world.ego_collision_log) == 1
    assert bounced == pytest.approx(-RESTITUTION * v, rel=0.05)
    assert world.ego_status().speed == pytest.approx(0.0, abs=1e-6)
    # No penetration beyond the contact slop, and the ego ends in front of the barrier.
    assert deepest <= PENETRATION_SLOP_M + 1e-9
    assert -2.0 < _front_overlap(world) <= PENETRATION_SLOP_M


def test_the_ego_driven_against_a_wall_stops_there_and_the_contact_lasts() -> None:
    world = world_from(_ego_before_a_barrier(0.0))
    world.egos[0].vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=5.0))
    run(world, 30.0)
    assert world.ego_status().speed < 0.1
    assert 0.0 <= _front_overlap(world) <= PENETRATION_SLOP_M + 1e-9
    barrier = int(world.obstacles.table().unique_ids[0])
    ego_id = world.egos[0].unique_id
    assert [o.unique_id for o in world.ego_contacts[ego_id]] == [barrier]
    # Pressing on: the contact lasts, no new collision is recorded.
    count = len(world.ego_collision_log)
    run(world, 2.0)
    assert [o.unique_id for o in world.ego_contacts[ego_id]] == [barrier]
    assert len(world.ego_collision_log) == count


def test_a_heavier_npc_pushes_the_stopped_ego_and_then_brakes_to_a_stop() -> None:
    # The bus drives in lane 2 but 3.5 m to its left, i.e. down lane 1 where the ego
    # stands braked; it does not see the ego and runs into it.
    world = world_from(
        {
            "map": "straight",
            "ego": {"start": {"lane": "R1_E_1", "s": 100.0}},
            "npcs": [
                {
                    "model": "2019_Hyundai_Universe",
                    "start": {"lane": "R1_E_2", "s": 40.0, "lateral": 3.5},
                    "speed_mps": 10.0,
                    "target_speed_mps": 10.0,
                }
            ],
        }
    )
    start_x = world.ego_status().pose.x
    bus, ego = 13000.0, world.egos[0].vehicle.model.mass
    speeds = []
    for _ in range(round(20.0 / world.physics_step_s)):
        world.step()
        if world.ego_collision_log and not speeds:
            speeds = [world.ego_status().velocity[0], float(world.npcs.speed[0])]
    # Just after the impact: the momentum exchange of a 1-D collision, e = RESTITUTION.
    u = 10.0
    assert speeds[0] == pytest.approx(bus * (1 + RESTITUTION) * u / (bus + ego), rel=0.05)
    assert speeds[1] == pytest.approx((bus - RESTITUTION * ego) * u / (bus + ego), rel=0.05)
    assert world.npcs.crashed[0]
    assert world.npcs.speed[0] == 0.0
    assert world.ego_status().speed == pytest.approx(0.0, abs=1e-6)
    assert world.ego_status().pose.x - start_x > 2.0


def test_npcs_never_interpenetrate_in_a_crash() -> None:
    world = world_from(
        {
            "map": "straight",
            "ego": EGO_OUT_OF_THE_WAY,
            "npcs": [
                {"start": {"lane": "R1_E_1", "s": 200.0}, "speed_mps": 2.0},
                {"start": {"lane": "R1_E_2", "s": 100.0, "lateral": 3.5}, "speed_mps": 15.0},
            ],
        }
    )
    deepest = -math.inf
    for _ in range(round(20.0 / world.physics_step_s)):
        world.step()
        table = world.npcs.table()
        boxes = Footprints(
            table.positions[:, :2], table.headings, table.sizes[:, 0], table.sizes[:, 1]
        )
        _, depth = penetration(
            Footprints(boxes.centres[:1], boxes.headings[:1], boxes.lengths[:1], boxes.widths[:1]),
            Footprints(boxes.centres[1:], boxes.headings[1:], boxes.lengths[1:], boxes.widths[1:]),
        )
        deepest = max(deepest, float(depth[0]))
    assert len(world.vehicle_collisions) == 1
    assert deepest <= PENETRATION_SLOP_M + 1e-9
    assert world.npcs.crashed.all()
    assert np.all(world.npcs.speed == 0.0)


def test_the_ego_pushes_a_cone_along_and_the_contact_lasts() -> None:
    world = world_from(
        {
            "map": "straight",
            "ego": {"start": {"lane": "R1_E_1", "s": 20.0}, "speed_mps": 5.0},
            "obstacles": [{"model": "Cone", "pose": {"x": 40.0, "y": -1.75, "heading_deg": 0}}],
        }
    )
    world.egos[0].vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=5.0))
    run(world, 8.0)
    cone = world.obstacles.table()
    assert cone.positions[0, 0] > 45.0  # pushed along ahead of the ego
    assert _front_overlap_with(world, cone.positions[0, 0] - 0.2) <= PENETRATION_SLOP_M + 1e-9
    assert len(world.ego_collision_log) == 1
    assert world.ego_status().speed == pytest.approx(5.0, abs=0.3)


def _front_overlap_with(world, face_x: float) -> float:
    table = world.objects()
    ego = int(np.flatnonzero(table.unique_ids == world.egos[0].unique_id)[0])
    return float(table.positions[ego, 0] + table.sizes[ego, 0] / 2.0 - face_x)
