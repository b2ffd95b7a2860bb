"""A WebSocket server for the web bridges, on the `websockets` library's threaded server.

Rules:
- The protocol (handshake, framing, masking, ping/pong, close, UTF-8 checks) is the
  `websockets` library's, a maintained implementation of RFC 6455; this module only owns the
  threads and the bounds. Why a library: a hand-written WebSocket is a security surface
  (fragmentation, masking, control frames, compression bombs) that the library has hardened.
- Who may connect is kame.net.peers' allowlist, asked before the handshake: a refused peer gets
  HTTP 403 and one log line.
- Incoming: a frame larger than `max_message_size` closes that connection (1009, the library's
  check, before the frame is buffered); at most `max_queue` received frames wait for the
  handler, after which TCP flow control holds the client back.
- Outgoing: `Client.send` never blocks. Frames wait in a per-client queue of at most
  `max_frames` frames and `max_bytes` bytes; when it is full the oldest frame is dropped and
  counted. One sender thread per client writes them, so a slow client costs only its own frames.
- Threads: the server's accept thread and, per client, the library's handler thread and our
  sender thread. `close()` stops accepting, closes every connection and joins them all; a sender
  still blocked on a client that reads nothing has the socket shut down under it.
This module moves frames; what they mean is the handler's business.
"""

from __future__ import annotations

import collections
import contextlib
import logging
import socket
import ssl
import threading
from collections.abc import Callable
from dataclasses import dataclass
from http import HTTPStatus
from typing import Any, Protocol

from websockets.exceptions import ConnectionClosed
from websockets.sync.server import Server, ServerConnection, serve

from kame.net import peers

log = logging.getLogger("kame.net.websocket_listener")

Frame = str | bytes
CLOSE_TIMEOUT = 2.0  # how long a closing handshake may wait on the client before its TCP connection is cut
SENDER_GRACE = 1.0  # how long a client's sender may take to finish its frame when the client goes


@dataclass(frozen=True)
class Limits:
    max_message_size: int = 10 * 1024 * 1024  # largest frame a client may send
    max_queue: int = 16  # received frames waiting for the handler
    max_frames: int = 1000  # frames waiting to go out to one client
    max_bytes: int = 64 * 1024 * 1024  # bytes waiting to go out to one client


class Session(Protocol):
    """What the handler makes of one client: told each frame it sends, and when it is gone."""

    def on_frame(self, frame: Frame) -> None: ...

    def on_close(self) -> None: ...


class Client:
    """One connected client: its peer address and the bounded queue of frames going to it."""

    def __init__(self, connection: ServerConnection, limits: Limits) -> None:
        self.connection = connection
        self.limits = limits
        address = connection.remote_address
        self.peer = f"{address[0]}:{address[1]}" if isinstance(address, tuple) else str(address)
        self.dropped = 0
        self.sent = 0
        self._queue: collections.deque[Frame] = collections.deque()
        self._queued_bytes = 0
        self._ready = threading.Condition()
        self._closed = False
        self._sender = threading.Thread(target=self._send_loop, name=f"kame-ws-send-{self.peer}", daemon=True)
        self._sender.start()

    def send(self, frame: Frame) -> bool:
        """Queue `frame`; False when the client is gone. Drops the oldest frames past the bounds."""
        with self._ready:
            if self._closed:
                return False
            self._queue.append(frame)
            self._queued_bytes += len(frame)
            while len(self._queue) > 1 and (len(self._queue) > self.limits.max_frames
                                            or self._queued_bytes > self.limits.max_bytes):
                self._queued_bytes -= len(self._queue.popleft())
                self.dropped += 1
            self._ready.notify()
        return True

    def queued(self) -> int:
        with self._ready:
            return len(self._queue)

    def _send_loop(self) -> None:
        while True:
            with self._ready:
                while not self._queue and not self._closed:
                    self._ready.wait()
                if self._closed:
                    return
                frame = self._queue.popleft()
                self._queued_bytes -= len(frame)
            try:
                self.connection.send(frame)
                self.sent += 1
            except ConnectionClosed:
                return
            except OSError as exc:  # the library raises it for a socket broken mid-write
                log.debug("sending to %s failed: %s", self.peer, exc)
                return

    def close(self) -> None:
        """Close the connection (its handler then ends) and stop the sender."""
        self._stop_sender()
        self.connection.close()

    def _stop_sender(self) -> None:
        with self._ready:
            self._closed = True
            self._queue.clear()
            self._queued_bytes = 0
            self._ready.notify()
        if threading.current_thread() is self._sender:
            return
        self._sender.join(SENDER_GRACE)
        if self._sender.is_alive():  # blocked writing to a peer that does not read: break the socket under it
            with contextlib.suppress(OSError):
                self.connection.socket.shutdown(socket.SHUT_RDWR)
            self._sender.join()


def _tls_context(tls: tuple[str, str]) -> ssl.SSLContext:
    """A server context for wss:// from a certificate file and its key file (OSError, ssl.SSLError)."""
    certfile, keyfile = tls
    context = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
    context.load_cert_chain(certfile, keyfile or None)
    return context


class WebSocketListener:
    """Serves WebSocket clients on `host:port` (port 0: any free port, see `port`). `open_session`
    is called on each client's own thread with its Client, and gets that client's frames in order.
    `tls` (certificate file, key file) serves wss://."""

    def __init__(self, host: str, port: int, open_session: Callable[[Client], Session], *,
                 limits: Limits = Limits(), tls: tuple[str, str] | None = None,
                 admit: Callable[[Any], bool] | None = None, where: str = "websocket server") -> None:
        self.limits = limits
        self._open_session = open_session
        self._where = where
        self._admit = admit
        self._clients: set[Client] = set()
        self._lock = threading.Lock()
        self._server: Server = serve(self._handle, host, port, ssl=_tls_context(tls) if tls else None,
                                     process_request=self._check_peer, max_size=limits.max_message_size,
                                     max_queue=limits.max_queue, compression=None,
                                     close_timeout=CLOSE_TIMEOUT)
        self.port: int = self._server.socket.getsockname()[1]
        self._thread = threading.Thread(target=self._server.serve_forever, name="kame-ws-accept", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def clients(self) -> list[Client]:
        with self._lock:
            return list(self._clients)

    def _check_peer(self, connection: ServerConnection, request: Any) -> Any:
        address = connection.remote_address
        allowed = self._admit(address) if self._admit is not None else peers.admit(address, self._where)
        if not allowed:
            return connection.respond(HTTPStatus.FORBIDDEN, "This address may not connect (KAME_ALLOWED_PEERS)\n")
        return None

    def _handle(self, connection: ServerConnection) -> None:
        client = Client(connection, self.limits)
        with self._lock:
            self._clients.add(client)
        session: Session | None = None
        try:
            session = self._open_session(client)
            for frame in connection:
                session.on_frame(frame)
        except ConnectionClosed:
            pass
        finally:
            with self._lock:
                self._clients.discard(client)
            client._stop_sender()
            if session is not None:
                session.on_close()

    def close(self) -> None:
        """Stop accepting, close every client (1001, going away) and join every thread."""
        for client in self.clients():  # first, so that no close handshake waits behind a stuck send
            client._stop_sender()
        self._server.shutdown()
        if self._thread.is_alive():
            self._thread.join()
