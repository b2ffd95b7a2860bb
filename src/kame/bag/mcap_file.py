"""MCAP files (the format of Foxglove and rosbag2) as kame's bags: read and written with the
`mcap` library, its ros1 profile (schemas "ros1msg": a type's full definition; messages "ros1":
the TCPROS bytes, as a bag holds them).

- `McapReader` answers what rosbag info, play and the Bag API ask a BagReader: connections (one
  per MCAP channel, its connection header remade from the schema and the channel's metadata),
  messages in log-time order as raw bytes, counts and times from the file's summary. The summary
  stands in for a bag's index: the whole file is one ChunkInfo (its time span, its counts per
  channel), and each MCAP chunk a ChunkHeader (its compression and sizes).
- `McapWriter` is what `rosbag record --mcap` writes through.
- `bag_to_mcap` and `mcap_to_bag` convert (`rosbag convert`): message bytes, receive times and
  connection headers are carried over unchanged, so a round trip gives back the same messages.
  A channel's metadata is its connection header less topic, type and message_definition (as
  the `mcap` CLI converts a bag).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator

from mcap.exceptions import McapError
from mcap.reader import make_reader
from mcap.records import Schema
from mcap.writer import CompressionType, Writer

from kame.bag.errors import BagError, BagFormatError
from kame.bag.reader import BagReader, MessageView, RawMessage, is_mcap
from kame.bag.records import ChunkHeader, ChunkInfo, Connection
from kame.bag.writer import BagWriter

__all__ = ["McapReader", "McapWriter", "bag_to_mcap", "is_mcap", "mcap_to_bag"]

PROFILE = "ros1"
ROS1_SCHEMA = "ros1msg"
ROS1_MESSAGES = "ros1"
_HEADER_IN_SCHEMA = ("topic", "type", "message_definition")
_COMPRESSIONS = {"none": CompressionType.NONE, "lz4": CompressionType.LZ4, "zstd": CompressionType.ZSTD}

Time = tuple[int, int]


def _time(ns: int) -> Time:
    return divmod(ns, 1_000_000_000)


def _ns(t: Time) -> int:
    return t[0] * 1_000_000_000 + t[1]


class McapReader:
    """A BagReader's reading side over an MCAP file with the ros1 encodings."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = os.fspath(path)
        self._file = open(self.path, "rb")
        try:
            self.size = os.fstat(self._file.fileno()).st_size
            self._reader = make_reader(self._file)
            try:
                summary = self._reader.get_summary()
            except (McapError, ValueError, EOFError) as exc:
                raise BagFormatError(f"{self.path}: not a readable MCAP file: {exc}") from exc
            if summary is None:
                raise BagFormatError(f"{self.path}: the MCAP file has no summary (not closed?)")
            self.connections: dict[int, Connection] = {}
            for channel in summary.channels.values():
                schema = summary.schemas.get(channel.schema_id)
                if channel.message_encoding != ROS1_MESSAGES or schema is None or schema.encoding != ROS1_SCHEMA:
                    raise BagFormatError(f"{self.path}: channel {channel.topic} is not ROS 1 "
                                         f"({channel.message_encoding}); kame reads ros1 MCAP files")
                header = {"topic": channel.topic, "type": schema.name,
                          "message_definition": schema.data.decode(), **channel.metadata}
                header.setdefault("md5sum", _md5sum(schema))
                self.connections[channel.id] = Connection(channel.id, channel.topic, header)
            stats = summary.statistics
            counts = dict(stats.channel_message_counts) if stats is not None else {}
            self.chunk_infos = ([ChunkInfo(0, _time(stats.message_start_time), _time(stats.message_end_time), counts)]
                                if stats is not None and stats.message_count else [])
            self._chunk_headers = [ChunkHeader(c.chunk_start_offset, c.compression or "none", c.uncompressed_size,
                                               0, c.compressed_size) for c in summary.chunk_indexes]
        except BaseException:
            self._file.close()
            raise

    def close(self) -> None:
        self._file.close()

    def __enter__(self) -> McapReader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def chunk_headers(self) -> list[ChunkHeader]:
        return list(self._chunk_headers)

    def connections_for(self, topics: Iterable[str] | str | None = None,
                        connection_filter: Callable[[Connection], bool] | None = None) -> list[Connection]:
        if isinstance(topics, str):
            topics = [topics]
        wanted = None if topics is None else set(topics)
        return [c for c in self.connections.values()
                if (wanted is None or c.topic in wanted) and (connection_filter is None or connection_filter(c))]

    def message_views(self, connections: list[Connection] | None = None, start: Time | None = None,
                      end: Time | None = None) -> Iterator[MessageView]:
        """Messages with start <= log time <= end, in log-time order (ties in file order)."""
        ids = None if connections is None else {c.id for c in connections}
        topics = None if connections is None else sorted({c.topic for c in connections})
        start_ns = _ns(start) if start is not None else None
        end_ns = _ns(end) + 1 if end is not None else None  # the library's end is exclusive
        try:
            for _, channel, message in self._reader.iter_messages(topics, start_ns, end_ns, log_time_order=True):
                if ids is not None and channel.id not in ids:
                    continue
                secs, nsecs = _time(message.log_time)
                yield self.connections[channel.id], secs, nsecs, memoryview(message.data), 0, message.sequence
        except (McapError, ValueError, EOFError) as exc:
            raise BagFormatError(f"{self.path}: {exc}") from exc

    def messages(self, connections: list[Connection] | None = None, start: Time | None = None,
                 end: Time | None = None) -> Iterator[RawMessage]:
        for conn, secs, nsecs, view, chunk_pos, offset in self.message_views(connections, start, end):
            yield RawMessage(conn, (secs, nsecs), bytes(view), (chunk_pos, offset))

    def index_times(self, connections: list[Connection]) -> list[Time]:
        return sorted((secs, nsecs) for _, secs, nsecs, *_ in self.message_views(connections))

    def message_count(self, topics: Iterable[str] | str | None = None) -> int:
        ids = {c.id for c in self.connections_for(topics)}
        return sum(n for info in self.chunk_infos for c, n in info.counts.items() if c in ids)

    @property
    def start_time(self) -> Time | None:
        return self.chunk_infos[0].start if self.chunk_infos else None

    @property
    def end_time(self) -> Time | None:
        return self.chunk_infos[0].end if self.chunk_infos else None


def _md5sum(schema: Schema) -> str:
    """The md5sum of a schema's type (a file written without one in its channels' metadata)."""
    from kame.msg.lookup import class_for

    try:
        cls = class_for(schema.name, "*", schema.data.decode())
    except Exception:  # a definition kame cannot read: the type is still listed, its md5sum unknown
        return "*"
    return "*" if cls is None else str(cls._md5sum)


class McapWriter:
    """What `rosbag record --mcap` writes through: a BagWriter's add_connection, write,
    write_pending, size and close, into an MCAP file. A connection becomes a channel whose schema
    is (type, definition) and whose metadata is the rest of its header. The open chunk (up to
    `chunk_size` bytes) is in memory until it is full or the file is closed: MCAP has no
    equivalent of `rosbag reindex`, so a recorder killed outright loses it."""

    def __init__(self, path: str, compression: str = "zstd", chunk_size: int = 768 * 1024) -> None:
        if compression not in _COMPRESSIONS:
            raise BagError(f"unknown MCAP compression [{compression}] (none, lz4 or zstd)")
        self._file = open(path, "wb")
        try:
            self._writer = Writer(self._file, chunk_size=chunk_size, compression=_COMPRESSIONS[compression])
            self._writer.start(profile=PROFILE, library="kame")
        except BaseException:
            self._file.close()
            raise
        self._schemas: dict[tuple[str, str], int] = {}
        self._sequence = 0

    def add_connection(self, topic: str, header: dict[str, str]) -> int:
        key = (header.get("type", ""), header.get("message_definition", ""))
        schema_id = self._schemas.get(key)
        if schema_id is None:
            schema_id = self._schemas[key] = self._writer.register_schema(key[0], ROS1_SCHEMA, key[1].encode())
        metadata = {k: v for k, v in header.items() if k not in _HEADER_IN_SCHEMA}
        return int(self._writer.register_channel(topic, ROS1_MESSAGES, schema_id, metadata))

    def write(self, conn_id: int, secs: int, nsecs: int, data: bytes | memoryview, owned: bool = False) -> None:
        stamp = secs * 1_000_000_000 + nsecs
        self._writer.add_message(conn_id, stamp, bytes(data), stamp, sequence=self._sequence)
        self._sequence += 1

    def write_pending(self) -> None:
        self._file.flush()

    @property
    def size(self) -> int:
        return self._file.tell()

    def close(self) -> None:
        if self._file.closed:
            return
        try:
            self._writer.finish()  # type: ignore[no-untyped-call]
        finally:
            self._file.close()


def bag_to_mcap(in_path: str, out_path: str, compression: str = "zstd",
                progress: Callable[[int, int], None] | None = None) -> int:
    """Write a bag's messages into a new MCAP file; returns the number of messages."""
    if compression not in _COMPRESSIONS:
        raise BagError(f"unknown MCAP compression [{compression}] (none, lz4 or zstd)")
    written = 0
    with BagReader(in_path) as reader, open(out_path, "wb") as out:
        total = max(reader.message_count(), 1)
        writer = Writer(out, compression=_COMPRESSIONS[compression])
        writer.start(profile=PROFILE, library="kame")
        schemas: dict[tuple[str, str], int] = {}
        channels: dict[int, int] = {}
        for m in reader.messages():
            channel_id = channels.get(m.conn.id)
            if channel_id is None:
                key = (m.conn.datatype, m.conn.msg_def)
                schema_id = schemas.get(key)
                if schema_id is None:
                    schema_id = schemas[key] = writer.register_schema(key[0], ROS1_SCHEMA, key[1].encode())
                metadata = {k: v for k, v in m.conn.header.items() if k not in _HEADER_IN_SCHEMA}
                channel_id = channels[m.conn.id] = writer.register_channel(m.conn.topic, ROS1_MESSAGES, schema_id,
                                                                           metadata)
            stamp = _ns(m.time)
            writer.add_message(channel_id, stamp, m.data, stamp, sequence=written)
            written += 1
            if progress is not None and written % 1000 == 0:
                progress(written, total)
        writer.finish()  # type: ignore[no-untyped-call]
    if progress is not None:
        progress(total, total)
    return written


def mcap_to_bag(in_path: str, out_path: str, compression: str = "none",
                progress: Callable[[int, int], None] | None = None) -> int:
    """Write an MCAP file's ros1 messages into a new bag; returns the number of messages."""
    written = 0
    with McapReader(in_path) as reader, BagWriter(out_path, "w", compression) as writer:
        total = max(reader.message_count(), 1)
        ids: dict[int, int] = {}
        for m in reader.messages():
            conn_id = ids.get(m.conn.id)
            if conn_id is None:
                conn_id = ids[m.conn.id] = writer.add_connection(m.conn.topic, m.conn.header)
            writer.write(conn_id, m.time[0], m.time[1], m.data)
            written += 1
            if progress is not None and written % 1000 == 0:
                progress(written, total)
    if progress is not None:
        progress(total, total)
    return written

