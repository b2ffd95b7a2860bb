"""Services over TCPROS: servers answering on each client connection's own thread, and clients.

The server side takes request bytes and gives back (ok, response bytes or error text); what
the bytes mean is the caller's (the rospy facade deserializes and runs the handler). A
client always waits for the server's header before sending its request: rospy servers lose
a request that arrives together with the client header.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING

from kame.net.handshake import HandshakeError, read_header, write_header
from kame.net.stream import connect, receive, set_nodelay, shut_down
from kame.node.master_proxy import MasterProxy
from kame.protocol import tcpros

if TYPE_CHECKING:
    import socket

log = logging.getLogger("kame.services")

MAX_REQUEST = 1 << 30
_RECV_MAX = 1 << 20
SPIN_FOR_ANSWER = 200e-6  # seconds a caller (or a persistent server) polls before it blocks

# handler(request bytes) -> (ok, response bytes) or (False, error text)
ServiceHandler = Callable[[bytes], tuple[bool, bytes | str]]


class ServiceError(Exception):
    """A call failed: the server answered with an error, or the connection broke."""


class ServiceServer:
    def __init__(self, name: str, type: str, md5sum: str, handler: ServiceHandler) -> None:
        self.name = name
        self.type = type
        self.md5sum = md5sum
        self.handler = handler
        self.closed = False
        self._connections: set[socket.socket] = set()
        self._lock = threading.Lock()

    @property
    def spec(self) -> tcpros.ServiceSpec:
        return tcpros.ServiceSpec(self.type, self.md5sum)

    def attach(self, sock: socket.socket, accepted: tcpros.ServiceClientAccepted) -> None:
        write_header(sock, accepted.reply)
        if accepted.probe:
            sock.close()
            return
        with self._lock:
            if self.closed:
                sock.close()
                return
            self._connections.add(sock)
        set_nodelay(sock, True)
        self._serve(sock, accepted)

    def _serve(self, sock: socket.socket, accepted: tcpros.ServiceClientAccepted) -> None:
        """Answer requests on this (the accepting) thread; one unless the client is persistent."""
        receiving = _Receiving(sock, spin=SPIN_FOR_ANSWER if accepted.persistent else 0.0)
        requests = tcpros.FrameReader(MAX_REQUEST)
        try:
            while not self.closed:
                try:
                    frames = receiving.frames(requests)
                except tcpros.TcprosError as exc:
                    log.error("%s: request from %s refused: %s", self.name, accepted.callerid, exc)
                    return
                except (OSError, ConnectionError):
                    return
                for frame in frames:
                    ok, payload = self.handler(bytes(frame))
                    sock.sendall(tcpros.encode_service_response(ok, payload))
                    if not accepted.persistent:
                        return
        except OSError:
            return
        finally:
            with self._lock:
                self._connections.discard(sock)
            sock.close()

    def close(self) -> None:
        with self._lock:
            self.closed = True
            connections = list(self._connections)
        for sock in connections:
            shut_down(sock)


class _Receiving:
    """Reads a socket into kame.protocol.tcpros's incremental readers."""

    def __init__(self, sock: socket.socket, spin: float = 0.0) -> None:
        self.sock = sock
        self.spin = spin
        self._responses = tcpros.ServiceResponseReader(MAX_REQUEST)

    def frames(self, reader: tcpros.FrameReader) -> list[memoryview]:
        """The frames completed by one read (possibly none); ConnectionError at end of stream.
        The reader sizes a frame over 64 MiB as its bytes arrive: a peer claiming a gigabyte
        and sending three bytes reserves no gigabyte."""
        chunk = receive(self.sock, 65536, self.spin)
        if not chunk:
            raise ConnectionError("connection closed by the peer")
        return reader.feed(chunk)

    def response(self) -> tuple[tcpros.ServiceResponse, bool]:
        """One service response, and whether the stream is clean after it (nothing more came:
        else the connection must not carry another call)."""
        reader = self._responses
        size = 65536
        while True:
            chunk = receive(self.sock, size, self.spin)
            if not chunk:
                raise ConnectionError("connection closed by the peer")
            responses = reader.feed(chunk)
            if responses:
                return responses[0], len(responses) == 1 and not reader.pending
            # At most 1 MiB per recv: recv(n) allocates n bytes first, so a peer claiming a
            # gigabyte and sending three bytes would make us reserve a gigabyte.
            size = max(65536, min(reader.missing, _RECV_MAX))


def parse_rosrpc(uri: str) -> tuple[str, int]:
    if not uri.startswith("rosrpc://"):
        raise ServiceError(f"invalid service URI [{uri}]")
    host, _, port = uri[len("rosrpc://"):].rstrip("/").rpartition(":")
    try:
        return host.strip("[]"), int(port)
    except ValueError:
        raise ServiceError(f"invalid service URI [{uri}]") from None


class ServiceClient:
    """Calls one service; with `persistent`, the connection is kept across calls.

    It needs a master and a caller id, not a node: rospy programs may call services without
    ever calling init_node (the tutorials' AddTwoInts client does)."""

    def __init__(self, master: MasterProxy, caller_id: str, name: str, type: str, md5sum: str,
                 persistent: bool, headers: dict[str, str] | None = None) -> None:
        self.master = master
        self.caller_id = caller_id
        self.name = name
        self.type = type
        self.md5sum = md5sum
        self.persistent = persistent
        self.headers = headers or {}
        self._sock: socket.socket | None = None
        self._address: tuple[str, int] | None = None
        self._receiving: _Receiving | None = None
        self._lock = threading.Lock()

    def _open(self, timeout: float | None) -> socket.socket:
        """Connect and handshake. The provider's address is remembered between calls (rospy asks
        the master every time); if it fails, the master is asked again, once."""
        for attempt in (0, 1):
            cached = self._address is not None
            if self._address is None:
                self._address = parse_rosrpc(self.master.call("lookupService", self.name))
            try:
                return self._handshake(self._address, timeout)
            except (OSError, HandshakeError, ServiceError):
                self._address = None
                if not cached or attempt:
                    raise
        raise AssertionError("unreachable")

    def _handshake(self, address: tuple[str, int], timeout: float | None) -> socket.socket:
        sock = connect(*address, timeout=timeout or 10.0)
        try:
            sock.settimeout(timeout)
            write_header(sock, tcpros.service_client_header_fields(
                callerid=self.caller_id, service=self.name, md5sum=self.md5sum,
                persistent=self.persistent, extra=self.headers))
            reply = tcpros.check_service_reply(read_header(sock))
            if isinstance(reply, tcpros.Rejected):
                raise ServiceError(f"service [{self.name}] refused the connection: {reply.error}")
            set_nodelay(sock, True)
        except BaseException:
            sock.close()
            raise
        return sock

    def call(self, request: bytes, timeout: float | None = None) -> bytes:
        """Send one serialized request; returns the serialized response or raises ServiceError."""
        with self._lock:
            sock = self._sock
            try:
                if sock is None:
                    sock = self._open(timeout)
                sock.sendall(tcpros.encode_frame(request))
                if self._receiving is None or self._receiving.sock is not sock:
                    self._receiving = _Receiving(sock, spin=SPIN_FOR_ANSWER)
                response, clean = self._receiving.response()
            except (OSError, HandshakeError) as exc:
                self._close_socket(sock)
                raise ServiceError(f"transport error completing service call: {exc}") from exc
            except tcpros.TcprosError as exc:
                # a refused response leaves the stream mid-frame: never read the next answer from it
                self._close_socket(sock)
                raise ServiceError(f"service [{self.name}] sent a bad response: {exc}") from exc
            except ServiceError:
                self._close_socket(sock)
                raise
            if self.persistent and clean:
                self._sock = sock
            else:
                self._close_socket(sock)
        if not response.ok:
            raise ServiceError(f"service [{self.name}] responded with an error: {response.error_text}")
        return response.payload

    def _close_socket(self, sock: socket.socket | None) -> None:
        if sock is not None:
            sock.close()
        self._sock = None

    def close(self) -> None:
        with self._lock:
            self._close_socket(self._sock)


def probe_service(master: MasterProxy, caller_id: str, name: str, timeout: float) -> dict[str, str]:
    """Ask a service for its header (what `rosservice` and wait_for_service do)."""
    host, port = parse_rosrpc(master.call("lookupService", name))
    sock = connect(host, port, timeout=timeout)
    try:
        sock.settimeout(timeout)
        write_header(sock, tcpros.service_probe_header_fields(callerid=caller_id, service=name))
        return read_header(sock)
    finally:
        sock.close()
