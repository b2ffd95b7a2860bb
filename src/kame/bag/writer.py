"""Writing bag 2.0 files: chunks, connections, index data, chunk info, the padded header.

Rules:
- An uncompressed chunk is streamed, as ROS's C++ recorder does: its header goes out with
  zero sizes, its records follow in batches (every _STREAM_BATCH bytes, and whenever
  `write_pending` is called: the recorder calls it twice a second), and when the chunk passes
  the threshold (768 KB by default, rosbag's) its header is patched in place and its index
  data records are written after it. A killed recorder leaves every record it had handed to
  the kernel: `rosbag reindex` keeps the complete messages of the torn last chunk too.
- A compressed chunk can only be written whole (header, payload, index data records, one
  writev); `write_pending` closes it early, so a killed recorder loses at most what arrived
  since the last call.
- A write that fails (a full disk, a file size limit) is undone (the file is cut back to the
  last whole batch) and raised; `close` then ends the bag with what is on disk, dropping the
  open chunk if even the index does not fit, so the bag stays readable.
- A connection record goes into the chunk just before the connection's first message, and
  all connection records are written again after the last chunk, at index_pos, followed by
  one chunk info record per chunk. The bag header is written with zeros first and patched
  on close: a bag whose header still says index_pos=0 was not closed.
- Messages arrive already serialized: this layer never sees message classes.
- Copies: small messages are copied into the chunk; a large one handed over with
  `owned=True` is written from where it lies (an uncompressed chunk goes out as a list of
  buffers), so a recorder's image costs no copy between its socket buffer and the file.
- `drop_behind=True` (a recorder: written once, not read back soon): every 8 MB the kernel
  is told to write back and forget the pages already written (posix_fadvise DONTNEED). The
  page cache then recycles a few warm pages instead of claiming fresh memory for every
  byte, which on a VM (balloon, free page reporting) costs several times the copy itself.
"""

from __future__ import annotations

import contextlib
import errno
import os
import struct
import time
from collections.abc import Mapping, Sequence
from typing import BinaryIO, cast

from kame.bag import records
from kame.bag.compression import COMPRESSIONS, compress
from kame.bag.errors import BagError
from kame.bag.records import ChunkInfo, Connection

__all__ = ["DEFAULT_CHUNK_THRESHOLD", "BagWriter"]

DEFAULT_CHUNK_THRESHOLD = 768 * 1024
_OWNED_MIN = 64 * 1024  # an owned message at least this large is kept by reference, not copied
_DROP_WINDOW = 8 << 20
_SLOW_ADVICE = 0.1  # seconds: the disk is not keeping up
_BACKOFF = 256 << 20
_IOV_MAX = 512  # buffers per writev (Linux allows 1024)
_STREAM_BATCH = 64 * 1024  # an open uncompressed chunk goes to disk in batches of about this size


class BagWriter:
    """Writes a bag to `path` ('w': a new file; 'a': append to an indexed bag).

    `path` may also be an open binary file with a descriptor (rosbag's `Bag(f, 'w')`): it is
    written through a duplicate of its descriptor, from its start ('w'); closing the writer
    leaves the caller's file open."""

    def __init__(self, path: str | os.PathLike[str] | BinaryIO, mode: str = "w", compression: str = "none",
                 chunk_threshold: int = DEFAULT_CHUNK_THRESHOLD, allow_unindexed: bool = False,
                 drop_behind: bool = False) -> None:
        if compression not in COMPRESSIONS:
            raise BagError(f"unsupported compression type: {compression}")
        self._caller_file: BinaryIO | None = None
        if isinstance(path, (str, os.PathLike)):
            self.path = os.fspath(path)
        else:
            self._caller_file = path
            self.path = str(getattr(path, "name", "<stream>"))
        self.compression = compression
        self.chunk_threshold = chunk_threshold
        self.connections: dict[int, Connection] = {}
        self.chunk_infos: list[ChunkInfo] = []
        self._written: set[int] = set()  # connections whose record is already in a chunk
        self._parts: list[bytes | bytearray | memoryview] = []  # the chunk's pending data before _chunk
        self._chunk = bytearray()
        self._chunk_len = 0  # the open chunk's data bytes, on disk and pending
        self._pending_len = 0  # bytes in _parts and _chunk (not yet written)
        self._chunk_pos: int | None = None  # where the open chunk's header lies, once streamed
        self._broken: OSError | None = None  # the write that failed; nothing more is written
        self._chunk_index: dict[int, bytearray] = {}
        self._chunk_counts: dict[int, int] = {}
        self._chunk_start: tuple[int, int] | None = None
        self._chunk_end: tuple[int, int] = (0, 0)
        self.closed = False
        if mode == "w":
            self._file: BinaryIO = self._open_file("wb")  # chunks go out whole, by writev
            self._file.seek(0)
            self._file.truncate()
            self._file.write(records.MAGIC + records.file_header_record(0, 0, 0))
            self._pos = records.FIRST_RECORD_POS
        elif mode == "a":
            self._open_append(allow_unindexed)
        else:
            raise ValueError(f"mode {mode!r} is not 'w' or 'a'")
        self._drop_behind = drop_behind and hasattr(os, "posix_fadvise")
        self._dropped = self._advised = self._pos  # see _drop_written

    def _open_append(self, allow_unindexed: bool) -> None:
        """Continue an indexed bag after its last chunk; with `allow_unindexed`, an unindexed
        one after its last intact chunk (the index is rebuilt and written on close)."""
        from kame.bag.reader import BagReader

        source = self.path if self._caller_file is None else self._caller_file
        with BagReader(source, allow_unindexed=allow_unindexed) as reader:
            self.connections = dict(reader.connections)
            self.chunk_infos = list(reader.chunk_infos)
            index_pos = reader.index_pos
            torn = reader.torn
            torn_entries = reader.chunk_entries(torn.pos) if torn is not None else []
        self._written = set(self.connections)
        self._file = self._open_file("r+b")
        self._file.seek(len(records.MAGIC))
        self._file.write(records.file_header_record(0, 0, 0))  # not closed until we say so
        self._file.truncate(index_pos)
        self._file.seek(index_pos)
        self._pos = index_pos
        if torn is not None:  # a killed recorder's last chunk: its real sizes and index data
            _pwrite_all(self._file, records.chunk_header_bytes("none", torn.uncompressed_size,
                                                               torn.compressed_size), torn.pos)
            by_conn: dict[int, list[bytes]] = {}
            for secs, nsecs, offset, conn_id in torn_entries:
                by_conn.setdefault(conn_id, []).append(records.pack_index_entry(secs, nsecs, offset))
            self._write([records.index_data_record(conn_id, b"".join(entries), len(entries))
                         for conn_id, entries in by_conn.items()])

    def _open_file(self, mode: str) -> BinaryIO:
        if self._caller_file is None:
            return cast(BinaryIO, open(self.path, mode, buffering=0))
        self._caller_file.flush()  # what the caller wrote through its buffer lands before our records
        duplicate: BinaryIO = open(os.dup(self._caller_file.fileno()), "r+b", buffering=0)
        return duplicate

    # ------------------------------------------------------------------ writing

    def add_connection(self, topic: str, header: Mapping[str, str]) -> int:
        """A new connection; its record is written with its first message."""
        conn_id = len(self.connections)
        while conn_id in self.connections:
            conn_id += 1
        self.connections[conn_id] = Connection(conn_id, topic, dict(header))
        return conn_id

    def write(self, conn_id: int, secs: int, nsecs: int, data: bytes | bytearray | memoryview,
              owned: bool = False) -> None:
        """Append one serialized message of connection `conn_id` received at (secs, nsecs).

        `owned=True` hands `data` over: nobody changes it any more, so a large one is kept by
        reference until its chunk is written instead of being copied into the chunk."""
        chunk = self._chunk
        if conn_id not in self._written:
            conn = self.connections[conn_id]
            record = records.connection_record(conn_id, conn.topic, conn.header)
            chunk += record
            self._chunk_len += len(record)
            self._pending_len += len(record)
            self._written.add(conn_id)
        offset = self._chunk_len
        prefix = records.message_data_prefix(conn_id, secs, nsecs, len(data))
        chunk += prefix
        if owned and len(data) >= _OWNED_MIN:
            self._parts += (chunk, data)
            self._chunk = bytearray()
        else:
            chunk += data
        self._chunk_len += len(prefix) + len(data)
        self._pending_len += len(prefix) + len(data)
        index = self._chunk_index.get(conn_id)
        if index is None:
            index = self._chunk_index[conn_id] = bytearray()
            self._chunk_counts[conn_id] = 0
        index += records.pack_index_entry(secs, nsecs, offset)
        self._chunk_counts[conn_id] += 1
        t = (secs, nsecs)
        if self._chunk_start is None:
            self._chunk_start = self._chunk_end = t
        elif t > self._chunk_end:
            self._chunk_end = t
        elif t < self._chunk_start:
            self._chunk_start = t
        if self._chunk_len > self.chunk_threshold:
            self.flush_chunk()
        elif self._pending_len >= _STREAM_BATCH and self.compression == "none":
            self._stream()

    def write_pending(self) -> None:
        """Hand everything written so far to the kernel, so that it survives our death: the
        open chunk's records (uncompressed), or the open chunk, closed (compressed)."""
        if self.compression == "none":
            if self._chunk_start is not None:
                self._stream()
        else:
            self.flush_chunk()

    def _stream(self) -> None:
        """Write the open chunk's pending records (after its zero-size header, the first time)."""
        buffers = self._take_pending()
        if self._chunk_pos is None:
            start = self._pos
            self._write([records.chunk_header_bytes("none", 0, 0), *buffers])
            self._chunk_pos = start
        else:
            self._write(buffers)

    def _take_pending(self) -> list[bytes | bytearray | memoryview]:
        buffers = [*self._parts, self._chunk]
        self._parts = []
        self._chunk = bytearray()
        self._pending_len = 0
        return buffers

    def flush_chunk(self) -> None:
        """Write the current chunk (if it holds anything) and its index data."""
        if self._chunk_start is None:  # empty, or connection records only: kept for the next message
            return
        if self._broken is not None:
            raise self._broken
        size = self._chunk_len
        tail = b"".join(records.index_data_record(conn_id, bytes(entries), self._chunk_counts[conn_id])
                        for conn_id, entries in self._chunk_index.items())
        info = ChunkInfo(self._pos if self._chunk_pos is None else self._chunk_pos, self._chunk_start,
                         self._chunk_end, dict(self._chunk_counts))
        if self._chunk_pos is not None:  # streamed: the rest, the real sizes, then the index data
            self._write(self._take_pending())
            _pwrite_all(self._file, records.chunk_header_bytes("none", size, size), self._chunk_pos)
            self._write([tail])
        else:
            data = self._take_pending()
            if self.compression == "none":
                payload_size = size
            else:
                payload = compress(self.compression, data[0] if len(data) == 1 else b"".join(data))
                data = [payload]
                payload_size = len(payload)
            head = records.chunk_header_bytes(self.compression, size, payload_size)
            self._write([head, *data, tail])
        self.chunk_infos.append(info)
        self._chunk_pos = None
        self._chunk_len = 0
        self._chunk_index = {}
        self._chunk_counts = {}
        self._chunk_start = None
        if self._drop_behind and self._pos - self._advised >= _DROP_WINDOW:
            self._drop_written()

    def _write(self, buffers: Sequence[bytes | bytearray | memoryview]) -> None:
        """Append the buffers at _pos; a failed write is cut off again, so the file ends with
        whole batches only, and leaves the writer broken (it writes nothing more but its end)."""
        if self._broken is not None:
            raise self._broken
        try:
            self._pos += _write_all(self._file, buffers)
        except OSError as exc:
            self._broken = exc
            with contextlib.suppress(OSError):
                self._file.truncate(self._pos)
                self._file.seek(self._pos)
            raise

    def _drop_written(self) -> None:
        """Ask the kernel to write back what we wrote since the last call and to forget what it
        wrote back since the call before (clean by now: dirty pages are never dropped).

        Starting write-back can wait for the disk. When it does (the disk is behind us), the
        next _BACKOFF bytes are left to the page cache and the kernel's own write-back, so a
        burst is absorbed by memory as it would be without this advice."""
        started = time.monotonic()
        try:
            os.posix_fadvise(self._file.fileno(), self._dropped, self._pos - self._dropped, os.POSIX_FADV_DONTNEED)
        except OSError:
            self._drop_behind = False  # advice only: a file system that refuses it is still written
        if time.monotonic() - started > _SLOW_ADVICE:
            self._dropped = self._advised = self._pos + _BACKOFF
        else:
            self._dropped, self._advised = self._advised, self._pos

    def flush(self) -> None:
        self.flush_chunk()

    def index(self) -> list[ChunkInfo]:
        """The chunks written so far and the open one (at the position it will have): the
        times and counts a reader of the finished bag would find."""
        if self._chunk_start is None:
            return list(self.chunk_infos)
        pos = self._pos if self._chunk_pos is None else self._chunk_pos
        return [*self.chunk_infos, ChunkInfo(pos, self._chunk_start, self._chunk_end, dict(self._chunk_counts))]

    @property
    def file(self) -> BinaryIO:
        """The file the records go to (unbuffered; its position is the end of what is written)."""
        return self._file

    @property
    def size(self) -> int:
        """Bytes written so far, plus the open chunk's pending bytes."""
        return self._pos + self._pending_len

    def close(self) -> None:
        """Write the last chunk, the index (connections and chunk infos) and patch the header."""
        if self.closed:
            return
        self.closed = True
        try:
            if self._broken is None:
                self.flush_chunk()
                self._write_index()
            else:
                self._end_broken()
        finally:
            self._file.close()

    def _write_index(self) -> None:
        index_pos = self._pos
        # the connections with messages in the chunks (after a failed write, not all that were written)
        present = {conn_id for info in self.chunk_infos for conn_id in info.counts}
        tail = [records.connection_record(c.id, c.topic, c.header) for c in self.connections.values()
                if c.id in present]
        n_conns = len(tail)
        tail += [records.chunk_info_record(info) for info in self.chunk_infos]
        self._write(tail)
        _pwrite_all(self._file, records.file_header_record(index_pos, n_conns, len(self.chunk_infos)),
                    len(records.MAGIC))

    def _end_broken(self) -> None:
        """After a failed write (already raised to the writer's caller): close the streamed
        chunk with the records that reached the disk and write the index; if even that does
        not fit, drop the open chunk (its space is what the index needs) and try once more.
        Raises the failure again only when the bag is left without an index."""
        failure = self._broken
        assert failure is not None
        self._broken = None
        self._take_pending()
        chunk_pos = self._chunk_pos
        try:
            if chunk_pos is not None:
                self._seal_streamed(chunk_pos)
            self._write_index()
            return
        except OSError:
            if chunk_pos is None:
                raise failure from None
        self._broken = None
        self.chunk_infos = [info for info in self.chunk_infos if info.pos != chunk_pos]
        self._pos = chunk_pos
        try:
            self._file.truncate(chunk_pos)
            self._file.seek(chunk_pos)
            self._write_index()
        except OSError:
            raise failure from None  # whole chunks and no index: `rosbag reindex` reads it

    def _seal_streamed(self, chunk_pos: int) -> None:
        """Close the open streamed chunk with the records on disk (they end at _pos: writes
        are whole batches of whole records), as `flush_chunk` would have."""
        size = self._pos - chunk_pos - len(records.chunk_header_bytes("none", 0, 0))
        kept = {conn_id: [e for e in struct.iter_unpack("<III", packed) if e[2] < size]
                for conn_id, packed in self._chunk_index.items()}
        kept = {conn_id: entries for conn_id, entries in kept.items() if entries}
        self._chunk_pos = None
        if not kept:
            self._file.truncate(chunk_pos)
            self._file.seek(chunk_pos)
            self._pos = chunk_pos
            return
        times = [(s, n) for entries in kept.values() for s, n, _ in entries]
        _pwrite_all(self._file, records.chunk_header_bytes("none", size, size), chunk_pos)
        self._write([records.index_data_record(conn_id, b"".join(records.pack_index_entry(*e) for e in entries),
                                               len(entries)) for conn_id, entries in kept.items()])
        self.chunk_infos.append(ChunkInfo(chunk_pos, min(times), max(times),
                                          {conn_id: len(entries) for conn_id, entries in kept.items()}))

    def __enter__(self) -> BagWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _write_all(file: BinaryIO, buffers: Sequence[bytes | bytearray | memoryview]) -> int:
    """Write the buffers in order at the file's position, as one writev when they are few
    (a chunk lands whole, or not at all if we are killed); returns the bytes written."""
    fd = file.fileno()
    total = 0
    for start in range(0, len(buffers), _IOV_MAX):
        batch: Sequence[bytes | bytearray | memoryview] = buffers[start : start + _IOV_MAX]
        want = sum(len(b) for b in batch)
        total += want
        done = os.writev(fd, batch)
        while done < want:  # a short write (a signal, a full disk): go on from where it stopped
            rest: list[bytes | bytearray | memoryview] = []
            for b in batch:
                if done >= len(b):
                    done -= len(b)
                    continue
                rest.append(memoryview(b)[done:] if done else b)
                done = 0
            batch = rest
            want = sum(len(b) for b in batch)
            done = os.writev(fd, batch)
            if done <= 0:
                raise OSError(errno.EIO, f"writing {file.name!r}: no progress")
    return total


def _pwrite_all(file: BinaryIO, data: bytes, pos: int) -> None:
    """Overwrite bytes already in the file (a header patch: no new blocks, so no ENOSPC)."""
    view = memoryview(data)
    while view:
        done = os.pwrite(file.fileno(), view, pos)
        if done <= 0:
            raise OSError(errno.EIO, f"writing {file.name!r}: no progress")
        view, pos = view[done:], pos + done
