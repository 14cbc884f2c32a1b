"""The contact response (world/contact.py's respond) as compiled loops: penetration along
the least-overlap axis, the push apart, and the sequential impulse sweeps."""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import BoolArray, FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.collision import _corners
from egosim.world.kernels.numpy_scalars import maximum, minimum


@kernel
def _penetration(
    centres: FloatArray,
    headings: FloatArray,
    lengths: FloatArray,
    widths: FloatArray,
    i: int,
    j: int,
) -> tuple[float, float, float]:
    """contact.penetration of bodies i and j: the unit normal (from i to j) and depth."""
    corners_a = _corners(centres[i, 0], centres[i, 1], headings[i], lengths[i], widths[i])
    corners_b = _corners(centres[j, 0], centres[j, 1], headings[j], lengths[j], widths[j])
    best_depth, best_x, best_y = np.inf, 0.0, 0.0
    for heading in (headings[i], headings[i] + math.pi / 2, headings[j], headings[j] + math.pi / 2):
        ax, ay = math.cos(heading), math.sin(heading)
        low_a, high_a, low_b, high_b = np.inf, -np.inf, np.inf, -np.inf
        for k in range(4):
            pa = corners_a[k, 0] * ax + corners_a[k, 1] * ay
            pb = corners_b[k, 0] * ax + corners_b[k, 1] * ay
            low_a, high_a = min(low_a, pa), max(high_a, pa)
            low_b, high_b = min(low_b, pb), max(high_b, pb)
        depth = minimum(high_a, high_b) - maximum(low_a, low_b)
        if depth < best_depth:
            best_depth, best_x, best_y = depth, ax, ay
    towards_b = (centres[j, 0] - centres[i, 0]) * best_x + (centres[j, 1] - centres[i, 1]) * best_y
    if towards_b < 0.0:
        return -best_x, -best_y, best_depth
    return best_x, best_y, best_depth


@kernel
def _batches(a: IntArray, b: IntArray, inverse: FloatArray) -> IntArray:
    """contact._batches: each contact's batch number (batches in order, contacts in order
    within each), no movable body twice in a batch."""
    count = a.shape[0]
    batch = np.full(count, -1, dtype=np.int64)
    used = np.full(inverse.shape[0], -1, dtype=np.int64)
    number, left = 0, count
    while left:
        for k in range(count):
            if batch[k] >= 0:
                continue
            ia, ib = a[k], b[k]
            if (inverse[ia] > 0.0 and used[ia] == number) or (
                inverse[ib] > 0.0 and used[ib] == number
            ):
                continue
            batch[k] = number
            left -= 1
            if inverse[ia] > 0.0:
                used[ia] = number
            if inverse[ib] > 0.0:
                used[ib] = number
        number += 1
    return batch


@kernel
def respond(
    centres: FloatArray,
    headings: FloatArray,
    lengths: FloatArray,
    widths: FloatArray,
    body_velocities: FloatArray,
    inverse: FloatArray,
    pairs: IntArray,
    coefficients: FloatArray,
    iterations: int,
) -> tuple[FloatArray, FloatArray, BoolArray]:
    """contact.respond: displacements, velocities and who moved. coefficients:
    restitution, friction, resting speed, slop."""
    restitution_of, friction, resting, slop = (
        coefficients[0], coefficients[1], coefficients[2], coefficients[3],
    )  # fmt: skip
    n = inverse.shape[0]
    velocities = body_velocities.copy()
    displacements = np.zeros((n, 2))
    count = 0
    a = np.empty(pairs.shape[0], dtype=np.int64)
    b = np.empty(pairs.shape[0], dtype=np.int64)
    total = np.empty(pairs.shape[0])
    normals = np.empty((pairs.shape[0], 2))
    depths = np.empty(pairs.shape[0])
    for k in range(pairs.shape[0]):
        i, j = pairs[k, 0], pairs[k, 1]
        both = inverse[i] + inverse[j]
        if not both > 0.0:
            continue
        nx, ny, depth = _penetration(centres, headings, lengths, widths, i, j)
        if not depth >= 0.0:
            continue
        a[count], b[count], total[count] = i, j, both
        normals[count, 0], normals[count, 1], depths[count] = nx, ny, depth
        count += 1
    moved = np.zeros(n, dtype=np.bool_)
    if count == 0:
        return displacements, velocities, moved
    a, b, total = a[:count], b[:count], total[:count]
    normals, depths = normals[:count], depths[:count]
    push = np.empty((count, 2))
    for k in range(count):
        amount = maximum(depths[k] - slop, 0.0)
        push[k, 0], push[k, 1] = amount * normals[k, 0], amount * normals[k, 1]
    for k in range(count):
        share = inverse[a[k]] / total[k]
        for d in range(2):
            displacements[a[k], d] += -push[k, d] * share
    for k in range(count):
        share = inverse[b[k]] / total[k]
        for d in range(2):
            displacements[b[k], d] += push[k, d] * share
    restitution = np.empty(count)
    for k in range(count):
        approach = (velocities[b[k], 0] - velocities[a[k], 0]) * normals[k, 0] + (
            velocities[b[k], 1] - velocities[a[k], 1]
        ) * normals[k, 1]
        restitution[k] = restitution_of if -approach > resting else 0.0
    batch_of = _batches(a, b, inverse)
    batches = batch_of.max() + 1
    impulse = np.empty((count, 2))
    for sweep in range(iterations):
        hit = False
        for number in range(batches):
            hitting_any = False
            for k in range(count):
                if batch_of[k] != number:
                    continue
                rx = velocities[b[k], 0] - velocities[a[k], 0]
                ry = velocities[b[k], 1] - velocities[a[k], 1]
                nx, ny = normals[k, 0], normals[k, 1]
                closing = rx * nx + ry * ny
                hitting = closing < 0.0
                hitting_any = hitting_any or hitting
                bounce = restitution[k] if sweep == 0 else 0.0
                normal_impulse = -(1.0 + bounce) * closing / total[k] if hitting else 0.0
                sx, sy = rx - closing * nx, ry - closing * ny
                slide_speed = math.hypot(sx, sy)
                spread = maximum(slide_speed, 1e-12)
                friction_impulse = minimum(slide_speed / total[k], friction * normal_impulse)
                impulse[k, 0] = normal_impulse * nx - friction_impulse * (sx / spread)
                impulse[k, 1] = normal_impulse * ny - friction_impulse * (sy / spread)
            if not hitting_any:
                continue
            hit = True
            for k in range(count):
                if batch_of[k] == number:
                    for d in range(2):
                        velocities[a[k], d] += -impulse[k, d] * inverse[a[k]]
            for k in range(count):
                if batch_of[k] == number:
                    for d in range(2):
                        velocities[b[k], d] += impulse[k, d] * inverse[b[k]]
        if not hit:
            break
    for i in range(n):
        moved[i] = (
            displacements[i, 0] != 0.0
            or displacements[i, 1] != 0.0
            or velocities[i, 0] != body_velocities[i, 0]
            or velocities[i, 1] != body_velocities[i, 1]
        )
    return displacements, velocities, moved
