"""HTTP/1.1 without sockets, as XML-RPC uses it: the one module in kame that reads and writes
HTTP messages. The servers and clients in kame.net only move the bytes.

Rules:
- Readers are incremental (h11's shape): `feed(bytes)`, then pull what became complete. A
  request refused for its form comes out as a `Refusal` carrying the status to answer with; the
  server sends it and closes, since the rest of the stream can no longer be trusted.
- Requests: HTTP/1.1 and 1.0, keep-alive as HTTP/1.1 says (1.0 only with `Connection:
  keep-alive`), pipelined requests in order. Bodies need Content-Length (none means empty);
  chunked bodies get 411, as XML-RPC clients never send them. Heads are bounded by
  `max_header`, bodies by `max_body` (413 before a byte of the body is held).
- The usual case costs little on a busy server: a request that arrives in one `feed` is parsed
  from that bytes object without copying it into a buffer, and a request head seen before (a
  client repeats its own) is looked up in a cache the server shares between its connections
  instead of parsed again.
- Responses: `Content-length` and `Content-type` spelled as rosmaster's (Python's http.server)
  are; `Connection: close` when the connection ends after it; a `Date` (RFC 9110's IMF-fixdate,
  as http.server sends) when the server gives one, which is how roswtf compares machines' clocks
  (`ResponseReader.date`). A response without
  Content-length (HTTP/1.0 style) ends at the close: `ResponseReader.feed_eof` finishes it.
- One error class, `HttpError`, for what a client reads (a bad or refused response).
No I/O, no clock: kame.net calls into this module.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import NamedTuple

__all__ = [
    "HttpError",
    "Refusal",
    "Request",
    "RequestReader",
    "ResponseReader",
    "date_header",
    "encode_request",
    "encode_response",
    "parse_date",
]

REASONS = {
    200: "OK", 400: "Bad Request", 404: "Not Found", 408: "Request Timeout", 411: "Length Required",
    413: "Payload Too Large", 431: "Request Header Fields Too Large", 500: "Internal Server Error",
    501: "Not Implemented", 503: "Service Unavailable", 505: "HTTP Version Not Supported",
}
DEFAULT_MAX_HEADER = 64 * 1024
DEFAULT_MAX_BODY = 32 * 1024 * 1024
_HEAD_CACHE_SIZE = 256  # distinct heads remembered per cache (a client repeats its own)
_HEAD_CACHE_MAX_BYTES = 1024  # longer heads are parsed every time, so the cache stays small


class HttpError(Exception):
    """A response that is not a complete HTTP 200 answer, or that breaks a limit."""


class Request(NamedTuple):
    method: str
    path: str
    version: str
    headers: Mapping[str, str]  # names lower-cased; read-only, shared by requests with equal heads
    body: bytes
    keep_alive: bool


class Refusal(NamedTuple):
    """A request that cannot be served: answer `status` and close the connection."""

    status: int
    why: str


class _Head(NamedTuple):
    method: str
    path: str
    version: str
    headers: Mapping[str, str]
    length: int
    keep_alive: bool


HeadCache = dict[bytes, _Head]


def new_head_cache() -> HeadCache:
    """A request-head cache for `RequestReader`s; a server shares one between its connections."""
    return {}


def _parse_request_head(raw: bytes, max_body: int) -> _Head | Refusal:
    lines = raw.decode("latin-1").split("\r\n")
    parts = lines[0].split(" ")
    if len(parts) != 3 or not parts[2].startswith("HTTP/"):
        return Refusal(400, f"bad request line {lines[0][:80]!r}")
    method, path, version = parts
    if version not in ("HTTP/1.1", "HTTP/1.0"):
        return Refusal(505, f"unsupported {version[:20]!r}")
    headers: dict[str, str] = {}
    for line in lines[1:]:
        name, sep, value = line.partition(":")
        if not sep:
            return Refusal(400, "bad header line")
        headers[name.strip().lower()] = value.strip()
    if "chunked" in headers.get("transfer-encoding", "").lower():
        return Refusal(411, "chunked request body")
    try:
        length = int(headers.get("content-length", "0"))
    except ValueError:
        length = -1
    if length < 0:
        return Refusal(400, "bad Content-Length")
    if length > max_body:
        return Refusal(413, f"body of {length} bytes")
    return _Head(method, path, version, MappingProxyType(headers), length, _keep_alive(version, headers))


def _keep_alive(version: str, headers: Mapping[str, str]) -> bool:
    connection = headers.get("connection", "").lower()
    if version == "HTTP/1.1":
        return "close" not in connection
    return "keep-alive" in connection


class RequestReader:
    """Splits one connection's byte stream into requests (a server's side).

    `feed` what arrived, then call `next_request` until it returns None (more bytes needed).
    After a `Refusal` the reader is done: the connection is to be closed.
    """

    __slots__ = ("_buf", "_data", "_head", "_heads", "_pos", "max_body", "max_header", "refused")

    def __init__(self, max_header: int = DEFAULT_MAX_HEADER, max_body: int = DEFAULT_MAX_BODY,
                 heads: HeadCache | None = None) -> None:
        self.max_header = max_header
        self.max_body = max_body
        self._heads = heads if heads is not None else new_head_cache()
        # Bytes not yet parsed: a fed bytes object read in place (`_data` from `_pos`) while it
        # is the only thing held, else `_buf`.
        self._data: bytes | None = None
        self._pos = 0
        self._buf = bytearray()
        self._head: _Head | None = None  # the request whose body is awaited
        self.refused = False

    @property
    def pending(self) -> int:
        """Bytes of an unfinished request held (0 between requests)."""
        if self._data is None:
            return len(self._buf) + (self._head is not None)
        return len(self._buf) + len(self._data) - self._pos + (self._head is not None)

    @property
    def body_wanted(self) -> int:
        """The Content-Length of a request whose head has come but not yet all of its body."""
        return self._head.length if self._head is not None else 0

    def feed(self, data: bytes | bytearray | memoryview) -> None:
        if self.refused:
            return
        if self._data is not None:
            self._buf += memoryview(self._data)[self._pos:]
            self._data = None
        if self._buf or type(data) is not bytes:
            self._buf += data
        else:
            self._data, self._pos = data, 0

    def next_request(self) -> Request | Refusal | None:
        """The next complete request, a Refusal, or None when more bytes are needed."""
        data: bytes | bytearray
        if self._data is not None:
            data, pos = self._data, self._pos
        elif self._buf:
            data, pos = self._buf, 0
        else:
            return None  # nothing held (also after a refusal, which drops what was held)
        head = self._head
        if head is None:
            end = data.find(b"\r\n\r\n", pos)
            if end < 0 or end - pos > self.max_header:
                if end >= 0 or len(data) - pos > self.max_header:
                    return self._refuse(Refusal(431, "request head too large"))
                self._keep(data, pos)
                return None
            raw = bytes(data[pos:end])
            head = self._heads.get(raw)
            if head is None:
                parsed = _parse_request_head(raw, self.max_body)
                if isinstance(parsed, Refusal):
                    return self._refuse(parsed)
                head = parsed
                if len(raw) <= _HEAD_CACHE_MAX_BYTES:
                    if len(self._heads) >= _HEAD_CACHE_SIZE:
                        self._heads.clear()
                    self._heads[raw] = head
            pos = end + 4
        length = head.length
        if len(data) - pos < length:
            self._head = head
            self._keep(data, pos)
            return None
        self._head = None
        body = data[pos:pos + length]
        pos += length
        if data is self._data:
            self._pos = pos
            if pos == len(data):
                self._data = None
        else:
            del self._buf[:pos]
        return Request(head.method, head.path, head.version, head.headers,
                       body if type(body) is bytes else bytes(body), head.keep_alive)

    def _keep(self, data: bytes | bytearray, pos: int) -> None:
        if data is self._data:
            self._data = None
            self._buf += memoryview(data)[pos:]
        elif pos:
            del self._buf[:pos]

    def _refuse(self, refusal: Refusal) -> Refusal:
        self.refused = True
        self._data = None
        self._buf.clear()
        self._head = None
        return refusal


def encode_response(status: int, body: bytes, content_type: str = "text/xml", version: str = "HTTP/1.1",
                    keep_alive: bool = True, date: bytes = b"") -> bytes:
    """A response's bytes; the head's bytes are built once per (version, status, type, keep-alive).

    `date`: a `date_header` line, or nothing."""
    key = (version, status, content_type, keep_alive)
    head = _RESPONSE_HEADS.get(key)
    if head is None:
        status_line = f"{version} {status} {REASONS.get(status, 'Unknown')}\r\n"
        before = f"Content-type: {content_type}\r\nContent-length: "
        after = "\r\n" if keep_alive else "\r\nConnection: close\r\n"
        head = _RESPONSE_HEADS[key] = (status_line.encode("latin-1"), before.encode("latin-1"),
                                       (after + "\r\n").encode("latin-1"))
    return head[0] + date + head[1] + b"%d" % len(body) + head[2] + body


_RESPONSE_HEADS: dict[tuple[str, int, str, bool], tuple[bytes, bytes, bytes]] = {}


_WEEKDAYS = ("Mon", "Tue", "Wed", "Thu", "Fri", "Sat", "Sun")
_MONTHS = ("Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec")


def date_header(seconds: float) -> bytes:
    """The `Date:` line (with its CRLF) for `seconds` since the epoch, in IMF-fixdate as
    email.utils.formatdate(usegmt=True) writes it. Not that function, nor datetime: the email
    package is 2.5 MB and datetime 0.5 MB in every node, for one line a second."""
    days, second = divmod(int(seconds // 1), 86400)
    year, month, day = _civil_from_days(days)
    return (f"Date: {_WEEKDAYS[(days + 3) % 7]}, {day:02d} {_MONTHS[month - 1]} {year:04d} "
            f"{second // 3600:02d}:{second // 60 % 60:02d}:{second % 60:02d} GMT\r\n").encode("latin-1")


def _civil_from_days(days: int) -> tuple[int, int, int]:
    """(year, month, day) of the proleptic Gregorian calendar, `days` after 1970-01-01
    (Howard Hinnant's civil_from_days: eras of 400 years, years starting in March)."""
    z = days + 719468
    era = z // 146097
    day_of_era = z - era * 146097
    year_of_era = (day_of_era - day_of_era // 1460 + day_of_era // 36524 - day_of_era // 146096) // 365
    day_of_year = day_of_era - (365 * year_of_era + year_of_era // 4 - year_of_era // 100)
    shifted_month = (5 * day_of_year + 2) // 153  # 0 = March
    day = day_of_year - (153 * shifted_month + 2) // 5 + 1
    month = shifted_month + 3 if shifted_month < 10 else shifted_month - 9
    return year_of_era + era * 400 + (month <= 2), month, day


def parse_date(value: str) -> float | None:
    """Seconds since the epoch of a Date header's value; None when it is not a date."""
    from email.utils import parsedate_to_datetime  # here: only roswtf reads dates (see date_header)

    try:
        when = parsedate_to_datetime(value)
    except (TypeError, ValueError, IndexError):
        return None
    if when.tzinfo is None:  # RFC 850's and asctime's forms carry no zone: GMT by definition
        return None
    return when.timestamp()


def encode_request(host: str, port: int, path: str, body: bytes, keep_alive: bool = True) -> bytes:
    """An XML-RPC POST (what a client sends)."""
    close = "" if keep_alive else "Connection: close\r\n"
    return (f"POST {path or '/'} HTTP/1.1\r\nHost: {host}:{port}\r\nUser-Agent: kame\r\nContent-Type: text/xml\r\n"
            f"Content-Length: {len(body)}\r\n{close}\r\n").encode("latin-1") + body


class ResponseReader:
    """Reads one response to a request we sent (a client's side).

    `feed` what arrives until it returns the body (bytes); at end of stream call `feed_eof`,
    which returns the body of a response that ends at the close or raises HttpError. Afterwards
    `keep_alive` says whether the connection may carry the next request. Anything but status
    200 raises HttpError (XML-RPC faults come with 200).
    """

    __slots__ = ("_buf", "_length", "date", "keep_alive", "max_body", "max_header")

    def __init__(self, max_header: int = DEFAULT_MAX_HEADER, max_body: int = DEFAULT_MAX_BODY) -> None:
        self.max_header = max_header
        self.max_body = max_body
        self._buf = bytearray()
        self._length: int | None = -1  # -1: head not yet read; None: the body ends at the close
        self.keep_alive = False
        self.date: str | None = None  # the response's Date header, as sent

    def feed(self, data: bytes | bytearray | memoryview) -> bytes | None:
        buf = self._buf
        buf += data
        if self._length == -1:
            end = buf.find(b"\r\n\r\n")
            if end < 0:
                if len(buf) > self.max_header:
                    raise HttpError("response head too large")
                return None
            self._length, self.keep_alive, self.date = _parse_response_head(bytes(buf[:end]), self.max_body)
            del buf[:end + 4]
        length = self._length
        if length is None:
            if len(buf) > self.max_body:
                raise HttpError("response too large")
            return None
        if len(buf) < length:
            return None
        return bytes(buf[:length])

    def feed_eof(self) -> bytes:
        if self._length is None:
            self.keep_alive = False
            return bytes(self._buf)
        if self._length == -1:
            raise HttpError("connection closed before the response")
        raise HttpError("response body cut short")


def _parse_response_head(raw: bytes, max_body: int) -> tuple[int | None, bool, str | None]:
    """(Content-Length or None, keep-alive, Date) of a 200 response's head."""
    lines = raw.decode("latin-1").split("\r\n")
    status = lines[0].split(" ", 2)
    if len(status) < 2 or status[1] != "200":
        raise HttpError(f"HTTP status {lines[0][:80]!r}")
    length: int | None = None
    date: str | None = None
    keep_alive = lines[0].startswith("HTTP/1.1")
    for line in lines[1:]:
        name, _, value = line.partition(":")
        name = name.strip().lower()
        if name == "content-length":
            try:
                length = int(value.strip())
            except ValueError:
                raise HttpError("bad Content-Length") from None
            if length < 0:
                raise HttpError("bad Content-Length")
        elif name == "connection":
            option = value.strip().lower()
            keep_alive = option == "keep-alive" or (keep_alive and option != "close")
        elif name == "date":
            date = value.strip()
    if length is not None and length > max_body:
        raise HttpError(f"response of {length} bytes is too large")
    return length, keep_alive and length is not None, date
