"""The Bag of ROS users' scripts (rosbag.Bag), over kame.bag's reader and writer.

Messages are deserialized with kame's own class when it has the type with the same md5sum,
otherwise with a class built from the connection's message_definition (so any bag reads,
whatever is installed). Timestamps are rospy.Time values.
"""

from __future__ import annotations

import collections
import io
import itertools
import os
import statistics
import time
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any, BinaryIO

from kame.bag.compression import COMPRESSIONS
from kame.bag.errors import BagError, BagFormatError, BagUnindexedError
from kame.bag.info import BagSummary, info_text, info_yaml, yaml_key
from kame.bag.reader import BagReader, open_reader
from kame.bag.records import MAGIC, ChunkInfo, Connection
from kame.bag.writer import DEFAULT_CHUNK_THRESHOLD, BagWriter
from kame.client.clock import Time
from kame.msg.errors import MessageError
from kame.msg.lookup import class_for, installed_class

if TYPE_CHECKING:
    from kame.bag.mcap_file import McapReader

__all__ = [
    "Bag",
    "BagMessage",
    "Compression",
    "ROSBagEncryptException",
    "ROSBagEncryptNotSupportedException",
    "ROSBagException",
    "ROSBagFormatException",
    "ROSBagUnindexedException",
]

ROSBagException = BagError
ROSBagFormatException = BagFormatError
ROSBagUnindexedException = BagUnindexedError


class ROSBagEncryptNotSupportedException(BagError):
    pass


class ROSBagEncryptException(BagError):
    pass


class Compression:
    NONE = "none"
    BZ2 = "bz2"
    LZ4 = "lz4"


BagMessage = collections.namedtuple("BagMessage", "topic message timestamp")
BagMessageWithConnectionHeader = collections.namedtuple("BagMessageWithConnectionHeader",
                                                        "topic message timestamp connection_header")
TopicTuple = collections.namedtuple("TopicTuple", ["msg_type", "message_count", "connections", "frequency"])
TypesAndTopicsTuple = collections.namedtuple("TypesAndTopicsTuple", ["msg_types", "topics"])
CompressionTuple = collections.namedtuple("CompressionTuple", ["compression", "uncompressed", "compressed"])


def message_class(conn: Connection) -> type[Any]:
    """The class that deserializes a connection's messages."""
    try:
        cls = class_for(conn.datatype, conn.md5sum, conn.msg_def)
    except MessageError as exc:
        raise BagError(f"cannot build message type [{conn.datatype}] from the bag's definition: "
                       f"{exc}") from exc
    if cls is None:
        raise BagError(f"Cannot deserialize messages of type [{conn.datatype}]: the bag has no "
                       "message_definition for it and kame does not have it installed")
    return cls


def _to_time(value: Any) -> tuple[int, int] | None:
    if value is None:
        return None
    if isinstance(value, (int, float)):
        secs = int(value)
        return (secs, round((value - secs) * 1e9))
    return (int(value.secs), int(value.nsecs))


class Bag:
    """A ROS bag opened for reading ('r'), writing ('w') or appending ('a')."""

    def __init__(self, f: str | os.PathLike[str] | BinaryIO, mode: str = "r", compression: str = Compression.NONE,
                 chunk_threshold: int = DEFAULT_CHUNK_THRESHOLD, allow_unindexed: bool = False,
                 options: dict[str, Any] | None = None, skip_index: bool = False) -> None:
        # rosbag's checks, in its order, before any file is touched
        if options is not None:
            if type(options) is not dict:
                raise ValueError("options must be of type dict")
            compression = options.get("compression", compression)
            chunk_threshold = options.get("chunk_threshold", chunk_threshold)
        if compression not in COMPRESSIONS:
            raise ValueError(f"compression must be one of: {', '.join(COMPRESSIONS)}")
        if chunk_threshold < 0:
            raise ValueError("chunk_threshold must be greater than or equal to zero")
        if not f:
            raise ValueError("filename (or stream) is invalid")
        if mode not in ("r", "w", "a"):
            raise ValueError(f'mode "{mode}" is invalid')
        self._caller_file: BinaryIO | None = None
        self._filename: str | None = None  # rosbag's for a file object
        if isinstance(f, (str, os.PathLike)):
            self._filename = os.fspath(f)
        else:
            try:
                f.fileno()
            except (AttributeError, OSError):
                raise ValueError("kame's Bag reads and writes a file with a descriptor, not a stream "
                                 "such as io.BytesIO") from None
            self._caller_file = f
        self._mode = mode
        self._compression = compression
        self._chunk_threshold = chunk_threshold
        self._reader: BagReader | McapReader | None = None
        self._writer: BagWriter | None = None
        self._topic_conns: dict[str, int] = {}
        self._read_file: BinaryIO | None = None  # `_file` of a bag opened by name for reading
        source: str | BinaryIO = self._caller_file if self._caller_file is not None else self._filename or ""
        if mode == "r":
            if self._caller_file is not None:
                self._reader = BagReader(self._caller_file, allow_unindexed=allow_unindexed)
            else:  # by name: a bag 2.0 or, by its first bytes, an MCAP file
                self._reader = open_reader(self._filename or "", allow_unindexed=allow_unindexed)
        elif mode == "w" or (self._filename is not None and
                             (not os.path.exists(self._filename) or os.path.getsize(self._filename) == 0)):
            self._writer = BagWriter(source, "w", compression, chunk_threshold)
        else:
            self._writer = BagWriter(source, "a", compression, chunk_threshold, allow_unindexed=allow_unindexed)
            for conn in self._writer.connections.values():
                self._topic_conns.setdefault(conn.topic, conn.id)

    @property
    def filename(self) -> str | None:
        return self._filename

    @property
    def mode(self) -> str:
        return self._mode

    @property
    def version(self) -> int:
        return 200

    # rosbag's private attributes, which its reindex and migration code (and scripts copied
    # from them) reach for: the open file, the file header record's offset, the format version
    _version = 200
    _file_header_pos = len(MAGIC)

    @property
    def _file(self) -> BinaryIO:
        if self._caller_file is not None:
            return self._caller_file
        if self._writer is not None:
            return self._writer.file
        if self._read_file is None:
            self._read_file = open(self._filename or "", "rb")  # closed by close()
        return self._read_file

    @property
    def size(self) -> int:
        """The file's size in bytes; ValueError once the bag is closed, as rosbag."""
        if self._closed:
            raise ValueError("I/O operation on closed bag")
        if self._writer is not None:
            return self._writer.size
        assert self._reader is not None
        return self._reader.size

    @property
    def compression(self) -> str:
        return self._compression

    @compression.setter
    def compression(self, value: str) -> None:
        if value not in COMPRESSIONS:
            raise ValueError(f"compression must be one of: {', '.join(COMPRESSIONS)}")
        self._compression = value
        if self._writer is not None:
            self._writer.flush_chunk()
            self._writer.compression = value

    @property
    def chunk_threshold(self) -> int:
        return self._chunk_threshold

    @chunk_threshold.setter
    def chunk_threshold(self, value: int) -> None:
        self._chunk_threshold = value
        if self._writer is not None:
            self._writer.chunk_threshold = value

    def _read_side(self) -> BagReader | McapReader:
        if self._reader is None:
            if self._writer is not None and not self._writer.closed:
                raise ValueError("the bag is open for writing; close it before reading")
            raise ValueError("I/O operation on closed bag")
        return self._reader

    _closed = False

    # ------------------------------------------------------------------ context

    def __enter__(self) -> Bag:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __iter__(self) -> Iterator[Any]:
        return self.read_messages()

    def close(self) -> None:
        self._closed = True
        if self._writer is not None:
            self._writer.close()
        if self._reader is not None:
            self._reader.close()
        for file in (self._read_file, self._caller_file):  # rosbag closes a file it was given, too
            if file is not None:
                file.close()

    def flush(self) -> None:
        if self._writer is not None:
            self._writer.flush()

    # ------------------------------------------------------------------ reading

    def read_messages(self, topics: Any = None, start_time: Any = None, end_time: Any = None,
                      connection_filter: Callable[..., bool] | None = None, raw: bool = False,
                      return_connection_header: bool = False) -> Iterator[Any]:
        if self._closed:  # the index stays readable after close (counts, times); the data does not
            raise ValueError("I/O operation on closed bag")
        reader = self._read_side()
        conn_filter: Callable[[Connection], bool] | None = None
        if connection_filter is not None:
            user_filter = connection_filter

            def conn_filter(c: Connection) -> bool:
                return bool(user_filter(c.topic, c.datatype, c.md5sum, c.msg_def, c.header))
        conns = reader.connections_for(topics, conn_filter) if topics is not None or conn_filter is not None else None
        if conns == []:
            return
        # (class, its buffer constructor: deserialize without the __init__ defaults it would overwrite)
        classes: dict[int, tuple[type[Any], Any]] = {}
        new_time = Time.__new__
        new_tuple = tuple.__new__
        result_type = BagMessageWithConnectionHeader if return_connection_header else BagMessage
        for conn, secs, nsecs, view, chunk_pos, offset in reader.message_views(conns, _to_time(start_time),
                                                                                 _to_time(end_time)):
            entry = classes.get(conn.id)
            if entry is None:
                cls = message_class(conn)
                entry = classes[conn.id] = (cls, cls._from_buffer)
            if raw:
                msg: Any = (conn.datatype, bytes(view), conn.md5sum, (chunk_pos, offset), entry[0])
            else:
                msg = entry[1](view)  # straight from the chunk: one copy, into the message's fields
            if nsecs < 1_000_000_000:  # canonical, as every writer stores it: skip Time's checks
                t = new_time(Time)
                t.secs = secs
                t.nsecs = nsecs
            else:
                t = Time(secs, nsecs)
            if return_connection_header:
                yield new_tuple(result_type, (conn.topic, msg, t, conn.header))
            else:
                yield new_tuple(result_type, (conn.topic, msg, t))

    def _index(self) -> tuple[dict[int, Connection], list[ChunkInfo]]:
        """The connections and chunks of the index, which rosbag keeps (and answers from) while
        writing and after closing."""
        if self._writer is not None:
            return self._writer.connections, self._writer.index()
        reader = self._read_side()
        return reader.connections, reader.chunk_infos

    def _time_chunks(self) -> list[ChunkInfo]:
        """The chunks rosbag takes a bag's start and end from: the first's start, the last's end
        (in file order, not the earliest and latest); while writing, the chunks already written,
        or the open one before there are any."""
        chunks = self._writer.chunk_infos if self._writer is not None else []
        chunks = chunks or self._index()[1]
        if not chunks:
            raise BagError("Bag contains no message")
        return chunks

    def get_message_count(self, topic_filters: Any = None) -> int:
        connections, chunks = self._index()
        if isinstance(topic_filters, str):
            topic_filters = [topic_filters]
        ids = {c.id for c in connections.values() if topic_filters is None or c.topic in topic_filters}
        return sum(n for info in chunks for conn_id, n in info.counts.items() if conn_id in ids)

    def get_start_time(self) -> float:
        secs, nsecs = self._time_chunks()[0].start
        return secs + nsecs / 1e9

    def get_end_time(self) -> float:
        secs, nsecs = self._time_chunks()[-1].end
        return secs + nsecs / 1e9

    def _frequencies(self, topics: list[str]) -> dict[str, float]:
        reader = self._read_side()
        out: dict[str, float] = {}
        for topic in topics:
            stamps = [s + n / 1e9 for s, n in reader.index_times(reader.connections_for(topic))]
            if len(stamps) > 1:
                med = statistics.median([b - a for a, b in itertools.pairwise(stamps)])
                if med > 0.0:
                    out[topic] = 1.0 / med
        return out

    def get_type_and_topic_info(self, topic_filters: Any = None) -> Any:
        reader = self._read_side()
        types: dict[str, str] = {}
        for conn in reader.connections.values():
            types.setdefault(conn.datatype, conn.md5sum)
        if topic_filters is not None:
            wanted = sorted(set([topic_filters] if isinstance(topic_filters, str) else topic_filters))
        else:
            wanted = sorted({c.topic for c in reader.connections.values()})
        topics = {}
        freqs = self._frequencies(wanted)
        for topic in wanted:
            conns = reader.connections_for(topic)
            if not conns:
                continue
            topics[topic] = TopicTuple(conns[0].datatype, reader.message_count(topic), len(conns), freqs.get(topic))
        return TypesAndTopicsTuple(dict(sorted(types.items())), topics)

    def get_compression_info(self) -> Any:
        headers = self._read_side().chunk_headers()
        if not headers:
            return CompressionTuple(self._compression, 0, 0)
        counts: dict[str, int] = collections.Counter(h.compression for h in headers)
        main = sorted(((v, k) for k, v in counts.items()), reverse=True)[0][1]
        return CompressionTuple(main, sum(h.uncompressed_size for h in headers),
                                sum(h.compressed_size for h in headers))

    def summary(self, frequencies: bool = False) -> BagSummary:
        reader = self._read_side()
        freqs = self._frequencies(sorted({c.topic for c in reader.connections.values()})) if frequencies else None
        return BagSummary(self._filename or "", self.size, reader.connections, reader.chunk_infos,
                          reader.chunk_headers(), freqs, "2.0" if isinstance(reader, BagReader) else "mcap")

    def __str__(self) -> str:
        return info_text(self.summary())

    def _get_yaml_info(self, key: str | None = None) -> str | None:
        text = info_yaml(self.summary())
        return text if not key else yaml_key(text, key)

    # ------------------------------------------------------------------ writing

    def write(self, topic: str, msg: Any, t: Any = None, raw: bool = False,
              connection_header: dict[str, str] | None = None) -> None:
        writer = self._writer
        if writer is None or writer.closed:
            raise io.UnsupportedOperation("write")  # what rosbag's read-only file raises
        if not topic:
            raise ValueError("topic is invalid")
        if msg is None:
            raise ValueError("msg is invalid")
        if t is None:  # wall time, as rosbag stamps it (no node or ROS clock needed)
            t = Time.from_sec(time.time())
        secs, nsecs = _to_time(t) or (0, 0)
        if raw:
            if len(msg) == 5:
                msg_type, data, md5sum, _pos, pytype = msg
            elif len(msg) == 4:
                msg_type, data, md5sum, pytype = msg
            else:
                raise ValueError("msg must be of length 4 or 5")
        conn_id = self._topic_conns.get(topic)
        if conn_id is None:
            if raw:
                definition = getattr(pytype, "_full_text", None) if pytype is not None else None
                if definition is None:
                    found = installed_class(msg_type, md5sum)
                    if found is None:
                        raise BagError(f"cannot locate message class and no message class provided for [{msg_type}]")
                    definition = found._full_text
                header = connection_header or {"topic": topic, "type": msg_type, "md5sum": md5sum,
                                               "message_definition": definition}
            else:
                header = connection_header or {"topic": topic, "type": msg._type, "md5sum": msg._md5sum,
                                               "message_definition": msg._full_text}
            conn_id = self._topic_conns[topic] = writer.add_connection(topic, header)
        if not raw:
            buff = io.BytesIO()
            msg.serialize(buff)
            data = buff.getvalue()
        writer.write(conn_id, secs, nsecs, data)

    # ------------------------------------------------------------------ repair

    def reindex(self) -> Iterator[int]:
        """Rebuild the index of a bag opened with mode 'a' and allow_unindexed=True (rosbag's
        way): yields the offset of each chunk. kame rebuilds it while opening, dropping what
        follows the last intact chunk; closing the bag writes the new index."""
        if self._writer is not None:
            yield from (info.pos for info in self._writer.chunk_infos)
        else:
            yield from (info.pos for info in self._read_side().chunk_infos)
