"""rosbag.bag: kame.client.bag under rosbag's name, with rosbag.bag's record helpers.

The underscored helpers (`_pack_uint32`, `_write_record`, `_read_sized`, `_read_header`, the
`_OP_*` codes, ...) are rosbag's own, with its signatures and errors: its reindex and migration
code, and scripts copied from them, read and write records with them on a bag's `_file`.
"""

from __future__ import annotations

import os
import struct
from collections.abc import Callable, Mapping
from io import BytesIO as StringIO
from typing import IO, Any, TypeVar

from kame.bag import records
from kame.client.bag import (
    Bag,
    BagMessage,
    BagMessageWithConnectionHeader,
    Compression,
    CompressionTuple,
    ROSBagEncryptException,
    ROSBagEncryptNotSupportedException,
    ROSBagException,
    ROSBagFormatException,
    ROSBagUnindexedException,
    TopicTuple,
    TypesAndTopicsTuple,
    message_class,
)
from kame.client.clock import Time

__all__ = [
    "Bag",
    "BagMessage",
    "BagMessageWithConnectionHeader",
    "ComparableMixin",
    "Compression",
    "CompressionTuple",
    "ROSBagEncryptException",
    "ROSBagEncryptNotSupportedException",
    "ROSBagException",
    "ROSBagFormatException",
    "ROSBagUnindexedException",
    "StringIO",
    "TopicTuple",
    "TypesAndTopicsTuple",
    "found_lz4",
    "message_class",
]

found_lz4 = True  # kame's lz4 chunks: the lz4 package is one of kame's dependencies

_OP_MSG_DEF = records.OP_MSG_DEF
_OP_MSG_DATA = records.OP_MSG_DATA
_OP_FILE_HEADER = records.OP_FILE_HEADER
_OP_INDEX_DATA = records.OP_INDEX_DATA
_OP_CHUNK = records.OP_CHUNK
_OP_CHUNK_INFO = records.OP_CHUNK_INFO
_OP_CONNECTION = records.OP_CONNECTION
_OP_CODES = {_OP_MSG_DEF: "MSG_DEF", _OP_MSG_DATA: "MSG_DATA", _OP_FILE_HEADER: "FILE_HEADER",
             _OP_INDEX_DATA: "INDEX_DATA", _OP_CHUNK: "CHUNK", _OP_CHUNK_INFO: "CHUNK_INFO",
             _OP_CONNECTION: "CONNECTION"}
_VERSION = records.MAGIC.decode().strip()
_FILE_HEADER_LENGTH = records.FILE_HEADER_LENGTH
_INDEX_VERSION = 1
_CHUNK_INDEX_VERSION = 1

_T = TypeVar("_T")


def _unpack_uint8(v: bytes) -> int:
    return int(struct.unpack("<B", v)[0])


def _unpack_uint32(v: bytes) -> int:
    return int(struct.unpack("<L", v)[0])


def _unpack_uint64(v: bytes) -> int:
    return int(struct.unpack("<Q", v)[0])


def _unpack_time(v: bytes) -> Time:
    return Time(*struct.unpack("<LL", v))


def _pack_uint8(v: int) -> bytes:
    return struct.pack("<B", v)


def _pack_uint32(v: int) -> bytes:
    return struct.pack("<L", v)


def _pack_uint64(v: int) -> bytes:
    return struct.pack("<Q", v)


def _pack_time(v: Any) -> bytes:
    return _pack_uint32(v.secs) + _pack_uint32(v.nsecs)


def _read_uint8(f: IO[bytes]) -> int:
    return _unpack_uint8(f.read(1))


def _read_uint32(f: IO[bytes]) -> int:
    return _unpack_uint32(f.read(4))


def _read_uint64(f: IO[bytes]) -> int:
    return _unpack_uint64(f.read(8))


def _read_time(f: IO[bytes]) -> Time:
    return _unpack_time(f.read(8))


def _decode_bytes(v: bytes) -> bytes:
    return v


def _decode_str(v: bytes | str) -> str:
    return v if isinstance(v, str) else v.decode()


def _read(f: IO[bytes], size: int) -> bytes:
    data = f.read(size)
    if len(data) != size:
        raise ROSBagException(f"expecting {size} bytes, read {len(data)}")
    return data


def _skip_sized(f: IO[bytes]) -> None:
    f.seek(_read_uint32(f), os.SEEK_CUR)


def _skip_record(f: IO[bytes]) -> None:
    _skip_sized(f)  # the header
    _skip_sized(f)  # the data


def _read_sized(f: IO[bytes]) -> bytes:
    try:
        size = _read_uint32(f)
    except struct.error as ex:
        raise ROSBagFormatException(f"error unpacking uint32: {ex}") from ex
    return _read(f, size)


def _write_sized(f: IO[bytes], v: bytes | str) -> None:
    data = v if isinstance(v, bytes) else v.encode()
    f.write(_pack_uint32(len(data)))
    f.write(data)


def _read_field(header: Mapping[str, bytes], field: str, unpack_fn: Callable[[bytes], _T]) -> _T:
    if field not in header:
        raise ROSBagFormatException(f'expected "{field}" field in record')
    try:
        return unpack_fn(header[field])
    except Exception as ex:  # rosbag wraps whatever the unpacking raised
        raise ROSBagFormatException(f'error reading field "{field}": {ex}') from ex


def _read_bytes_field(header: Mapping[str, bytes], field: str) -> bytes:
    return _read_field(header, field, _decode_bytes)


def _read_str_field(header: Mapping[str, bytes], field: str) -> str:
    return _read_field(header, field, _decode_str)


def _read_uint8_field(header: Mapping[str, bytes], field: str) -> int:
    return _read_field(header, field, _unpack_uint8)


def _read_uint32_field(header: Mapping[str, bytes], field: str) -> int:
    return _read_field(header, field, _unpack_uint32)


def _read_uint64_field(header: Mapping[str, bytes], field: str) -> int:
    return _read_field(header, field, _unpack_uint64)


def _read_time_field(header: Mapping[str, bytes], field: str) -> Time:
    return _read_field(header, field, _unpack_time)


def _write_header(f: IO[bytes], header: Mapping[str | bytes, str | bytes]) -> bytes:
    fields = [(k if isinstance(k, bytes) else k.encode()) + b"=" + (v if isinstance(v, bytes) else v.encode())
              for k, v in header.items()]
    header_str = b"".join(_pack_uint32(len(field)) + field for field in fields)
    _write_sized(f, header_str)
    return header_str


def _write_record(f: IO[bytes], header: Mapping[str | bytes, str | bytes], data: bytes | str = "",
                  padded_size: int | None = None) -> None:
    """A record: its header, then `data`; with `padded_size`, spaces that pad the header to that
    size instead (the file header record)."""
    header_str = _write_header(f, header)
    if padded_size is not None:
        data = " " * (padded_size - len(header_str)) if len(header_str) < padded_size else ""
    _write_sized(f, data)


def _build_header_from_str(header: bytes, req_op: int | None) -> dict[str, bytes]:
    header_dict: dict[str, bytes] = {}
    while header != b"":
        if len(header) < 4:
            raise ROSBagFormatException("Error reading header field")
        (size,) = struct.unpack("<L", header[:4])
        header = header[4:]
        if len(header) < size:
            raise ROSBagFormatException(f"Error reading header field: expected {size} bytes, read {len(header)}")
        name, sep, value = header[:size].partition(b"=")
        if sep == b"":
            raise ROSBagFormatException("Error reading header field")
        header_dict[name.decode()] = value
        header = header[size:]
    if req_op is not None:
        op = _read_uint8_field(header_dict, "op")
        if req_op != op:
            raise ROSBagFormatException(f"Expected op code: {_OP_CODES[req_op]}, got {_OP_CODES[op]}")
    return header_dict


def _read_header(f: IO[bytes], req_op: int | None = None) -> dict[str, bytes]:
    try:
        header = _read_sized(f)
    except ROSBagException as ex:
        raise ROSBagFormatException(f"Error reading header: {ex}") from ex
    return _build_header_from_str(header, req_op)


def _peek_next_header_op(f: IO[bytes]) -> int:
    pos = f.tell()
    op = _read_uint8_field(_read_header(f), "op")
    f.seek(pos)
    return op


def _read_record_data(f: IO[bytes]) -> bytes:
    try:
        return _read_sized(f)
    except ROSBagException as ex:
        raise ROSBagFormatException(f"Error reading record data: {ex}") from ex


class ComparableMixin:
    """Comparisons by `_cmpkey()`, which a subclass defines (rosbag's index entries and chunk infos)."""

    __slots__: list[str] = []

    def _compare(self, other: object, method: Callable[[Any, Any], bool]) -> Any:
        try:
            return method(self._cmpkey(), other._cmpkey())  # type: ignore[attr-defined]
        except (AttributeError, TypeError):  # no _cmpkey, or keys of different types
            return NotImplemented

    def __lt__(self, other: object) -> Any:
        return self._compare(other, lambda s, o: s < o)

    def __le__(self, other: object) -> Any:
        return self._compare(other, lambda s, o: s <= o)

    def __eq__(self, other: object) -> Any:
        return self._compare(other, lambda s, o: s == o)

    def __ge__(self, other: object) -> Any:
        return self._compare(other, lambda s, o: s >= o)

    def __gt__(self, other: object) -> Any:
        return self._compare(other, lambda s, o: s > o)

    def __ne__(self, other: object) -> Any:
        return self._compare(other, lambda s, o: s != o)

    __hash__ = None  # type: ignore[assignment]  # as rosbag's: compared, not hashed
