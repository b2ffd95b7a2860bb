"""The ROS bag 2.0 record format, without files: records to bytes and bytes to records.

Rules (ros1-interop spec §10):
- A record is `uint32 header_len`, header, `uint32 data_len`, data. The header is a TCPROS
  header body (fields `uint32 len` + `name=value`, binary values); readers accept any field
  order, we write rosbag's Python writer order (insertion order) so that a bag we write is
  byte for byte what `rosbag.Bag` writes.
- Times are `uint32 secs, uint32 nsecs`; here they travel as (secs, nsecs) tuples, which sort
  the way times do.
- Every length read from bytes is checked against the bytes there are before it is used: a
  lying length is a BagFormatError naming the offset, never a read past the buffer.
No I/O, no clock: kame.bag.reader and kame.bag.writer do the file work.
"""

from __future__ import annotations

import struct
from collections.abc import Iterable, Mapping, Sequence

from kame.bag.errors import BagFormatError
from kame.protocol.header import TcprosError, decode_header_fields_raw

__all__ = [
    "FILE_HEADER_RECORD_SIZE",
    "FIRST_RECORD_POS",
    "MAGIC",
    "OP_CHUNK",
    "OP_CHUNK_INFO",
    "OP_CONNECTION",
    "OP_FILE_HEADER",
    "OP_INDEX_DATA",
    "OP_MSG_DATA",
    "OP_MSG_DEF",
    "ChunkHeader",
    "ChunkInfo",
    "Connection",
    "FileHeader",
    "Record",
    "chunk_header_bytes",
    "chunk_info_record",
    "connection_record",
    "encode_record",
    "file_header_record",
    "index_data_record",
    "message_data_prefix",
    "parse_chunk_header",
    "parse_chunk_info",
    "parse_connection",
    "parse_file_header",
    "parse_index_data",
    "read_record",
    "walk_records",
]

MAGIC = b"#ROSBAG V2.0\n"
#: The bag header record is padded to this many header + data bytes (4104 with its lengths).
FILE_HEADER_LENGTH = 4096
FILE_HEADER_RECORD_SIZE = FILE_HEADER_LENGTH + 8
FIRST_RECORD_POS = len(MAGIC) + FILE_HEADER_RECORD_SIZE  # 4117: where the first chunk starts

OP_MSG_DEF = 0x01
OP_MSG_DATA = 0x02
OP_FILE_HEADER = 0x03
OP_INDEX_DATA = 0x04
OP_CHUNK = 0x05
OP_CHUNK_INFO = 0x06
OP_CONNECTION = 0x07

_U32 = struct.Struct("<I")
_U64 = struct.Struct("<Q")
_TIME = struct.Struct("<II")
_INDEX_ENTRY = struct.Struct("<III")
_unpack_u32 = _U32.unpack_from
unpack_u32 = _unpack_u32
_pack_u32 = _U32.pack

#: A message data record up to its data: header (op, conn, time in the Python writer's order)
#: and the data length. Packed per message, so it is one struct call.
_MSG_PREFIX = struct.Struct("<II4sI5sII5sIII")
_MSG_HEADER_LEN = 4 + 4 + 4 + 9 + 4 + 13


Time = tuple[int, int]


def _field(name: str, value: bytes) -> bytes:
    line = name.encode() + b"=" + value
    return _pack_u32(len(line)) + line


def encode_fields(fields: Iterable[tuple[str, bytes]]) -> bytes:
    """A record header in the given field order."""
    return b"".join(_field(name, value) for name, value in fields)


def encode_record(fields: Iterable[tuple[str, bytes]], data: bytes = b"") -> bytes:
    header = encode_fields(fields)
    return b"".join((_pack_u32(len(header)), header, _pack_u32(len(data)), data))


def _op(op: int) -> tuple[str, bytes]:
    return ("op", bytes((op,)))


def _time(t: Time) -> bytes:
    return _TIME.pack(*t)


def file_header_record(index_pos: int, conn_count: int, chunk_count: int) -> bytes:
    """The bag header record, padded with spaces to 4104 bytes."""
    header = encode_fields([_op(OP_FILE_HEADER), ("index_pos", _U64.pack(index_pos)),
                            ("conn_count", _pack_u32(conn_count)), ("chunk_count", _pack_u32(chunk_count))])
    padding = FILE_HEADER_LENGTH - len(header)
    return _pack_u32(len(header)) + header + _pack_u32(padding) + b" " * padding


def chunk_header_bytes(compression: str, uncompressed_size: int, data_len: int) -> bytes:
    """A chunk record up to its data (the compressed payload follows)."""
    header = encode_fields([_op(OP_CHUNK), ("compression", compression.encode()),
                            ("size", _pack_u32(uncompressed_size))])
    return _pack_u32(len(header)) + header + _pack_u32(data_len)


def connection_record(conn_id: int, topic: str, conn_header: Mapping[str, str | bytes]) -> bytes:
    """A connection record; its data is the connection header (topic, type, md5sum,
    message_definition first, as rosbag writes them, then any other fields)."""
    first = ("topic", "type", "md5sum", "message_definition")
    items: dict[str, bytes] = {"topic": topic.encode()}
    for k, v in conn_header.items():
        if k != "topic":
            items[k] = v.encode() if isinstance(v, str) else bytes(v)
    order = [k for k in first if k in items] + [k for k in items if k not in first]
    data = encode_fields((k, items[k]) for k in order)
    return encode_record([_op(OP_CONNECTION), ("topic", topic.encode()), ("conn", _pack_u32(conn_id))], data)


def message_data_prefix(conn_id: int, secs: int, nsecs: int, data_len: int) -> bytes:
    """A message data record up to its data: append the serialized message after it."""
    return _MSG_PREFIX.pack(_MSG_HEADER_LEN, 4, b"op=\x02", 9, b"conn=", conn_id, 13, b"time=", secs, nsecs,
                            data_len)


def index_data_record(conn_id: int, entries: bytes, count: int) -> bytes:
    """An index data record: `entries` is `count` packed (secs, nsecs, uint32 offset) triples."""
    return encode_record([_op(OP_INDEX_DATA), ("conn", _pack_u32(conn_id)), ("ver", _pack_u32(1)),
                          ("count", _pack_u32(count))], entries)


def pack_index_entry(secs: int, nsecs: int, offset: int) -> bytes:
    return _INDEX_ENTRY.pack(secs, nsecs, offset)


def chunk_info_record(info: ChunkInfo) -> bytes:
    data = b"".join(_pack_u32(conn) + _pack_u32(count) for conn, count in info.counts.items())
    return encode_record([_op(OP_CHUNK_INFO), ("ver", _pack_u32(1)), ("chunk_pos", _U64.pack(info.pos)),
                          ("start_time", _time(info.start)), ("end_time", _time(info.end)),
                          ("count", _pack_u32(len(info.counts)))], data)


# ------------------------------------------------------------------------------------ reading


class _Value:
    """Equality and repr over `__slots__`. The record types are plain slotted classes rather
    than dataclasses: `rosbag info` must start in milliseconds and `dataclasses` alone costs
    more to import than reading a bag's whole index."""

    __slots__: tuple[str, ...] = ()

    def _values(self) -> tuple[object, ...]:
        return tuple(getattr(self, name) for name in self.__slots__)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Value) and type(other) is type(self) and self._values() == other._values()

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name in self.__slots__)
        return f"{type(self).__name__}({fields})"


class Record(_Value):
    """A record found in a buffer: its header fields and where its data lies."""

    __slots__ = ("data_len", "data_pos", "header", "pos")

    def __init__(self, pos: int, header: dict[str, bytes], data_pos: int, data_len: int) -> None:
        self.pos = pos
        self.header = header
        self.data_pos = data_pos
        self.data_len = data_len

    @property
    def end(self) -> int:
        return self.data_pos + self.data_len

    @property
    def op(self) -> int:
        value = self.header.get("op")
        if value is None or len(value) != 1:
            raise BagFormatError(f"record at offset {self.pos} has no valid 'op' field")
        return value[0]


def read_record(buf: bytes | memoryview, pos: int, limit: int | None = None, base: int = 0) -> Record:
    """The record at `pos` of `buf`, which must end by `limit` (default: the buffer's end).
    `base` is added to offsets in error messages (the buffer's position in its file)."""
    end = len(buf) if limit is None else min(limit, len(buf))
    if pos + 4 > end:
        raise BagFormatError(f"truncated record at offset {base + pos}: no room for a header length")
    (header_len,) = _unpack_u32(buf, pos)
    header_end = pos + 4 + header_len
    if header_end + 4 > end:
        raise BagFormatError(f"record at offset {base + pos} claims a {header_len}-byte header, "
                             f"but only {max(end - pos - 8, 0)} bytes follow")
    try:
        header = decode_header_fields_raw(buf[pos + 4:header_end])
    except TcprosError as exc:
        raise BagFormatError(f"bad record header at offset {base + pos}: {exc}") from exc
    (data_len,) = _unpack_u32(buf, header_end)
    data_pos = header_end + 4
    if data_pos + data_len > end:
        raise BagFormatError(f"record at offset {base + pos} claims {data_len} data bytes, "
                             f"but only {end - data_pos} remain")
    return Record(pos, header, data_pos, data_len)


def walk_records(buf: bytes | memoryview, pos: int = 0, base: int = 0) -> Iterable[Record]:
    """Every record of `buf` from `pos` on (a chunk's payload, or a file's tail)."""
    while pos < len(buf):
        record = read_record(buf, pos, base=base)
        yield record
        pos = record.end


def _get(record: Record, name: str, size: int | None = None) -> bytes:
    value = record.header.get(name)
    if value is None:
        raise BagFormatError(f"record at offset {record.pos} (op {record.header.get('op', b'?')!r}) "
                             f"lacks its '{name}' field")
    if size is not None and len(value) != size:
        raise BagFormatError(f"record at offset {record.pos}: field '{name}' has {len(value)} bytes, "
                             f"expected {size}")
    return value


def _u32(record: Record, name: str) -> int:
    return int(_unpack_u32(_get(record, name, 4))[0])


def _u64(record: Record, name: str) -> int:
    return int(_U64.unpack(_get(record, name, 8))[0])


def _t(record: Record, name: str) -> Time:
    secs, nsecs = _TIME.unpack(_get(record, name, 8))
    return (secs, nsecs)


def _expect(record: Record, op: int, what: str) -> None:
    if record.op != op:
        raise BagFormatError(f"expected a {what} record at offset {record.pos}, found op {record.op:#04x}")


class FileHeader(_Value):
    __slots__ = ("chunk_count", "conn_count", "index_pos")

    def __init__(self, index_pos: int, conn_count: int, chunk_count: int) -> None:
        self.index_pos = index_pos
        self.conn_count = conn_count
        self.chunk_count = chunk_count


def parse_file_header(record: Record) -> FileHeader:
    _expect(record, OP_FILE_HEADER, "bag header")
    return FileHeader(_u64(record, "index_pos"), _u32(record, "conn_count"), _u32(record, "chunk_count"))


class ChunkHeader(_Value):
    __slots__ = ("compressed_size", "compression", "data_pos", "pos", "uncompressed_size")

    def __init__(self, pos: int, compression: str, uncompressed_size: int, data_pos: int,
                 compressed_size: int) -> None:
        self.pos = pos
        self.compression = compression
        self.uncompressed_size = uncompressed_size
        self.data_pos = data_pos  # relative to the buffer the record was read from
        self.compressed_size = compressed_size


def parse_chunk_header(record: Record) -> ChunkHeader:
    _expect(record, OP_CHUNK, "chunk")
    try:
        compression = _get(record, "compression").decode()
    except UnicodeDecodeError as exc:
        raise BagFormatError(f"chunk at offset {record.pos}: compression name is not text") from exc
    return ChunkHeader(record.pos, compression, _u32(record, "size"), record.data_pos, record.data_len)


class Connection(_Value):
    """A connection: one topic as one publisher (or one writer) gave it."""

    __slots__ = ("header", "id", "topic")

    def __init__(self, id: int, topic: str, header: dict[str, str]) -> None:
        self.id = id
        self.topic = topic
        self.header = header

    @property
    def datatype(self) -> str:
        return self.header.get("type", "")

    @property
    def md5sum(self) -> str:
        return self.header.get("md5sum", "")

    @property
    def msg_def(self) -> str:
        return self.header.get("message_definition", "")


def parse_connection(record: Record, buf: bytes | memoryview) -> Connection:
    _expect(record, OP_CONNECTION, "connection")
    try:
        topic = _get(record, "topic").decode()
        raw = decode_header_fields_raw(buf[record.data_pos:record.end])
        header = {k: v.decode() for k, v in raw.items()}
    except (UnicodeDecodeError, TcprosError) as exc:
        raise BagFormatError(f"bad connection record at offset {record.pos}: {exc}") from exc
    return Connection(_u32(record, "conn"), topic, header)


class ChunkInfo(_Value):
    """Where a chunk is, its time span and how many messages of each connection it holds."""

    __slots__ = ("counts", "end", "pos", "start")

    def __init__(self, pos: int, start: Time, end: Time, counts: dict[int, int] | None = None) -> None:
        self.pos = pos
        self.start = start
        self.end = end
        self.counts = {} if counts is None else counts

    @property
    def message_count(self) -> int:
        return sum(self.counts.values())


def parse_chunk_info(record: Record, buf: bytes | memoryview) -> ChunkInfo:
    _expect(record, OP_CHUNK_INFO, "chunk info")
    ver = _u32(record, "ver")
    if ver != 1:
        raise BagFormatError(f"chunk info at offset {record.pos} has unknown version {ver}")
    count = _u32(record, "count")
    if count * 8 > record.data_len:
        raise BagFormatError(f"chunk info at offset {record.pos} claims {count} connections in "
                             f"{record.data_len} bytes")
    data = bytes(buf[record.data_pos:record.data_pos + count * 8])
    pairs = struct.unpack(f"<{2 * count}I", data)
    counts = dict(zip(pairs[0::2], pairs[1::2], strict=False))
    return ChunkInfo(_u64(record, "chunk_pos"), _t(record, "start_time"), _t(record, "end_time"), counts)


def parse_index_data(record: Record, buf: bytes | memoryview) -> tuple[int, list[tuple[int, int, int]]]:
    """(connection id, [(secs, nsecs, offset in the uncompressed chunk), ...])."""
    _expect(record, OP_INDEX_DATA, "index data")
    ver = _u32(record, "ver")
    if ver != 1:
        raise BagFormatError(f"index data at offset {record.pos} has unknown version {ver}")
    count = _u32(record, "count")
    if count * 12 > record.data_len:
        raise BagFormatError(f"index data at offset {record.pos} claims {count} entries in "
                             f"{record.data_len} bytes")
    entries = list(_INDEX_ENTRY.iter_unpack(buf[record.data_pos:record.data_pos + count * 12]))
    return _u32(record, "conn"), entries


def message_header(record: Record) -> tuple[int, Time]:
    """(connection id, time) of a message data record."""
    _expect(record, OP_MSG_DATA, "message data")
    return _u32(record, "conn"), _t(record, "time")


def message_data_span(buf: bytes | memoryview, offset: int) -> tuple[int, int]:
    """(start, end) of the data of the message data record at `offset` of an uncompressed chunk,
    without parsing its header (the index already said which connection and time it is)."""
    n = len(buf)
    if offset + 4 > n:
        raise BagFormatError(f"index points past its chunk (offset {offset} of {n} bytes)")
    (header_len,) = _unpack_u32(buf, offset)
    start = offset + 8 + header_len
    if start > n:
        raise BagFormatError(f"message record at chunk offset {offset} claims a {header_len}-byte header, "
                             f"past the chunk's {n} bytes")
    (data_len,) = _unpack_u32(buf, start - 4)
    end = start + data_len
    if end > n:
        raise BagFormatError(f"message record at chunk offset {offset} claims {data_len} data bytes, "
                             f"past the chunk's {n} bytes")
    return start, end


def sorted_counts(counts: Mapping[int, int]) -> Sequence[tuple[int, int]]:
    return sorted(counts.items())
