"""The publishing side of a TCPROS topic (ROS wiki: ROS/TCPROS, "Topics").

publish() is called from the simulation loop, so per subscriber connection it only appends to
a bounded queue drained by that connection's writer thread (or, when the connection is idle
and the message small, offers it to the socket without blocking; while output is held, keeps
it to go out with the next ones in one write). A subscriber that stops reading loses its
oldest messages (counted) and delays nobody else.
"""

from __future__ import annotations

import logging
import socket
import threading
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

from .connection_header import error_header, write_header
from .errors import ConnectionRefusedByPeerError, NodeShutdownError
from .tcpros import close_quietly, encode_frames, send_frames, set_nodelay
from .types import MessageTypeInfo

log = logging.getLogger(__name__)

ANY_MD5 = "*"

#: Chooses the type served on one connection from the subscriber's header, or raises
#: ConnectionRefusedByPeerError(reason).
Negotiator = Callable[[Mapping[str, str]], MessageTypeInfo]
#: Serialized message per md5sum: a mapping, or a function called at most once per md5.
Variants = Mapping[str, bytes] | Callable[[str], bytes]

#: How often an idle writer checks whether its subscriber hung up (s).
_IDLE_CHECK_S = 1.0
#: Stray bytes from a subscriber read (and dropped) per idle check, 4 KiB each.
_STRAY_READS_PER_CHECK = 16
#: Messages up to this size are offered to an idle connection's socket by publish() itself,
#: without blocking: handing them to the writer thread would dominate their latency.
_DIRECT_SEND_MAX = 64 * 1024


@dataclass
class ConnectionStats:
    connection_id: int
    peer: str
    md5sum: str
    bytes_sent: int = 0
    messages_sent: int = 0
    dropped: int = 0
    connected: bool = True


class OutputHold:
    """A node's hold on its topic output (Node.holding_output): while it is on, each
    connection keeps the small messages it is sent and writes them 64 KiB at a time; when
    it ends, every connection that kept some writes the rest."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._depth = 0
        self._keeping: list[_Outbox] = []

    def begin(self) -> None:
        with self._lock:
            self._depth += 1

    def end(self) -> None:
        with self._lock:
            self._depth -= 1
            if self._depth:
                return
            keeping, self._keeping = self._keeping, []
        for outbox in keeping:
            outbox.send_kept()

    def keeps(self, outbox: _Outbox, first: bool) -> bool:
        """Whether `outbox` is to keep what it is sent now (called under its lock); if so,
        and it keeps nothing yet (`first`), it is told to send what it kept when the hold
        ends."""
        if not self._depth:  # the common case, without the lock: no hold began
            return False
        if not first:
            # Told already: the hold's end sends what it keeps, under its lock, after this.
            return True
        with self._lock:
            if self._depth and first:
                self._keeping.append(outbox)
            return self._depth > 0


class _Outbox:
    """One subscriber connection: a bounded queue drained by its own writer thread."""

    def __init__(
        self,
        sock: socket.socket,
        stats: ConnectionStats,
        queue_size: int,
        on_closed: Callable[[_Outbox], None],
        output_hold: OutputHold,
    ) -> None:
        self.sock = sock
        self.stats = stats
        self.md5sum = stats.md5sum
        self._queue: deque[bytes] = deque()
        self._queue_size = queue_size
        # The lock of the condition, entered as itself: put() takes it for every message.
        self._lock = threading.RLock()
        self._ready = threading.Condition(self._lock)
        # The unsent end of a frame publish() began sending; it goes out before the queue.
        self._tail: memoryview | None = None
        self._writing = False
        self._closed = False
        self._on_closed = on_closed
        # Until open(), messages only queue: the connection header must go out first.
        self._open = False
        # While the node holds its output, small messages to an idle connection wait here
        # (in order, before anything queued after them) and go out in one write when they
        # fill _DIRECT_SEND_MAX or the hold ends: a burst of many messages then costs one
        # system call instead of one per message.
        self._output_hold = output_hold
        self._held: list[bytes] = []
        self._held_size = 0
        self._thread = threading.Thread(
            target=self._write, name=f"tcpros out {stats.peer}", daemon=True
        )

    def open(self, reply: Mapping[str, str]) -> None:
        """Send the connection header, then start sending what queued before it."""
        with self._ready:
            # Under the lock: a put() meanwhile waits for the header instead of queueing
            # behind it, where a burst right after connecting would overflow the queue.
            write_header(self.sock, reply)
            self._open = True
        self._thread.start()

    def send_kept(self) -> None:
        """The output hold has ended: send what was kept."""
        with self._ready:
            if self._held and not self._closed:
                self._offer(*self._take_held())

    def put(self, payloads: Sequence[bytes]) -> None:
        """Queue messages to go out in this order (one write when the socket takes them)."""
        with self._lock:
            if self._closed:
                return
            size = len(payloads[0]) if len(payloads) == 1 else sum(map(len, payloads))
            keep = (
                size <= _DIRECT_SEND_MAX
                and self._idle()
                and self._output_hold.keeps(self, first=not self._held)
            )
            if self._held and (not keep or self._held_size + size > _DIRECT_SEND_MAX):
                self._offer(*self._take_held())  # what was kept goes first
                keep = keep and self._idle()
            if keep:
                self._held.extend(payloads)
                self._held_size += size
                return
            self._offer(payloads, size)

    def _idle(self) -> bool:
        """Open, and nothing of its output left to the writer (lock held)."""
        return self._open and not self._queue and self._tail is None and not self._writing

    def _take_held(self) -> tuple[list[bytes], int]:
        held, size = self._held, self._held_size
        self._held, self._held_size = [], 0
        return held, size

    def _offer(self, payloads: Sequence[bytes], size: int) -> None:
        """Send `payloads` now if the connection is idle and the socket takes them, else
        queue them for the writer (lock held)."""
        if size <= _DIRECT_SEND_MAX and self._idle() and self._send_now(payloads):
            if self._tail is not None:
                self._ready.notify()
            return
        for data in payloads:
            if len(self._queue) >= self._queue_size:
                self._queue.popleft()
                self.stats.dropped += 1
            self._queue.append(data)
        self._ready.notify()

    def _send_now(self, payloads: Sequence[bytes]) -> bool:
        """Offer frames to the socket without blocking (lock held, writer idle); False if the
        socket took none of them. What it did not take is left in ``_tail`` for the writer."""
        frames = encode_frames(payloads)
        try:
            sent = self.sock.send(frames, socket.MSG_DONTWAIT)
        except OSError:
            return False  # full (BlockingIOError) or broken: the writer takes over
        if sent == 0:
            return False
        if sent < len(frames):
            self._tail = memoryview(frames)[sent:]
        self.stats.bytes_sent += len(frames)
        self.stats.messages_sent += len(payloads)
        return True

    def close(self) -> None:
        with self._ready:
            if self._closed:
                return
            self._closed = True
            self._held, self._held_size = [], 0
            self._ready.notify()
        self.stats.connected = False
        close_quietly(self.sock)

    def _peer_hung_up(self) -> bool:
        # A subscriber sends nothing after its header: whatever it sends is read and
        # dropped, so bytes waiting ahead of its hang-up cannot hide the hang-up. A few
        # reads per check: a peer that never stops sending must not hold the caller here.
        try:
            for _ in range(_STRAY_READS_PER_CHECK):
                if self.sock.recv(4096, socket.MSG_DONTWAIT) == b"":
                    return True
        except BlockingIOError:
            return False
        except OSError:
            return True
        return False

    def _write(self) -> None:
        try:
            while True:
                with self._ready:
                    while not self._queue and self._tail is None and not self._closed:
                        if not self._ready.wait(_IDLE_CHECK_S) and self._peer_hung_up():
                            return
                    if self._closed:
                        return
                    tail, self._tail = self._tail, None
                    batch = list(self._queue)
                    self._queue.clear()
                    self._writing = True
                if tail is not None:
                    self.sock.sendall(tail)
                send_frames(self.sock, batch)
                self.stats.bytes_sent += sum(len(data) + 4 for data in batch)
                self.stats.messages_sent += len(batch)
                with self._ready:
                    self._writing = False
        except OSError as exc:
            # A subscriber leaving (broken pipe, reset) is routine: every rostopic echo does.
            log.debug(
                "subscriber %s of connection %d left: %s",
                self.stats.peer,
                self.stats.connection_id,
                exc,
            )
        finally:
            self.close()
            self._on_closed(self)


class Publisher:
    """A topic advertised by a node. Create it with ``Node.advertise``."""

    def __init__(
        self,
        topic: str,
        msg_type: MessageTypeInfo,
        caller_id: str,
        *,
        latch: bool = False,
        queue_size: int = 100,
        negotiate: Negotiator | None = None,
        on_close: Callable[[Publisher], None] | None = None,
        output_hold: OutputHold | None = None,
    ) -> None:
        if queue_size < 1:
            raise ValueError("queue_size must be at least 1")
        self.topic = topic
        self.msg_type = msg_type
        self.caller_id = caller_id
        self.latch = latch
        self.queue_size = queue_size
        self._negotiate = negotiate
        self._on_close = on_close
        self._lock = threading.Lock()
        # Replaced, never mutated, so publish() enqueues to a snapshot outside the lock.
        self._outboxes: tuple[_Outbox, ...] = ()
        self._latched: bytes | Variants | None = None
        self._latch_fixed = False
        self._closed = False
        self._output_hold = output_hold or OutputHold()
        self.messages_published = 0

    @property
    def num_subscribers(self) -> int:
        return len(self._outboxes)

    @property
    def connections(self) -> list[ConnectionStats]:
        return [outbox.stats for outbox in self._outboxes]

    def publish(self, data: bytes) -> None:
        """Queue one serialized message for every subscriber (same bytes for all)."""
        self.publish_many((data,))

    def publish_variants(self, variants: Variants) -> None:
        """Queue one message serialized per md5sum; each subscriber gets the variant of the type
        negotiated for its connection. A callable is invoked at most once per md5sum."""
        self.publish_many((variants,))

    def publish_many(self, messages: Sequence[bytes | Variants]) -> None:
        """Queue several messages (bytes or variants, as above) that each subscriber gets in
        this order, in one write where its socket takes them: a burst costs one system call
        per subscriber instead of one per message."""
        if not messages:
            return
        produced: dict[str, list[bytes]] = {}
        for outbox in self._begin_publish(messages):
            payloads = produced.get(outbox.md5sum)
            if payloads is None:
                payloads = produced[outbox.md5sum] = [
                    _variant(message, outbox.md5sum) for message in messages
                ]
            outbox.put(payloads)

    def latch_first(self, message: bytes | Variants) -> None:
        """Latch `message` for good: every connection accepted from now on gets it first and
        later messages do not replace it (the static part of a topic whose other messages
        stream, e.g. a map under moving markers). It is not sent here; publish it too."""
        with self._lock:
            self.latch = True
            self._latched = message
            self._latch_fixed = True

    def _begin_publish(self, messages: Sequence[bytes | Variants]) -> tuple[_Outbox, ...]:
        """Count ``messages`` and latch the last; the connections they go to. A connection
        accepted after this point gets the last as its latched message instead."""
        with self._lock:
            if self._closed:
                raise NodeShutdownError(f"publisher of {self.topic} is closed")
            if self.latch and messages and not self._latch_fixed:
                self._latched = messages[-1]
            self.messages_published += len(messages)
            return self._outboxes

    def accept(
        self, sock: socket.socket, header: Mapping[str, str], peer: str, connection_id: int
    ) -> None:
        """Answer a subscriber's connection header and start serving it; the socket is ours."""
        try:
            served = self._choose_type(header)
        except ConnectionRefusedByPeerError as exc:
            log.warning(
                "refused subscriber %s (%s) of %s: %s",
                header.get("callerid"),
                peer,
                self.topic,
                exc.reason,
            )
            write_header(sock, error_header(exc.reason))
            close_quietly(sock)
            return
        reply = {
            "callerid": self.caller_id,
            "topic": self.topic,
            "type": served.name,
            "md5sum": served.md5sum,
            "message_definition": served.definition,
            "latching": "1" if self.latch else "0",
        }
        if header.get("tcp_nodelay") == "1":
            set_nodelay(sock)
        stats = ConnectionStats(connection_id, header.get("callerid", peer), served.md5sum)
        outbox = _Outbox(sock, stats, self.queue_size, self._forget, self._output_hold)
        # The outbox joins before the reply goes out, so a subscriber that has read the reply
        # gets every message published after it.
        with self._lock:
            if self._closed:
                outbox.close()
                return
            if self._latched is not None:
                outbox.put((_variant(self._latched, served.md5sum),))
            self._outboxes = (*self._outboxes, outbox)
        try:
            outbox.open(reply)
        except OSError as exc:
            log.debug("subscriber %s of %s left before the reply: %s", peer, self.topic, exc)
            outbox.close()
            self._forget(outbox)

    def _choose_type(self, header: Mapping[str, str]) -> MessageTypeInfo:
        if "md5sum" not in header or "callerid" not in header:
            raise ConnectionRefusedByPeerError("connection header lacks md5sum or callerid")
        served = self._negotiate(header) if self._negotiate else self.msg_type
        wanted = header["md5sum"]
        if ANY_MD5 not in (wanted, served.md5sum) and wanted != served.md5sum:
            raise ConnectionRefusedByPeerError(
                f"Client [{header['callerid']}] wants topic [{self.topic}] to have datatype/md5sum "
                f"[{header.get('type', '?')}/{wanted}], but our version has "
                f"[{served.name}/{served.md5sum}]. Dropping connection."
            )
        return served

    def _forget(self, outbox: _Outbox) -> None:
        with self._lock:
            self._outboxes = tuple(o for o in self._outboxes if o is not outbox)

    def close(self) -> None:
        """Disconnect all subscribers and unregister from the master."""
        with self._lock:
            if self._closed:
                return
            self._closed = True
            outboxes, self._outboxes = self._outboxes, ()
        for outbox in outboxes:
            outbox.close()
        if self._on_close is not None:
            self._on_close(self)


def _variant(variants: bytes | Variants, md5sum: str) -> bytes:
    if isinstance(variants, bytes):
        return variants
    if callable(variants):
        return variants(md5sum)
    return variants[md5sum]
