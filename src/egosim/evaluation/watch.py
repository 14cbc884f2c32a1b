"""InfractionWatch: the infractions of one ego, found step by step as they begin."""

from __future__ import annotations

from egosim.evaluation.infractions import Infraction, InfractionKind
from egosim.evaluation.rules import (
    BlockedWatch,
    ExcursionWatch,
    Sample,
    StopLineWatch,
    in_own_lane,
    lane_departure_m,
    off_road_m,
    wrong_way,
)
from egosim.world import World
from egosim.world.traffic import ObjectType

DEFAULT_BLOCKED_AFTER_S = 60.0

_COLLISION_KIND = {
    int(ObjectType.PEDESTRIAN): InfractionKind.COLLISION_PEDESTRIAN,
    int(ObjectType.NPC_VEHICLE): InfractionKind.COLLISION_VEHICLE,
    int(ObjectType.EGO): InfractionKind.COLLISION_VEHICLE,
    int(ObjectType.OBSTACLE): InfractionKind.COLLISION_STATIC,
}


def ego_sample(world: World, index: int = 0) -> Sample:
    """What the rules look at of ego `index` now."""
    status = world.ego_status(index)
    lane = world.ego_lane_state(index)
    pose = status.pose
    width = lane.distance_left + lane.distance_right
    # The lane it drives along is the projection the world keeps; another one is
    # looked for only when the ego is outside that lane.
    inside = in_own_lane(lane.lateral_offset, width)
    return Sample(
        time_s=world.sim_time,
        x=pose.x,
        y=pose.y,
        yaw=pose.yaw,
        speed_mps=status.speed,
        lane_id=lane.lane_id,
        s=lane.s,
        lateral_m=lane.lateral_offset,
        lane_width_m=width,
        body_width_m=world.egos[index].vehicle.model.width,
        nearest=None if inside else world.map.project(pose.x, pose.y),
    )


class InfractionWatch:
    """Call observe(world, ego_sample(world, ego_index)) after every world step: the
    infractions of ego `ego_index` that began in it (collisions from the world's log,
    stop lines, lane and road excursions, wrong-way driving, standing blocked).
    `records()` has them all, an excursion's magnitude grown to the largest it reached."""

    def __init__(
        self,
        world: World,
        ego_index: int = 0,
        *,
        blocked_after_s: float = DEFAULT_BLOCKED_AFTER_S,
        lane_departure_margin_m: float = 0.0,
    ) -> None:
        self.ego_index = ego_index
        self._map = world.map
        self._margin_m = lane_departure_margin_m
        self._stop_lines = StopLineWatch(world.map)
        self._lane = ExcursionWatch(InfractionKind.LANE_DEPARTURE)
        self._road = ExcursionWatch(InfractionKind.OFF_ROAD)
        self._wrong_way = ExcursionWatch(InfractionKind.WRONG_WAY)
        self._blocked = BlockedWatch(blocked_after_s)
        self._events: list[Infraction] = []
        self._collisions_seen = len(world.ego_collision_log)
        self._wrong_way_since: float | None = None
        self._speed_before = world.ego_status(ego_index).speed
        """The ego's speed at the sample before: a collision's impact speed."""

    @property
    def blocked(self) -> bool:
        """The ego has stood still longer than allowed."""
        return self._blocked.record is not None

    def observe(self, world: World, sample: Sample) -> list[Infraction]:
        """The infractions that began with `sample`, the ego's sample after this step."""
        before = self._count()
        self._collisions(world)
        self._speed_before = sample.speed_mps
        signals = world.signals
        self._events.extend(self._stop_lines.observe(sample, lambda i: signals.light(i).aspect))
        departure = lane_departure_m(sample, self._margin_m)
        self._lane.observe(sample, departure, f"over the edge of lane {sample.lane_id}")
        self._road.observe(sample, off_road_m(sample), "off every lane")
        self._observe_wrong_way(sample)
        if (event := self._blocked.observe(sample)) is not None:
            self._events.append(event)
        return self._since(before)

    def records(self) -> list[Infraction]:
        """Every infraction so far (not sorted)."""
        return [*self._events, *self._lane.records, *self._road.records, *self._wrong_way.records]

    def _count(self) -> tuple[int, int, int, int]:
        return (
            len(self._events),
            len(self._lane.records),
            len(self._road.records),
            len(self._wrong_way.records),
        )

    def _since(self, counts: tuple[int, int, int, int]) -> list[Infraction]:
        lists = (self._events, self._lane.records, self._road.records, self._wrong_way.records)
        return [
            record for found, seen in zip(lists, counts, strict=True) for record in found[seen:]
        ]

    def _collisions(self, world: World) -> None:
        log = world.ego_collision_log
        if len(log) < self._collisions_seen:  # the log was cleared by a scenario load
            self._collisions_seen = 0
        ego_id = world.egos[self.ego_index].unique_id
        for record in log[self._collisions_seen :]:
            if record.ego_id != ego_id:
                continue
            other = record.other
            kind = _COLLISION_KIND.get(int(other.object_type), InfractionKind.COLLISION_STATIC)
            detail = f"with {other.name} (id {other.unique_id})"
            x, y = other.position[0], other.position[1]
            self._events.append(Infraction(kind, record.time_s, x, y, detail, self._speed_before))
        self._collisions_seen = len(log)

    def _observe_wrong_way(self, sample: Sample) -> None:
        if not wrong_way(sample, self._map):
            self._wrong_way_since = None
            self._wrong_way.observe(sample, None)
            return
        if self._wrong_way_since is None:
            self._wrong_way_since = sample.time_s
        lasted = sample.time_s - self._wrong_way_since
        against = sample.nearest.lane_id if sample.nearest is not None else sample.lane_id
        self._wrong_way.observe(sample, lasted, f"against lane {against}")
