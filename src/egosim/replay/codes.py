"""The numbers of MoraiSimProcHandle and MoraiSimProcStatus, and how option words are read.

The protocol document writes the option bits as 0x0001, 0x0010, 0x0100,
0x1000, which read as hexadecimal are bits 0, 4, 8 and 12. Clients written
from the same table as binary digits send 1, 2, 4, 8 instead. Both readings
are accepted: they only share 0x0001 = 1, which means the same in both.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum


class ProcessCommand(IntEnum):
    """MoraiSimProcHandle.sim_process_status."""

    NONE = 0  # options only, the playback state stays as it is
    PLAY = 1
    PAUSE = 2
    STOP = 32


class CommandResult(IntEnum):
    """MoraiSimProcStatus.command_result."""

    INITIAL = 0x00
    SUCCESS = 0x01
    COMMAND_FAILED = 0x10
    BAG_LOAD_FAILED = 0x20
    LOADED_BUT_FAILED = 0x30


class Mode(IntEnum):
    """MoraiSimProcStatus.current_mode."""

    SIMULATION = 0x01
    REPLAY = 0x10


class PlaybackStatus(IntEnum):
    """MoraiSimProcStatus.current_status."""

    RUNNING = 0x01
    PAUSED = 0x10
    AT_END = 0x20  # paused because the end of the bag was reached


# (document's hexadecimal bit, binary-digit reading) of each replay_option.
LOAD_FILE = (0x0001, 0x0001)
SET_TARGET = (0x0010, 0x0002)
SET_START_TIME = (0x0100, 0x0004)
SET_SPEED = (0x1000, 0x0008)
# ... and of each replay_target_option.
TARGET_EGO = (0x0001, 0x0001)
TARGET_NPC = (0x0010, 0x0002)
TARGET_PEDESTRIAN = (0x0100, 0x0004)


class UnknownBitsError(ValueError):
    """An option word has bits neither reading defines."""


@dataclass(frozen=True)
class ReplayOptions:
    """Which fields of a MoraiSimProcHandle apply."""

    load_file: bool = False
    set_target: bool = False
    set_start_time: bool = False
    set_speed: bool = False

    @classmethod
    def decode(cls, word: int) -> ReplayOptions:
        load, target, start, speed = _decode(
            word, (LOAD_FILE, SET_TARGET, SET_START_TIME, SET_SPEED)
        )
        return cls(load, target, start, speed)


@dataclass(frozen=True)
class ReplayTargets:
    """Which recorded actors a replay drives."""

    ego: bool = True
    npcs: bool = True
    pedestrians: bool = True

    @classmethod
    def decode(cls, word: int) -> ReplayTargets:
        ego, npcs, pedestrians = _decode(word, (TARGET_EGO, TARGET_NPC, TARGET_PEDESTRIAN))
        return cls(ego, npcs, pedestrians)


def _decode(word: int, flags: tuple[tuple[int, int], ...]) -> list[bool]:
    # The fields are int16: a word with the top bit set arrives negative.
    word &= 0xFFFF
    known = 0
    for hexadecimal, binary in flags:
        known |= hexadecimal | binary
    if word & ~known:
        raise UnknownBitsError(f"option word {word:#06x} has unknown bits {word & ~known:#06x}")
    return [bool(word & (hexadecimal | binary)) for hexadecimal, binary in flags]
