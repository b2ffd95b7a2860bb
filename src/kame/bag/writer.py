"""Writing bag 2.0 files: chunks, connections, index data, chunk info, the padded header.

Rules:
- A chunk is built in memory and written whole (header, payload, its index data records) in
  one writev once its uncompressed size passes the threshold (768 KB by default, rosbag's), so
  a killed recorder leaves only complete chunks behind and `rosbag reindex` loses nothing it
  had written.
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

import errno
import os
import time
from collections.abc import Mapping, Sequence
from typing import BinaryIO

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


class BagWriter:
    """Writes a bag to `path` ('w': a new file; 'a': append to an indexed bag)."""

    def __init__(self, path: str | os.PathLike[str], mode: str = "w", compression: str = "none",
                 chunk_threshold: int = DEFAULT_CHUNK_THRESHOLD, allow_unindexed: bool = False,
                 drop_behind: bool = False) -> None:
        if compression not in COMPRESSIONS:
            raise BagError(f"unsupported compression type: {compression}")
        self.path = os.fspath(path)
        self.compression = compression
        self.chunk_threshold = chunk_threshold
        self.connections: dict[int, Connection] = {}
        self.chunk_infos: list[ChunkInfo] = []
        self._written: set[int] = set()  # connections whose record is already in a chunk
        self._parts: list[bytes | bytearray | memoryview] = []  # the chunk's data before _chunk
        self._chunk = bytearray()
        self._chunk_len = 0  # bytes in _parts and _chunk
        self._chunk_index: dict[int, bytearray] = {}
        self._chunk_counts: dict[int, int] = {}
        self._chunk_start: tuple[int, int] | None = None
        self._chunk_end: tuple[int, int] = (0, 0)
        self.closed = False
        if mode == "w":
            self._file: BinaryIO = open(self.path, "wb", buffering=0)  # chunks go out whole, by writev
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

        with BagReader(self.path, allow_unindexed=allow_unindexed) as reader:
            self.connections = dict(reader.connections)
            self.chunk_infos = list(reader.chunk_infos)
            index_pos = reader.index_pos
        self._written = set(self.connections)
        self._file = open(self.path, "r+b", buffering=0)
        self._file.seek(len(records.MAGIC))
        self._file.write(records.file_header_record(0, 0, 0))  # not closed until we say so
        self._file.truncate(index_pos)
        self._file.seek(index_pos)
        self._pos = index_pos

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

    def flush_chunk(self) -> None:
        """Write the current chunk (if it holds anything) and its index data."""
        if self._chunk_start is None:  # empty, or connection records only: kept for the next message
            return
        data = [*self._parts, self._chunk]
        size = self._chunk_len
        if self.compression == "none":
            payload_size = size
        else:
            payload = compress(self.compression, data[0] if len(data) == 1 else b"".join(data))
            data = [payload]
            payload_size = len(payload)
        pos = self._pos
        head = records.chunk_header_bytes(self.compression, size, payload_size)
        tail = b"".join(records.index_data_record(conn_id, bytes(entries), self._chunk_counts[conn_id])
                        for conn_id, entries in self._chunk_index.items())
        self._pos += _write_all(self._file, [head, *data, tail])
        self.chunk_infos.append(ChunkInfo(pos, self._chunk_start, self._chunk_end, dict(self._chunk_counts)))
        self._parts = []
        self._chunk = bytearray()
        self._chunk_len = 0
        self._chunk_index = {}
        self._chunk_counts = {}
        self._chunk_start = None
        if self._drop_behind and self._pos - self._advised >= _DROP_WINDOW:
            self._drop_written()

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

    @property
    def size(self) -> int:
        """Bytes written so far, plus the open chunk."""
        return self._pos + self._chunk_len

    def close(self) -> None:
        """Write the last chunk, the index (connections and chunk infos) and patch the header."""
        if self.closed:
            return
        self.closed = True
        try:
            self.flush_chunk()
            index_pos = self._pos
            tail = [records.connection_record(c.id, c.topic, c.header) for c in self.connections.values()
                    if c.id in self._written]
            n_conns = len(tail)
            tail += [records.chunk_info_record(info) for info in self.chunk_infos]
            _write_all(self._file, tail)
            self._file.seek(len(records.MAGIC))
            _write_all(self._file, [records.file_header_record(index_pos, n_conns, len(self.chunk_infos))])
        finally:
            self._file.close()

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
