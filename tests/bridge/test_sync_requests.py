"""Requests tagged with a later frame: kept in order, bounded, run in their tick."""

from __future__ import annotations

from egosim.bridge import BridgeContext, simulation_context
from egosim.bridge.sync_mode import MAX_PENDING_ACTIONS, at_frame, serve_wait_for_tick
from egosim.bridge.table import ROWS_BY_KEY
from egosim.world import World
from egosim.world.map import build_builtin_map

# The row the test's requests arrive on (any frame-tagged sync-mode service).
REQUESTS = ROWS_BY_KEY["sync_mode_ctrl_cmd"]


def sync_context() -> BridgeContext:
    world = World(build_builtin_map("straight"))
    context = simulation_context(world)
    context.sync.start("client", time_step_ms=10)
    return context


def tick_to(context: BridgeContext, frame: int) -> None:
    service = context.profile.service("morai_msgs/MoraiWaitForTickSrv")
    request = service.request.new(
        request=context.profile.message("morai_msgs/WaitForTick").new(user_id="client", frame=frame)
    )
    row = context.row("sync_mode_wait_for_tick")
    assert serve_wait_for_tick(context, row, request).response.tick_status


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
