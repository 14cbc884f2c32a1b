"""N websocket clients that read frames like the live view's page: for the view
benchmarks, run as a process of its own so it does not share the server's CPU time.

Usage: python benchmarks/websocket_browsers.py URL N SECONDS   (prints the frames read)
"""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import aiohttp

SCRIPT = Path(__file__)


async def one(url: str, seconds: float, counts: list[int], index: int) -> None:
    async with aiohttp.ClientSession() as session, session.ws_connect(url, max_msg_size=0) as ws:
        end = asyncio.get_running_loop().time() + seconds
        while (left := end - asyncio.get_running_loop().time()) > 0:
            try:
                await asyncio.wait_for(ws.receive(), left)
            except asyncio.TimeoutError:
                break
            counts[index] += 1


async def main(url: str, n: int, seconds: float) -> None:
    counts = [0] * n
    await asyncio.gather(*(one(url, seconds, counts, i) for i in range(n)))
    print(sum(counts))


if __name__ == "__main__":
    asyncio.run(main(sys.argv[1], int(sys.argv[2]), float(sys.argv[3])))
