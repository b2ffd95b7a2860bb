"""rosmaster.master: a ROS master and parameter server started inside this process.

`Master(port).start()` serves kame's master (kame.master.server) from an event loop on a thread
this object owns; `stop()` closes the server and joins the thread. Port 0 picks a free port.
"""

from __future__ import annotations

import asyncio
import os
import threading

from kame.master.server import MasterServer
from kame.net.address import address_override, advertised_host, bind_host

DEFAULT_MASTER_PORT = 11311
NUM_WORKERS = 3  # upstream's XML-RPC worker count: accepted for its signature, kame's server is asyncio
START_TIMEOUT = 10.0

__all__ = ["DEFAULT_MASTER_PORT", "NUM_WORKERS", "Master"]


class Master:
    """A master on `port`; `uri` is set once started."""

    def __init__(self, port: int = DEFAULT_MASTER_PORT, num_workers: int = NUM_WORKERS) -> None:
        self.port = port
        self.num_workers = num_workers
        self.uri: str | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._thread: threading.Thread | None = None
        self._server: MasterServer | None = None

    def start(self) -> None:
        """Start serving (OSError when the port is taken)."""
        if self._thread is not None:
            return
        loop = asyncio.new_event_loop()
        self._loop = loop
        self._thread = threading.Thread(target=loop.run_forever, name="rosmaster", daemon=True)
        self._thread.start()

        async def start() -> str:
            override = address_override(os.environ)
            self._server = MasterServer(bind_host(override), self.port, advertised_host(override))
            return await self._server.start()

        try:
            self.uri = asyncio.run_coroutine_threadsafe(start(), loop).result(START_TIMEOUT)
        except BaseException:
            self.stop()
            raise
        assert self._server is not None
        self.port = self._server.port

    def ok(self) -> bool:
        """True while serving."""
        return self._thread is not None and self._thread.is_alive() and self.uri is not None

    def stop(self) -> None:
        """Close the server, end the loop and join its thread."""
        loop, thread, server = self._loop, self._thread, self._server
        if loop is None or thread is None:
            return

        async def close() -> None:
            if server is not None:
                await server.close()
            others = [t for t in asyncio.all_tasks() if t is not asyncio.current_task()]
            for task in others:
                task.cancel()
            await asyncio.gather(*others, return_exceptions=True)

        try:
            asyncio.run_coroutine_threadsafe(close(), loop).result(START_TIMEOUT)
        finally:
            loop.call_soon_threadsafe(loop.stop)
            thread.join(START_TIMEOUT)
            if not thread.is_alive():
                loop.close()
            self._loop = self._thread = self._server = None
            self.uri = None
