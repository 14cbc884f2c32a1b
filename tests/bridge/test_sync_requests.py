"""Requests tagged with a later frame: kept in order, bounded, run in their tick; those
tagged with the current or an earlier frame act on the next tick, and a WaitForTick for
such a frame ticks once (as MORAI's clients send them)."""

from __future__ import annotations

from typing import Any

from egosim.bridge import BridgeContext, simulation_context
from egosim.bridge.protocol.table import ROWS_BY_KEY
from egosim.bridge.sync.sync_mode import MAX_PENDING_ACTIONS, at_frame, serve_wait_for_tick
from egosim.world import World
from egosim.world.map import build_builtin_map

# The row the test's requests arrive on (any frame-tagged sync-mode service).
REQUESTS = ROWS_BY_KEY["sync_mode_ctrl_cmd"]


def sync_context() -> BridgeContext:
    world = World(build_builtin_map("straight"))
    context = simulation_context(world)
    context.sync.start("client", time_step_ms=10)
    return context


def tick_to(context: BridgeContext, frame: int) -> Any:
    service = context.profile.service("morai_msgs/MoraiWaitForTickSrv")
    request = service.request.new(
        request=context.profile.message("morai_msgs/WaitForTick").new(user_id="client", frame=frame)
    )
    row = context.row("sync_mode_wait_for_tick")
    reply = serve_wait_for_tick(context, row, request).response
    assert reply.tick_status
    return reply


def recorder(log: list[tuple[int, str]], frame: int, name: str):
    def action(context: BridgeContext) -> bool:
        log.append((frame, name))
        return True

    return action


def test_requests_for_later_frames_run_in_their_tick_in_arrival_order() -> None:
    context = sync_context()
    ran: list[tuple[int, str]] = []
    for frame, name in [(3, "a"), (2, "b"), (3, "c")]:
        assert at_frame(context, REQUESTS, frame, recorder(ran, frame, name))
    tick_to(context, 1)
    assert ran == []
    tick_to(context, 2)
    assert ran == [(2, "b")]
    tick_to(context, 3)
    assert ran == [(2, "b"), (3, "a"), (3, "c")]


def test_waiting_requests_are_bounded_and_free_their_places_when_run() -> None:
    context = sync_context()
    ran: list[tuple[int, str]] = []
    accepted = [
        at_frame(context, REQUESTS, 2 + k % 50, recorder(ran, 2 + k % 50, "x"))
        for k in range(MAX_PENDING_ACTIONS)
    ]
    assert all(accepted)
    assert not at_frame(context, REQUESTS, 60, recorder(ran, 60, "refused"))

    tick_to(context, 2)  # frame 2's share runs and leaves
    assert len(ran) == MAX_PENDING_ACTIONS // 50
    assert at_frame(context, REQUESTS, 60, recorder(ran, 60, "accepted"))


def test_a_tick_for_the_current_or_an_earlier_frame_steps_once() -> None:
    context = sync_context()
    tick_to(context, 3)
    for frame, expected in [(3, 4), (3, 5), (0, 6), (1, 7)]:
        reply = tick_to(context, frame)
        assert (reply.frame, reply.time) == (expected, f"{expected * 0.01:.6f}")
    assert tick_to(context, 9).frame == 9  # a later frame: up to it


def test_requests_for_the_current_or_an_earlier_frame_act_on_the_next_tick() -> None:
    context = sync_context()
    tick_to(context, 4)
    ran: list[tuple[int, str]] = []
    for frame, name in [(4, "current"), (2, "earlier"), (0, "zero"), (5, "next")]:
        assert at_frame(context, REQUESTS, frame, recorder(ran, frame, name))
    assert [name for _, name in ran] == ["current", "earlier", "zero", "next"]
