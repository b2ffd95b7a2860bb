"""TCPROS without sockets: connection headers, message frames, service responses, handshakes.

Rules (ros1-interop spec §6, quirks §13.5-9):
- Connection headers are kame.protocol.header's codec, re-exported here.
- A topic frame is `uint32 length` + payload. A service response is `uint8 ok` + `uint32 length`
  + payload, where ok=0 makes the payload a UTF-8 error text, possibly empty (roscpp).
- Readers are incremental (h11 style): `feed(bytes)` returns what became complete. Lengths are
  checked against a maximum before anything is buffered, so a garbage or hostile prefix is an
  error, never a huge allocation.
- Handshake checks are pure functions over header dicts: they return what to reply (and what
  the runtime needs to know) or a `Rejected` carrying rospy's exact error text.
- One error class, `TcprosError`; its `remote` flag says whose fault it was (the bytes we were
  given, or the values our own caller passed in).
No I/O, no clock: the socket loop lives in kame.net and calls into this module.
"""

from __future__ import annotations

import mmap
import struct
from collections.abc import Mapping
from typing import Literal, NamedTuple

from kame.protocol.header import (
    TcprosError,
    decode_header,
    decode_header_fields,
    decode_header_fields_raw,
    encode_header,
    encode_header_fields,
)

__all__ = [
    "DEFAULT_MAX_FRAME",
    "DEFAULT_MAX_HEADER",
    "FrameReader",
    "HeaderReader",
    "Rejected",
    "ReplyInfo",
    "ServiceClientAccepted",
    "ServiceResponse",
    "ServiceResponseReader",
    "ServiceSpec",
    "SubscriberAccepted",
    "TcprosError",
    "TopicSpec",
    "accept_service_client",
    "accept_subscriber",
    "check_publisher_reply",
    "check_service_reply",
    "classify_connection",
    "decode_header",
    "decode_header_fields",
    "decode_header_fields_raw",
    "encode_frame",
    "encode_frame_prefix",
    "encode_header",
    "encode_header_fields",
    "encode_service_response",
    "error_header_fields",
    "frame_parts",
    "publisher_reply_fields",
    "service_client_header_fields",
    "service_probe_header_fields",
    "service_reply_fields",
    "subscriber_header_fields",
]

#: Largest connection header accepted (the outer length). Real headers are a few hundred bytes
#: plus `message_definition`, whose full text reaches tens of KiB for deeply nested types
#: (MoveIt's action goals); 1 MiB leaves an order of magnitude of room while a stray protocol
#: (an HTTP "GET " reads as 542 MB) or a hostile prefix is refused at once. roscpp allows 1e9.
DEFAULT_MAX_HEADER = 1 << 20
#: Largest message frame accepted by default: 1 GiB, roscpp's own sanity bound (1e9).
DEFAULT_MAX_FRAME = 1 << 30
#: A frame's buffer is allocated whole when its length prefix arrives, so that it is filled with
#: one copy, or none with `get_buffer`. Up to this size it is a bytearray, committed at once:
#: the bounded chunk a peer can make us hold beyond what it sent. A longer one is an anonymous
#: private mapping, whose pages the kernel commits as they are first written: a peer that
#: announces 64 MiB (or 1 GiB) and sends ten bytes costs a page of memory, not 64 MiB.
_COMMIT_LIMIT = 1 << 20
#: With `reuse`, a frame's buffer up to this size is kept for the next frame (a stream of camera
#: images is then received with no allocation and no page faults); a longer one is let go.
_SPARE_LIMIT = 64 << 20
#: `get_buffer` hands out the frame's own buffer (recv straight into it) when at least this much
#: of the frame is still missing; below that a scratch buffer that may hold many frames wins.
_DIRECT_MIN = 64 << 10
#: A scratch read smaller than 1/_PIN_RATIO of its buffer is copied out, so that frames kept by
#: a slow consumer do not pin mostly-empty 64 KiB buffers.
_PIN_RATIO = 4

_U32 = struct.Struct("<I")
_unpack_u32 = _U32.unpack_from
_pack_u32 = _U32.pack
_RESPONSE_PREFIX = struct.Struct("<BI")


# -------------------------------------------------------------------------------- frame codec


def encode_frame_prefix(length: int) -> bytes:
    """The 4-byte length prefix of a frame, for scatter writes (prefix and payload sent apart)."""
    if not 0 <= length <= 0xFFFFFFFF:
        raise TcprosError(f"frame length {length} does not fit a uint32", remote=False)
    return _pack_u32(length)


def encode_frame(payload: bytes | bytearray | memoryview) -> bytes:
    """`uint32 length` + payload: a topic message or a service request on the wire."""
    return encode_frame_prefix(len(payload) if not isinstance(payload, memoryview) else payload.nbytes) + payload


def frame_parts(payload: bytes | bytearray | memoryview) -> list[bytes | bytearray | memoryview]:
    """A frame as buffers for one scatter write (sendmsg): the length prefix, then the payload
    itself, not copied. What a publisher sends for a payload it did not serialize (bag play,
    rosout's relay)."""
    return [encode_frame_prefix(len(payload) if not isinstance(payload, memoryview) else payload.nbytes), payload]


def encode_service_response(ok: bool, payload: bytes | bytearray | memoryview | str) -> bytes:
    """A service server's response: `uint8 ok` + `uint32 length` + payload. With ok=False the
    payload is the error text (a str is encoded as UTF-8; "" is what roscpp sends)."""
    raw = payload.encode() if isinstance(payload, str) else payload
    size = raw.nbytes if isinstance(raw, memoryview) else len(raw)
    if size > 0xFFFFFFFF:
        raise TcprosError(f"service response of {size} bytes does not fit a uint32 length", remote=False)
    return _RESPONSE_PREFIX.pack(1 if ok else 0, size) + raw


# -------------------------------------------------------------------------------- readers


class HeaderReader:
    """Reads one connection header from a byte stream.

    `feed` returns the header's fields once complete, else None. Bytes after the header (a
    latched message may follow at once) are kept in `trailing` for the frame reader. The outer
    length is checked against `max_header` as soon as its 4 bytes arrive.
    """

    __slots__ = ("_buf", "fields", "max_header", "trailing")

    def __init__(self, max_header: int = DEFAULT_MAX_HEADER) -> None:
        self.max_header = max_header
        self._buf = bytearray()
        self.fields: dict[str, str] | None = None
        self.trailing = b""

    @property
    def done(self) -> bool:
        return self.fields is not None

    def feed(self, data: bytes | bytearray | memoryview) -> dict[str, str] | None:
        if self.fields is not None:
            raise TcprosError("HeaderReader.feed after the header was complete; feed `trailing` and "
                              "later bytes to a frame reader", remote=False)
        buf = self._buf
        buf += data
        if len(buf) < 4:
            return None
        (size,) = _unpack_u32(buf, 0)
        if size > self.max_header:
            raise TcprosError(f"connection header of {size} bytes refused (limit {self.max_header}): "
                              "not a TCPROS peer, or a corrupt stream")
        end = 4 + size
        if len(buf) < end:
            return None
        self.fields = decode_header_fields(memoryview(buf)[4:end])
        self.trailing = bytes(buf[end:])
        self._buf = bytearray()
        return self.fields


class FrameReader:
    """Splits a TCPROS byte stream into frames (`uint32 length` + payload), incrementally.

    Frames come back as read-only memoryviews; the copies are at most one per byte:
    - `feed(bytes)`: frames wholly inside the chunk are zero-copy slices of it (they keep that
      bytes object alive). Other buffer types are copied once to bytes first, since a caller's
      bytearray may be reused for the next read.
    - A frame split across chunks is gathered into its own buffer (one copy) allocated when its
      length is known; nothing is ever re-joined, so splitting costs O(bytes), not O(bytes^2).
      Past _COMMIT_LIMIT that buffer is a mapping whose pages are committed as they are
      written: what a peer makes us hold is what it sent, plus at most _COMMIT_LIMIT.
    - `get_buffer()` / `buffer_updated(n)` (asyncio.BufferedProtocol's shape): when a large frame
      is in progress the buffer handed out is that frame's own storage, so `recv_into` fills it
      with no copy at all; otherwise it is a fresh scratch buffer parsed like `feed`.
    - `reuse=True` is for a consumer that is done with every frame before it asks for the next
      buffer (a subscriber that deserializes, which copies): the scratch buffer and the frame
      buffers are then reused instead of allocated, zeroed and paged in afresh for every read.
    A length above `max_frame` raises TcprosError before anything is allocated for it.
    `partial` numbers the frame being gathered (0 when none is), for a reader that gives each
    frame that spans chunks a deadline; `release()` drops every buffer when the stream is over.
    """

    __slots__ = ("_body", "_direct", "_filled", "_head", "_need", "_reuse", "_scratch", "_scratch_read",
                 "_scratch_write", "_serial", "_spare", "max_frame", "partial")

    def __init__(self, max_frame: int = DEFAULT_MAX_FRAME, reuse: bool = False) -> None:
        self.max_frame = max_frame
        self._reuse = reuse
        self._spare: bytearray | mmap.mmap | None = None  # with reuse: the last frame buffer, for the next one
        self._head = bytearray()  # the first 0-3 bytes of a split length prefix
        self._body: bytearray | mmap.mmap | None = None  # the frame being gathered across chunks
        self._serial = 0  # frames gathered so far, numbering the next
        self.partial = 0
        self._need = 0
        self._filled = 0
        self._scratch: bytearray | None = None
        # with reuse: the views of _scratch that every read hands out and parses, made once
        self._scratch_write = memoryview(b"")
        self._scratch_read = memoryview(b"")
        self._direct = False

    @property
    def pending(self) -> int:
        """Bytes of an incomplete frame held (0 at a frame boundary: a clean place to close)."""
        return len(self._head) + (4 + self._filled if self._body is not None else 0)

    def feed(self, data: bytes | bytearray | memoryview) -> list[memoryview]:
        """Every frame completed by `data`, in order (possibly none)."""
        if type(data) is not bytes:
            data = bytes(data)
        return self._feed(data)

    def get_buffer(self, sizehint: int = 65536) -> memoryview:
        """A writable buffer to `recv_into`; report the count with `buffer_updated`. Valid only
        until then. Never larger than the frame in progress when it is the frame's own storage."""
        body = self._body
        if body is not None and self._need - self._filled >= _DIRECT_MIN:
            self._direct = True
            return memoryview(body)[self._filled : self._need]
        self._direct = False
        size = max(sizehint, 4096)
        if self._reuse:
            if len(self._scratch_write) != size:
                self._scratch = bytearray(size)
                self._scratch_write = memoryview(self._scratch)
                self._scratch_read = self._scratch_write.toreadonly()
            return self._scratch_write
        self._scratch = bytearray(size)
        return memoryview(self._scratch)

    def buffer_updated(self, nbytes: int) -> list[memoryview]:
        """The frames completed by the `nbytes` just written into `get_buffer()`'s buffer."""
        if self._direct:
            self._direct = False
            if nbytes > self._need - self._filled:
                raise TcprosError("buffer_updated reports more bytes than the buffer held", remote=False)
            self._filled += nbytes
            return [self._finish()] if self._filled == self._need else []
        buf = self._scratch
        if buf is None:
            raise TcprosError("buffer_updated without get_buffer", remote=False)
        if nbytes > len(buf):
            raise TcprosError("buffer_updated reports more bytes than the buffer held", remote=False)
        if self._reuse:
            view = self._scratch_read
            if nbytes >= 4 and self._body is None and not self._head:
                # the usual read of small messages: exactly one whole frame
                (length,) = _unpack_u32(view, 0)
                if length + 4 == nbytes and length <= self.max_frame:
                    return [view[4:nbytes]]
            return self._feed(view[:nbytes])
        self._scratch = None
        if nbytes * _PIN_RATIO < len(buf):
            return self._feed(bytes(memoryview(buf)[:nbytes]))
        return self._feed(memoryview(buf).toreadonly()[:nbytes])

    # -- internals

    def _too_big(self, length: int) -> TcprosError:
        return TcprosError(f"frame of {length} bytes refused (limit {self.max_frame}): a corrupt stream, "
                           "or raise max_frame")

    def _feed(self, data: bytes | memoryview) -> list[memoryview]:
        out: list[memoryview] = []
        n = len(data)
        pos = 0
        view = memoryview(data)
        if self._body is not None or self._head:
            pos = self._resume(view, out)
            if self._body is not None or self._head:
                return out  # all of data went into the unfinished frame
        unpack = _unpack_u32
        limit = self.max_frame
        while n - pos >= 4:
            (length,) = unpack(data, pos)
            if length > limit:
                raise self._too_big(length)
            start = pos + 4
            end = start + length
            if end > n:
                self._begin(length)
                self._fill(view[start:])
                return out
            out.append(view[start:end])
            pos = end
        if pos < n:
            self._head += view[pos:]
        return out

    def _resume(self, view: memoryview, out: list[memoryview]) -> int:
        """Continue the unfinished frame with `view`; return how many bytes it took."""
        pos = 0
        if self._body is None:
            head = self._head
            pos = min(4 - len(head), len(view))
            head += view[:pos]
            if len(head) < 4:
                return pos
            length: int = _unpack_u32(head, 0)[0]
            head.clear()
            if length > self.max_frame:
                raise self._too_big(length)
            if len(view) - pos >= length:  # the whole payload is here: no gathering
                out.append(view[pos : pos + length])
                return pos + length
            self._begin(length)
        pos += self._fill(view[pos:])
        if self._filled == self._need:
            out.append(self._finish())
        return pos

    @property
    def frame_size(self) -> int:
        """The length of the frame whose body is being gathered (0 when none is)."""
        return self._need if self._body is not None else 0

    def release(self) -> None:
        """Drop every buffer now: the stream is over. Without this they would live as long as
        whatever holds the reader, which may be a reference cycle waiting for the collector."""
        self._body = self._spare = self._scratch = None
        self._scratch_write = self._scratch_read = memoryview(b"")
        self._head = bytearray()
        self._need = self._filled = self.partial = 0

    def _begin(self, length: int) -> None:
        self._need = length
        self._filled = 0
        self._serial += 1
        self.partial = self._serial
        if self._reuse and self._spare is not None and len(self._spare) >= length:
            self._body = self._spare
        elif length > _COMMIT_LIMIT:
            try:
                self._body = mmap.mmap(-1, length, flags=mmap.MAP_PRIVATE)
            except OSError as exc:  # a strict overcommit policy (vm.overcommit_memory=2) refuses it
                raise TcprosError(f"cannot map {length} bytes for a frame: {exc.strerror}", remote=False) from None
        else:
            self._body = bytearray(length)

    def _fill(self, chunk: memoryview) -> int:
        body = self._body
        assert body is not None
        take = min(len(chunk), self._need - self._filled)
        body[self._filled : self._filled + take] = chunk[:take]
        self._filled += take
        return take

    def _finish(self) -> memoryview:
        body = self._body
        assert body is not None
        self._body = None
        self.partial = 0
        if self._reuse and len(body) <= _SPARE_LIMIT:
            self._spare = body
        return memoryview(body).toreadonly()[: self._need]


class ServiceResponse(NamedTuple):
    """One service response: ok=True carries the serialized Response, ok=False an error text."""

    ok: bool
    payload: bytes

    @property
    def error_text(self) -> str:
        """The server's error text (ok=False); undecodable bytes are replaced, not fatal."""
        return self.payload.decode("utf-8", "replace")


class ServiceResponseReader:
    """Reads service responses (`uint8 ok` + `uint32 length` + payload) incrementally. Payloads are
    bytes (one copy: responses come one per request, so simplicity wins over zero-copy here)."""

    __slots__ = ("_buf", "max_frame")

    def __init__(self, max_frame: int = DEFAULT_MAX_FRAME) -> None:
        self.max_frame = max_frame
        self._buf = bytearray()

    @property
    def pending(self) -> int:
        """Bytes of an incomplete response held."""
        return len(self._buf)

    @property
    def missing(self) -> int:
        """Bytes still to come for the response under way, once its prefix is here (else 0): how
        much a reader may ask the socket for."""
        buf = self._buf
        if len(buf) < 5:
            return 0
        length: int = _RESPONSE_PREFIX.unpack_from(buf, 0)[1]
        return max(0, 5 + length - len(buf))

    def feed(self, data: bytes | bytearray | memoryview) -> list[ServiceResponse]:
        buf = self._buf
        # The usual case, a whole response in one bytes object, is parsed from it in place.
        src: bytes | bytearray
        if buf or type(data) is not bytes:
            buf += data
            src = buf
        else:
            src = data
        out: list[ServiceResponse] = []
        pos = 0
        n = len(src)
        while n - pos >= 5:
            ok, length = _RESPONSE_PREFIX.unpack_from(src, pos)
            if ok > 1:
                raise TcprosError(f"service response ok byte is {ok}, expected 0 or 1: a corrupt stream")
            if length > self.max_frame:
                raise TcprosError(f"service response of {length} bytes refused (limit {self.max_frame})")
            end = pos + 5 + length
            if end > n:
                break
            payload = src[pos + 5 : end]
            out.append(ServiceResponse(ok == 1, payload if type(payload) is bytes else bytes(payload)))
            pos = end
        if src is buf:
            if pos:
                del buf[:pos]  # O(1) in CPython: bytearray drops a prefix by moving its start
        elif pos < n:
            buf += memoryview(src)[pos:]
        return out


# -------------------------------------------------------------------------------- handshakes


class TopicSpec(NamedTuple):
    """What a publisher offers on one topic (plain strings; no message classes needed)."""

    type: str
    md5sum: str
    message_definition: str = ""
    latching: bool = False


class ServiceSpec(NamedTuple):
    """What a service server offers. request/response types default to roscpp's `<type>Request`."""

    type: str
    md5sum: str
    request_type: str = ""
    response_type: str = ""


class Rejected(NamedTuple):
    """A failed handshake: `error` is the text to send (`error=<text>`, then close) or to log."""

    error: str

    @property
    def reply(self) -> dict[str, str]:
        return error_header_fields(self.error)


class SubscriberAccepted(NamedTuple):
    """A publisher accepted a subscriber: send `reply`, then frames (the latched one first)."""

    topic: str
    callerid: str
    tcp_nodelay: bool | None  # None: the subscriber did not say, and the publisher's own choice applies
    reply: dict[str, str]


class ServiceClientAccepted(NamedTuple):
    """A service server accepted a client: send `reply`. If `probe`, close right after (rospy);
    else serve one request, or many while `persistent`."""

    service: str
    callerid: str
    persistent: bool
    probe: bool
    reply: dict[str, str]


class ReplyInfo(NamedTuple):
    """A publisher's or service server's reply header, checked by the connecting side."""

    type: str
    md5sum: str
    callerid: str
    latching: bool
    message_definition: str
    fields: dict[str, str]


# rospy's TOPIC_ANYTYPE / SERVICE_ANYTYPE
_ANY = "*"


def error_header_fields(text: str) -> dict[str, str]:
    """The error reply: a single `error` field; the sender closes the socket after it."""
    return {"error": text}


def classify_connection(header: Mapping[str, str]) -> Literal["topic", "service"] | Rejected:
    """What an incoming connection on a node's TCPROS server asks for (rospy's dispatch)."""
    if "topic" in header:
        return "topic"
    if "service" in header:
        return "service"
    return Rejected("no topic or service name detected")


def subscriber_header_fields(
    *,
    callerid: str,
    topic: str,
    type: str,
    md5sum: str,
    message_definition: str | None = "",
    tcp_nodelay: bool = False,
    extra: Mapping[str, str] | None = None,
) -> dict[str, str]:
    """What a subscriber sends (rospy's set; message_definition=None omits it as roscpp does).
    `extra` fields are added and override, as rospy's user `headers` do."""
    fields = {"callerid": callerid, "md5sum": md5sum, "tcp_nodelay": "1" if tcp_nodelay else "0",
              "topic": topic, "type": type}
    if message_definition is not None:
        fields["message_definition"] = message_definition
    if extra:
        fields.update(extra)
    return fields


def publisher_reply_fields(
    *, callerid: str, topic: str, spec: TopicSpec, extra: Mapping[str, str] | None = None
) -> dict[str, str]:
    """What a publisher replies (rospy and roscpp send this same set)."""
    fields = {"callerid": callerid, "latching": "1" if spec.latching else "0", "md5sum": spec.md5sum,
              "message_definition": spec.message_definition, "topic": topic, "type": spec.type}
    if extra:
        fields.update(extra)
    return fields


def service_client_header_fields(
    *, callerid: str, service: str, md5sum: str, persistent: bool = False, extra: Mapping[str, str] | None = None
) -> dict[str, str]:
    """What a service client sends (rospy's form: `persistent=1` only when persistent)."""
    fields = {"callerid": callerid, "md5sum": md5sum, "service": service}
    if persistent:
        fields["persistent"] = "1"
    if extra:
        fields.update(extra)
    return fields


def service_probe_header_fields(*, callerid: str, service: str) -> dict[str, str]:
    """The probe `rosservice` and wait_for_service send to learn the type (`md5sum=*`, `probe=1`)."""
    return {"callerid": callerid, "md5sum": _ANY, "probe": "1", "service": service}


def service_reply_fields(*, callerid: str, service: str, spec: ServiceSpec) -> dict[str, str]:
    """A service server's reply: the union of rospy's (callerid, md5sum, service, type) and
    roscpp's (callerid, md5sum, request_type, response_type, type); both clients ignore the rest."""
    return {
        "callerid": callerid,
        "md5sum": spec.md5sum,
        "request_type": spec.request_type or spec.type + "Request",
        "response_type": spec.response_type or spec.type + "Response",
        "service": service,
        "type": spec.type,
    }


def _missing(header: Mapping[str, str], required: tuple[str, ...]) -> Rejected | None:
    for name in required:
        if name not in header:
            return Rejected(f"Missing required '{name}' field")
    return None


def accept_subscriber(
    header: Mapping[str, str],
    *,
    callerid: str,
    publications: Mapping[str, TopicSpec],
    extra: Mapping[str, str] | None = None,
) -> SubscriberAccepted | Rejected:
    """The publisher's check of a subscriber's header, with rospy's error texts.

    `callerid` is this node's name; `publications` maps resolved topic names to what we publish.
    The md5sums must match, or either side's be `*` (rospy accepts the subscriber's `*`, roscpp
    also its own); the type is compared only to explain an md5 mismatch.
    """
    missing = _missing(header, ("topic", "md5sum", "callerid"))
    if missing:
        return missing
    topic = header["topic"]
    spec = publications.get(topic)
    if spec is None:
        listing = [[name, s.type] for name, s in publications.items()]
        return Rejected(f"[{callerid}] is not a publisher of [{topic}]. Topics are {listing}")
    md5sum = header["md5sum"]
    if md5sum != spec.md5sum and md5sum != _ANY and spec.md5sum != _ANY:
        requested_type = header.get("type", spec.type)
        if requested_type != spec.type:
            return Rejected(f"topic types do not match: [{requested_type}] vs. [{spec.type}]")
        return Rejected(
            f"Client [{header['callerid']}] wants topic [{topic}] to have datatype/md5sum "
            f"[{requested_type}/{md5sum}], but our version has [{spec.type}/{spec.md5sum}] Dropping connection."
        )
    return SubscriberAccepted(
        topic=topic,
        callerid=header["callerid"],
        tcp_nodelay=header["tcp_nodelay"].strip() == "1" if "tcp_nodelay" in header else None,
        reply=publisher_reply_fields(callerid=callerid, topic=topic, spec=spec, extra=extra),
    )


def accept_service_client(
    header: Mapping[str, str], *, callerid: str, services: Mapping[str, ServiceSpec]
) -> ServiceClientAccepted | Rejected:
    """The service server's check of a client's header, with rospy's error texts. `*` (the probe's
    md5sum) is accepted; `persistent` is `1`/`true` in any case, as rospy reads it."""
    missing = _missing(header, ("service", "md5sum", "callerid"))
    if missing:
        return missing
    service = header["service"]
    spec = services.get(service)
    if spec is None:
        return Rejected(f"[{callerid}] is not a provider of  [{service}]")  # sic: rospy's two spaces
    md5sum = header["md5sum"]
    if md5sum != spec.md5sum and md5sum != _ANY and spec.md5sum != _ANY:
        return Rejected(f"request from [{header['callerid']}]: md5sums do not match: [{md5sum}] vs. [{spec.md5sum}]")
    return ServiceClientAccepted(
        service=service,
        callerid=header["callerid"],
        persistent=header.get("persistent", "").lower() in ("1", "true"),
        probe=header.get("probe") == "1",
        reply=service_reply_fields(callerid=callerid, service=service, spec=spec),
    )


def _check_reply(header: Mapping[str, str]) -> ReplyInfo | Rejected:
    if "error" in header:
        return Rejected(f"remote error reported: {header['error']}")
    for name in ("md5sum", "type"):
        if name not in header:
            return Rejected(f"header missing required field [{name}]")
    return ReplyInfo(
        type=header["type"],
        md5sum=header["md5sum"],
        callerid=header.get("callerid", ""),
        latching=header.get("latching", "0") == "1",
        message_definition=header.get("message_definition", ""),
        fields=dict(header),
    )


def check_publisher_reply(header: Mapping[str, str]) -> ReplyInfo | Rejected:
    """The subscriber's check of a publisher's reply (rospy's texts): an `error` field is failure,
    `md5sum` and `type` are required."""
    return _check_reply(header)


def check_service_reply(header: Mapping[str, str]) -> ReplyInfo | Rejected:
    """The service client's check of the server's reply: the same rule as for topics (rospy uses
    one check for both; rospy and roscpp servers both send md5sum and type)."""
    return _check_reply(header)
