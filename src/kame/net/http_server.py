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
- Per request, the usual case costs little: a request that arrives in one segment is parsed from
  it without copying into the buffer, a request head seen before (a client repeats its own) is
  looked up instead of parsed, and the deadline is set once per batch of data, not per request.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from kame.net import peers

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
    headers: Mapping[str, str]  # names lower-cased; read-only, shared by requests with equal heads
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


# A parsed request head: method, path, version, headers, Content-Length, keep-alive.
_Head = tuple[str, str, str, Mapping[str, str], int, bool]
_HEAD_CACHE_SIZE = 256  # distinct heads remembered per server (a client repeats its own)
_HEAD_CACHE_MAX_BYTES = 1024  # longer heads are parsed every time, so the cache stays small


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
    head: _Head | None = None
    need: int = 0
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
        if self.buf:
            self.buf += data
            self._process(self.buf)
        else:
            # The usual case, a whole request in one segment, is parsed from `data` itself:
            # only an incomplete rest is copied into `buf`.
            self._process(data)

    def pause_writing(self) -> None:
        # The client does not read its responses: stop reading its requests until it does.
        self.paused = True
        if self.transport is not None:
            self.transport.pause_reading()

    def resume_writing(self) -> None:
        self.paused = False
        if self.transport is not None:
            self.transport.resume_reading()
            self._process(self.buf)

    # ---------------------------------------------------------------------------- requests

    def _process(self, data: bytes | bytearray) -> None:
        """Serve the complete requests in `data` (which is either `buf` or, with `buf` empty,
        what just arrived), keep the rest in `buf`, and set the connection's deadline."""
        limits = self.server.limits
        pos = 0
        served = False
        while self.transport is not None and not self.paused:
            if self.head is None:
                end = data.find(b"\r\n\r\n", pos)
                if end < 0:
                    if len(data) - pos > limits.max_header:
                        self._refuse(431, "request head too large")
                        return
                    break
                if end - pos > limits.max_header:
                    self._refuse(431, "request head too large")
                    return
                if not self._start_request(bytes(data[pos:end])):
                    return
                pos = end + 4
            need = self.need
            if len(data) - pos < need:
                break
            body = data[pos : pos + need]
            pos += need
            head = self.head
            assert head is not None
            method, path, version, headers, _, keep_alive = head
            self.head = None
            if self.reserved:
                self._release()
            try:
                response = self.server.handler(
                    HttpRequest(method, path, headers, body if type(body) is bytes else bytes(body), self.peer))
            except Exception:
                log.exception("handler failed for %s %s from %s", method, path, self.peer)
                response = HttpResponse(500, b"", "text/plain")
            self._send(response, version, keep_alive)
            if not keep_alive:
                return
            self.served += 1
            served = True
        if data is self.buf:
            del self.buf[:pos]
        elif pos < len(data):
            self.buf += memoryview(data)[pos:]
        if self.transport is None:
            return
        if served:
            self.server._touch(self)
        # One deadline per batch: a request that arrived whole never needed its own.
        if self.buf or self.head is not None:
            if served or not self.receiving:
                # a request has started arriving: it must be complete within request_timeout
                self.receiving = True
                self._arm(limits.request_timeout)
        elif served:
            self.receiving = False
            self._arm(limits.idle_timeout)

    def _start_request(self, raw: bytes) -> bool:
        """Take a request head (cached by its bytes: a client repeats the same head)."""
        heads = self.server._heads
        head = heads.get(raw)
        if head is None:
            head = self._parse_head(raw)
            if head is None:
                return False
            if len(raw) <= _HEAD_CACHE_MAX_BYTES:
                if len(heads) >= _HEAD_CACHE_SIZE:
                    heads.clear()
                heads[raw] = head
        length = head[4]
        if length and not self.server._reserve(self, length):
            self._refuse(503, f"busy: cannot take {length} more bytes now")
            return False
        self.head = head
        self.need = length
        return True

    def _parse_head(self, raw: bytes) -> _Head | None:
        lines = raw.decode("latin-1").split("\r\n")
        parts = lines[0].split(" ")
        if len(parts) != 3 or not parts[2].startswith("HTTP/"):
            self._refuse(400, f"bad request line {lines[0][:80]!r}")
            return None
        method, path, version = parts
        if version not in ("HTTP/1.1", "HTTP/1.0"):
            self._refuse(505, f"unsupported {version[:20]!r}")
            return None
        headers: dict[str, str] = {}
        for line in lines[1:]:
            name, sep, value = line.partition(":")
            if not sep:
                self._refuse(400, "bad header line")
                return None
            headers[name.strip().lower()] = value.strip()
        if "chunked" in headers.get("transfer-encoding", "").lower():
            self._refuse(411, "chunked request body")
            return None
        try:
            length = int(headers.get("content-length", "0"))
        except ValueError:
            length = -1
        if length < 0:
            self._refuse(400, "bad Content-Length")
            return None
        if length > self.server.limits.max_body:
            self._refuse(413, f"body of {length} bytes")
            return None
        return method, path, version, MappingProxyType(headers), length, _keep_alive(version, headers)

    def _send(self, response: HttpResponse, version: str, keep_alive: bool) -> None:
        assert self.transport is not None
        key = (version, response.status, response.content_type, keep_alive)
        head = _RESPONSE_HEADS.get(key)
        if head is None:
            head = _RESPONSE_HEADS[key] = _response_head(*key)
        body = response.body
        self.transport.write(head[0] + b"%d" % len(body) + head[1] + body)
        if not keep_alive:
            self.transport.close()

    def _refuse(self, status: int, why: str) -> None:
        log.warning("refusing request from %s: %s (%d)", self.peer, why, status)
        if self.transport is not None:
            self._send(HttpResponse(status, b"", "text/plain"), "HTTP/1.1", keep_alive=False)
        self.buf.clear()
        self.head = None
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


def _response_head(version: str, status: int, content_type: str, keep_alive: bool) -> tuple[bytes, bytes]:
    """The response head's bytes before and after the Content-length value."""
    before = f"{version} {status} {_REASONS.get(status, 'Unknown')}\r\nContent-type: {content_type}\r\nContent-length: "
    after = "\r\n" if keep_alive else "\r\nConnection: close\r\n"
    return before.encode("latin-1"), (after + "\r\n").encode("latin-1")


_RESPONSE_HEADS: dict[tuple[str, int, str, bool], tuple[bytes, bytes]] = {}


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
        self._heads: dict[bytes, _Head] = {}
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
