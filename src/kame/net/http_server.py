"""A small asyncio HTTP/1.1 server for request/response protocols such as XML-RPC.

Rules:
- One asyncio.Protocol per connection parses requests straight from data_received and calls a
  synchronous handler inline on the event loop: no task, no thread hop per request. The handler
  must be quick and must not block (the master's handlers are pure in-memory code).
- Keep-alive as HTTP/1.1 says (1.0 only with `Connection: keep-alive`); pipelined requests are
  answered in order. Bodies need Content-Length (chunked requests get 411, as XML-RPC clients
  never send them).
- Everything a client can make us hold is bounded: header bytes, body bytes (413 and close
  without reading the body), total bytes being received across connections (503), the number of
  connections (the longest-idle connection is closed to make room, else the new one is), the time
  a connection may stay silent, and the time a started request may take to arrive. A client
  that stops reading its responses is paused, not buffered for.
- Refusals are logged at WARNING with the peer address; the server keeps serving everyone else.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from dataclasses import dataclass, field

log = logging.getLogger("kame.net.http")

_REASONS = {
    200: "OK", 400: "Bad Request", 404: "Not Found", 408: "Request Timeout", 411: "Length Required",
    413: "Payload Too Large", 431: "Request Header Fields Too Large", 500: "Internal Server Error",
    501: "Not Implemented", 503: "Service Unavailable", 505: "HTTP Version Not Supported",
}


@dataclass(frozen=True)
class HttpRequest:
    method: str
    path: str
    headers: dict[str, str]  # names lower-cased
    body: bytes
    peer: str


@dataclass(frozen=True)
class HttpResponse:
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
    transport: asyncio.Transport | None = None
    peer: str = "?"
    buf: bytearray = field(default_factory=bytearray)
    # the request being received: its head, once parsed, and its Content-Length
    head: tuple[str, str, str, dict[str, str]] | None = None
    need: int = 0
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
        if not self.buf and self.head is None:
            # a new request starts: it must arrive within request_timeout
            self._arm(self.server.limits.request_timeout)
        self.buf += data
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
        limits = self.server.limits
        while self.transport is not None and not self.paused:
            if self.head is None:
                end = self.buf.find(b"\r\n\r\n")
                if end < 0:
                    if len(self.buf) > limits.max_header:
                        self._refuse(431, "request head too large")
                    return
                if end > limits.max_header:
                    self._refuse(431, "request head too large")
                    return
                if not self._parse_head(bytes(self.buf[:end])):
                    return
                del self.buf[: end + 4]
            if len(self.buf) < self.need:
                return
            body = bytes(self.buf[: self.need])
            del self.buf[: self.need]
            assert self.head is not None
            method, path, version, headers = self.head
            self.head = None
            self._release()
            keep_alive = _keep_alive(version, headers)
            try:
                response = self.server.handler(HttpRequest(method, path, headers, body, self.peer))
            except Exception:
                log.exception("handler failed for %s %s from %s", method, path, self.peer)
                response = HttpResponse(500, b"", "text/plain")
            self._send(response, version, keep_alive)
            if not keep_alive:
                return
            self.served += 1
            self.server._touch(self)
            self._arm(limits.idle_timeout if not self.buf else limits.request_timeout)

    def _parse_head(self, raw: bytes) -> bool:
        lines = raw.decode("latin-1").split("\r\n")
        parts = lines[0].split(" ")
        if len(parts) != 3 or not parts[2].startswith("HTTP/"):
            self._refuse(400, f"bad request line {lines[0][:80]!r}")
            return False
        method, path, version = parts
        if version not in ("HTTP/1.1", "HTTP/1.0"):
            self._refuse(505, f"unsupported {version[:20]!r}")
            return False
        headers: dict[str, str] = {}
        for line in lines[1:]:
            name, sep, value = line.partition(":")
            if not sep:
                self._refuse(400, "bad header line")
                return False
            headers[name.strip().lower()] = value.strip()
        if "chunked" in headers.get("transfer-encoding", "").lower():
            self._refuse(411, "chunked request body")
            return False
        try:
            length = int(headers.get("content-length", "0"))
        except ValueError:
            length = -1
        if length < 0:
            self._refuse(400, "bad Content-Length")
            return False
        if length > self.server.limits.max_body:
            self._refuse(413, f"body of {length} bytes")
            return False
        if not self.server._reserve(self, length):
            self._refuse(503, f"busy: cannot take {length} more bytes now")
            return False
        self.head = (method, path, version, headers)
        self.need = length
        return True

    def _send(self, response: HttpResponse, version: str, keep_alive: bool) -> None:
        assert self.transport is not None
        head = (
            f"{version} {response.status} {_REASONS.get(response.status, 'Unknown')}\r\n"
            f"Content-type: {response.content_type}\r\nContent-length: {len(response.body)}\r\n"
        )
        if not keep_alive:
            head += "Connection: close\r\n"
        self.transport.write(head.encode("latin-1") + b"\r\n" + response.body)
        if not keep_alive:
            self.transport.close()

    def _refuse(self, status: int, why: str) -> None:
        log.warning("refusing request from %s: %s (%d)", self.peer, why, status)
        if self.transport is not None:
            self._send(HttpResponse(status, b"", "text/plain"), "HTTP/1.1", keep_alive=False)
        self.buf.clear()
        self.head = None

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
        if self.buf or self.head is not None:
            self._refuse(408, "request not completed in time")
        else:
            log.info("closing idle connection from %s", self.peer)
            self.transport.close()

    def _release(self) -> None:
        self.server._budget.receiving -= self.reserved
        self.reserved = 0

    @property
    def idle(self) -> bool:
        return not self.buf and self.head is None


def _keep_alive(version: str, headers: dict[str, str]) -> bool:
    connection = headers.get("connection", "").lower()
    if version == "HTTP/1.1":
        return "close" not in connection
    return "keep-alive" in connection


class HttpServer:
    """Serves `handler` on (host, port). Use `await start()`, then `await close()`."""

    def __init__(self, handler: Handler, host: str, port: int, limits: ServerLimits | None = None) -> None:
        self.handler = handler
        self.host = host
        self.port = port
        self.limits = limits or ServerLimits()
        self._budget = _Budget()
        self._connections: dict[_Connection, None] = {}  # least recently active first
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
            lambda: _Connection(self), self.host, self.port, reuse_address=True, backlog=1024)
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
            # reconnects once by itself when a kept-alive connection turns out closed.
            idle = [c for c in self._connections if c.idle]
            victim = next((c for c in idle if not c.served), idle[0] if idle else None)
            if victim is None:
                return False
            log.warning("closing idle connection from %s to make room", victim.peer)
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
