"""A small threaded HTTP/1.1 server for a node's XML-RPC API (the "slave" API).

A node gets few calls (requestTopic, publisherUpdate, getBusInfo, ...), so one thread per
connection is plenty, and it keeps asyncio out of every node's start-up. The listening
socket is bound in the constructor, so its port can be advertised before serving starts.
HTTP is kame.protocol.http's; this module is the sockets and threads around it.
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
from kame.net.http_date import current_date_header
from kame.net.stream import AcceptStarvation, peer_of
from kame.protocol.http import Refusal, Request, RequestReader, encode_response

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
        reader = RequestReader(MAX_HEAD, MAX_BODY)

        def touch() -> None:
            with self._lock:
                if conn in self._connections:
                    self._connections[conn] = time.monotonic()

        try:
            while not self._closing:
                request = _read_request(conn, reader, touch)
                if request is None:
                    return
                if isinstance(request, Refusal):
                    log.warning("refusing XML-RPC request from %s: %s (%d)", peer_of(conn), request.why,
                                request.status)
                    conn.sendall(encode_response(request.status, b"", "text/plain", keep_alive=False,
                                                 date=current_date_header()))
                    return
                try:
                    answer = self._handler(request.body)
                except Exception:
                    log.exception("XML-RPC handler failed")
                    conn.sendall(encode_response(500, b"", "text/plain", keep_alive=False,
                                                 date=current_date_header()))
                    return
                conn.sendall(encode_response(200, answer, "text/xml", request.version, request.keep_alive,
                                             current_date_header()))
                touch()
                if not request.keep_alive:
                    return
        except OSError:
            return
        finally:
            with self._lock:
                self._connections.pop(conn, None)
            conn.close()


def _read_request(conn: socket.socket, reader: RequestReader,
                  touch: Callable[[], None] = lambda: None) -> Request | Refusal | None:
    """The next request (or refusal) from the reader and the socket; None at a clean end.
    Raises OSError (TimeoutError) when the peer goes quiet or a request takes too long: a
    connection may idle IDLE_TIMEOUT between requests, a started request must arrive whole
    within REQUEST_TIMEOUT."""
    deadline = time.monotonic() + REQUEST_TIMEOUT if reader.pending else None
    while True:
        request = reader.next_request()
        if request is not None:
            # the answer is sent with the whole idle timeout, not what the request left
            conn.settimeout(IDLE_TIMEOUT)
            return request
        if deadline is None:
            conn.settimeout(IDLE_TIMEOUT)
        else:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError("request not received in time")
            conn.settimeout(min(IDLE_TIMEOUT, remaining))
        # At most 1 MiB per recv: recv(n) allocates n bytes first.
        chunk = conn.recv(max(65536, min(reader.body_wanted, 1 << 20)))
        if not chunk:
            return None
        if deadline is None:
            deadline = time.monotonic() + REQUEST_TIMEOUT
        touch()
        reader.feed(chunk)
