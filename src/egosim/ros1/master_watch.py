"""Noticing a restarted master: rospy never re-registers with a new master; egosim does.

A node that joined a master it did not start asks it for its pid every
`WATCH_PERIOD_S`. When the pid changes, or the master answers again after it was
unreachable, the master is a new one that knows nothing of the node: the watch calls
`reregister`, which registers every publisher, subscriber, service, parameter
subscription and parameter the node has again.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from .errors import MasterError, PeerUnreachableError
from .master_client import MasterClient

log = logging.getLogger(__name__)

WATCH_PERIOD_S = 0.5


class MasterWatch:
    def __init__(
        self,
        master: MasterClient,
        reregister: Callable[[], None],
        stopped: threading.Event,
        period_s: float = WATCH_PERIOD_S,
    ) -> None:
        self._master = master
        self._reregister = reregister
        self._stopped = stopped
        self._period_s = period_s
        self._pid: int | None = self._probe()
        self._thread = threading.Thread(target=self._run, name="master watch", daemon=True)

    def start(self) -> MasterWatch:
        self._thread.start()
        return self

    def _probe(self) -> int | None:
        """The master's pid, None while it does not answer."""
        try:
            return self._master.get_pid(timeout=self._period_s * 2)
        except (MasterError, PeerUnreachableError, OSError):
            return None

    def _run(self) -> None:
        while not self._stopped.wait(self._period_s):
            pid = self._probe()
            if pid is None:
                if self._pid is not None:
                    log.warning("master %s does not answer", self._master.master_uri)
                self._pid = None
                continue
            if pid == self._pid:
                continue
            log.warning(
                "master %s is a new one (pid %s, was %s): registering everything again",
                self._master.master_uri,
                pid,
                self._pid if self._pid is not None else "unreachable",
            )
            self._pid = pid
            try:
                self._reregister()
            except (MasterError, PeerUnreachableError, OSError) as error:
                log.error("registering again with %s failed: %s", self._master.master_uri, error)
                self._pid = None  # try again at the next probe
