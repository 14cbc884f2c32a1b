"""What a case's supervisor and its simulator worker (`python -m egosim.batch.worker`) say
to each other, one line at a time.

To the worker, on its standard input:
    run "CASE_DIR" "MASTER_URI"  run the case in CASE_DIR on the ROS master at MASTER_URI
                            (the supervisor's: JSON strings)
    stop                    end the case running now, as its stack leaving would
    (end of input)          end the case running now, then exit

From the worker, among its output (stdout and stderr, merged):
    egosim-batch: case "CASE_DIR"   a case begins: what follows is its simulator's log
    egosim-batch: master URI        the case's simulator starts, on the case's master at
                                    URI (the stack's time to connect counts from here)
    egosim-batch: serving           every topic and service of the simulator is up
    egosim-batch: running           the stack is connected and the drive has begun
    egosim-batch: ended REASON      the drive is over (the simulator then stops)
    egosim-batch: done STATUS       the case is over: score.json written, everything it
                                    started ended; STATUS is its run's exit status
    egosim-batch: done STATUS last  ... and the worker exits (it is replaced)
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path

PREFIX = "egosim-batch: "
RUN, STOP = "run", "stop"
CASE, MASTER, SERVING, RUNNING, ENDED, DONE = (
    "case",
    "master",
    "serving",
    "running",
    "ended",
    "done",
)
LAST = "last"
DONE_LINE = re.compile(r"^egosim-batch: done (-?\d+)( last)?$")


def run_command(case_dir: Path, master_uri: str) -> bytes:
    return f"{RUN} {json.dumps(str(case_dir))} {json.dumps(master_uri)}\n".encode()


def stop_command() -> bytes:
    return f"{STOP}\n".encode()


@dataclass(frozen=True)
class Command:
    kind: str
    """RUN or STOP."""
    case_dir: Path = Path()
    master_uri: str = ""


def parse_command(line: str) -> Command:
    """A RUN (with its case folder and master) or STOP command; ValueError for anything
    else."""
    word, _, argument = line.strip().partition(" ")
    if word == STOP and not argument:
        return Command(STOP)
    if word == RUN:
        decoder = json.JSONDecoder()
        folder, end = decoder.raw_decode(argument)
        master_uri, end = decoder.raw_decode(argument, end + 1)
        if isinstance(folder, str) and isinstance(master_uri, str) and end == len(argument):
            return Command(RUN, Path(folder), master_uri)
    raise ValueError(f"not a worker command: {line.strip()!r}")


def case_line(case_dir: Path) -> str:
    return f"{PREFIX}{CASE} {json.dumps(str(case_dir))}"


def case_dir_of(line: str) -> Path | None:
    """The folder of a `case` line, None for any other line."""
    if not line.startswith(f"{PREFIX}{CASE} "):
        return None
    try:
        folder = json.loads(line[len(PREFIX) + len(CASE) + 1 :])
    except ValueError:
        return None
    return Path(folder) if isinstance(folder, str) else None


def done_line(status: int, last: bool) -> str:
    return f"{PREFIX}{DONE} {status}" + (f" {LAST}" if last else "")


@dataclass(frozen=True)
class Done:
    status: int
    last: bool
    """The worker exits after this case."""


def done_of(line: str) -> Done | None:
    match = DONE_LINE.match(line)
    if match is None:
        return None
    return Done(int(match.group(1)), match.group(2) is not None)
