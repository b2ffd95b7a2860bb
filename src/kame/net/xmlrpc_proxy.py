"""Blocking XML-RPC calls over one kept-alive HTTP/1.1 connection per proxy.

For a node's calls to the master and to other nodes: the calling thread waits for the
answer. The connection is reused across calls (rospy opens one per call), serialised by a
lock, and reopened once when a server closed an idle connection under us.
"""

from __future__ import annotations

import socket
import threading
from urllib.parse import urlsplit

from kame.protocol.xmlrpc import Value, decode_response, encode_request

MAX_RESPONSE = 64 * 1024 * 1024
MAX_HEAD = 64 * 1024


class XmlRpcTransportError(OSError):
    """The call could not be made or its answer was not a complete HTTP 200 response."""


class XmlRpcProxy:
    def __init__(self, uri: str, timeout: float = 10.0) -> None:
        parts = urlsplit(uri)
        if parts.scheme != "http" or not parts.hostname:
            raise ValueError(f"not an http URI: {uri!r}")
        self.uri = uri
        self.host = parts.hostname
        self.port = parts.port or 80
        self.path = parts.path or "/"
        self.timeout = timeout
        self._sock: socket.socket | None = None
        self._lock = threading.Lock()

    def call(self, method: str, *params: object, timeout: float | None = None) -> Value:
        """Call `method`; raises XmlRpcTransportError (OSError), or the codec's Fault/MalformedError."""
        body = encode_request(method, params)
        head = (
            f"POST {self.path} HTTP/1.1\r\nHost: {self.host}:{self.port}\r\nUser-Agent: kame\r\n"
            f"Content-Type: text/xml\r\nContent-Length: {len(body)}\r\n\r\n"
        ).encode("latin-1")
        with self._lock:
            for attempt in (0, 1):
                reused = self._sock is not None
                try:
                    sock = self._sock or self._connect(timeout)
                    sock.settimeout(timeout if timeout is not None else self.timeout)
                    sock.sendall(head + body)
                    data = self._read_response(sock)
                    break
                except (OSError, XmlRpcTransportError) as exc:
                    self._drop()
                    if not (reused and attempt == 0):
                        if isinstance(exc, XmlRpcTransportError):
                            raise
                        raise XmlRpcTransportError(f"{self.uri}: {exc}") from exc
        return decode_response(data)

    def close(self) -> None:
        with self._lock:
            self._drop()

    def _connect(self, timeout: float | None) -> socket.socket:
        sock = socket.create_connection((self.host, self.port), timeout=timeout or self.timeout)
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self._sock = sock
        return sock

    def _drop(self) -> None:
        if self._sock is not None:
            try:
                self._sock.close()
            except OSError:
                pass
            self._sock = None

    def _read_response(self, sock: socket.socket) -> bytes:
        buf = bytearray()
        while True:
            end = buf.find(b"\r\n\r\n")
            if end >= 0:
                break
            if len(buf) > MAX_HEAD:
                raise XmlRpcTransportError(f"{self.uri}: response head too large")
            chunk = sock.recv(65536)
            if not chunk:
                raise XmlRpcTransportError(f"{self.uri}: connection closed before the response")
            buf += chunk
        lines = bytes(buf[:end]).decode("latin-1").split("\r\n")
        status = lines[0].split(" ", 2)
        if len(status) < 2 or status[1] != "200":
            raise XmlRpcTransportError(f"{self.uri}: HTTP status {lines[0][:80]!r}")
        length: int | None = None
        keep_alive = lines[0].startswith("HTTP/1.1")
        for line in lines[1:]:
            name, _, value = line.partition(":")
            name = name.strip().lower()
            if name == "content-length":
                try:
                    length = int(value.strip())
                except ValueError:
                    raise XmlRpcTransportError(f"{self.uri}: bad Content-Length") from None
            elif name == "connection":
                keep_alive = value.strip().lower() == "keep-alive"
        body = buf[end + 4:]
        if length is None:
            while chunk := sock.recv(65536):
                body += chunk
                if len(body) > MAX_RESPONSE:
                    raise XmlRpcTransportError(f"{self.uri}: response too large")
            self._drop()
            return bytes(body)
        if length > MAX_RESPONSE:
            raise XmlRpcTransportError(f"{self.uri}: response of {length} bytes is too large")
        while len(body) < length:
            chunk = sock.recv(min(1 << 20, length - len(body)))
            if not chunk:
                raise XmlRpcTransportError(f"{self.uri}: response body cut short")
            body += chunk
        if not keep_alive:
            self._drop()
        return bytes(body[:length])
