"""What `egosim run` tells the user once it is ready: what runs, and what to try next."""

from __future__ import annotations

from ..bridge import ClockMode
from ..bridge.protocol.units import heading_deg
from ..world import World
from ..world.traffic import ObjectType
from .options import RunOptions

CLOCK_TEXT = {
    ClockMode.REAL: "real time",
    ClockMode.SIM: "sim time (/clock)",
    ClockMode.SYNC: "sync (the client steps the world)",
}

TRY_NEXT = {
    ClockMode.REAL: "PYTHONPATH=DIR rostopic echo -n 1 /Ego_topic",
    ClockMode.SIM: "PYTHONPATH=DIR rostopic echo -n 1 /Ego_topic",
    ClockMode.SYNC: "PYTHONPATH=DIR rosservice call /SyncModeCmd "
    "'{request: {user_id: me, start_sync_mode: true}}'",
}


def plural(count: int, noun: str) -> str:
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"


def scenario_text(options: RunOptions, world: World) -> str:
    if options.scenario is not None:
        return str(options.scenario)
    return "the town's default" if world.map.name == "town" else "none"


def ready_summary(world: World, options: RunOptions) -> str:
    """A few lines beside `egosim: ready`: map, scenario, the ego, the traffic, the clock."""
    ego = world.ego_status().pose
    heading = heading_deg(ego.yaw)
    lane = world.ego_lane_state().lane_id
    scripted = world.scripted
    npcs = len(world.npcs) + len(scripted.table(ObjectType.NPC_VEHICLE))
    walkers = len(world.pedestrians) + len(scripted.table(ObjectType.PEDESTRIAN))
    things = len(world.obstacles) + len(scripted.table(ObjectType.OBSTACLE))
    rate = f" at {options.rtf:g}x" if options.clock is ClockMode.SIM and options.rtf else ""
    if options.clock is ClockMode.SIM and not options.rtf:
        rate = " as fast as possible"
    return "\n".join(
        [
            f"egosim: map {world.map.name}, scenario {scenario_text(options, world)}, "
            f"clock {CLOCK_TEXT[options.clock]}{rate}",
            f"egosim: ego at x={ego.x:.1f} y={ego.y:.1f} m, heading {heading:.1f} deg, "
            f"lane {lane or '-'}; {plural(npcs, 'NPC')}, "
            f"{plural(walkers, 'pedestrian')}, "
            f"{plural(things, 'obstacle')}, "
            f"{plural(len(world.signals.light_ids), 'traffic light')}",
            "egosim: try `egosim msgs --export-python DIR` (messages for rospy), then "
            f"`{TRY_NEXT[options.clock]}`",
        ]
    )
