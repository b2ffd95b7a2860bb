"""TCPROS handshakes on blocking sockets (connection headers in and out), shared by topics and services."""

from __future__ import annotations

import socket
import struct
import time
from collections.abc import Mapping

from kame.net.stream import recv_exactly
from kame.protocol.tcpros import HeaderReader, TcprosError, decode_header_fields, encode_header

MAX_HEADER = 1024 * 1024
_LENGTH = struct.Struct("<I")


class HandshakeError(Exception):
    """The peer's header was missing, malformed or refused the connection."""


class MalformedHeader(HandshakeError):
    """The peer's header arrived but cannot be read (a field without '=', a lying length, too
    large): a server tells the peer why in an error header before it closes; a subscriber tries
    the publisher again, ever more slowly."""


class ClosedBeforeHeader(HandshakeError):
    """The peer closed the connection without sending a byte (a port probe, not a bad peer)."""


def read_header(sock: socket.socket, timeout: float | None = None) -> dict[str, str]:
    """A connection header; with `timeout`, the whole header must arrive within it (else
    TimeoutError), not merely each read, so a peer trickling bytes cannot hold us."""
    deadline = None if timeout is None else time.monotonic() + timeout
    if timeout is not None:
        sock.settimeout(timeout)
    first = sock.recv(4)  # usually the whole prefix, in the one recv it always took
    if not first:
        raise ClosedBeforeHeader("connection closed before any header byte")
    if len(first) < 4:
        first += recv_exactly(sock, 4 - len(first), deadline)
    (size,) = _LENGTH.unpack(first)
    if size > MAX_HEADER:
        raise MalformedHeader(f"connection header of {size} bytes is too large (limit {MAX_HEADER})")
    try:
        return decode_header_fields(recv_exactly(sock, size, deadline))
    except TcprosError as exc:
        raise MalformedHeader(str(exc)) from exc


def read_header_and_rest(sock: socket.socket, timeout: float | None = None) -> tuple[dict[str, str], bytes]:
    """Read a header with the bytes that followed it in the same reads (a latched message);
    with `timeout`, the whole header must arrive within it."""
    deadline = None if timeout is None else time.monotonic() + timeout
    reader = HeaderReader(MAX_HEADER)
    while True:
        if deadline is not None:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("connection header not received in time")
            sock.settimeout(left)
        data = sock.recv(65536)
        if not data:
            raise HandshakeError("connection closed during the handshake")
        try:
            fields = reader.feed(data)
        except TcprosError as exc:
            raise MalformedHeader(str(exc)) from exc
        if fields is not None:
            return fields, bytes(reader.trailing)


def write_header(sock: socket.socket, fields: Mapping[str, str]) -> None:
    sock.sendall(encode_header(fields))
