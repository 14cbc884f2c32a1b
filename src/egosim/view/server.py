"""The live view's web server (aiohttp, on its own thread and event loop).

GET / and /static/... serve the page from the package, /map.json the map (gzipped,
made once); /ws is one websocket per browser: a hello, the plots' history (the last
minute, so a late page starts full), then the newest frame whenever the loop offers
one (a browser that cannot keep up skips frames; one that stalls a send for
SEND_TIMEOUT_S or stops answering pings is dropped) and the ROS graph every few
seconds. Requests from the page go to the loop thread through the app's inbox.
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import gzip
import json
import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from aiohttp import WSMsgType, web

from ..app.inbox import Inbox, LoopStoppedError
from ..json_value import JsonValue
from ..ros1.graph import SystemState, nodes_of
from .controls import PreparedRequest
from .hub import FrameHub
from .messages import Hello, Reply

log = logging.getLogger(__name__)

STATIC_DIR = Path(__file__).parent / "static"
#: A frame not handed to a browser's socket within this time drops that browser, s.
SEND_TIMEOUT_S = 5.0
#: Websocket ping period; a browser that misses a pong is dropped, s.
HEARTBEAT_S = 10.0
#: Browsers served at once; more are refused (bounded memory and CPU).
MAX_CLIENTS = 32
#: Largest request a browser may send, bytes.
MAX_REQUEST_BYTES = 4096
#: How often the ROS graph is asked of the master while a browser watches, s.
GRAPH_PERIOD_S = 3.0
#: How often the graph poller looks whether a browser is there, s.
GRAPH_WAKE_S = 0.25
#: Time the loop may take to answer a request from the page, s.
REQUEST_TIMEOUT_S = 10.0
STARTUP_TIMEOUT_S = 10.0
#: What closing a browser's socket, or the server, may take before it is cut, s.
CLOSE_TIMEOUT_S = 1.0
#: Requests the page sends often and needs no answer to (posted, not awaited).
FIRE_AND_FORGET = frozenset({"keys"})


class ViewServerError(Exception):
    """The server could not start (address in use, bad host...)."""


@dataclass(frozen=True)
class ViewBackend:
    """What the server reaches of the simulator."""

    hub: FrameHub
    inbox: Inbox
    prepare: Callable[[JsonValue], PreparedRequest]
    """Does a request's file work on a worker thread (ViewControls.prepare)."""
    apply: Callable[[JsonValue | PreparedRequest], Reply]
    """Runs one page request on the loop thread (ViewControls.apply)."""
    capture: Callable[[], None]
    """Takes a frame now, on the loop thread (ViewStage.capture)."""
    history: Callable[[], str]
    """The "history" message's JSON: the plotted series so far (PlotHistory)."""
    map_json: Callable[[], str]
    system_state: Callable[[], SystemState]
    hello: Hello


class _Client:
    def __init__(self, ws: web.WebSocketResponse) -> None:
        self.ws = ws
        self.sent = 0
        self.lidar = False


class ViewServer:
    def __init__(self, backend: ViewBackend, host: str, port: int, readonly: bool) -> None:
        self.backend = backend
        self.host = host
        self.port = port
        self.readonly = readonly
        self._clients: set[_Client] = set()
        self._thread: threading.Thread | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._runner: web.AppRunner | None = None
        self._wake_event: asyncio.Event | None = None
        self._graph: str | None = None
        self._map_gzip: bytes | None = None
        self._stopped = threading.Event()

    @property
    def url(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"http://{host}:{self.port}/"

    # -- life cycle (caller's thread) ---------------------------------------------------

    def start(self) -> None:
        """Bind and serve on a new thread; raises ViewServerError if it cannot bind."""
        started: list[BaseException | None] = []
        ready = threading.Event()

        def serve() -> None:
            loop = asyncio.new_event_loop()
            self._loop = loop
            try:
                loop.run_until_complete(self._open())
                started.append(None)
            except (OSError, ValueError) as error:
                started.append(error)
                ready.set()
                loop.close()
                return
            ready.set()
            try:
                loop.run_until_complete(self._serve_until_stopped())
            finally:
                loop.close()

        self._thread = threading.Thread(target=serve, name="egosim-view", daemon=True)
        self._thread.start()
        if not ready.wait(STARTUP_TIMEOUT_S):
            raise ViewServerError(f"the view did not start within {STARTUP_TIMEOUT_S} s")
        if started[0] is not None:
            raise ViewServerError(f"cannot serve on {self.host}:{self.port}: {started[0]}")
        self.backend.hub.notify = self._notify

    def close(self) -> None:
        self.backend.hub.notify = lambda: None
        loop = self._loop
        if loop is not None and not loop.is_closed():
            with contextlib.suppress(RuntimeError):
                loop.call_soon_threadsafe(self._stopped.set)
        if self._thread is not None:
            # Its own cleanup gives up on browsers after CLOSE_TIMEOUT_S; the thread is a
            # daemon, so a stop never waits on the view longer than this.
            self._thread.join(2 * CLOSE_TIMEOUT_S)

    def _notify(self) -> None:
        """A frame was offered (loop thread): wake the senders; never blocks."""
        loop = self._loop
        if loop is not None and not loop.is_closed():
            with contextlib.suppress(RuntimeError):
                loop.call_soon_threadsafe(self._wake)

    # -- server thread -------------------------------------------------------------------

    async def _open(self) -> None:
        self._wake_event = asyncio.Event()
        app = web.Application(client_max_size=MAX_REQUEST_BYTES)
        app.router.add_get("/", self._index)
        app.router.add_get("/ws", self._websocket)
        app.router.add_get("/map.json", self._map)
        app.router.add_static("/static/", STATIC_DIR, follow_symlinks=False)
        self._runner = web.AppRunner(
            app, access_log=None, handle_signals=False, shutdown_timeout=CLOSE_TIMEOUT_S
        )
        await self._runner.setup()
        site = web.TCPSite(self._runner, self.host, self.port, reuse_address=True)
        await site.start()
        # aiohttp keeps the listening server private and types it as the abstract base.
        server = site._server
        sockets = server.sockets if isinstance(server, asyncio.Server) else ()
        if sockets:
            self.port = sockets[0].getsockname()[1]  # the one the OS chose for port 0

    async def _serve_until_stopped(self) -> None:
        graph = asyncio.create_task(self._poll_graph())
        while not self._stopped.is_set():
            await asyncio.sleep(0.1)
        graph.cancel()
        await asyncio.gather(*(client.ws.close() for client in list(self._clients)))
        assert self._runner is not None
        await self._runner.cleanup()

    def _wake(self) -> None:
        event = self._wake_event
        self._wake_event = asyncio.Event()
        assert event is not None
        event.set()

    async def _index(self, _: web.Request) -> web.FileResponse:
        return web.FileResponse(STATIC_DIR / "index.html")

    async def _map(self, _: web.Request) -> web.Response:
        if self._map_gzip is None:
            text = await asyncio.get_running_loop().run_in_executor(None, self.backend.map_json)
            self._map_gzip = gzip.compress(text.encode(), compresslevel=6)
        return web.Response(
            body=self._map_gzip,
            content_type="application/json",
            headers={"Content-Encoding": "gzip", "Cache-Control": "no-store"},
        )

    async def _websocket(self, request: web.Request) -> web.StreamResponse:
        if len(self._clients) >= MAX_CLIENTS:
            return web.Response(status=503, text=f"at most {MAX_CLIENTS} browsers at once")
        # No per-message compression: deflating every frame for every browser costs the
        # server far more CPU than the bytes it saves on loopback.
        ws = web.WebSocketResponse(
            heartbeat=HEARTBEAT_S,
            max_msg_size=MAX_REQUEST_BYTES,
            compress=False,
            timeout=CLOSE_TIMEOUT_S,
        )
        await ws.prepare(request)
        client = _Client(ws)
        self._clients.add(client)
        self._set_watchers()
        log.debug("view: a browser connected (%d watching)", len(self._clients))
        sender: asyncio.Task[None] | None = None
        try:
            # Hello, graph and history come before any frame; the first frame is one taken
            # for this browser, never an older one the hub still holds.
            await self._send(client, json.dumps({**self.backend.hello, "readonly": self.readonly}))
            if self._graph is not None:
                await self._send(client, self._graph)
            history = await asyncio.get_running_loop().run_in_executor(None, self.backend.history)
            await self._send(client, history)
            client.sent = self.backend.hub.sequence
            sender = asyncio.create_task(self._send_frames(client))
            self.backend.inbox.post(self.backend.capture)  # a first frame, even when paused
            async for message in ws:
                if message.type is WSMsgType.TEXT:
                    await self._on_request(client, message.data)
        finally:
            if sender is not None:
                sender.cancel()
            self._clients.discard(client)
            self._set_watchers()
            await ws.close()
            # Routine: every closed tab and reload does it.
            log.debug("view: a browser left (%d still watching)", len(self._clients))
        return ws

    def _set_watchers(self) -> None:
        hub = self.backend.hub
        hub.clients = len(self._clients)
        hub.lidar_wanted = any(c.lidar for c in self._clients)

    async def _send(self, client: _Client, text: str) -> bool:
        """Hand `text` to the browser; False (and the browser dropped) if it cannot take it."""
        if client.ws.closed:
            return False
        try:
            await asyncio.wait_for(client.ws.send_str(text), SEND_TIMEOUT_S)
        except (TimeoutError, asyncio.TimeoutError):
            log.info("view: dropping a browser that does not keep up")
            await client.ws.close()
            return False
        except ConnectionError:  # the browser went (a closed tab): its departure is logged
            await client.ws.close()
            return False
        return True

    async def _send_frames(self, client: _Client) -> None:
        hub = self.backend.hub
        while not client.ws.closed:
            event = self._wake_event
            assert event is not None
            if hub.sequence <= client.sent:
                await event.wait()
                continue
            latest = hub.latest()
            if latest is None:
                continue
            client.sent = latest[0]
            if not await self._send(client, latest[1]):
                return

    async def _on_request(self, client: _Client, text: str) -> None:
        try:
            request: JsonValue = json.loads(text)
        except ValueError:
            await self._reply(client, {"ok": False, "error": "a request is JSON"})
            return
        op = request.get("op") if isinstance(request, dict) else None
        if op == "layers" and isinstance(request, dict):
            # Which layers this browser draws: the server's own business.
            client.lidar = request.get("lidar") is True
            self._set_watchers()
            return
        if self.readonly:
            await self._reply(client, {"ok": False, "op": op, "error": "the view is read-only"})
            return
        inbox = self.backend.inbox
        apply, capture = self.backend.apply, self.backend.capture
        if isinstance(op, str) and op in FIRE_AND_FORGET:
            inbox.post(functools.partial(apply, request))
            return

        loop = asyncio.get_running_loop()
        prepared = await loop.run_in_executor(None, self.backend.prepare, request)

        def run() -> Reply:
            reply = apply(prepared)
            capture()  # show the result at once, even paused or in sync mode
            return reply

        reply: Reply
        try:
            reply = await loop.run_in_executor(
                None, functools.partial(inbox.call, run, REQUEST_TIMEOUT_S)
            )
        except (LoopStoppedError, TimeoutError) as error:
            reply = {"ok": False, "op": op, "error": f"the simulation did not answer: {error}"}
        await self._reply(client, reply)

    async def _reply(self, client: _Client, reply: Reply) -> None:
        await self._send(client, json.dumps({"type": "reply", **reply}))

    async def _poll_graph(self) -> None:
        loop = asyncio.get_running_loop()
        polled_at = -float("inf")
        while True:
            await asyncio.sleep(GRAPH_WAKE_S)
            fresh = self._graph is not None and loop.time() - polled_at < GRAPH_PERIOD_S
            if not self._clients or fresh:
                continue
            polled_at = loop.time()
            try:
                state = await loop.run_in_executor(None, self.backend.system_state)
            except Exception as error:  # the master may be gone or slow; keep serving
                log.debug("view: no ROS graph from the master: %s", error)
                continue
            self._graph = json.dumps({"type": "graph", "nodes": nodes_of(state)})
            for client in list(self._clients):
                await self._send(client, self._graph)
