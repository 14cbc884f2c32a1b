"""File names that come from the network resolve only inside configured data roots.

ScenarioLoad.file_name, SaveSensorData.file_dir and MoraiSimProcHandle.rosbag_file_name
are chosen by any ROS peer; following them blindly would let a peer read or
write anywhere the simulator can.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Sequence
from pathlib import Path


class PathOutsideRootsError(ValueError):
    """The name resolves outside every data root (absolute elsewhere, `..`, symlink out)."""


def resolve_in_roots(name: str, roots: Sequence[Path], *, must_exist: bool = True) -> Path:
    """The real path of `name` inside one of `roots`, trying each root in order.

    A relative `name` is taken relative to each root; an absolute one must
    already lie inside a root. Symlinks are resolved before the check, so a
    link pointing out of a root is refused like `..` is.
    """
    if not name or "\x00" in name:
        raise PathOutsideRootsError(f"invalid file name {name!r}")
    real_roots = [Path(root).resolve() for root in roots]
    candidates = [Path(name)] if Path(name).is_absolute() else [r / name for r in real_roots]
    refused = None
    for candidate in candidates:
        resolved = candidate.resolve()
        if not any(resolved.is_relative_to(root) for root in real_roots):
            refused = resolved
            continue
        if must_exist and not resolved.exists():
            continue
        return resolved
    listed = [str(r) for r in real_roots]
    if refused is not None:
        raise PathOutsideRootsError(
            f"{name!r} resolves outside the data roots {listed} ({refused})"
        )
    raise FileNotFoundError(f"{name!r} not found in the data roots {listed}")


class NotARegularFileError(OSError):
    """A name that resolves to a pipe, device, socket or directory, not a file."""


#: The largest file a network request may make the simulator read (a scenario, ...).
MAX_READ_BYTES = 16 * 1024 * 1024


def read_regular_file(path: Path, max_bytes: int = MAX_READ_BYTES) -> bytes:
    """The bytes of the regular file at `path`, at most `max_bytes`.

    The file is opened without blocking and checked before anything is read, so a named
    pipe or a device never stalls the reader waiting for data that may never come.
    """
    descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    with os.fdopen(descriptor, "rb") as file:
        mode = os.fstat(file.fileno()).st_mode
        if not stat.S_ISREG(mode):
            raise NotARegularFileError(f"{path} is not a regular file")
        data = file.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise OSError(f"{path} is larger than {max_bytes} bytes")
    return data
