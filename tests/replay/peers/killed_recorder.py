"""Records ego messages, reports what reached the disk, then waits to be killed.

argv: bag path, message count, chunk size (bytes), flush interval (s).
Prints one JSON line of RecorderStats once every message has been handed to
the writer and at least one chunk is on disk.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import threading
import time
from pathlib import Path

from egosim.replay import BagRecorder
from tests.replay.drive import EGO, ego_message, stamp


def main() -> None:
    path, count, chunk_size, flush_interval = sys.argv[1:5]
    recorder = BagRecorder(
        Path(path), chunk_size=int(chunk_size), flush_interval=float(flush_interval)
    )
    handle = recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition)
    for k in range(int(count)):
        recorder.write(handle, stamp(k / 50), EGO.serialize(ego_message(k / 50, k)))
    while recorder.stats.written < int(count) or recorder.stats.flushed == 0:
        time.sleep(0.01)
    print(json.dumps(dataclasses.asdict(recorder.stats)), flush=True)
    threading.Event().wait()  # until SIGKILL


if __name__ == "__main__":
    main()
