"""Writing bag 2.0 files: chunks, connections, index data, chunk info, the padded header.

Rules:
- A chunk is built in memory and written whole (header, payload, its index data records) in
  one write once its uncompressed size passes the threshold (768 KB by default, rosbag's), so
  a killed recorder leaves only complete chunks behind and `rosbag reindex` loses nothing it
  had written.
- A connection record goes into the chunk just before the connection's first message, and
  all connection records are written again after the last chunk, at index_pos, followed by
  one chunk info record per chunk. The bag header is written with zeros first and patched
  on close: a bag whose header still says index_pos=0 was not closed.
- Messages arrive already serialized: this layer never sees message classes.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import BinaryIO

from kame.bag import records
from kame.bag.compression import COMPRESSIONS, compress
from kame.bag.errors import BagError
from kame.bag.records import ChunkInfo, Connection

__all__ = ["DEFAULT_CHUNK_THRESHOLD", "BagWriter"]

DEFAULT_CHUNK_THRESHOLD = 768 * 1024


class BagWriter:
    """Writes a bag to `path` ('w': a new file; 'a': append to an indexed bag)."""

    def __init__(self, path: str | os.PathLike[str], mode: str = "w", compression: str = "none",
                 chunk_threshold: int = DEFAULT_CHUNK_THRESHOLD, allow_unindexed: bool = False) -> None:
        if compression not in COMPRESSIONS:
            raise BagError(f"unsupported compression type: {compression}")
        self.path = os.fspath(path)
        self.compression = compression
        self.chunk_threshold = chunk_threshold
        self.connections: dict[int, Connection] = {}
        self.chunk_infos: list[ChunkInfo] = []
        self._written: set[int] = set()  # connections whose record is already in a chunk
        self._chunk = bytearray()
        self._chunk_index: dict[int, bytearray] = {}
        self._chunk_counts: dict[int, int] = {}
        self._chunk_start: tuple[int, int] | None = None
        self._chunk_end: tuple[int, int] = (0, 0)
        self.closed = False
        if mode == "w":
            self._file: BinaryIO = open(self.path, "wb")
            self._file.write(records.MAGIC + records.file_header_record(0, 0, 0))
            self._pos = records.FIRST_RECORD_POS
        elif mode == "a":
            self._open_append(allow_unindexed)
        else:
            raise ValueError(f"mode {mode!r} is not 'w' or 'a'")

    def _open_append(self, allow_unindexed: bool) -> None:
        """Continue an indexed bag after its last chunk; with `allow_unindexed`, an unindexed
        one after its last intact chunk (the index is rebuilt and written on close)."""
        from kame.bag.reader import BagReader

        with BagReader(self.path, allow_unindexed=allow_unindexed) as reader:
            self.connections = dict(reader.connections)
            self.chunk_infos = list(reader.chunk_infos)
            index_pos = reader.index_pos
        self._written = set(self.connections)
        self._file = open(self.path, "r+b")
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

    def write(self, conn_id: int, secs: int, nsecs: int, data: bytes | bytearray | memoryview) -> None:
        """Append one serialized message of connection `conn_id` received at (secs, nsecs)."""
        chunk = self._chunk
        if conn_id not in self._written:
            conn = self.connections[conn_id]
            chunk += records.connection_record(conn_id, conn.topic, conn.header)
            self._written.add(conn_id)
        offset = len(chunk)
        chunk += records.message_data_prefix(conn_id, secs, nsecs, len(data))
        chunk += data
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
        if len(chunk) > self.chunk_threshold:
            self.flush_chunk()

    def flush_chunk(self) -> None:
        """Write the current chunk (if it holds anything) and its index data."""
        if self._chunk_start is None:
            if self._chunk:  # connection records only: keep them for the next message
                return
            return
        raw = self._chunk
        payload = compress(self.compression, raw)
        pos = self._pos
        parts = [records.chunk_header_bytes(self.compression, len(raw), len(payload)), payload]
        for conn_id, entries in self._chunk_index.items():
            parts.append(records.index_data_record(conn_id, bytes(entries), self._chunk_counts[conn_id]))
        blob = b"".join(parts)
        self._file.write(blob)
        self._pos += len(blob)
        self.chunk_infos.append(ChunkInfo(pos, self._chunk_start, self._chunk_end, dict(self._chunk_counts)))
        self._chunk = bytearray()
        self._chunk_index = {}
        self._chunk_counts = {}
        self._chunk_start = None

    def flush(self) -> None:
        self.flush_chunk()
        self._file.flush()

    @property
    def size(self) -> int:
        """Bytes written so far, plus the open chunk."""
        return self._pos + len(self._chunk)

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
            tail += [records.chunk_info_record(info) for info in self.chunk_infos]
            self._file.write(b"".join(tail))
            self._file.seek(len(records.MAGIC))
            self._file.write(records.file_header_record(index_pos, len(tail) - len(self.chunk_infos),
                                                        len(self.chunk_infos)))
        finally:
            self._file.close()

    def __enter__(self) -> BagWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
