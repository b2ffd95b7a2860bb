"""The TCPROS connection header codec, without sockets: also the record-header format of bags.

Rules (ros1-interop spec §6, §10):
- A connection header is `uint32 total length` + fields, each `uint32 length` + `key=value`.
  We write fields sorted by key (rospy and roscpp both do); we read any order, split each field
  at its first `=` (values may hold `=` and newlines) and let the last duplicate win (both
  parsers do). `encode_header_fields`/`decode_header_fields*` are the body without the outer
  length: bag records and UDPROS carry that form.
- Kept apart from kame.protocol.tcpros, with nothing but `struct` imported, because the bag
  tools (`rosbag info`) parse thousands of record headers and must start in milliseconds.
No I/O.
"""

from __future__ import annotations

import struct
from collections.abc import Mapping

__all__ = [
    "TcprosError",
    "decode_header",
    "decode_header_fields",
    "decode_header_fields_raw",
    "encode_header",
    "encode_header_fields",
]

_U32 = struct.Struct("<I")
_unpack_u32 = _U32.unpack_from
_pack_u32 = _U32.pack


class TcprosError(Exception):
    """A TCPROS protocol violation. `remote` is True when the bytes we were given are at fault
    (the peer, or a file), False when our own caller passed something unencodable."""

    def __init__(self, message: str, *, remote: bool = True) -> None:
        super().__init__(message)
        self.remote = remote


# -------------------------------------------------------------------------------- header codec


def _field_bytes(key: str, value: str | bytes) -> bytes:
    if "=" in key:
        raise TcprosError(f"connection header key {key!r} contains '='", remote=False)
    raw = value.encode() if isinstance(value, str) else bytes(value)
    return key.encode() + b"=" + raw


def encode_header_fields(fields: Mapping[str, str | bytes]) -> bytes:
    """The header body: each field as `uint32 length` + `key=value`, sorted by key (bytewise, as
    roscpp's std::map; rospy sorts the same ASCII keys identically). No outer length."""
    parts: list[bytes] = []
    for key in sorted(fields, key=str.encode):
        line = _field_bytes(key, fields[key])
        parts.append(_pack_u32(len(line)))
        parts.append(line)
    return b"".join(parts)


def encode_header(fields: Mapping[str, str | bytes]) -> bytes:
    """A whole connection header as written on a TCPROS socket: `uint32 total length` + body."""
    body = encode_header_fields(fields)
    return _pack_u32(len(body)) + body


def decode_header_fields_raw(data: bytes | bytearray | memoryview) -> dict[str, bytes]:
    """The fields of a header body (no outer length) with their values as bytes, as bag record
    headers need (their values are binary). Raises TcprosError on a malformed body."""
    view = memoryview(data).cast("B") if not isinstance(data, bytes) else data
    n = len(view)
    out: dict[str, bytes] = {}
    pos = 0
    while pos < n:
        if n - pos < 4:
            raise TcprosError(f"malformed connection header: {n - pos} stray byte(s) at offset {pos}, "
                              "too few for a field length")
        (size,) = _unpack_u32(view, pos)
        pos += 4
        if size == 0:
            raise TcprosError(f"malformed connection header: zero-length field at offset {pos - 4}")
        if size > n - pos:
            raise TcprosError(f"malformed connection header: field at offset {pos - 4} claims {size} bytes "
                              f"but only {n - pos} remain")
        line = bytes(view[pos : pos + size])
        pos += size
        key, sep, value = line.partition(b"=")
        if not sep:
            raise TcprosError(f"malformed connection header: field without '=': {line[:80]!r}")
        try:
            name = key.decode()
        except UnicodeDecodeError as exc:
            raise TcprosError(f"malformed connection header: key {key[:80]!r} is not UTF-8") from exc
        out[name] = value
    return out


def decode_header_fields(data: bytes | bytearray | memoryview) -> dict[str, str]:
    """The fields of a header body (no outer length) as text. Raises TcprosError on a malformed
    body or a value that is not UTF-8."""
    out: dict[str, str] = {}
    for key, value in decode_header_fields_raw(data).items():
        try:
            out[key] = value.decode()
        except UnicodeDecodeError as exc:
            raise TcprosError(f"malformed connection header: value of {key!r} is not UTF-8") from exc
    return out


def decode_header(data: bytes | bytearray | memoryview) -> dict[str, str]:
    """A whole connection header (outer length included, nothing after it)."""
    view = memoryview(data).cast("B")
    if len(view) < 4:
        raise TcprosError(f"connection header truncated: {len(view)} byte(s), the length alone takes 4")
    (size,) = _unpack_u32(view, 0)
    if size != len(view) - 4:
        raise TcprosError(f"connection header length says {size} bytes but {len(view) - 4} follow")
    return decode_header_fields(view[4:])
