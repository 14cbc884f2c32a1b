"""Which processes still run from a folder (a batch must leave none behind)."""

from __future__ import annotations

import os
from pathlib import Path


def processes_using(folder: Path) -> list[str]:
    """Command lines of live processes whose command line or working directory is in
    `folder`."""
    found = []
    mark = str(folder)
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
            cwd = os.readlink(entry / "cwd")
            state = (entry / "stat").read_text().split(") ")[-1][0]
        except OSError:
            continue
        if state != "Z" and (mark in cmdline or cwd.startswith(mark)):
            found.append(cmdline)
    return found
