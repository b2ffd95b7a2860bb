"""A small threaded HTTP/1.1 server for a node's XML-RPC API (the "slave" API).

A node gets few calls (requestTopic, publisherUpdate, getBusInfo, ...), so one thread per
connection is plenty, and it keeps asyncio out of every node's start-up. The listening
socket is bound in the constructor, so its port can be advertised before serving starts.
Bounded like the master's server: header and body sizes, connections, idle time.
"""

from __future__ import annotations

import logging
import socket
import threading
from collections.abc import Callable

log = logging.getLogger("kame.net.rpc")

MAX_HEAD = 64 * 1024
MAX_BODY = 32 * 1024 * 1024
MAX_CONNECTIONS = 64
IDLE_TIMEOUT = 60.0

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
        self._connections: set[socket.socket] = set()
        self._thread = threading.Thread(target=self._accept_loop, name=name, daemon=True)

    def start(self) -> None:
        self._thread.start()

    def close(self) -> None:
        self._closing = True
        try:
            self.sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        self.sock.close()
        with self._lock:
            connections = list(self._connections)
        for conn in connections:
            try:
                conn.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
        if self._thread.is_alive() and self._thread is not threading.current_thread():
            self._thread.join(timeout=1.0)

    def _accept_loop(self) -> None:
        while not self._closing:
            try:
                conn, addr = self.sock.accept()
            except OSError:
                if self._closing:
                    return
                continue
            with self._lock:
                if len(self._connections) >= MAX_CONNECTIONS:
                    log.warning("refusing XML-RPC connection from %s: too many connections", addr)
                    conn.close()
                    continue
                self._connections.add(conn)
            threading.Thread(target=self._serve, args=(conn,), name=f"{self._name}-conn", daemon=True).start()

    def _serve(self, conn: socket.socket) -> None:
        conn.settimeout(IDLE_TIMEOUT)
        conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        buf = bytearray()
        try:
            while not self._closing:
                request = _read_request(conn, buf)
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
                if not keep_alive:
                    return
        except OSError:
            return
        finally:
            with self._lock:
                self._connections.discard(conn)
            conn.close()


_REASONS = {200: "OK", 400: "Bad Request", 411: "Length Required", 413: "Payload Too Large",
            431: "Request Header Fields Too Large", 500: "Internal Server Error"}


def _response(status: int, body: bytes, keep_alive: bool) -> bytes:
    head = (
        f"HTTP/1.1 {status} {_REASONS.get(status, 'Error')}\r\nServer: kame\r\nContent-Type: text/xml\r\n"
        f"Content-Length: {len(body)}\r\nConnection: {'keep-alive' if keep_alive else 'close'}\r\n\r\n"
    )
    return head.encode("latin-1") + body


def _read_request(conn: socket.socket, buf: bytearray) -> tuple[bytes, bool, int] | None:
    """One request from `buf` + the socket: (body, keep_alive, status); None at a clean end."""
    while True:
        end = buf.find(b"\r\n\r\n")
        if end >= 0:
            break
        if len(buf) > MAX_HEAD:
            return b"", False, 431
        chunk = conn.recv(65536)
        if not chunk:
            return None
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
        chunk = conn.recv(min(1 << 20, length - len(buf)))
        if not chunk:
            return None
        buf += chunk
    body = bytes(buf[:length])
    del buf[:length]
    return body, keep_alive, 200
