"""A small threaded HTTP/1.1 server for a node's XML-RPC API (the "slave" API).

A node gets few calls (requestTopic, publisherUpdate, getBusInfo, ...), so one thread per
connection is plenty, and it keeps asyncio out of every node's start-up. The listening
socket is bound in the constructor, so its port can be advertised before serving starts.
Bounded like the master's server: header and body sizes, idle time, the time a started
request may take to arrive, and the number of connections; at that limit the connection that has
been quiet longest is closed to make room, so clients that connect and stall can never lock the
master's publisherUpdate (or anyone else) out.
"""

from __future__ import annotations

import logging
import socket
import threading
import time
from collections.abc import Callable

from kame.net import peers
from kame.net.stream import AcceptStarvation, peer_of

log = logging.getLogger("kame.net.rpc")

MAX_HEAD = 64 * 1024
MAX_BODY = 32 * 1024 * 1024
MAX_CONNECTIONS = 64
IDLE_TIMEOUT = 60.0
REQUEST_TIMEOUT = 30.0  # a request must arrive completely within this once its first byte has

# handler(body) -> response body (text/xml); it runs on the connection's thread.
RpcHandler = Callable[[bytes], bytes]


class RpcServer:
    def __init__(self, host: str, port: int, handler: RpcHandler, name: str = "kame-rpc") -> None:
        family = socket.AF_INET6 if ":" in host else socket.AF_INET
        self.sock = socket.socket(family, socket.SOCK_STREAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.bind((host, port))
        self.sock.listen(128)
        self.port: int = self.sock.getsockname()[1]
        self._handler = handler
        self._name = name
        self._closing = False
        self._lock = threading.Lock()
        # each open connection -> when it last received bytes or answered a request
        self._connections: dict[socket.socket, float] = {}
        self._connection_threads: set[threading.Thread] = set()
        self._starved = AcceptStarvation(self.sock)
        self._thread = threading.Thread(target=self._accept_loop, name=name, daemon=True)

    def start(self) -> None:
        self._thread.start()

    def close(self, timeout: float = 2.0) -> None:
        """Stop accepting, end every connection and wait up to `timeout` for their threads."""
        deadline = time.monotonic() + timeout
        self._closing = True
        self._starved.stop()
        try:
            self.sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        self.sock.close()
        if self._thread.is_alive() and self._thread is not threading.current_thread():
            self._thread.join(max(0.0, deadline - time.monotonic()))
        with self._lock:  # the accept loop has ended: no connection comes after this
            connections = list(self._connections)
            threads = [t for t in self._connection_threads if t is not threading.current_thread()]
        for conn in connections:
            try:
                conn.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
        for thread in threads:
            thread.join(max(0.0, deadline - time.monotonic()))

    def _accept_loop(self) -> None:
        starved = self._starved
        last_warning, evicted = -1.0, 0
        while not self._closing:
            try:
                conn, addr = self.sock.accept()
            except OSError as exc:
                if self._closing:
                    return
                starved.failed(exc)
                continue
            starved.ok()
            if not peers.admit(addr, self._name):
                conn.close()
                continue
            with self._lock:
                quietest = None
                if len(self._connections) >= MAX_CONNECTIONS:
                    quietest = min(self._connections, key=self._connections.__getitem__)
                    del self._connections[quietest]
                self._connections[conn] = time.monotonic()
            if quietest is not None:
                # one line a second at most, with a count: a flood of connections is not a flood of lines
                now = time.monotonic()
                if now - last_warning >= 1.0:
                    more = f" (and {evicted} more since the last warning)" if evicted else ""
                    log.warning("too many XML-RPC connections: closing the one quiet longest (%s) for %s%s",
                                peer_of(quietest), addr, more)
                    last_warning, evicted = now, 0
                else:
                    evicted += 1
                try:
                    quietest.shutdown(socket.SHUT_RDWR)  # its thread sees the end and closes it
                except OSError:
                    pass
            thread = threading.Thread(target=self._serve, args=(conn,), name=f"{self._name}-conn", daemon=True)
            with self._lock:
                self._connection_threads = {t for t in self._connection_threads if t.is_alive()}
                self._connection_threads.add(thread)
                thread.start()

    def _serve(self, conn: socket.socket) -> None:
        conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        buf = bytearray()

        def touch() -> None:
            with self._lock:
                if conn in self._connections:
                    self._connections[conn] = time.monotonic()

        try:
            while not self._closing:
                request = _read_request(conn, buf, touch)
                if request is None:
                    return
                body, keep_alive, status = request
                if status != 200:
                    conn.sendall(_response(status, b"", False))
                    return
                try:
                    answer = self._handler(body)
                except Exception:
                    log.exception("XML-RPC handler failed")
                    conn.sendall(_response(500, b"", False))
                    return
                conn.sendall(_response(200, answer, keep_alive))
                touch()
                if not keep_alive:
                    return
        except OSError:
            return
        finally:
            with self._lock:
                self._connections.pop(conn, None)
            conn.close()


_REASONS = {200: "OK", 400: "Bad Request", 411: "Length Required", 413: "Payload Too Large",
            431: "Request Header Fields Too Large", 500: "Internal Server Error"}


def _response(status: int, body: bytes, keep_alive: bool) -> bytes:
    head = (
        f"HTTP/1.1 {status} {_REASONS.get(status, 'Error')}\r\nServer: kame\r\nContent-Type: text/xml\r\n"
        f"Content-Length: {len(body)}\r\nConnection: {'keep-alive' if keep_alive else 'close'}\r\n\r\n"
    )
    return head.encode("latin-1") + body


def _recv(conn: socket.socket, size: int, deadline: float | None) -> bytes:
    """recv, waiting at most IDLE_TIMEOUT, or until `deadline` once a request has started."""
    if deadline is not None:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise TimeoutError("request not received in time")
        conn.settimeout(min(IDLE_TIMEOUT, remaining))
    return conn.recv(size)


def _read_request(conn: socket.socket, buf: bytearray,
                  touch: Callable[[], None] = lambda: None) -> tuple[bytes, bool, int] | None:
    """One request from `buf` + the socket: (body, keep_alive, status); None at a clean end.
    Raises OSError (TimeoutError) when the peer goes quiet or a request takes too long."""
    deadline = time.monotonic() + REQUEST_TIMEOUT if buf else None
    conn.settimeout(IDLE_TIMEOUT)
    while True:
        end = buf.find(b"\r\n\r\n")
        if end >= 0:
            break
        if len(buf) > MAX_HEAD:
            return b"", False, 431
        chunk = _recv(conn, 65536, deadline)
        if not chunk:
            return None
        if deadline is None:
            deadline = time.monotonic() + REQUEST_TIMEOUT
        touch()
        buf += chunk
    lines = bytes(buf[:end]).decode("latin-1").split("\r\n")
    del buf[: end + 4]
    request_line = lines[0].split()
    if len(request_line) != 3:
        return b"", False, 400
    keep_alive = request_line[2] == "HTTP/1.1"
    length: int | None = None
    for line in lines[1:]:
        name, _, value = line.partition(":")
        name = name.strip().lower()
        value = value.strip()
        if name == "content-length":
            try:
                length = int(value)
            except ValueError:
                return b"", False, 400
        elif name == "connection":
            keep_alive = value.lower() == "keep-alive" or (keep_alive and value.lower() != "close")
        elif name == "transfer-encoding":
            return b"", False, 411
    if length is None:
        return b"", False, 411
    if length > MAX_BODY or length < 0:
        return b"", False, 413
    while len(buf) < length:
        chunk = _recv(conn, min(1 << 20, length - len(buf)), deadline)
        if not chunk:
            return None
        touch()
        buf += chunk
    body = bytes(buf[:length])
    del buf[:length]
    conn.settimeout(IDLE_TIMEOUT)  # the answer is sent with the whole idle timeout, not what the request left
    return body, keep_alive, 200
