"""Header stamps while a client holds time: the world's time, exact to the nanosecond,
from the stamp synchronous mode started at; after a stop the run's clock goes on from
the last stamp and never back. And 2021.08's SyncModeCmd, which has no time_step, ticks
MORAI's fixed 20 ms."""

from __future__ import annotations

import itertools
from typing import Any

from egosim.bridge import BridgeContext, ClockMode, simulation_context
from egosim.bridge.protocol.releases import canonical, convert
from egosim.bridge.sync.sync_mode import serve_sync_mode_cmd, serve_wait_for_tick
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map

STEP_S = 0.01  # the real-time loop's physics step
WALL_START_S = 1_712_345_678.123_456


class WallClock:
    """time.time as the test sets it."""

    def __init__(self, now: float) -> None:
        self.now = now

    def __call__(self) -> float:
        return self.now


def real_time_context(wall: WallClock) -> BridgeContext:
    return simulation_context(
        World(build_builtin_map("straight")), clock_mode=ClockMode.REAL, wall_clock=wall
    )


def stamp_ns(header: Any) -> int:
    return header.stamp.sec * 1_000_000_000 + header.stamp.nanosec


def sync_mode_cmd(context: BridgeContext, start: bool, time_step: int = 20) -> Any:
    profile = context.profile
    command = profile.message("morai_msgs/SyncModeCmd").new(
        user_id="planner", start_sync_mode=start, time_step=time_step
    )
    request = profile.service("morai_msgs/MoraiSyncModeCmdSrv").request.new(request=command)
    return serve_sync_mode_cmd(context, context.row("sync_mode_cmd"), request).response


def wait_for_tick(context: BridgeContext, frame: int) -> Any:
    profile = context.profile
    tick = profile.message("morai_msgs/WaitForTick").new(user_id="planner", frame=frame)
    request = profile.service("morai_msgs/MoraiWaitForTickSrv").request.new(request=tick)
    return serve_wait_for_tick(context, context.row("sync_mode_wait_for_tick"), request).response


def real_time_ticks(context: BridgeContext, wall: WallClock, count: int) -> list[tuple[int, int]]:
    """The loop's ticks, the wall clock 10.3 ms on each time (a busy machine):
    (wall time, header stamp) of each, ns."""
    ticks = []
    for _ in range(count):
        wall.now += 0.0103
        context.tick(STEP_S)
        ticks.append((round(wall.now * 1e9), stamp_ns(context.header())))
    return ticks


def test_sync_ticks_of_a_real_time_run_are_stamped_exactly_their_step_apart() -> None:
    wall = WallClock(WALL_START_S)
    context = real_time_context(wall)
    wall_ns, before = real_time_ticks(context, wall, 3)[-1]
    assert before == wall_ns  # real time: the wall clock

    frame = sync_mode_cmd(context, start=True).frame
    stamps = []
    for k, jitter_s in enumerate((0.0093, 0.0035, 0.0029, 0.0027, 0.05), start=1):
        wall.now += jitter_s  # the wall clock runs as it likes between the calls
        reply = wait_for_tick(context, frame + k)
        assert (reply.tick_status, reply.frame) == (True, frame + k)
        stamps.append(stamp_ns(reply.vehicle_status.header))
    assert [b - a for a, b in itertools.pairwise([before, *stamps])] == [20_000_000] * 5
    assert stamps[-1] == stamp_ns(context.header())  # every header of the tick


def test_after_a_stop_real_time_goes_on_from_the_last_sync_stamp() -> None:
    wall = WallClock(WALL_START_S)
    context = real_time_context(wall)
    real_time_ticks(context, wall, 2)
    frame = sync_mode_cmd(context, start=True).frame
    # 100 ticks of 20 ms (2 s of the world) in 0.2 s of wall time: ahead of the wall
    last_sync = stamp_ns(wait_for_tick(context, frame + 100).vehicle_status.header)
    assert last_sync > round(wall.now * 1e9) + 1_000_000_000

    sync_mode_cmd(context, start=False)
    stopped_ns = round(wall.now * 1e9)
    after = real_time_ticks(context, wall, 5)
    # the wall clock's steps, from the last sync stamp on
    assert [stamp for _, stamp in after] == [last_sync + w - stopped_ns for w, _ in after]

    again = sync_mode_cmd(context, start=True, time_step=40).frame
    resumed = stamp_ns(wait_for_tick(context, again + 1).vehicle_status.header)
    assert resumed == after[-1][1] + 40_000_000


def test_a_sim_clock_run_stamps_its_sync_ticks_with_its_simulation_time() -> None:
    world = World(build_builtin_map("straight"))
    context = simulation_context(world, clock_mode=ClockMode.SYNC)
    frame = sync_mode_cmd(context, start=True).frame
    stamps = [
        stamp_ns(wait_for_tick(context, frame + k).vehicle_status.header) for k in range(1, 6)
    ]
    assert stamps == [20_000_000 * k for k in range(1, 6)]
    sync_mode_cmd(context, start=False)
    context.tick(STEP_S)
    assert stamp_ns(context.header()) == 110_000_000
    assert f"{world.sim_time:.6f}" == "0.110000"


def test_a_2021_08_sync_mode_cmd_asks_for_ticks_of_20_ms() -> None:
    old = get_profile("2021.08").message("morai_msgs/SyncModeCmd")
    sent = old.new(user_id="planner", start_sync_mode=True)
    assert convert(sent, old, canonical("morai_msgs/SyncModeCmd")).time_step == 20
    context = simulation_context(World(build_builtin_map("straight")), clock_mode=ClockMode.SYNC)
    service = get_profile("2021.08").service("morai_msgs/MoraiSyncModeCmdSrv")
    request = convert(
        service.request.new(request=sent),
        service.request,
        context.profile.service("morai_msgs/MoraiSyncModeCmdSrv").request,
    )
    reply = serve_sync_mode_cmd(context, context.row("sync_mode_cmd"), request).response
    assert (reply.result, reply.time_step) == (True, 20)
    assert wait_for_tick(context, reply.frame + 1).time == "0.020000"


def test_a_26_r1_time_step_of_0_still_asks_for_the_physics_step() -> None:
    context = simulation_context(World(build_builtin_map("straight")), clock_mode=ClockMode.SYNC)
    assert sync_mode_cmd(context, start=True, time_step=0).time_step == 10
