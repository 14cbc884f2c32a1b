"""Contact response between touching rectangles: resolve the penetration, exchange momentum.

Bodies are rigid boxes in the plane that translate (impulses act through their centres,
so a contact does not spin them). Each has a mass; an infinite mass (inverse mass 0) is
immovable: obstacles, parked cars, bodies whose motion a replay or a client dictates.

For a contact with unit normal n (from body a to body b) and relative velocity
v_rel = v_b - v_a, the normal impulse j (N s) is, while the bodies approach (v_rel·n < 0),

    j = -(1 + e) (v_rel·n) / (1/m_a + 1/m_b)

with restitution e, and the tangential impulse opposes the sliding velocity, bounded by
Coulomb friction |j_t| <= mu j. A 1-D collision of equal masses then gives the textbook
v_a' = v (1 - e) / 2, v_b' = v (1 + e) / 2, and every impulse conserves momentum. Below
RESTING_SPEED_MPS of approach the restitution is 0, so bodies pressed together (a car
driving against a wall) come to rest instead of chattering. The penetration left after
a step is removed by moving the bodies apart along n, shared in proportion to their
inverse masses, down to PENETRATION_SLOP_M.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from egosim.world import kernels
from egosim.world.arrays import BoolArray, FloatArray, IntArray
from egosim.world.collision import Footprints, corners
from egosim.world.kernels import contact as compiled

RESTITUTION = 0.2
"""Share of the approach speed a contact gives back (car bodies crumple: mostly plastic)."""
FRICTION = 0.5
"""Coulomb coefficient between two bodies sliding along each other (steel on steel, paint)."""
RESTING_SPEED_MPS = 0.5
"""Approach speed below which a contact is inelastic (bodies at rest against each other)."""
PENETRATION_SLOP_M = 0.005
"""Overlap left in place: bodies resting against each other stay in contact."""
ITERATIONS = 8
"""Sweeps over the contacts at most: a body in several contacts settles within a few."""


@dataclass(frozen=True)
class ContactModel:
    """The coefficients of the contact response."""

    restitution: float = RESTITUTION
    friction: float = FRICTION
    resting_speed_mps: float = RESTING_SPEED_MPS
    slop_m: float = PENETRATION_SLOP_M


@dataclass(frozen=True, eq=False)
class Bodies:
    """N bodies: their footprints, map-frame velocities (N, 2) m/s and inverse masses
    (N,) 1/kg, 0 for an immovable body."""

    footprints: Footprints
    velocities: FloatArray
    inverse_masses: FloatArray


@dataclass(frozen=True, eq=False)
class Response:
    """What contacts do to the bodies: displacements (N, 2) m and velocities (N, 2) m/s
    after the contact, both in the map frame; `moved` marks the bodies either changed."""

    displacements: FloatArray
    velocities: FloatArray
    moved: BoolArray


def penetration(a: Footprints, b: Footprints) -> tuple[FloatArray, FloatArray]:
    """Pairwise contact normals (K, 2), unit, pointing from a to b, and depths (K,) m: the
    overlap along the separating axis where it is smallest (negative when apart)."""
    corners_a, corners_b = corners(a), corners(b)
    best_depth = np.full(len(a.headings), np.inf)
    best_axis = np.zeros((len(a.headings), 2))
    for heading in (a.headings, a.headings + math.pi / 2, b.headings, b.headings + math.pi / 2):
        axis = np.stack((np.cos(heading), np.sin(heading)), axis=1)
        projection_a = np.einsum("kcd,kd->kc", corners_a, axis)
        projection_b = np.einsum("kcd,kd->kc", corners_b, axis)
        depth = np.minimum(projection_a.max(axis=1), projection_b.max(axis=1)) - np.maximum(
            projection_a.min(axis=1), projection_b.min(axis=1)
        )
        better = depth < best_depth
        best_depth = np.where(better, depth, best_depth)
        best_axis[better] = axis[better]
    towards_b = np.einsum("kd,kd->k", b.centres - a.centres, best_axis)
    normals = np.where((towards_b < 0.0)[:, None], -best_axis, best_axis)
    return normals, best_depth


def respond(bodies: Bodies, pairs: IntArray, model: ContactModel | None = None) -> Response:
    """The response to the contacts between `pairs` (K, 2) of bodies, each pair touching
    now; pairs of two immovable bodies are left alone."""
    model = model or ContactModel()
    if kernels.ACTIVE:
        foot = bodies.footprints
        return Response(
            *compiled.respond(
                np.ascontiguousarray(foot.centres),
                np.ascontiguousarray(foot.headings),
                np.ascontiguousarray(foot.lengths),
                np.ascontiguousarray(foot.widths),
                np.ascontiguousarray(bodies.velocities),
                np.ascontiguousarray(bodies.inverse_masses, dtype=np.float64),
                np.ascontiguousarray(pairs, dtype=np.int64).reshape(-1, 2),
                np.array(
                    (model.restitution, model.friction, model.resting_speed_mps, model.slop_m)
                ),
                ITERATIONS,
            )
        )
    velocities = bodies.velocities.copy()
    displacements = np.zeros_like(velocities)
    inverse = bodies.inverse_masses
    a, b = pairs[:, 0], pairs[:, 1]
    total = inverse[a] + inverse[b]
    live = total > 0.0
    a, b, total = a[live], b[live], total[live]
    if a.size == 0:
        return Response(displacements, velocities, np.zeros(len(inverse), bool))
    foot = bodies.footprints
    normals, depths = penetration(_rows(foot, a), _rows(foot, b))
    touching = depths >= 0.0
    a, b, total, normals, depths = (
        a[touching],
        b[touching],
        total[touching],
        normals[touching],
        depths[touching],
    )
    share_a, share_b = inverse[a] / total, inverse[b] / total
    push = np.maximum(depths - model.slop_m, 0.0)[:, None] * normals
    np.add.at(displacements, a, -push * share_a[:, None])
    np.add.at(displacements, b, push * share_b[:, None])

    approach = np.einsum("kd,kd->k", velocities[b] - velocities[a], normals)
    restitution = np.where(-approach > model.resting_speed_mps, model.restitution, 0.0)
    batches = _batches(a, b, inverse)
    for sweep in range(ITERATIONS):
        hit = False
        for batch in batches:
            ia, ib, n = a[batch], b[batch], normals[batch]
            relative = velocities[ib] - velocities[ia]
            closing = np.einsum("kd,kd->k", relative, n)
            hitting = closing < 0.0
            if not hitting.any():
                continue
            hit = True
            # The restitution acts on a contact's first exchange only; later sweeps only
            # stop bodies that a neighbour's impulse sent back into a contact.
            bounce = restitution[batch] if sweep == 0 else 0.0
            normal_impulse = np.where(hitting, -(1.0 + bounce) * closing / total[batch], 0.0)
            sliding = relative - closing[:, None] * n
            slide_speed = np.hypot(sliding[:, 0], sliding[:, 1])
            tangent = sliding / np.maximum(slide_speed, 1e-12)[:, None]
            friction_impulse = np.minimum(
                slide_speed / total[batch], model.friction * normal_impulse
            )
            impulse = normal_impulse[:, None] * n - friction_impulse[:, None] * tangent
            np.add.at(velocities, ia, -impulse * inverse[ia][:, None])
            np.add.at(velocities, ib, impulse * inverse[ib][:, None])
        if not hit:
            break
    moved = np.any(displacements != 0.0, axis=1) | np.any(velocities != bodies.velocities, axis=1)
    return Response(displacements, velocities, moved)


def _batches(a: IntArray, b: IntArray, inverse: FloatArray) -> list[IntArray]:
    """Contacts split into batches in which no movable body appears twice, in order:
    impulses within a batch are independent, batch after batch they are sequential
    (Gauss-Seidel), so every exchange conserves momentum and gives back no more energy
    than the restitution allows."""
    remaining = list(range(len(a)))
    batches = []
    while remaining:
        used: set[int] = set()
        batch, rest = [], []
        for k in remaining:
            bodies = [int(i) for i in (a[k], b[k]) if inverse[i] > 0.0]
            if used.intersection(bodies):
                rest.append(k)
            else:
                batch.append(k)
                used.update(bodies)
        batches.append(np.array(batch, dtype=np.int64))
        remaining = rest
    return batches


def _rows(footprints: Footprints, index: IntArray) -> Footprints:
    return Footprints(
        footprints.centres[index],
        footprints.headings[index],
        footprints.lengths[index],
        footprints.widths[index],
    )
