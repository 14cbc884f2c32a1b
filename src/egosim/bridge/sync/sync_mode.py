"""MORAI's synchronous mode (morai_msgs 26.r1, 24.r2, 2021.08): the client steps the world.

Any run serves it: SyncModeCmd(start) switches the simulator into synchronous mode,
where the world advances only on WaitForTick (the loop stops stepping it and rows
publish only on ticks), and SyncModeCmd(stop) returns it to the clock mode it had
(real time, or sim time at its --rtf); `--clock sync` starts a run in it, the world
held until the first client starts. While a client holds time, header stamps carry
the world's time: the stamp at the start plus frames x step (bridge/clock.py); after
a stop the run's clock goes on from there.

Frames: SyncModeCmd(start) answers with the current frame F and the tick length
(time_step ms; 0 asks for the simulator's physics step; a 2021.08 request, which has
no time_step, gets MORAI's fixed 20 ms). Every tick advances the world by exactly one
step of time_step and the frame by one. WaitForTick(frame=N) ticks until the world is
at frame N, publishing each tick's due outputs before it answers; N at or before the
current frame ticks exactly once (MORAI's own examples send a frame that never
advances, or 0, and expect a tick per call); more than MAX_TICKS_PER_REQUEST ticks at
once are refused.

A request tagged with frame N (CtrlCmd, the CtrlCmd a 2021.08 WaitForTick carries,
SetGear, ScenarioLoad, AddObject, RemoveObject) takes effect in the tick that produces
frame N, i.e. before the world steps from N-1 to N. For N later than the next frame it
is kept until then (result true: accepted; a failure then is logged). For the next
frame, and for the current or an earlier one, it is applied at once, so it acts on
the next tick, and its result is the real outcome: MORAI's clients tag a command with
the frame the last WaitForTick answered, or with a frame that never advances, and the
command must drive the tick they ask for next.

WaitForTickResponse.time is the world's simulation time in seconds with 6 decimals
("12.340000").
"""

from __future__ import annotations

import logging
from contextlib import nullcontext
from typing import TYPE_CHECKING

from ...msgs import Message, get_profile
from ...world.vehicle import Gear
from ..context import BridgeContext
from ..egos.ego import ego_status_of, on_ctrl_cmd
from ..protocol.releases import CANONICAL_PROFILE, convert
from ..protocol.table import Row
from ..scene.scenarios import ScenarioRequest, ScenarioRequestError, load_requested_scenario
from .sync_session import MAX_PENDING_ACTIONS, Action, SyncSession

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, morai_2021_08

log = logging.getLogger(__name__)

MAX_TICKS_PER_REQUEST = 500
MAX_TIME_STEP_MS = 1000


def _session(context: BridgeContext, row: Row) -> SyncSession[BridgeContext] | None:
    """The active session, or None (logged) when sync mode is not started."""
    session = context.sync
    if not session.active:
        log.error("%s: synchronous mode is not started (call SyncModeCmd first)", row.name)
        return None
    return session


def result_message(context: BridgeContext, ok: bool) -> morai_26_r1.SyncModeResultResponse:
    return context.profile.message("morai_msgs/SyncModeResultResponse").new(result=ok)


def service_response(context: BridgeContext, service_type: str, response: Message) -> object:
    return context.profile.message(f"morai_msgs/{service_type}Response").new(response=response)


def serve_sync_mode_cmd(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiSyncModeCmdSrvRequest
) -> object:
    """/SyncModeCmd: start (with a tick length) or stop synchronous mode."""
    command = request.request
    session = context.sync
    ok = True
    if command.start_sync_mode:
        step_ms = int(command.time_step) or round(context.world.physics_step_s * 1000)
        ok = 0 < step_ms <= MAX_TIME_STEP_MS
        if ok:
            session.start(command.user_id, step_ms)
            context.clock.hold()
            log.info(
                "sync mode started by %r at frame %d, %d ms",
                command.user_id,
                session.frame,
                step_ms,
            )
        else:
            log.error("%s: time_step %d ms is not 1..%d", row.name, step_ms, MAX_TIME_STEP_MS)
    else:
        session.stop()
        context.clock.release()
        log.info(
            "sync mode stopped at frame %d; the %s clock runs",
            session.frame,
            context.clock.mode.value,
        )
    return service_response(
        context,
        "MoraiSyncModeCmdSrv",
        context.profile.message("morai_msgs/SyncModeCmdResponse").new(
            user_id=command.user_id,
            frame=session.frame,
            result=ok,
            time_step=session.time_step_ms,
        ),
    )


def serve_wait_for_tick(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiWaitForTickSrvRequest
) -> object:
    """/SyncModeWaitForTick: tick to the requested frame (once for the current or an
    earlier one); the ego's status there."""
    tick = request.request
    session = _session(context, row)
    ticked = False
    if session is not None:
        target = int(tick.frame)
        if tick.user_id != session.user_id:
            log.error("%s: user %r did not start sync mode", row.name, tick.user_id)
        elif (ticks := max(target - session.frame, 1)) > MAX_TICKS_PER_REQUEST:
            log.error("%s: %d ticks at once (max %d)", row.name, ticks, MAX_TICKS_PER_REQUEST)
        else:
            # Every frame's outputs are out before the reply, so several frames' go out
            # together. One frame's rows go out as they are built: the subscribers' side
            # reads them while the tick goes on (held to the end, it reads them after,
            # and its next request comes later).
            with context.hold_output() if ticks > 1 else nullcontext():
                for _ in range(ticks):
                    _tick(context, session)
            ticked = True
    world = context.world
    return service_response(
        context,
        "MoraiWaitForTickSrv",
        context.profile.message("morai_msgs/WaitForTickResponse").new(
            tick_status=ticked,
            pause_status=world.paused,
            frame=context.sync.frame,
            vehicle_status=ego_status_of(context, 0),
            time=f"{world.sim_time:.6f}",
        ),
    )


def _tick(context: BridgeContext, session: SyncSession[BridgeContext]) -> None:
    frame = session.frame + 1
    for name, action in session.due(frame):
        if not action(context):
            log.error("%s for frame %d failed", name, frame)
    try:
        context.tick(session.time_step_ms / 1000.0)
    finally:
        session.capture_cameras = False
    session.frame = frame


def at_frame(context: BridgeContext, row: Row, frame: int, action: Action[BridgeContext]) -> bool:
    """Apply `action`, requested on `row`, in the tick producing `frame` (see the
    module's docstring)."""
    session = _session(context, row)
    if session is None:
        return False
    if frame <= session.frame + 1:
        return bool(action(context))
    if not session.schedule(frame, row.name, action):
        log.error("%s: %d requests already wait for their frames", row.name, MAX_PENDING_ACTIONS)
        return False
    return True


def driving(
    row: Row, command: morai_26_r1.CtrlCmd, sensor_capture: bool = False
) -> Action[BridgeContext]:
    """The action that hands the main ego a (26.r1) CtrlCmd requested on `row` (and, with
    `sensor_capture`, has the tick publish the camera frames)."""

    def drive(context: BridgeContext) -> bool:
        on_ctrl_cmd(context, row, command)
        context.sync.capture_cameras = context.sync.capture_cameras or sensor_capture
        return True

    return drive


def serve_ctrl_cmd(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiSyncModeCtrlCmdSrvRequest
) -> object:
    """/SyncModeCtrlCmd: the main ego's CtrlCmd from the tick producing `frame` on; with
    sensor_capture, that tick renders and publishes the cameras' frames (before the
    WaitForTick reply, like every output of the tick)."""
    drive = driving(row, request.request.command, bool(request.request.sensor_capture))
    ok = at_frame(context, row, int(request.request.frame), drive)
    return service_response(context, "MoraiSyncModeCtrlCmdSrv", result_message(context, ok))


def apply_tick_command(
    context: BridgeContext, row: Row, request: morai_2021_08.MoraiWaitForTickSrvRequest
) -> None:
    """Release 2021.08 sends the ego's CtrlCmd inside WaitForTick (later releases use
    SyncModeCtrlCmd): it drives from the tick producing the requested frame on (the
    tick this call makes, for the current or an earlier frame)."""
    sent = request.request.command
    command = convert(
        sent,
        get_profile("2021.08").message("morai_msgs/CtrlCmd"),
        get_profile(CANONICAL_PROFILE).message("morai_msgs/CtrlCmd"),
    )
    at_frame(context, row, int(request.request.frame), driving(row, command))


def serve_set_gear(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiSyncModeSetGearSrvRequest
) -> object:
    """/SyncModeSetGear: the main ego's gear (EventInfo codes 1 P, 2 R, 3 N, 4 D)."""
    try:
        gear = Gear(int(request.request.gear))
    except ValueError:
        log.error("%s: gear %s is not 1..4", row.name, request.request.gear)
        return service_response(context, "MoraiSyncModeSetGearSrv", result_message(context, False))

    def shift(context: BridgeContext) -> bool:
        context.world.egos[0].vehicle.set_gear(gear)
        return True

    ok = at_frame(context, row, int(request.request.frame), shift)
    return service_response(context, "MoraiSyncModeSetGearSrv", result_message(context, ok))


def serve_scenario_load(
    context: BridgeContext,
    row: Row,
    prepared: ScenarioRequest[morai_26_r1.SyncModeScenarioLoad],
) -> object:
    """/SyncModeScenarioLoad: ScenarioLoad (same fields and file roots) at a frame."""

    def apply(context: BridgeContext) -> bool:
        try:
            load_requested_scenario(context, prepared)
        except ScenarioRequestError as error:
            log.error("%s: %s", row.name, error)
            return False
        return True

    ok = at_frame(context, row, int(prepared.request.frame), apply)
    return service_response(context, "MoraiSyncModeSLSrv", result_message(context, ok))


def publish_sync_mode_info(context: BridgeContext, row: Row) -> bytes:
    """/SyncModeInfo: who runs sync mode, whether it is on, and the current frame; its
    bytes (master_id, status, frame, can_send_tick)."""
    session = context.sync
    pack = context.profile.message("morai_msgs/SyncModeInfo").flat().pack
    return pack(session.user_id, session.active, session.frame, session.active)
