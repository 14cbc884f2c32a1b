"""The view's server over real sockets: a simulation loop on its thread, aiohttp clients
standing in for browsers (the page itself is tested in Chromium, tests/e2e)."""

from __future__ import annotations

import asyncio
import contextlib
import gzip
import json
import socket
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass

import aiohttp
import pytest

from egosim.app.inbox import Inbox
from egosim.app.loop import SimulationLoop
from egosim.bridge.context import BridgeContext
from egosim.view.controls import ViewControls
from egosim.view.hub import MAX_FRAME_RATE_HZ, FrameHub
from egosim.view.server import ViewBackend, ViewServer, ViewServerError
from egosim.view.snapshot import encode, map_snapshot
from egosim.view.stage import ViewStage

WAIT_S = 20.0


@dataclass
class Running:
    server: ViewServer
    context: BridgeContext

    @property
    def ws_url(self) -> str:
        return f"ws://127.0.0.1:{self.server.port}/ws"


@contextlib.contextmanager
def serve(context: BridgeContext, readonly: bool = False, port: int = 0) -> Iterator[Running]:
    inbox = Inbox()
    hub = FrameHub()
    controls = ViewControls(context, None)
    stage = ViewStage(context, hub, controls, "real")
    backend = ViewBackend(
        hub=hub,
        inbox=inbox,
        prepare=controls.prepare,
        apply=controls.apply,
        capture=stage.capture,
        history=lambda: encode(stage.history.message()),
        map_json=lambda: encode(map_snapshot(context.world.map)),
        system_state=lambda: ([["/Ego_topic", ["/egosim"]]], [], []),
        hello={"type": "hello", "clock_mode": "real"},
    )
    server = ViewServer(backend, "127.0.0.1", port, readonly)
    stop = threading.Event()

    def step() -> None:
        context.world.step(0.01)
        stage.after_step()

    loop = SimulationLoop(step, inbox, 0.01, 1.0, stop)
    thread = threading.Thread(target=loop.run)
    thread.start()
    try:
        server.start()
        yield Running(server, context)
    finally:
        server.close()
        stop.set()
        thread.join(WAIT_S)
        inbox.close()


@pytest.fixture
def running(town: BridgeContext) -> Iterator[Running]:
    with serve(town) as served:
        yield served


async def receive_until(ws: aiohttp.ClientWebSocketResponse, kind: str) -> dict:
    """The next message of type `kind` (others are skipped)."""
    deadline = time.monotonic() + WAIT_S
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            raise AssertionError(f"no {kind} message within {WAIT_S} s")
        message = json.loads((await asyncio.wait_for(ws.receive(), left)).data)
        if message["type"] == kind:
            return message


def test_a_browser_gets_hello_frames_and_the_ros_graph(running: Running) -> None:
    async def browse() -> tuple[dict, dict, dict, int]:
        async with aiohttp.ClientSession() as session, session.ws_connect(running.ws_url) as ws:
            hello = await receive_until(ws, "hello")
            frame = await receive_until(ws, "frame")
            graph = await receive_until(ws, "graph")
            # Frames keep to a 30/s grid: over a span, at most its share plus the
            # frame on each end (and the one taken for a newcomer).
            frames, start = 0, time.monotonic()
            while time.monotonic() - start < 2.0:
                await receive_until(ws, "frame")
                frames += 1
            return hello, frame, graph, frames / (time.monotonic() - start)

    hello, frame, graph, frames = asyncio.run(browse())
    assert hello["readonly"] is False
    assert frame["egos"][0]["id"] == running.context.world.egos[0].unique_id
    assert graph["nodes"][0]["name"] == "/egosim"
    assert 0 < frames <= MAX_FRAME_RATE_HZ + 1.5


def test_the_map_comes_gzipped_and_the_page_from_the_package(running: Running) -> None:
    async def fetch() -> tuple[dict, str, str]:
        base = f"http://127.0.0.1:{running.server.port}"
        async with aiohttp.ClientSession(auto_decompress=False) as session:
            async with session.get(f"{base}/map.json") as response:
                assert response.headers["Content-Encoding"] == "gzip"
                map_data = json.loads(gzip.decompress(await response.read()))
            async with session.get(f"{base}/") as response:
                page = await response.text()
            async with session.get(f"{base}/static/view.js") as response:
                script = await response.text()
        return map_data, page, script

    map_data, page, script = asyncio.run(fetch())
    assert map_data["name"] == "town"
    assert "/static/view.js" in page
    assert "WebSocket" in script
    assert "http" not in page.replace("http-equiv", "")  # nothing fetched from elsewhere


def test_a_pause_request_reaches_the_world_through_the_inbox(running: Running) -> None:
    async def pause() -> tuple[dict, dict]:
        async with aiohttp.ClientSession() as session, session.ws_connect(running.ws_url) as ws:
            await ws.send_str(json.dumps({"op": "pause"}))
            reply = await receive_until(ws, "reply")
            while not (frame := await receive_until(ws, "frame"))["paused"]:
                pass
            return reply, frame

    reply, _ = asyncio.run(pause())
    assert reply == {"type": "reply", "ok": True, "op": "pause"}
    assert running.context.world.paused
    held = running.context.world.sim_time
    time.sleep(0.2)
    assert running.context.world.sim_time == held


def test_a_read_only_view_refuses_controls(town: BridgeContext) -> None:
    async def pause(url: str) -> tuple[dict, dict]:
        async with aiohttp.ClientSession() as session, session.ws_connect(url) as ws:
            hello = await receive_until(ws, "hello")
            await ws.send_str(json.dumps({"op": "pause"}))
            return hello, await receive_until(ws, "reply")

    with serve(town, readonly=True) as running:
        hello, reply = asyncio.run(pause(running.ws_url))
        assert hello["readonly"] is True
        assert reply["ok"] is False
        assert "read-only" in reply["error"]
        assert not town.world.paused


def test_a_bad_request_is_answered(running: Running) -> None:
    async def send_garbage() -> list[dict]:
        async with aiohttp.ClientSession() as session, session.ws_connect(running.ws_url) as ws:
            await ws.send_str("{not json")
            first = await receive_until(ws, "reply")
            await ws.send_str(json.dumps({"op": "load", "name": "/etc/passwd"}))
            second = await receive_until(ws, "reply")
            await ws.send_str(json.dumps({"op": ["keys"]}))
            return [first, second, await receive_until(ws, "reply")]

    first, second, third = asyncio.run(send_garbage())
    assert not first["ok"]
    assert not second["ok"]
    assert "outside the data roots" in second["error"]
    assert not third["ok"]
    assert "'op' string" in third["error"]


def test_a_taken_port_is_a_clear_error(town: BridgeContext) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        with (
            pytest.raises(ViewServerError, match="cannot serve"),
            serve(town, port=taken.getsockname()[1]),
        ):
            pass


def test_a_late_browser_gets_the_last_minute_before_its_first_frame(running: Running) -> None:
    world = running.context.world
    deadline = time.monotonic() + WAIT_S
    while world.sim_time < 1.0:  # the loop runs in real time, with nobody watching
        assert time.monotonic() < deadline, "the simulation did not run 1 s"
        time.sleep(0.05)

    async def browse() -> list[dict]:
        async with aiohttp.ClientSession() as session, session.ws_connect(running.ws_url) as ws:
            messages: list[dict] = []
            while not messages or messages[-1]["type"] != "frame":
                messages.append(json.loads((await asyncio.wait_for(ws.receive(), WAIT_S)).data))
            return messages

    messages = asyncio.run(browse())
    kinds = [m["type"] for m in messages]
    assert kinds.index("hello") < kinds.index("history") < kinds.index("frame")
    history, frame = messages[kinds.index("history")], messages[-1]
    (ego,) = history["egos"]
    assert ego["id"] == world.egos[0].unique_id
    assert ego["t"][0] < 0.2 and len(ego["t"]) >= 10  # from the start, not from the connect
    # The first frame is taken for this browser: never older than the history.
    assert frame["sim_time"] >= ego["t"][-1] >= 0.9
