"""What the bridge hands its publishers over a fixed drive, in every release: the busy
town of tests/compiled_paths.py with a second ego (reported by /Ego_topic for the second
half of the run), every row of the table but the sensors' readings (GPS, IMU, LiDAR,
radar, camera) and with the extended status rows on, each message serialised for every
release a subscriber may ask for.

`python -m tests.bridge.published_bytes` prints each (topic, release)'s digest as JSON
(tests/data/protocol/published_digests.json was recorded so, from the code before the
rows wrote their own bytes); the test compares the digests with it.
"""

from __future__ import annotations

import hashlib
import json
import socket
import struct
import sys
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from egosim.app.inbox import Inbox
from egosim.bridge import HANDLERS, Bridge, default_network_settings, simulation_context
from egosim.ros1 import Node
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.vehicle import Pose
from tests.compiled_paths import busy_town, drive

TICKS = 400
SECOND_EGO_FROM_TICK = TICKS // 2
"""From this tick on /Ego_topic (and the object lists) report the second ego."""
SENSOR_ROWS = frozenset({"gps", "imu", "lidar", "radar", "camera"})
EXTENDED_ROWS = frozenset({"ego_status_extended", "object_status_extended"})
RECORDED = Path(__file__).parents[1] / "data" / "protocol" / "published_digests.json"
_LENGTH = struct.Struct("<I")


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port: int = sock.getsockname()[1]
        return port


def published_digests(ticks: int = TICKS) -> dict[str, str]:
    """sha256 of every message (length-prefixed, in order) per "topic release"."""
    town = build_builtin_map("town")
    world = World(town, parse_scenario(busy_town(town), "busy town"))
    x, y, z, heading = town.pose_at("R5_E_1", 60.0)
    second = world.add_ego(world.egos[0].vehicle.model.name, Pose(x=x, y=y, z=z, yaw=heading))
    defaults = default_network_settings()
    settings = replace(
        defaults,
        rows=tuple(
            replace(row, enabled=row.enabled or row.key in EXTENDED_ROWS) for row in defaults.rows
        ),
    )
    digests: dict[str, hashlib._Hash] = {}
    with Node(
        "published_bytes", master_uri=f"http://127.0.0.1:{_free_port()}/", rosout_logger=None
    ) as node:
        bridge = Bridge(node, settings, HANDLERS, Inbox())
        context = simulation_context(world, settings=settings, bridge=bridge)
        bridge.open(context)
        bridge.taps.append(lambda *_: None)  # every row is built as if it had a subscriber
        bridge.outlets[:] = [o for o in bridge.outlets if o.row.key not in SENSOR_ROWS]
        for outlet in bridge.outlets:
            releases = [(r.profile_name, r.message_type.md5sum) for r in outlet.releases]
            recorder = _recorder(outlet.row.name, releases, digests)
            outlet.publisher.publish_many = recorder  # type: ignore[method-assign]
        for k in range(ticks):
            if k == SECOND_EGO_FROM_TICK:
                context.session.camera_index = world.egos.index(second)
            drive(world, k)
            context.tick(world.physics_step_s)
    return {key: digest.hexdigest() for key, digest in sorted(digests.items())}


def _recorder(
    topic: str, releases: Sequence[tuple[str, str]], digests: dict[str, hashlib._Hash]
) -> object:
    def publish_many(messages: Sequence[object]) -> None:
        for message in messages:
            for release, md5sum in releases:
                data = message if isinstance(message, bytes) else message(md5sum)  # type: ignore[operator]
                digest = digests.setdefault(f"{topic} {release}", hashlib.sha256())
                digest.update(_LENGTH.pack(len(data)))
                digest.update(data)

    return publish_many


if __name__ == "__main__":
    json.dump(published_digests(), sys.stdout, indent=1)
    print()
