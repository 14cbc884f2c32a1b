"""Odd numbers through the compiled kernels: NaN, infinities, huge and tiny values,
negative sizes. Each kernel's caller returns what the numpy path returns (bit for bit,
NaN where it has NaN), never crashes, and never hands back an index outside its arrays.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import numpy as np
import pytest

from egosim.world import kernels
from egosim.world.collision import Footprints, SweptPairs, touching_pairs
from egosim.world.contact import Bodies, respond
from egosim.world.kernels.sorting import resort, search_sorted_near
from egosim.world.map import ProjectionMemory, build_builtin_map
from egosim.world.vehicle import (
    DEFAULT_EGO_MODEL,
    ControlCommand,
    LongitudinalMode,
    Pose,
    RoadSurface,
    Vehicle,
    ego_model,
    ego_vehicle,
)

pytestmark = [
    pytest.mark.skipif(
        not kernels.AVAILABLE, reason="no compiled path: numba missing or EGOSIM_COMPILED=0"
    ),
    # numpy warns of the invalid values and overflows these cases are made of.
    pytest.mark.filterwarnings("ignore::RuntimeWarning"),
]

Result = TypeVar("Result")

TOWN = build_builtin_map("town")
CASES = 40
ODD = np.array([np.nan, np.inf, -np.inf, 1e308, -1e308, 1e-310, -0.0, 0.0, 1e16, -1e16])


def odd_values(rng: np.random.Generator, shape: tuple[int, ...], scale: float) -> np.ndarray:
    """Ordinary values of about `scale`, a third of them swapped for odd ones."""
    values = rng.normal(0.0, scale, shape)
    swap = rng.random(shape) < 0.33
    values[swap] = rng.choice(ODD, int(swap.sum()))
    return values


def both_paths(run: Callable[[], Result], monkeypatch: pytest.MonkeyPatch) -> tuple[Result, Result]:
    """`run`'s result on the compiled path, then on the numpy path."""
    monkeypatch.setattr(kernels, "ACTIVE", True)
    compiled = run()
    monkeypatch.setattr(kernels, "ACTIVE", False)
    plain = run()
    monkeypatch.setattr(kernels, "ACTIVE", True)
    return compiled, plain


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("seed", range(CASES))
def test_swept_collisions_of_odd_boxes_agree_and_stay_in_range(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(0, 40))

    def boxes() -> Footprints:
        return Footprints(
            odd_values(rng, (n, 2), 5.0),
            odd_values(rng, (n,), 3.0),
            odd_values(rng, (n,), 4.0),
            odd_values(rng, (n,), 2.0),
        )

    before, after = boxes(), boxes()
    compiled, plain = both_paths(lambda: touching_pairs(before, after), monkeypatch)
    assert same_bits(compiled, plain), f"seed {seed}: {compiled} against {plain}"
    assert np.all((compiled >= 0) & (compiled < n)), f"seed {seed}: a pair outside the boxes"
    assert np.all(compiled[:, 0] < compiled[:, 1])


@pytest.mark.parametrize("seed", range(CASES // 4))
def test_sweeps_step_after_step_agree_with_sweeps_from_scratch(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The compiled sweep that starts from the last one's extents and order (boxes that
    move a little, some turning or resized, some odd) finds the pairs of a fresh one."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 40))
    centres = rng.normal(0.0, 8.0, (n, 2))
    headings = rng.normal(0.0, 3.0, n)
    sizes = np.abs(rng.normal(3.0, 1.0, (n, 2)))
    sweep = SweptPairs()
    monkeypatch.setattr(kernels, "ACTIVE", True)
    before = Footprints(centres, headings, sizes[:, 0], sizes[:, 1])
    for _ in range(12):
        centres = centres + rng.normal(0.0, 0.3, (n, 2))
        turning = rng.random(n) < 0.3
        headings = np.where(turning, headings + rng.normal(0.0, 0.2, n), headings)
        odd = rng.random(n) < 0.05
        headings[odd] = rng.choice(ODD, int(odd.sum()))
        after = Footprints(centres.copy(), headings.copy(), sizes[:, 0].copy(), sizes[:, 1].copy())
        found = sweep.pairs(before, after)
        fresh = both_paths(lambda b=before, a=after: touching_pairs(b, a), monkeypatch)
        assert same_bits(found, fresh[0]) and same_bits(found, fresh[1])
        before = after


@pytest.mark.parametrize("seed", range(CASES // 4))
def test_a_resort_from_any_earlier_order_is_the_stable_sort(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(0, 60))
    keys = np.round(odd_values(rng, (n,), 3.0))  # rounded: ties, zeros of both signs
    for earlier in (rng.permutation(n), np.argsort(keys + rng.normal(0.0, 0.1, n)), np.arange(n)):
        assert same_bits(resort(keys, earlier.astype(np.int64)), np.argsort(keys, kind="stable"))


@pytest.mark.parametrize("seed", range(CASES // 4))
def test_a_search_from_any_guess_is_the_search(seed: int) -> None:
    rng = np.random.default_rng(seed)
    values = np.sort(np.round(odd_values(rng, (int(rng.integers(0, 30)),), 5.0)))
    for value in [*np.round(odd_values(rng, (10,), 5.0)), *values[:3]]:
        for right in (False, True):
            answer = int(np.searchsorted(values, value, side="right" if right else "left"))
            for guess in range(-2, len(values) + 3):
                assert search_sorted_near(values, float(value), right, guess) == answer


FINITE_ODD = np.array([1e16, -1e16, 1e-310, -1e-310, -0.0, 0.0])
"""Extreme values whose contact arithmetic stays finite."""


def odd_bodies(rng: np.random.Generator, odd: np.ndarray) -> tuple[Bodies, np.ndarray]:
    """A few bodies with some `odd` values among their places, sizes and velocities, and
    pairs of them."""
    n = int(rng.integers(2, 12))

    def values(shape: tuple[int, ...], scale: float) -> np.ndarray:
        figures = rng.normal(0.0, scale, shape)
        swap = rng.random(shape) < 0.33
        figures[swap] = rng.choice(odd, int(swap.sum()))
        return figures

    bodies = Bodies(
        Footprints(
            values((n, 2), 2.0),
            values((n,), 3.0),
            np.abs(values((n,), 4.0)),
            np.abs(values((n,), 2.0)),
        ),
        values((n, 2), 10.0),
        # What a population gives: 1/kg of a body up to 10^6 kg, or 0 (immovable).
        np.where(rng.random(n) < 0.2, 0.0, rng.uniform(1e-6, 1e-2, n)),
    )
    first = rng.integers(0, n - 1, 2 * n)
    return bodies, np.unique(np.column_stack((first, rng.integers(first + 1, n))), axis=0)


@pytest.mark.parametrize("seed", range(CASES))
def test_contact_response_to_extreme_bodies_agrees(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    bodies, pairs = odd_bodies(np.random.default_rng(seed), FINITE_ODD)
    compiled, plain = both_paths(lambda: respond(bodies, pairs), monkeypatch)
    for field in ("displacements", "velocities", "moved"):
        a, b = getattr(compiled, field), getattr(plain, field)
        assert same_bits(a, b), f"seed {seed}, {field}: {a} against {b}"


@pytest.mark.parametrize("seed", range(CASES))
def test_contact_response_to_bodies_beyond_numbers_moves_only_bodies_in_contact(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """NaN, infinite or overflowing figures: the response has a row per body and moves
    none but those of the pairs, on either path (the two paths' numbers then differ)."""
    bodies, pairs = odd_bodies(np.random.default_rng(seed), ODD)
    n = len(bodies.inverse_masses)
    for response in both_paths(lambda: respond(bodies, pairs), monkeypatch):
        assert response.displacements.shape == response.velocities.shape == (n, 2)
        assert not response.moved[np.setdiff1d(np.arange(n), pairs)].any()


@pytest.mark.parametrize("seed", range(CASES))
def test_lane_projection_of_odd_points_agrees(seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 30))
    xy = odd_values(rng, (n, 2), 150.0)
    hints = odd_values(rng, (n,), 3.0)
    compiled, plain = both_paths(lambda p=xy, h=hints: TOWN.project_many(p, h), monkeypatch)
    for field in ("lane_index", "s", "lateral", "heading", "distance_left", "distance_right"):
        a, b = getattr(compiled, field), getattr(plain, field)
        assert same_bits(a, b), f"seed {seed}, {field}: {a} against {b}"
    lanes = compiled.lane_index
    assert np.all((lanes >= 0) & (lanes < len(TOWN.lane_ids)))


@pytest.mark.parametrize("seed", range(CASES // 4))
def test_lane_projection_that_remembers_its_last_points_agrees(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Points projected again and again with a memory (some standing still, some moving,
    the list growing and shrinking, odd ones among them) land where a fresh projection
    puts them."""
    rng = np.random.default_rng(seed)
    memory = ProjectionMemory()
    xy = rng.normal(0.0, 150.0, (int(rng.integers(1, 30)), 2))
    hints = odd_values(rng, (len(xy),), 3.0)
    for _ in range(10):
        moving = rng.random(len(xy)) < 0.5
        xy = xy + np.where(moving[:, None], rng.normal(0.0, 1.0, xy.shape), 0.0)
        odd = rng.random(xy.shape) < 0.03
        xy[odd] = rng.choice(ODD, int(odd.sum()))
        if rng.random() < 0.3:
            count = int(rng.integers(1, 40))
            xy = np.resize(xy, (count, 2))
            hints = np.resize(hints, count)
        monkeypatch.setattr(kernels, "ACTIVE", True)
        remembered = TOWN.project_many(xy, hints, memory)
        compiled, plain = both_paths(lambda p=xy, h=hints: TOWN.project_many(p, h), monkeypatch)
        for field in ("lane_index", "s", "lateral", "heading", "distance_left", "width"):
            a, b, c = (getattr(p, field) for p in (remembered, compiled, plain))
            assert same_bits(a, b) and same_bits(a, c), f"seed {seed}, {field}"


@pytest.mark.parametrize("seed", range(CASES // 4))
def test_lane_poses_searched_from_hints_agree(seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 30))
    lanes = rng.integers(0, len(TOWN.lane_ids), n)
    stations = rng.uniform(0.0, 50.0, n)
    hints = np.zeros(n, np.int64)
    for _ in range(10):
        stations = stations + rng.uniform(0.0, 3.0, n)
        odd = rng.random(n) < 0.05
        stations[odd] = rng.choice(ODD, int(odd.sum()))
        changing = rng.random(n) < 0.1
        lanes = np.where(changing, rng.integers(0, len(TOWN.lane_ids), n), lanes)
        monkeypatch.setattr(kernels, "ACTIVE", True)
        hinted = TOWN.poses_at(lanes, stations, search_hints=hints)
        compiled, plain = both_paths(lambda k=lanes, s=stations: TOWN.poses_at(k, s), monkeypatch)
        assert same_bits(hinted, compiled) and same_bits(hinted, plain), f"seed {seed}"


@pytest.mark.parametrize("seed", range(CASES))
def test_lane_poses_at_odd_stations_agree(seed: int, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 30))
    lanes = rng.integers(0, len(TOWN.lane_ids), n)
    stations = odd_values(rng, (n,), 100.0)
    lateral = odd_values(rng, (n,), 2.0)
    for moved in (None, lateral):

        def poses(moved: np.ndarray | None = moved) -> np.ndarray:
            return TOWN.poses_at(lanes, stations, moved)

        compiled, plain = both_paths(poses, monkeypatch)
        assert same_bits(compiled, plain), f"seed {seed}: {compiled} against {plain}"


@pytest.mark.parametrize("seed", range(CASES // 4))
def test_ego_dynamics_under_odd_commands_and_road_agree(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(seed)
    modes = rng.choice([int(mode) for mode in LongitudinalMode], 30)
    commands = odd_values(rng, (30, 5), 1.0)
    surfaces = odd_values(rng, (30, 2), 0.1)
    # The world's road surface has the pitch of a grade's arctangent: never infinite.
    surfaces[:, 1] = np.arctan(surfaces[:, 1])

    def drive() -> list[str]:
        vehicle = ego_vehicle(ego_model(DEFAULT_EGO_MODEL), Pose(0.0, 0.0, 0.0), None)
        assert isinstance(vehicle, Vehicle)
        statuses = []
        for mode, (accel, brake, steer, velocity, acceleration), (z, pitch) in zip(
            modes, commands, surfaces, strict=True
        ):
            # A command the gate rejects (a NaN pedal, say) leaves the last one in force.
            vehicle.command(
                ControlCommand(
                    mode=int(mode),
                    accel=float(accel),
                    brake=float(brake),
                    front_steer=float(steer),
                    velocity=float(velocity),
                    acceleration=float(acceleration),
                )
            )
            vehicle.step(0.01, RoadSurface(z=float(z), pitch=float(pitch)))
            statuses.append(repr(vehicle.status()))
        return statuses

    compiled, plain = both_paths(drive, monkeypatch)
    assert compiled == plain
