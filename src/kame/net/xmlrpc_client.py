"""XML-RPC calls over HTTP/1.1: the sockets around kame.protocol.http's request writer and
response reader, for every kame caller (nodes, the master's notifications, the CLI tools).

- `XmlRpcProxy` (blocking): a node's calls to the master and to other nodes, and the tools'.
  The calling thread waits for the answer. One kept-alive connection per proxy (rospy opens
  one per call), serialised by a lock, reopened once when a server closed an idle connection
  under us. Every wait is bounded by the call's timeout, set on the proxy's own socket: nothing
  here touches process-wide socket defaults.
- `call` / `post` (asyncio): notifications to peers that may be slow, dead or hostile. One
  connection per call; the whole call (connect, send, receive) has one deadline, the response
  size is capped, and every failure surfaces as an exception for the caller to log; nothing
  retries.
"""

from __future__ import annotations

import re
import socket
import threading

from kame.net.address import resolvable
from kame.protocol.http import HttpError, ResponseReader, encode_request
from kame.protocol.xmlrpc import Value, decode_response
from kame.protocol.xmlrpc import encode_request as encode_call

__all__ = ["HttpError", "XmlRpcProxy", "XmlRpcTransportError", "call", "post"]

MAX_RESPONSE = 64 * 1024 * 1024
MAX_NOTIFICATION_RESPONSE = 32 * 1024 * 1024
MAX_HEAD = 64 * 1024


class XmlRpcTransportError(OSError):
    """The call could not be made or its answer was not a complete HTTP 200 response."""


# The URIs ROS passes around (http://host:port/ and the like), read without urllib.parse: it
# and the ipaddress module it loads are 0.46 MB in every node. Anything else goes to urlsplit.
_PLAIN_URI = re.compile(r"http://([A-Za-z0-9._-]+|\[[0-9A-Fa-f:.]+\]):([0-9]{1,5})(/[A-Za-z0-9/._~%!$&'()*+,;=:@-]*)?")


def _split(uri: str) -> tuple[str, int, str]:
    plain = _PLAIN_URI.fullmatch(uri)
    if plain is not None and int(plain[2]) <= 65535:
        return plain[1].strip("[]").lower(), int(plain[2]) or 80, plain[3] or "/"
    from urllib.parse import urlsplit

    parts = urlsplit(uri)
    if parts.scheme != "http" or not parts.hostname:
        raise HttpError(f"not an http URI: {uri!r}")
    return parts.hostname, parts.port or 80, parts.path or "/"


class XmlRpcProxy:
    def __init__(self, uri: str, timeout: float = 10.0) -> None:
        try:
            self.host, self.port, self.path = _split(uri)
        except HttpError as exc:
            raise ValueError(str(exc)) from None
        self.uri = uri
        self.timeout = timeout
        self._sock: socket.socket | None = None
        self._lock = threading.Lock()
        self.last_date: str | None = None  # the last response's Date header (the server's clock)

    def call(self, method: str, *params: object, timeout: float | None = None) -> Value:
        """Call `method`; raises XmlRpcTransportError (OSError), or the codec's Fault/MalformedError."""
        request = encode_request(self.host, self.port, self.path, encode_call(method, params))
        with self._lock:
            for attempt in (0, 1):
                reused = self._sock is not None
                try:
                    sock = self._sock or self._connect(timeout)
                    sock.settimeout(timeout if timeout is not None else self.timeout)
                    sock.sendall(request)
                    data = self._read_response(sock)
                    break
                except (OSError, HttpError) as exc:
                    self._drop()
                    if not (reused and attempt == 0):
                        raise XmlRpcTransportError(f"{self.uri}: {exc}") from exc
        return decode_response(data)

    def close(self) -> None:
        with self._lock:
            self._drop()

    def _connect(self, timeout: float | None) -> socket.socket:
        # typeshed says str; the address goes to getaddrinfo, which takes bytes as well (see resolvable)
        sock = socket.create_connection((resolvable(self.host), self.port),  # type: ignore[arg-type]
                                        timeout=timeout or self.timeout)
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
        reader = ResponseReader(MAX_HEAD, MAX_RESPONSE)
        while True:
            chunk = sock.recv(65536)
            body = reader.feed(chunk) if chunk else reader.feed_eof()
            if body is not None:
                break
        if not reader.keep_alive:
            self._drop()
        self.last_date = reader.date
        return body


async def post(uri: str, body: bytes, timeout: float, max_response: int = MAX_NOTIFICATION_RESPONSE) -> bytes:
    """POST an XML-RPC body to `uri` and return the response body. Raises OSError, TimeoutError
    or HttpError."""
    import asyncio  # here, not at the top: nodes use only the blocking proxy, and asyncio (with
    # ssl) is a third of a node's memory and import time

    return await asyncio.wait_for(_post(uri, body, max_response), timeout)


async def call(uri: str, method: str, params: list[Value], timeout: float) -> Value:
    """One XML-RPC call. Raises what `post` raises, and the codec's Fault or MalformedError."""
    return decode_response(await post(uri, encode_call(method, params), timeout))


async def _post(uri: str, body: bytes, max_response: int) -> bytes:
    import asyncio  # loaded already by post's caller

    host, port, path = _split(uri)
    reader, writer = await asyncio.open_connection(host, port, limit=MAX_HEAD)
    try:
        writer.write(encode_request(host, port, path, body, keep_alive=False))
        await writer.drain()
        response = ResponseReader(MAX_HEAD, max_response)
        while True:
            chunk = await reader.read(65536)
            answer = response.feed(chunk) if chunk else response.feed_eof()
            if answer is not None:
                return answer
    finally:
        writer.close()
