"""Outgoing XML-RPC notifications (publisherUpdate, paramUpdate, shutdown) delivered in order
per destination on short-lived threads, so that one dead or slow peer delays no other."""

from __future__ import annotations

import logging
import threading
import xmlrpc.client
from collections import deque
from typing import Any

from . import rpc
from .errors import PeerUnreachableError, Ros1Error

log = logging.getLogger(__name__)


class Notifier:
    def __init__(self, caller_id: str, timeout: float = 5.0) -> None:
        self._caller_id = caller_id
        self._timeout = timeout
        self._lock = threading.Lock()
        self._queues: dict[str, deque[tuple[str, tuple[Any, ...]]]] = {}
        self._closed = False

    def send(self, api: str, method: str, *args: Any) -> None:
        with self._lock:
            if self._closed:
                return
            queue = self._queues.get(api)
            if queue is None:
                queue = self._queues[api] = deque()
                threading.Thread(
                    target=self._drain, args=(api,), name=f"notify {api}", daemon=True
                ).start()
            queue.append((method, args))

    def close(self) -> None:
        with self._lock:
            self._closed = True

    def _drain(self, api: str) -> None:
        while True:
            with self._lock:
                queue = self._queues[api]
                if not queue or self._closed:
                    del self._queues[api]
                    return
                method, args = queue.popleft()
            try:
                rpc.call(api, method, self._caller_id, *args, timeout=self._timeout)
            except PeerUnreachableError as exc:  # the node left without unregistering
                log.debug("%s to %s failed: %s", method, api, exc)
            except (Ros1Error, xmlrpc.client.Error) as exc:
                log.info("%s to %s failed: %s", method, api, exc)
            except Exception as exc:  # a bad API or value must not end the queue
                log.warning("%s to %s failed: %s: %s", method, api, type(exc).__name__, exc)
