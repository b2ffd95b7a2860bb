"""A small asyncio HTTP/1.1 server for request/response protocols such as XML-RPC: the I/O around
kame.protocol.http's request reader.

Rules:
- One asyncio.Protocol per connection parses requests straight from data_received and calls a
  synchronous handler inline on the event loop: no task, no thread hop per request. The handler
  must be quick and must not block (the master's handlers are pure in-memory code).
- HTTP itself (keep-alive, pipelining, Content-Length, 411/413/431/...) is kame.protocol.http's.
- Everything a client can make us hold is bounded: header bytes, body bytes (413 and close
  without reading the body), total bytes being received across connections (503), the number of
  connections (the longest-idle connection is closed to make room, else the new one is), the time
  a connection may stay silent, and the time a started request may take to arrive. A client
  that stops reading its responses is paused, not buffered for.
- Refusals are logged at WARNING with the peer address; the server keeps serving everyone else.
- Per request, the usual case costs little: the reader parses a request that arrives in one
  segment in place and looks up heads seen before in a cache shared by the server's connections,
  and the deadline is set once per batch of data, not per request.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import NamedTuple

from kame.net import peers
from kame.net.http_date import current_date_header
from kame.protocol.http import Refusal, RequestReader, encode_response, new_head_cache

log = logging.getLogger("kame.net.http")


class HttpRequest(NamedTuple):  # a NamedTuple: a frozen dataclass costs a microsecond more per request
    method: str
    path: str
    headers: Mapping[str, str]  # names lower-cased; read-only, shared by requests with equal heads
    body: bytes
    peer: str


class HttpResponse(NamedTuple):  # a NamedTuple too: built once per request
    status: int
    body: bytes = b""
    content_type: str = "text/xml"


Handler = Callable[[HttpRequest], HttpResponse]


@dataclass(frozen=True)
class ServerLimits:
    max_body: int = 32 * 1024 * 1024
    max_header: int = 64 * 1024
    max_receiving: int = 256 * 1024 * 1024  # body bytes being received, all connections together
    max_connections: int = 1000
    idle_timeout: float = 60.0  # a connection with no request under way is closed after this
    request_timeout: float = 30.0  # a request must arrive completely within this once started


@dataclass
class _Budget:
    receiving: int = 0


@dataclass(eq=False)
class _Connection(asyncio.Protocol):
    server: HttpServer
    reader: RequestReader
    transport: asyncio.Transport | None = None
    peer: str = "?"
    receiving: bool = False  # the deadline set is the current request's request_timeout
    reserved: int = 0  # bytes of the shared receive budget this connection holds
    deadline: float = 0.0
    timer: asyncio.TimerHandle | None = None
    paused: bool = False
    served: int = 0  # requests answered on this connection

    # ---------------------------------------------------------------------------- asyncio

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        assert isinstance(transport, asyncio.Transport)
        self.transport = transport
        peer = transport.get_extra_info("peername")
        self.peer = f"{peer[0]}:{peer[1]}" if isinstance(peer, tuple) else str(peer)
        if not peers.admit(peer, "master"):
            transport.close()
            return
        if not self.server._admit(self):
            log.warning("refusing connection from %s: too many connections", self.peer)
            transport.abort()
            return
        self._arm(self.server.limits.idle_timeout)

    def connection_lost(self, exc: Exception | None) -> None:
        self.server._forget(self)
        self._release()
        if self.timer is not None:
            self.timer.cancel()
            self.timer = None
        self.transport = None

    def data_received(self, data: bytes) -> None:
        self.reader.feed(data)
        self._process()

    def pause_writing(self) -> None:
        # The client does not read its responses: stop reading its requests until it does.
        self.paused = True
        if self.transport is not None:
            self.transport.pause_reading()

    def resume_writing(self) -> None:
        self.paused = False
        if self.transport is not None:
            self.transport.resume_reading()
            self._process()

    # ---------------------------------------------------------------------------- requests

    def _process(self) -> None:
        """Serve the complete requests received, then set the connection's deadline."""
        reader = self.reader
        served = False
        while self.transport is not None and not self.paused:
            request = reader.next_request()
            if request is None:
                break
            if isinstance(request, Refusal):
                self._refuse(request.status, request.why)
                return
            if self.reserved:
                self._release()
            try:
                response = self.server.handler(
                    HttpRequest(request.method, request.path, request.headers, request.body, self.peer))
            except Exception:
                log.exception("handler failed for %s %s from %s", request.method, request.path, self.peer)
                response = HttpResponse(500, b"", "text/plain")
            self._send(response, request.version, request.keep_alive)
            if not request.keep_alive:
                return
            self.served += 1
            served = True
        if self.transport is None:
            return
        if served:
            self.server._touch(self)
        # One deadline per batch: a request that arrived whole never needed its own.
        if reader.pending:
            wanted = reader.body_wanted
            if wanted and not self.reserved and not self.server._reserve(self, wanted):
                self._refuse(503, f"busy: cannot take {wanted} more bytes now")
                return
            if served or not self.receiving:
                # a request has started arriving: it must be complete within request_timeout
                self.receiving = True
                self._arm(self.server.limits.request_timeout)
        elif served:
            self.receiving = False
            self._arm(self.server.limits.idle_timeout)

    def _send(self, response: HttpResponse, version: str, keep_alive: bool) -> None:
        assert self.transport is not None
        self.transport.write(encode_response(response.status, response.body, response.content_type, version,
                                             keep_alive, current_date_header()))
        if not keep_alive:
            self.transport.close()

    def _refuse(self, status: int, why: str) -> None:
        log.warning("refusing request from %s: %s (%d)", self.peer, why, status)
        if self.transport is not None:
            self._send(HttpResponse(status, b"", "text/plain"), "HTTP/1.1", keep_alive=False)
        self.receiving = False

    # ---------------------------------------------------------------------------- timing and budget

    def _arm(self, timeout: float) -> None:
        loop = self.server.loop
        self.deadline = loop.time() + timeout
        if self.timer is None or self.timer.when() > self.deadline:
            if self.timer is not None:
                self.timer.cancel()
            self.timer = loop.call_at(self.deadline, self._check_deadline)

    def _check_deadline(self) -> None:
        # One timer per connection, moved later lazily: activity that pushes the deadline back
        # only updates `deadline`, so a request costs a clock read, not a timer cancel and create.
        self.timer = None
        if self.transport is None:
            return
        now = self.server.loop.time()
        if now < self.deadline:
            self.timer = self.server.loop.call_at(self.deadline, self._check_deadline)
            return
        if self.reader.pending:
            self._refuse(408, "request not completed in time")
        else:
            log.info("closing idle connection from %s", self.peer)
            self.transport.close()

    def _release(self) -> None:
        self.server._budget.receiving -= self.reserved
        self.reserved = 0

    @property
    def idle(self) -> bool:
        return not self.reader.pending


class HttpServer:
    """Serves `handler` on (host, port). Use `await start()`, then `await close()`."""

    def __init__(self, handler: Handler, host: str, port: int, limits: ServerLimits | None = None) -> None:
        self.handler = handler
        self.host = host
        self.port = port
        self.limits = limits or ServerLimits()
        self._budget = _Budget()
        self._heads = new_head_cache()
        self._connections: dict[_Connection, None] = {}  # least recently active first
        self._evicted = 0  # connections closed to make room since the last warning about it
        self._evict_logged = float("-inf")
        self._server: asyncio.Server | None = None
        self._loop: asyncio.AbstractEventLoop | None = None

    @property
    def loop(self) -> asyncio.AbstractEventLoop:
        assert self._loop is not None, "server not started"
        return self._loop

    async def start(self) -> int:
        """Bind and listen; returns the bound port (useful with port 0)."""
        self._loop = asyncio.get_running_loop()
        self._server = await self._loop.create_server(
            lambda: _Connection(self, RequestReader(self.limits.max_header, self.limits.max_body, self._heads)),
            self.host, self.port, reuse_address=True, backlog=1024)
        sock = self._server.sockets[0]
        self.port = int(sock.getsockname()[1])
        return self.port

    async def close(self) -> None:
        if self._server is not None:
            self._server.close()
            for conn in list(self._connections):
                if conn.transport is not None:
                    conn.transport.abort()
            await self._server.wait_closed()
            self._server = None

    @property
    def connection_count(self) -> int:
        return len(self._connections)

    def _admit(self, conn: _Connection) -> bool:
        if len(self._connections) >= self.limits.max_connections:
            # Make room by closing a connection that is doing nothing: first one that never sent
            # a request (a flood), else the one idle the longest. Python's XML-RPC client
            # reconnects once by itself when a kept-alive connection turns out closed. When none
            # is idle (clients that start a request and stall: they used to lock everyone else
            # out until their request_timeout), the one whose deadline is nearest goes: it would
            # be closed soonest anyway.
            idle = [c for c in self._connections if c.idle]
            victim = next((c for c in idle if not c.served), idle[0] if idle else None)
            if victim is None:
                victim = min(self._connections, key=lambda c: c.deadline, default=None)
            if victim is None:
                return False
            self._evicted += 1
            now = self.loop.time()
            if now - self._evict_logged >= 1.0:  # a flood of connections is not a flood of lines
                more = f" ({self._evicted - 1} more since the last such line)" if self._evicted > 1 else ""
                log.warning("too many connections: closing %s connection from %s to make room%s",
                            "idle" if victim.idle else "stalled", victim.peer, more)
                self._evict_logged, self._evicted = now, 0
            self._forget(victim)
            if victim.transport is not None:
                victim.transport.abort()
        self._connections[conn] = None
        return True

    def _touch(self, conn: _Connection) -> None:
        # keep `_connections` ordered by last activity, least recent first
        if self._connections.pop(conn, False) is None:
            self._connections[conn] = None

    def _forget(self, conn: _Connection) -> None:
        self._connections.pop(conn, None)

    def _reserve(self, conn: _Connection, length: int) -> bool:
        if self._budget.receiving + length > self.limits.max_receiving:
            return False
        self._budget.receiving += length
        conn.reserved = length
        return True
