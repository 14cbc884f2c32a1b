"""The contacts of a world step: found among every population's objects, recorded, answered.

Ego against anything: a CollisionData record. NPC vehicle against NPC vehicle: a
VehicleCollision record. A collision that begins halts the agents in it that halt
(Population.halt: a struck NPC brakes to a standstill and stays, a struck pedestrian
stops). Every contact with a vehicle in it gets the response of world/contact.py, each
body with the inverse mass its population gives it (0: immovable), and each population
takes the share of its rows (Population.shove); pedestrians pass each other.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from egosim.world.arrays import IntArray
from egosim.world.collision import (
    ContactTracker,
    EgoCollision,
    Footprints,
    SweptPairs,
    VehicleCollision,
)
from egosim.world.contact import Bodies, ContactModel, Response, respond
from egosim.world.populations.base import Population, Shove
from egosim.world.traffic import ObjectState, ObjectTable, ObjectType


@dataclass(frozen=True)
class StepContacts:
    """What one step's contacts amount to."""

    ego_contacts: dict[int, list[ObjectState]]
    """What each ego (by unique id) touches now, as it is now: contacts that last."""
    vehicle_contacts: list[VehicleCollision]
    """The NPC-NPC contacts of now, time-stamped when they began."""
    ego_collisions: list[EgoCollision]
    """The ego collisions that began now."""
    vehicle_collisions: list[VehicleCollision]
    """The NPC-NPC collisions that began now."""


def joined_footprints(parts: Sequence[Footprints]) -> Footprints:
    """The footprints of `parts` (at least one) one after the other, in new arrays
    (np.concatenate copies: none shares memory with a population's own)."""
    filled = [part for part in parts if len(part.headings)] or parts[:1]
    return Footprints(
        np.concatenate([part.centres for part in filled]),
        np.concatenate([part.headings for part in filled]),
        np.concatenate([part.lengths for part in filled]),
        np.concatenate([part.widths for part in filled]),
    )


class ContactHandler:
    """Answers the contacts of each step; remembers which pairs touch (so a collision is
    recorded once, when it begins) and where every object stood after the last step (so
    the next step's sweep starts there)."""

    def __init__(self, table: ObjectTable) -> None:
        self._tracker = ContactTracker()
        self._sweep = SweptPairs()
        self._footprints = joined_footprints([Footprints.of(table)])

    def forget(self, table: ObjectTable) -> None:
        """Start again from the objects of `table`, with no contact remembered."""
        self._tracker.clear()
        self._footprints = joined_footprints([Footprints.of(table)])

    def step(
        self, populations: Sequence[Population], model: ContactModel, now: float
    ) -> StepContacts:
        """The contacts among the objects of `populations` (in that order, the order of
        the object table), swept from where they stood after the last step; time `now`."""
        parts = [population.footprints() for population in populations]
        bounds = list(itertools.accumulate((len(part.headings) for part in parts), initial=0))
        footprints = joined_footprints(parts)
        before = self._footprints if len(self._footprints.headings) == bounds[-1] else footprints
        self._footprints = footprints
        pairs = self._sweep.pairs(before, footprints)
        if len(pairs) == 0:
            self._tracker.begin([], now)
            return StepContacts({}, [], [], [])
        # The whole table only where something touches: most steps nothing does.
        table = ObjectTable.concatenate([population.table() for population in populations])
        kinds = table.object_types[pairs]
        vehicles = (kinds == ObjectType.EGO) | (kinds == ObjectType.NPC_VEHICLE)
        contacts, struck = self._record(table, pairs, kinds, now)
        _halt(populations, bounds, struck)
        inverse_masses = np.concatenate([population.inverse_masses() for population in populations])
        bodies = Bodies(footprints, table.velocities[:, :2], inverse_masses)
        response = respond(bodies, pairs[np.any(vehicles, axis=1)], model)
        if response.moved.any():
            _shove(populations, bounds, response, bodies)
            # Contacts move bodies, never turn them: the next sweep starts from here.
            self._footprints = replace(
                footprints, centres=footprints.centres + response.displacements
            )
        return contacts

    def _record(
        self, table: ObjectTable, pairs: IntArray, kinds: IntArray, now: float
    ) -> tuple[StepContacts, list[int]]:
        """The contacts with an ego and between NPC vehicles, and the rows of the non-egos
        whose collision began now."""
        ego_pair = np.any(kinds == ObjectType.EGO, axis=1)
        npc_pair = np.all(kinds == ObjectType.NPC_VEHICLE, axis=1)
        relevant = pairs[ego_pair | npc_pair]
        ids = table.unique_ids
        rows = {(int(ids[i]), int(ids[j])): (int(i), int(j)) for i, j in relevant}
        fresh = self._tracker.begin(list(rows), now)
        contacts = StepContacts({}, [], [], [])
        for pair, (i, j) in rows.items():
            records = (table.record(i), table.record(j))
            for me, other in (records, records[::-1]):
                if me.object_type == ObjectType.EGO:
                    contacts.ego_contacts.setdefault(me.unique_id, []).append(other)
            if not any(r.object_type == ObjectType.EGO for r in records):
                began = self._tracker.began_at.get(pair, now)
                contacts.vehicle_contacts.append(VehicleCollision(began, records))
        struck = []
        for pair in fresh:
            i, j = rows[pair]
            records = (table.record(i), table.record(j))
            if not any(r.object_type == ObjectType.EGO for r in records):
                contacts.vehicle_collisions.append(VehicleCollision(now, records))
            for row, (me, other) in zip((i, j), (records, records[::-1]), strict=True):
                if me.object_type == ObjectType.EGO:
                    contacts.ego_collisions.append(EgoCollision(now, me.unique_id, other))
                else:
                    struck.append(row)
        return contacts, struck


def _halt(populations: Sequence[Population], bounds: list[int], struck: list[int]) -> None:
    """Hand each population the rows of its own that were struck."""
    if not struck:
        return
    rows = np.array(struck, dtype=np.int64)
    owner = np.searchsorted(bounds, rows, side="right") - 1
    for k, population in enumerate(populations):
        mine = rows[owner == k] - bounds[k]
        if mine.size:
            population.halt(mine)


def _shove(
    populations: Sequence[Population], bounds: list[int], response: Response, bodies: Bodies
) -> None:
    """Hand each population the response of its moved rows."""
    change = response.velocities - bodies.velocities
    for population, start, stop in zip(populations, bounds[:-1], bounds[1:], strict=True):
        rows = np.flatnonzero(response.moved[start:stop])
        if rows.size:
            at = start + rows
            population.shove(
                Shove(rows, response.displacements[at], response.velocities[at], change[at])
            )
