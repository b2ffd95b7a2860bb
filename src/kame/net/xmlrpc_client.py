"""Asynchronous XML-RPC calls over HTTP/1.1, one connection per call, bounded in time and size.

Made for notifications to peers that may be slow, dead or hostile: the whole call (connect,
send, receive) has one deadline, the response size is capped, and every failure surfaces as an
exception for the caller to log; nothing here retries.
"""

from __future__ import annotations

import asyncio
from urllib.parse import urlsplit

from kame.protocol.xmlrpc import Value, decode_response, encode_request

MAX_RESPONSE = 32 * 1024 * 1024
MAX_HEAD = 64 * 1024


class HttpError(Exception):
    """The peer answered with something other than a complete HTTP 200 response."""


async def post(uri: str, body: bytes, timeout: float, max_response: int = MAX_RESPONSE) -> bytes:
    """POST an XML-RPC body to `uri` and return the response body. Raises OSError, TimeoutError
    or HttpError."""
    return await asyncio.wait_for(_post(uri, body, max_response), timeout)


async def call(uri: str, method: str, params: list[Value], timeout: float) -> Value:
    """One XML-RPC call. Raises what `post` raises, and the codec's Fault or MalformedError."""
    return decode_response(await post(uri, encode_request(method, params), timeout))


async def _post(uri: str, body: bytes, max_response: int) -> bytes:
    parts = urlsplit(uri)
    if parts.scheme != "http" or not parts.hostname:
        raise HttpError(f"not an http URI: {uri!r}")
    host, port = parts.hostname, parts.port or 80
    reader, writer = await asyncio.open_connection(host, port, limit=MAX_HEAD)
    try:
        writer.write(
            f"POST {parts.path or '/'} HTTP/1.1\r\nHost: {host}:{port}\r\nContent-Type: text/xml\r\n"
            f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n".encode("latin-1") + body
        )
        await writer.drain()
        try:
            head = await reader.readuntil(b"\r\n\r\n")
        except (asyncio.IncompleteReadError, asyncio.LimitOverrunError) as e:
            raise HttpError("bad or missing response head") from e
        lines = head.decode("latin-1").split("\r\n")
        status = lines[0].split(" ", 2)
        if len(status) < 2 or status[1] != "200":
            raise HttpError(f"HTTP status {lines[0][:80]!r}")
        length = None
        for line in lines[1:]:
            name, _, value = line.partition(":")
            if name.strip().lower() == "content-length":
                try:
                    length = int(value.strip())
                except ValueError as e:
                    raise HttpError("bad Content-Length") from e
        if length is None:
            return await _read_to_end(reader, max_response)  # HTTP/1.0 style: body ends at close
        if length > max_response:
            raise HttpError(f"response of {length} bytes is too large")
        try:
            return await reader.readexactly(length)
        except asyncio.IncompleteReadError as e:
            raise HttpError("response body cut short") from e
    finally:
        writer.close()


async def _read_to_end(reader: asyncio.StreamReader, max_response: int) -> bytes:
    data = bytearray()
    while chunk := await reader.read(65536):
        data += chunk
        if len(data) > max_response:
            raise HttpError("response too large")
    return bytes(data)
