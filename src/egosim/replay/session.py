"""The replay system behind /Morai_SimProc: MoraiSimProcHandle commands in, a status out.

Pure logic over a playback clock that only `advance(dt)` moves (dt in sim
seconds), so a replay is as deterministic as the simulation driving it.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

from egosim.datapaths import PathOutsideRootsError, resolve_in_roots

from .codes import (
    CommandResult,
    Mode,
    PlaybackStatus,
    ProcessCommand,
    ReplayOptions,
    ReplayTargets,
    UnknownBitsError,
)
from .errors import ReplayError
from .frame import ReplayFrame
from .timeline import DEFAULT_TOPICS, BagTimeline, ReplayTopics

log = logging.getLogger(__name__)


class ProcHandleCommand(Protocol):
    """The fields of morai_msgs/MoraiSimProcHandle (a deserialised message has them)."""

    # Read-only: the session reads a command, never changes it.
    @property
    def sim_process_status(self) -> int: ...
    @property
    def replay_option(self) -> int: ...
    @property
    def rosbag_file_name(self) -> str: ...
    @property
    def replay_target_option(self) -> int: ...
    @property
    def replay_speed(self) -> int: ...
    @property
    def start_time(self) -> int: ...  # ms


@dataclass(frozen=True)
class ProcStatus:
    """The content of a morai_msgs/MoraiSimProcStatus (header aside)."""

    latest_command_time_ns: int
    command_result: CommandResult
    current_mode: Mode
    current_status: PlaybackStatus


class _CommandRejectedError(Exception):
    """A command that cannot be applied; nothing of it was."""


class ReplaySession:
    """Loads bags from the data roots and plays them back at the commanded speed.

    A command is applied in the order load, target, start time, speed, then
    the playback state. A failed load (missing, corrupt, outside the roots,
    unsupported release) applies nothing and leaves any earlier bag loaded.
    Any other invalid part rejects the rest of the command, reported as
    `LOADED_BUT_FAILED` when the same command loaded a bag, else
    `COMMAND_FAILED`.
    """

    def __init__(
        self,
        roots: Sequence[Path],
        *,
        profile: str | None = None,
        topics: ReplayTopics = DEFAULT_TOPICS,
    ) -> None:
        self.roots = list(roots)
        self.profile = profile
        self.topics = topics
        self.timeline: BagTimeline | None = None
        self.targets = ReplayTargets()
        self.speed = 1
        self.start_time = 0.0  # s from the bag's start; where playback (re)starts
        self.playback_time = 0.0  # s from the bag's start
        self.mode = Mode.SIMULATION
        self.playback_status = PlaybackStatus.RUNNING
        self.command_result = CommandResult.INITIAL
        self.latest_command_time_ns = 0

    def handle(self, command: ProcHandleCommand, *, received_ns: int) -> CommandResult:
        """Apply one MoraiSimProcHandle; `received_ns` is the sim time it arrived.

        (MoraiSimProcHandle carries no header in 26.r1, so the time of arrival
        stands for the header stamp the status reports.)
        """
        self.latest_command_time_ns = received_ns
        self.command_result = self._apply(command)
        return self.command_result

    def advance(self, dt: float) -> None:
        """Move the playback clock by `dt` sim seconds times the speed, while playing."""
        if dt < 0:
            raise ValueError(f"dt must not be negative, got {dt}")
        if self.timeline is None or self.mode is not Mode.REPLAY:
            return
        if self.playback_status is not PlaybackStatus.RUNNING:
            return
        self.playback_time = min(self.playback_time + dt * self.speed, self.timeline.duration)
        if self.playback_time >= self.timeline.duration:
            self.playback_status = PlaybackStatus.AT_END

    def frame(self) -> ReplayFrame | None:
        """The recorded scene at the playback clock, selected targets only; None in simulation."""
        if self.timeline is None or self.mode is not Mode.REPLAY:
            return None
        return self.timeline.sample(self.playback_time).restricted(
            ego=self.targets.ego, npcs=self.targets.npcs, pedestrians=self.targets.pedestrians
        )

    def status(self) -> ProcStatus:
        return ProcStatus(
            self.latest_command_time_ns, self.command_result, self.mode, self.playback_status
        )

    def _apply(self, command: ProcHandleCommand) -> CommandResult:
        try:
            options = ReplayOptions.decode(command.replay_option)
            process = ProcessCommand(command.sim_process_status)
        except (UnknownBitsError, ValueError) as exc:
            log.error("MoraiSimProcHandle rejected: %s", exc)
            return CommandResult.COMMAND_FAILED
        if options.load_file:
            try:
                self._load(command.rosbag_file_name)
            except (PathOutsideRootsError, FileNotFoundError) as exc:
                log.error(
                    "cannot load rosbag %r: %s (bag names resolve inside the data roots: "
                    "egosim run --data-root DIR)",
                    command.rosbag_file_name,
                    exc,
                )
                return CommandResult.BAG_LOAD_FAILED
            except (OSError, ReplayError) as exc:
                log.error("cannot load rosbag %r: %s", command.rosbag_file_name, exc)
                return CommandResult.BAG_LOAD_FAILED
        try:
            self._apply_settings(command, options, process)
        except _CommandRejectedError as exc:
            log.error("MoraiSimProcHandle rejected: %s", exc)
            if options.load_file:
                return CommandResult.LOADED_BUT_FAILED
            return CommandResult.COMMAND_FAILED
        return CommandResult.SUCCESS

    def _load(self, name: str) -> None:
        path = resolve_in_roots(name, self.roots)
        self.timeline = BagTimeline.open(path, profile=self.profile, topics=self.topics)
        log.info("loaded rosbag %s (%.3f s)", path, self.timeline.duration)
        self.start_time = 0.0
        self.playback_time = 0.0
        self.mode = Mode.REPLAY
        self.playback_status = PlaybackStatus.PAUSED

    def _apply_settings(
        self, command: ProcHandleCommand, options: ReplayOptions, process: ProcessCommand
    ) -> None:
        """Validate every part of the command, then apply them all."""
        targets = self.targets
        if options.set_target:
            try:
                targets = ReplayTargets.decode(command.replay_target_option)
            except UnknownBitsError as exc:
                raise _CommandRejectedError(str(exc)) from exc
            if not (targets.ego or targets.npcs or targets.pedestrians):
                raise _CommandRejectedError("replay_target_option selects no target")
        start_time = self.start_time
        if options.set_start_time:
            start_time = command.start_time / 1000.0
            self._require_bag("set start time")
            assert self.timeline is not None
            if not 0.0 <= start_time <= self.timeline.duration:
                raise _CommandRejectedError(
                    f"start_time {command.start_time} ms outside the bag "
                    f"(0..{self.timeline.duration * 1000:.0f} ms)"
                )
        if options.set_speed and command.replay_speed <= 0:
            raise _CommandRejectedError(
                f"replay_speed must be positive, got {command.replay_speed}"
            )
        if process in (ProcessCommand.PLAY, ProcessCommand.PAUSE):
            self._require_bag(process.name.lower())

        self.targets = targets
        if options.set_speed:
            self.speed = command.replay_speed
        if options.set_start_time:
            self.start_time = start_time
            self._seek(start_time)
        if process is ProcessCommand.PLAY:
            self._enter_replay()
            if self.playback_status is PlaybackStatus.AT_END:
                self._seek(self.start_time)
            self.playback_status = PlaybackStatus.RUNNING
            self.advance(0.0)  # a bag played from its very end is at its end at once
        elif process is ProcessCommand.PAUSE:
            self._enter_replay()
            if self.playback_status is not PlaybackStatus.AT_END:
                self.playback_status = PlaybackStatus.PAUSED
        elif process is ProcessCommand.STOP:
            self.mode = Mode.SIMULATION
            self.playback_status = PlaybackStatus.RUNNING
            self.playback_time = self.start_time

    def _require_bag(self, action: str) -> None:
        if self.timeline is None:
            raise _CommandRejectedError(f"cannot {action}: no rosbag loaded")

    def _enter_replay(self) -> None:
        if self.mode is Mode.SIMULATION:
            self.mode = Mode.REPLAY
            self.playback_status = PlaybackStatus.PAUSED
            self.playback_time = self.start_time

    def _seek(self, time: float) -> None:
        self.playback_time = time
        if self.mode is Mode.REPLAY and self.playback_status is PlaybackStatus.AT_END:
            self.playback_status = PlaybackStatus.PAUSED
