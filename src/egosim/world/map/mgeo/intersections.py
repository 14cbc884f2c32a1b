"""MGeo intersection controllers and synced light sets -> intersections and approach groups.

Each synced traffic-light set (lights that always show the same aspect) is one approach
group; an intersection controller cycles over its synced sets. Intersection ids are the
trailing numbers of the controllers' idx ("IntTL12" -> 12) when those are unique, else
1, 2, ... in file order. A synced set without a known controller, and a light in no synced
set, each make an intersection of their own (numbered after the controllers, reported).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from egosim.world.map.lanes import IntersectionSite, TrafficLightSite
from egosim.world.map.mgeo.lights import LightHead
from egosim.world.map.mgeo.records import Record, unique_by_idx

_TRAILING_NUMBER = re.compile(r"(\d+)$")


@dataclass
class _Draft:
    center: tuple[float, float] | None
    groups: list[tuple[str, ...]] = field(default_factory=list)


def build_intersections(
    heads: list[LightHead],
    synced_items: list[Record],
    controller_items: list[Record],
    notes: list[str],
) -> tuple[list[TrafficLightSite], list[IntersectionSite]]:
    by_idx = {head.idx: head for head in heads}
    controllers = unique_by_idx(controller_items)
    synced = unique_by_idx(synced_items)
    # Keys name the record an intersection comes from: (file kind, idx).
    drafts: dict[tuple[str, str], _Draft] = {}
    members: dict[tuple[str, str], list[str]] = {}
    for idx, controller in controllers.items():
        center = None
        if controller.data.get("point") is not None:
            x, y, _ = controller.point("point")
            center = (float(x), float(y))
        drafts["controller", idx] = _Draft(center)
        members["controller", idx] = list(controller.ids("synced_signal_id_list"))
    for idx, record in synced.items():
        owner = ("controller", record.text("intersection_controller_id") or "")
        if owner in members and idx not in members[owner]:
            members[owner].append(idx)
    owned = {s for listed in members.values() for s in listed}
    for idx in synced:
        if idx not in owned:
            notes.append(f"synced_traffic_light_set.json: {idx}: no intersection controller")
            drafts["synced", idx], members["synced", idx] = _Draft(None), [idx]
    grouped: dict[str, str] = {}
    for owner, synced_ids in members.items():
        for synced_id in synced_ids:
            if synced_id not in synced:
                notes.append(
                    f"intersection_controller_set.json: {owner[1]}: synced set {synced_id} unknown"
                )
                continue
            group = _group(synced[synced_id], by_idx, grouped, notes)
            if group:
                drafts[owner].groups.append(group)
    for head in heads:
        if head.idx not in grouped:
            notes.append(f"traffic_light_set.json: {head.idx}: in no synced set, runs alone")
            drafts["light", head.idx] = _Draft(None, [(head.idx,)])
    return _sites(drafts, by_idx, list(controllers))


def _group(
    record: Record, heads: dict[str, LightHead], grouped: dict[str, str], notes: list[str]
) -> tuple[str, ...]:
    group = []
    for light_id in record.ids("signal_id_list"):
        if light_id not in heads:
            notes.append(f"synced_traffic_light_set.json: {record.idx}: light {light_id} skipped")
            continue
        if light_id in grouped:
            raise record.fail(f"light {light_id} is already in synced set {grouped[light_id]}")
        grouped[light_id] = record.idx
        group.append(light_id)
    return tuple(group)


def _sites(
    drafts: dict[tuple[str, str], _Draft],
    heads: dict[str, LightHead],
    controller_ids: list[str],
) -> tuple[list[TrafficLightSite], list[IntersectionSite]]:
    numbers = _numbers(controller_ids)
    next_number = max(numbers.values(), default=0) + 1
    lights: list[TrafficLightSite] = []
    intersections: list[IntersectionSite] = []
    for key, draft in drafts.items():
        if not draft.groups:
            continue
        if key not in numbers:
            numbers[key], next_number = next_number, next_number + 1
        light_ids = tuple(i for group in draft.groups for i in group)
        center = draft.center
        if center is None:
            mean = np.mean([heads[i].position[:2] for i in light_ids], axis=0)
            center = (float(mean[0]), float(mean[1]))
        intersections.append(IntersectionSite(numbers[key], center, light_ids, tuple(draft.groups)))
        lights.extend(
            TrafficLightSite(
                id=i,
                position=heads[i].position,
                heading=heads[i].heading,
                light_type=heads[i].light_type,
                lane_ids=heads[i].lane_ids,
                intersection_id=numbers[key],
            )
            for i in light_ids
        )
    return lights, intersections


def _numbers(controller_ids: list[str]) -> dict[tuple[str, str], int]:
    """Controller key -> intersection id: trailing numbers when unique, else 1, 2, ..."""
    keys = [("controller", idx) for idx in controller_ids]
    found = [_TRAILING_NUMBER.search(idx) for idx in controller_ids]
    numbers = [int(m.group(1)) for m in found if m]
    if len(numbers) == len(keys) and len(set(numbers)) == len(numbers):
        return dict(zip(keys, numbers, strict=True))
    return {key: k for k, key in enumerate(keys, start=1)}
