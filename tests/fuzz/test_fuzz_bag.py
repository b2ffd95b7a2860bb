"""Properties of bags: any messages written come back in time order, through every compression
and chunk size; records and indexes in any state of damage read back or raise BagError; a bag
cut anywhere (a killed recorder) is reindexed to a prefix of what was written."""

from __future__ import annotations

import tempfile
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

from kame.bag import records
from kame.bag.errors import BagError, BagFormatError
from kame.bag.reader import BagReader
from kame.bag.writer import BagWriter

HEADER = {"type": "std_msgs/String", "md5sum": "992ce8a1687cec8c8bd883ec73ca41d1",
          "message_definition": "string data\n"}
_MESSAGES = st.lists(st.tuples(st.integers(0, 2), st.integers(0, 50), st.integers(0, 999_999_999),
                               st.binary(max_size=40)), max_size=40)


def _write(path: Path, messages: list[tuple[int, int, int, bytes]], compression: str = "none",
           chunk_threshold: int = 200) -> BagWriter:
    writer = BagWriter(path, "w", compression, chunk_threshold)
    conns = [writer.add_connection(f"/t{i}", HEADER) for i in range(3)]
    for conn, secs, nsecs, data in messages:
        writer.write(conns[conn], secs, nsecs, data)
    return writer


def _read(path: Path, allow_unindexed: bool = False) -> list[tuple[str, int, int, bytes]]:
    with BagReader(path, allow_unindexed=allow_unindexed) as reader:
        return [(m.conn.topic, m.time[0], m.time[1], m.data) for m in reader.messages()]


@given(messages=_MESSAGES, compression=st.sampled_from(["none", "lz4", "bz2"]), threshold=st.integers(1, 2000))
def test_what_is_written_is_read_in_time_order(messages: list[tuple[int, int, int, bytes]], compression: str,
                                               threshold: int) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "b.bag"
        _write(path, messages, compression, threshold).close()
        expected = sorted(((f"/t{c}", s, n, d) for c, s, n, d in messages), key=lambda m: (m[1], m[2]))
        assert _read(path) == expected


@given(messages=_MESSAGES, cut=st.integers(0, 10_000))
def test_a_bag_cut_anywhere_reindexes_to_a_prefix(messages: list[tuple[int, int, int, bytes]], cut: int) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "b.bag"
        writer = _write(path, messages)
        writer.write_pending()  # what a killed recorder leaves: all of it on disk, cut anywhere
        killed = Path(tmp) / "killed.bag"
        killed.write_bytes(path.read_bytes()[:cut + records.FIRST_RECORD_POS])
        writer.close()
        try:
            got = _read(killed, allow_unindexed=True)
        except BagError:
            return
        written = [(f"/t{c}", s, n, d) for c, s, n, d in messages]
        assert sorted(got) == sorted(written[:len(got)])


@given(data=st.data(), messages=_MESSAGES.filter(bool))
def test_a_damaged_bag_reads_or_says_why(data: st.DataObject, messages: list[tuple[int, int, int, bytes]]) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "b.bag"
        _write(path, messages, data.draw(st.sampled_from(["none", "lz4"]))).close()
        blob = bytearray(path.read_bytes())
        for _ in range(data.draw(st.integers(1, 4))):
            pos = data.draw(st.integers(len(records.MAGIC), len(blob) - 1))
            blob[pos] = data.draw(st.integers(0, 255))
        path.write_bytes(bytes(blob))
        for allow_unindexed in (False, True):
            try:
                _read(path, allow_unindexed)
            except BagError:
                pass


@given(junk=st.binary(max_size=80), base=st.integers(0, 100))
def test_any_bytes_read_as_records_or_say_why(junk: bytes, base: int) -> None:
    try:
        for record in records.walk_records(junk, base=base):
            assert record.end <= len(junk)
            for parse in (records.parse_connection, records.parse_chunk_info, records.parse_index_data):
                try:
                    parse(record, junk)
                except BagFormatError:
                    pass
    except BagFormatError:
        pass
