"""Reading bag 2.0 files: the index, chunks, and messages in time order, as raw bytes.

Rules:
- Opening reads the 13-byte magic, the bag header and the index at its end (connection and
  chunk info records) with a handful of reads: no chunk is touched, so `rosbag info` costs
  the same for 1 MB and 100 GB. Chunk headers (compression, sizes) are read when asked for.
- Reading a chunk reads it and the index data records after it in one read, decompresses
  it once, and takes messages straight at the offsets the index gives. A chunk whose index
  data is missing or inconsistent is walked record by record instead.
- Every offset and length from the file is checked against the file size before a read, so
  a lying bag yields a BagError naming the offset, never a read outside the file or a hang.
- A bag without a usable index (not closed: index_pos=0, or a broken tail) raises
  BagUnindexedError unless opened with `allow_unindexed`, which rebuilds the index in memory
  by walking the chunks and stops at the first broken one (`reindex_end` says where). An
  uncompressed chunk torn by a killed recorder (its header still has the zero sizes it was
  streamed with, or its data runs past the end of the file) keeps every whole message record
  it holds; `torn` then says where it is and how much of it is good, for reindex to seal it.
- Messages come out in time order (ties in file order); chunks that overlap in time are
  merged, others are read one after another.
"""

from __future__ import annotations

import heapq
import itertools
import os
import struct
from collections.abc import Callable, Iterable, Iterator
from typing import TYPE_CHECKING, BinaryIO

from kame.bag import records
from kame.bag.compression import decompress
from kame.bag.errors import BagError, BagFormatError, BagUnindexedError
from kame.bag.records import ChunkHeader, ChunkInfo, Connection
from kame.protocol.header import TcprosError, decode_header_fields_raw

if TYPE_CHECKING:
    from kame.bag.mcap_file import McapReader

__all__ = ["BagReader", "MessageView", "RawMessage", "is_mcap", "open_reader"]

MCAP_MAGIC = b"\x89MCAP0\r\n"

Time = tuple[int, int]
#: (connection, secs, nsecs, data, chunk position, offset in the uncompressed chunk)
MessageView = tuple[Connection, int, int, memoryview, int, int]
_NO_END = (0xFFFFFFFF, 0xFFFFFFFF)


class RawMessage:
    """One message as stored: its connection, receive time and serialized bytes."""

    __slots__ = ("conn", "data", "position", "time")

    def __init__(self, conn: Connection, time: Time, data: bytes, position: tuple[int, int]) -> None:
        self.conn = conn
        self.time = time
        self.data = data
        self.position = position  # (chunk position, offset in the uncompressed chunk)


class _ChunkEntries:
    __slots__ = ("data", "entries", "info")

    def __init__(self, info: ChunkInfo, data: bytes | memoryview, entries: list[tuple[int, int, int, int]]) -> None:
        self.info = info
        self.data = data
        self.entries = entries  # (secs, nsecs, offset, conn), sorted


class BagReader:
    def __init__(self, path: str | os.PathLike[str] | BinaryIO, allow_unindexed: bool = False) -> None:
        """`path` may also be an open binary file (anything with a fileno()): it is read through
        a duplicate of its descriptor, so the caller's file stays the caller's to close."""
        if isinstance(path, (str, os.PathLike)):
            self.path = os.fspath(path)
            self._fd = os.open(self.path, os.O_RDONLY)
        else:
            self.path = str(getattr(path, "name", "<stream>"))
            self._fd = os.dup(path.fileno())
        try:
            self.size = os.fstat(self._fd).st_size
            self.connections: dict[int, Connection] = {}
            self.chunk_infos: list[ChunkInfo] = []
            self._chunk_headers: dict[int, ChunkHeader] = {}
            self._reindexed: dict[int, list[tuple[int, int, int, int]]] = {}
            self._chunk_ends: dict[int, int] = {}
            self.indexed = True
            self.reindex_end: int | None = None  # after a rebuild: where the good data ends
            self.torn: ChunkHeader | None = None  # after a rebuild: the torn last chunk, its good part
            self._open(allow_unindexed)
        except BaseException:
            os.close(self._fd)
            raise

    # ------------------------------------------------------------------ file access

    def _read(self, pos: int, size: int) -> bytes:
        if pos < 0 or size < 0 or pos + size > self.size:
            raise BagFormatError(f"{self.path}: a read of {size} bytes at offset {pos} would pass the end "
                                 f"of the file ({self.size} bytes)")
        data = os.pread(self._fd, size, pos)
        if len(data) != size:
            raise BagFormatError(f"{self.path}: short read at offset {pos} (file changed while reading?)")
        return data

    def close(self) -> None:
        if self._fd >= 0:
            os.close(self._fd)
            self._fd = -1

    def __enter__(self) -> BagReader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------------ opening

    def _open(self, allow_unindexed: bool) -> None:
        if self.size < len(records.MAGIC):
            raise BagFormatError(f"{self.path} is empty or too short to be a bag ({self.size} bytes)")
        magic = self._read(0, len(records.MAGIC))
        if magic != records.MAGIC:
            if magic.startswith(b"#ROSRECORD V1.") or magic.startswith(b"#ROSBAG V1."):
                raise BagError(f"{self.path} is a version 1.x bag: kame reads bag format 2.0")
            raise BagFormatError(f"{self.path} is not a bag file (it does not start with #ROSBAG V2.0)")
        head = self._read(len(records.MAGIC), min(self.size - len(records.MAGIC), records.FILE_HEADER_RECORD_SIZE))
        try:
            header = records.parse_file_header(records.read_record(head, 0, base=len(records.MAGIC)))
        except BagFormatError as exc:
            raise BagFormatError(f"{self.path}: bad bag header: {exc}") from exc
        self.index_pos = header.index_pos
        self.header_end = len(records.MAGIC) + records.read_record(head, 0).end
        problem = None
        if header.index_pos == 0 or (header.chunk_count == 0 and self.size > records.FIRST_RECORD_POS):
            problem = "the bag was not closed (its index was never written)"
        elif header.index_pos < self.header_end or header.index_pos > self.size:
            problem = f"its index position {header.index_pos} lies outside the file ({self.size} bytes)"
        else:
            try:
                self._read_index(header)
            except BagError as exc:
                problem = f"its index is broken: {exc}"
        if problem is None:
            return
        if not allow_unindexed:
            raise BagUnindexedError(f"{self.path} is unindexed: {problem}; run rosbag reindex")
        self.indexed = False
        self.connections = {}
        self.chunk_infos = []
        self.rebuild_index()

    def _read_index(self, header: records.FileHeader) -> None:
        tail = self._read(header.index_pos, self.size - header.index_pos)
        for record in records.walk_records(tail, base=header.index_pos):
            op = record.op
            if op == records.OP_CONNECTION:
                conn = records.parse_connection(record, tail)
                self.connections.setdefault(conn.id, conn)
            elif op == records.OP_CHUNK_INFO:
                info = records.parse_chunk_info(record, tail)
                if not records.FIRST_RECORD_POS <= info.pos < header.index_pos:
                    raise BagFormatError(f"chunk info at offset {header.index_pos + record.pos} points at "
                                         f"{info.pos}, outside the chunk section")
                self.chunk_infos.append(info)
        if len(self.chunk_infos) != header.chunk_count:
            raise BagFormatError(f"the header promises {header.chunk_count} chunks, the index lists "
                                 f"{len(self.chunk_infos)}")
        for info in self.chunk_infos:
            for conn_id in info.counts:
                if conn_id not in self.connections:
                    raise BagFormatError(f"chunk at {info.pos} names connection {conn_id}, which has no record")
        ordered = sorted(info.pos for info in self.chunk_infos)
        for pos, nxt in zip(ordered, [*ordered[1:], header.index_pos], strict=False):
            self._chunk_ends[pos] = nxt

    def rebuild_index(self, progress: Callable[[int], None] | None = None) -> None:
        """Walk the chunks from the first on, rebuilding connections, chunk infos and message
        entries; stop at the first chunk that is truncated or corrupt."""
        pos = records.FIRST_RECORD_POS
        end = self.size
        good_end = pos
        while pos < end:
            if progress is not None:
                progress(pos)
            try:
                next_pos = self._reindex_chunk(pos)
            except BagError:
                break
            if next_pos is None:  # the index section (a closed bag's tail)
                break
            pos = good_end = next_pos
            if self.torn is not None:
                break
        self.reindex_end = good_end
        self.index_pos = good_end
        self._chunk_ends = {}
        ordered = sorted(info.pos for info in self.chunk_infos)
        for p, nxt in zip(ordered, [*ordered[1:], good_end], strict=False):
            self._chunk_ends[p] = nxt

    def _record_head(self, pos: int, whole: bool = True) -> records.Record:
        """The record at file offset `pos`, its header parsed, its data not read (positions are
        absolute); the data must lie inside the file, if `whole`."""
        if pos + 8 > self.size:
            raise BagFormatError(f"truncated record at offset {pos}")
        head = self._read(pos, min(self.size - pos, 4096))
        (header_len,) = records.unpack_u32(head, 0)
        if header_len + 8 > len(head):
            if pos + 8 + header_len > self.size:
                raise BagFormatError(f"record at offset {pos} claims a {header_len}-byte header, past the end")
            head = self._read(pos, header_len + 8)
        try:
            fields = decode_header_fields_raw(head[4:4 + header_len])
        except TcprosError as exc:
            raise BagFormatError(f"bad record header at offset {pos}: {exc}") from exc
        (data_len,) = records.unpack_u32(head, 4 + header_len)
        data_pos = pos + 8 + header_len
        if whole and data_pos + data_len > self.size:
            raise BagFormatError(f"record at offset {pos} claims {data_len} data bytes, but only "
                                 f"{self.size - data_pos} remain in the file")
        return records.Record(pos, fields, data_pos, data_len)

    def _reindex_chunk(self, pos: int) -> int | None:
        """Index the chunk at `pos` and skip the index data records after it; return where the
        next chunk starts, or None when `pos` holds no chunk."""
        head = self._record_head(pos, whole=False)
        if head.op != records.OP_CHUNK:
            return None
        chunk = records.parse_chunk_header(head)
        torn = chunk.compression == "none" and (chunk.compressed_size == 0 or head.end > self.size)
        if chunk.compressed_size == 0 and not torn:
            raise BagFormatError(f"unterminated chunk at {pos}")
        if head.end > self.size and not torn:
            raise BagFormatError(f"chunk at offset {pos} claims {head.data_len} data bytes, but only "
                                 f"{self.size - head.data_pos} remain in the file")
        chunk = ChunkHeader(pos, chunk.compression, chunk.uncompressed_size, chunk.data_pos - pos,
                            chunk.compressed_size)
        if torn:
            data: bytes | memoryview = self._read(head.data_pos, self.size - head.data_pos)
        else:
            payload = self._read(pos + chunk.data_pos, chunk.compressed_size)
            data = decompress(chunk.compression, payload, chunk.uncompressed_size, f" at offset {pos}")
        entries: list[tuple[int, int, int, int]] = []
        new_conns: list[Connection] = []
        good = 0
        for record in _whole_records(data) if torn else records.walk_records(data):
            op = record.op
            if op == records.OP_CONNECTION:
                new_conns.append(records.parse_connection(record, data))
            elif op == records.OP_MSG_DATA:
                conn_id, t = records.message_header(record)
                entries.append((t[0], t[1], record.pos, conn_id))
            good = record.end
        if torn:
            chunk = ChunkHeader(pos, "none", good, chunk.data_pos, good)
            self.torn = chunk
        for conn in new_conns:
            self.connections.setdefault(conn.id, conn)
        known = self.connections
        entries = [e for e in entries if e[3] in known]
        if torn and not entries:  # nothing to keep: the good data ends before it
            self.torn = None
            return None
        next_pos = pos + chunk.data_pos + chunk.compressed_size
        while not torn and next_pos + 8 <= self.size:  # skip the index data records that follow the chunk
            try:
                record = self._record_head(next_pos)
            except BagFormatError:
                break
            if record.op != records.OP_INDEX_DATA:
                break
            next_pos = record.end
        if entries:
            entries.sort()
            counts: dict[int, int] = {}
            for e in entries:
                counts[e[3]] = counts.get(e[3], 0) + 1
            info = ChunkInfo(pos, (entries[0][0], entries[0][1]), (entries[-1][0], entries[-1][1]), counts)
            self.chunk_infos.append(info)
            self._chunk_headers[pos] = chunk
            self._reindexed[pos] = entries
        return next_pos

    # ------------------------------------------------------------------ chunks

    def chunk_entries(self, pos: int) -> list[tuple[int, int, int, int]]:
        """The (secs, nsecs, offset, connection) of every message of the chunk at `pos`, in
        time order."""
        info = next(i for i in self.chunk_infos if i.pos == pos)
        return self._reindexed.get(pos) or self._load_chunk(info, None).entries

    def chunk_header(self, info: ChunkInfo) -> ChunkHeader:
        header = self._chunk_headers.get(info.pos)
        if header is None:
            record = self._record_head(info.pos)
            parsed = records.parse_chunk_header(record)
            header = ChunkHeader(info.pos, parsed.compression, parsed.uncompressed_size, parsed.data_pos - info.pos,
                                 parsed.compressed_size)
            self._chunk_headers[info.pos] = header
        return header

    def chunk_headers(self) -> list[ChunkHeader]:
        return [self.chunk_header(info) for info in self.chunk_infos]

    def _load_chunk(self, info: ChunkInfo, conns: set[int] | None) -> _ChunkEntries:
        where = f" at offset {info.pos}"
        end = self._chunk_ends.get(info.pos, self.size)
        blob = self._read(info.pos, end - info.pos)
        data: bytes | memoryview
        if self.torn is not None and self.torn.pos == info.pos:
            data = memoryview(blob)[self.torn.data_pos:self.torn.data_pos + self.torn.compressed_size]
        else:
            record = records.read_record(blob, 0, base=info.pos)
            chunk = records.parse_chunk_header(record)
            # a view, not a slice: an uncompressed chunk's messages are then copied once, not twice
            data = decompress(chunk.compression, memoryview(blob)[record.data_pos:record.end],
                              chunk.uncompressed_size, where)
        entries = self._reindexed.get(info.pos)
        if entries is None:
            entries = self._index_entries(blob, record.end, info, len(data))
            if entries is None:
                entries = self._walk_entries(data, info)
        if conns is not None:
            entries = [e for e in entries if e[3] in conns]
        return _ChunkEntries(info, data, entries)

    def _index_entries(self, blob: bytes, pos: int, info: ChunkInfo,
                       data_len: int) -> list[tuple[int, int, int, int]] | None:
        out: list[tuple[int, int, int, int]] = []
        seen: dict[int, int] = {}
        try:
            while pos < len(blob):
                record = records.read_record(blob, pos)
                if record.op != records.OP_INDEX_DATA:
                    break
                conn_id, entries = records.parse_index_data(record, blob)
                out.extend([(s, n, off, conn_id) for s, n, off in entries])
                seen[conn_id] = seen.get(conn_id, 0) + len(entries)
                pos = record.end
        except BagFormatError:
            return None
        if seen != info.counts or any(e[2] >= data_len for e in out):
            return None
        out.sort()  # linear when in order already; one connection's messages may be written out of time order
        return out

    def _walk_entries(self, data: bytes | memoryview, info: ChunkInfo) -> list[tuple[int, int, int, int]]:
        out = []
        for record in records.walk_records(data, base=0):
            if record.op == records.OP_MSG_DATA:
                conn_id, t = records.message_header(record)
                out.append((t[0], t[1], record.pos, conn_id))
        out.sort()
        return out

    # ------------------------------------------------------------------ messages

    def connections_for(self, topics: Iterable[str] | str | None = None,
                        connection_filter: Callable[[Connection], bool] | None = None) -> list[Connection]:
        if isinstance(topics, str):
            topics = [topics]
        wanted = None if topics is None else set(topics)
        return [c for c in self.connections.values()
                if (wanted is None or c.topic in wanted) and (connection_filter is None or connection_filter(c))]

    def messages(self, connections: list[Connection] | None = None, start: Time | None = None,
                 end: Time | None = None) -> Iterator[RawMessage]:
        """Messages of `connections` (default: all) with start <= time <= end, in time order."""
        for conn, secs, nsecs, view, chunk_pos, offset in self.message_views(connections, start, end):
            yield RawMessage(conn, (secs, nsecs), bytes(view), (chunk_pos, offset))

    def message_views(self, connections: list[Connection] | None = None, start: Time | None = None,
                      end: Time | None = None) -> Iterator[MessageView]:
        """As `messages`, as plain tuples (connection, secs, nsecs, data, chunk position, offset)
        whose data is a zero-copy view into the chunk (holding it keeps the chunk's buffer
        alive): for readers that deserialize at once and need neither a copy nor an object per
        message."""
        conns = {c.id: c for c in (self.connections.values() if connections is None else connections)}
        wanted = None if connections is None else set(conns)
        lo = start or (0, 0)
        hi = end or _NO_END
        chunks = [info for info in self.chunk_infos
                  if info.end >= lo and info.start <= hi
                  and (wanted is None or any(c in wanted for c in info.counts))]
        chunks.sort(key=lambda info: (info.start, info.pos))
        # strictly: chunks meeting at one timestamp are merged, so that the tie keeps file order
        sequential = all(a.end < b.start for a, b in itertools.pairwise(chunks))
        if sequential:
            for info in chunks:
                yield from self._chunk_messages(self._load_chunk(info, wanted), conns, lo, hi)
        else:
            yield from self._merged(chunks, wanted, conns, lo, hi)

    def _chunk_messages(self, loaded: _ChunkEntries, conns: dict[int, Connection], lo: Time,
                        hi: Time) -> Iterator[MessageView]:
        data = loaded.data
        view = memoryview(data)
        pos = loaded.info.pos
        unpack = records.unpack_u32
        n = len(data)
        entries = loaded.entries
        if entries and ((entries[0][0], entries[0][1]) < lo or (entries[-1][0], entries[-1][1]) > hi):
            entries = [e for e in entries if lo <= (e[0], e[1]) <= hi]
        for secs, nsecs, offset, conn_id in entries:
            # records.message_data_span, inlined: this loop runs once per message
            try:
                (header_len,) = unpack(data, offset)
                a = offset + 8 + header_len
                (data_len,) = unpack(data, a - 4)
            except struct.error:
                a, data_len = n + 1, 0
            b = a + data_len
            if b > n:
                records.message_data_span(data, offset)  # raises the precise BagFormatError
            yield conns[conn_id], secs, nsecs, view[a:b], pos, offset

    def _merged(self, chunks: list[ChunkInfo], wanted: set[int] | None, conns: dict[int, Connection],
                lo: Time, hi: Time) -> Iterator[MessageView]:
        heap: list[tuple[int, int, int, int, Iterator[MessageView], MessageView]] = []
        i = 0
        n = len(chunks)
        while heap or i < n:
            while i < n and (not heap or chunks[i].start <= (heap[0][0], heap[0][1])):
                it = self._chunk_messages(self._load_chunk(chunks[i], wanted), conns, lo, hi)
                first = next(it, None)
                if first is not None:
                    heapq.heappush(heap, (first[1], first[2], chunks[i].pos, first[5], it, first))
                i += 1
            if not heap:
                continue
            _, _, cpos, _, it, msg = heapq.heappop(heap)
            yield msg
            nxt = next(it, None)
            if nxt is not None:
                heapq.heappush(heap, (nxt[1], nxt[2], cpos, nxt[5], it, nxt))

    def index_times(self, connections: list[Connection]) -> list[Time]:
        """The receive times of the messages of `connections`, sorted, from the index data
        records alone (chunk payloads are not read)."""
        wanted = {c.id for c in connections}
        times: list[Time] = []
        for info in self.chunk_infos:
            if not any(c in wanted for c in info.counts):
                continue
            entries = self._reindexed.get(info.pos)
            if entries is None:
                header = self.chunk_header(info)
                start = info.pos + header.data_pos + header.compressed_size
                end = self._chunk_ends.get(info.pos, self.size)
                blob = self._read(start, max(end - start, 0))
                entries = self._index_entries(blob, 0, info, 1 << 32)
                if entries is None:
                    entries = self._load_chunk(info, None).entries
            times.extend((e[0], e[1]) for e in entries if e[3] in wanted)
        times.sort()
        return times

    # ------------------------------------------------------------------ summary

    def message_count(self, topics: Iterable[str] | str | None = None) -> int:
        ids = {c.id for c in self.connections_for(topics)}
        return sum(n for info in self.chunk_infos for c, n in info.counts.items() if c in ids)

    @property
    def start_time(self) -> Time | None:
        return min((info.start for info in self.chunk_infos), default=None)

    @property
    def end_time(self) -> Time | None:
        return max((info.end for info in self.chunk_infos), default=None)


def is_mcap(path: str | os.PathLike[str]) -> bool:
    """Whether the file starts as an MCAP file does."""
    with open(path, "rb") as f:
        return f.read(len(MCAP_MAGIC)) == MCAP_MAGIC


def open_reader(path: str | os.PathLike[str], allow_unindexed: bool = False) -> BagReader | McapReader:
    """The reader for a bag 2.0 file or, by its first bytes, an MCAP file (kame.bag.mcap_file,
    imported only then: reading bags needs neither the `mcap` library nor its import time)."""
    if is_mcap(path):
        from kame.bag.mcap_file import McapReader

        return McapReader(path)
    return BagReader(path, allow_unindexed=allow_unindexed)


def _whole_records(data: bytes | memoryview) -> Iterator[records.Record]:
    """The records of a torn chunk up to the first that is cut short or is not a message or a
    connection (what follows a torn chunk is not its data)."""
    pos = 0
    while pos < len(data):
        try:
            record = records.read_record(data, pos)
            if record.op not in (records.OP_MSG_DATA, records.OP_CONNECTION):
                return
            if record.op == records.OP_MSG_DATA:
                records.message_header(record)
        except BagFormatError:
            return
        yield record
        pos = record.end
