"""Which websocket server the live view uses: aiohttp against websockets.

Each library serves the same job in this process: a ~20 KB text frame broadcast at
30 frames/s to N websocket clients that live in a child process. Reported: the
server's CPU time per second of wall time (all its threads), per client, and the
frames the clients received. Run: .venv/bin/python benchmarks/view_server_libraries.py
"""

from __future__ import annotations

import asyncio
import json
import resource
import subprocess
import sys
import time

from aiohttp import web
from loopback import free_port
from websocket_browsers import SCRIPT as BROWSERS_SCRIPT
from websockets.asyncio.server import serve

FRAME = json.dumps({"objects": [[round(i * 0.37, 2)] * 6 for i in range(400)]})
RATE_HZ = 30
SECONDS = 5.0
CLIENTS = (1, 10)


def cpu_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


async def broadcast(clients: set, send) -> None:
    period = 1.0 / RATE_HZ
    while True:
        await asyncio.sleep(period)
        await asyncio.gather(*(send(ws) for ws in list(clients)), return_exceptions=True)


async def serve_aiohttp(port: int) -> tuple[object, set]:
    clients: set = set()

    async def handler(request: web.Request) -> web.WebSocketResponse:
        ws = web.WebSocketResponse()
        await ws.prepare(request)
        clients.add(ws)
        async for _ in ws:
            pass
        clients.discard(ws)
        return ws

    app = web.Application()
    app.router.add_get("/ws", handler)
    runner = web.AppRunner(app, access_log=None)
    await runner.setup()
    await web.TCPSite(runner, "127.0.0.1", port).start()
    task = asyncio.create_task(broadcast(clients, lambda ws: ws.send_str(FRAME)))
    return (runner, task), clients


async def serve_websockets(port: int) -> tuple[object, set]:
    clients: set = set()

    async def handler(ws) -> None:
        clients.add(ws)
        try:
            await ws.wait_closed()
        finally:
            clients.discard(ws)

    server = await serve(handler, "127.0.0.1", port, compression=None)
    task = asyncio.create_task(broadcast(clients, lambda ws: ws.send(FRAME)))
    return (server, task), clients


async def measure(library: str, n: int) -> dict[str, float]:
    port = free_port()
    start = serve_aiohttp if library == "aiohttp" else serve_websockets
    (server, task), clients = await start(port)
    child = await asyncio.create_subprocess_exec(
        sys.executable,
        str(BROWSERS_SCRIPT),
        f"ws://127.0.0.1:{port}/ws",
        str(n),
        str(SECONDS + 1.0),
        stdout=subprocess.PIPE,
    )
    deadline = time.monotonic() + 10.0
    while len(clients) < n:
        if time.monotonic() > deadline:
            raise RuntimeError(f"{library}: only {len(clients)} of {n} clients connected")
        await asyncio.sleep(0.05)
    cpu0, wall0 = cpu_seconds(), time.monotonic()
    await asyncio.sleep(SECONDS)
    cpu, wall = cpu_seconds() - cpu0, time.monotonic() - wall0
    out, _ = await asyncio.wait_for(child.communicate(), 30.0)
    task.cancel()
    if library == "aiohttp":
        await server.cleanup()
    else:
        server.close()
        await server.wait_closed()
    return {
        "cpu_percent": 100.0 * cpu / wall,
        "cpu_percent_per_client": 100.0 * cpu / wall / n,
        "frames_received_per_client_s": int(out) / n / (SECONDS + 1.0),
    }


def main() -> None:
    print(f"frame {len(FRAME)} bytes at {RATE_HZ}/s for {SECONDS:.0f} s")
    print(f"{'library':<11}{'clients':>8}{'server CPU %':>14}{'per client %':>14}{'frames/s':>10}")
    for library in ("aiohttp", "websockets"):
        for n in CLIENTS:
            r = asyncio.run(measure(library, n))
            print(
                f"{library:<11}{n:>8}{r['cpu_percent']:>14.2f}"
                f"{r['cpu_percent_per_client']:>14.2f}{r['frames_received_per_client_s']:>10.1f}"
            )


if __name__ == "__main__":
    main()
