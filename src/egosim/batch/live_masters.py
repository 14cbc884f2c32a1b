"""The ports of the case masters a stack may still reach.

A case's master shuts down with its simulator while its stack may still be ending (the
next case begins meanwhile: case_runner). Its port is then free, and the system could
give it to a new master, which that stack would reach instead of nothing. So every case
master in use, or shut down with its stack not yet ended, is noted here, and a new case's
master takes none of these ports: a stack only ever reaches its own case's master.
"""

from __future__ import annotations

import threading
from collections import Counter


class LiveMasters:
    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._ports: Counter[int] = Counter()

    def add(self, port: int) -> None:
        with self._lock:
            self._ports[port] += 1

    def remove(self, port: int) -> None:
        with self._lock:
            self._ports[port] -= 1
            if self._ports[port] <= 0:
                del self._ports[port]

    def ports(self) -> frozenset[int]:
        with self._lock:
            return frozenset(self._ports)
