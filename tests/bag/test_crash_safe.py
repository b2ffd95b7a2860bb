"""A bag that its writer never closed (a killed recorder, a full disk) keeps every message that
reached the file: the open chunk is streamed, `rosbag reindex` seals a torn last chunk with its
whole records, and a failed write ends the bag readable with what is on disk."""

from __future__ import annotations

import errno
import os
import shutil
import subprocess
from pathlib import Path

import pytest

import rosbag
from kame.bag import writer as writer_module
from kame.bag.reader import BagReader
from kame.bag.writer import BagWriter
from kame.cli.rosbag import reindex_file
from tests.support import SYSTEM_PYTHON, have_debian_ros

HEADER = {"type": "std_msgs/String", "md5sum": "992ce8a1687cec8c8bd883ec73ca41d1",
          "message_definition": "string data\n"}


def _string(text: str) -> bytes:
    return len(text).to_bytes(4, "little") + text.encode()


def _killed_copy(tmp_path: Path, n: int, cut: int = 0) -> tuple[Path, int]:
    """A bag as a recorder killed after writing `n` messages and calling write_pending leaves it
    (minus `cut` bytes off its end); and how many bytes the writer had put on disk."""
    path = tmp_path / "live.bag"
    writer = BagWriter(path, "w", chunk_threshold=10_000)
    conn = writer.add_connection("/t", HEADER)
    for i in range(n):
        writer.write(conn, 100, i, _string(f"message {i:05d}"))
    writer.write_pending()
    killed = tmp_path / "killed.bag.active"
    shutil.copyfile(path, killed)
    size = killed.stat().st_size
    if cut:
        os.truncate(killed, size - cut)
    writer.close()
    return killed, size


def _texts(path: Path) -> list[str]:
    with rosbag.Bag(path) as bag:
        return [m.message.data for m in bag.read_messages()]


def test_a_killed_writer_leaves_the_open_chunk_on_disk_and_reindex_keeps_all_of_it(tmp_path: Path) -> None:
    killed, _ = _killed_copy(tmp_path, 1000)  # 10 kB chunks: several closed and one open
    with pytest.raises(rosbag.ROSBagUnindexedException):
        rosbag.Bag(killed)
    with BagReader(killed, allow_unindexed=True) as reader:
        assert reader.torn is not None and reader.message_count() == 1000
    reindex_file(str(killed), str(tmp_path / "fixed.bag"))
    assert _texts(tmp_path / "fixed.bag") == [f"message {i:05d}" for i in range(1000)]


def test_reindex_keeps_the_whole_records_of_a_chunk_torn_mid_record(tmp_path: Path) -> None:
    killed, _ = _killed_copy(tmp_path, 1000, cut=7)
    reindex_file(str(killed), str(killed))
    assert _texts(killed) == [f"message {i:05d}" for i in range(999)]


@pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")
def test_rosbag_of_ros1_reads_a_bag_whose_torn_chunk_was_sealed(tmp_path: Path) -> None:
    killed, _ = _killed_copy(tmp_path, 300, cut=3)
    reindex_file(str(killed), str(killed))
    out = subprocess.run([SYSTEM_PYTHON, "-c", "import rosbag,sys; b = rosbag.Bag(sys.argv[1]); "
                          "print(b.get_message_count(), [m.message.data for m in b.read_messages()][-1])",
                          str(killed)], capture_output=True, text=True, timeout=60, env={"PATH": "/usr/bin"})
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["299", "message", "00298"]


def _fill_disk(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, room_after: int,
               chunk_threshold: int = 200_000) -> tuple[Path, int]:
    """Write until ENOSPC past 150 kB (with 200 kB chunks: in the third batch of a streamed one),
    then close with `room_after` bytes free; returns the bag and how many messages were handed
    to the writer."""
    real_writev = os.writev
    room = [150_000]

    def small_disk(fd: int, buffers: list[bytes]) -> int:
        want = sum(len(b) for b in buffers)
        if want > room[0]:
            raise OSError(errno.ENOSPC, "No space left on device")
        room[0] -= want
        return real_writev(fd, buffers)

    monkeypatch.setattr(writer_module.os, "writev", small_disk)
    path = tmp_path / "full.bag"
    writer = BagWriter(path, "w", chunk_threshold=chunk_threshold)
    conn = writer.add_connection("/t", HEADER)
    written = 0
    with pytest.raises(OSError, match="No space left"):
        for i in range(10_000):
            writer.write(conn, 100, i, _string(f"message {i:05d}"))
            written += 1
    room[0] = room_after
    writer.close()  # the failure was said once; the bag is ended with what is on disk
    return path, written


def test_a_full_disk_ends_the_bag_indexed_with_what_reached_it(tmp_path: Path,
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    path, written = _fill_disk(tmp_path, monkeypatch, room_after=100_000)  # room for the index
    texts = _texts(path)
    assert 1000 < len(texts) < written and texts == [f"message {i:05d}" for i in range(len(texts))]


def test_a_disk_too_full_for_the_open_chunk_keeps_the_closed_ones(tmp_path: Path,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    path, written = _fill_disk(tmp_path, monkeypatch, room_after=2_000, chunk_threshold=40_000)
    texts = _texts(path)
    assert 1000 < len(texts) < written and texts == [f"message {i:05d}" for i in range(len(texts))]



@pytest.mark.parametrize("compression", ["lz4", "bz2"])
def test_a_compressed_bag_loses_nothing_handed_over_before_a_kill(tmp_path: Path, compression: str) -> None:
    # A compressed chunk cannot be streamed: write_pending closes it instead.
    path = tmp_path / "c.bag"
    writer = BagWriter(path, "w", compression)
    conn = writer.add_connection("/t", HEADER)
    for i in range(300):
        writer.write(conn, 100, i, _string(f"message {i:05d}"))
        if i % 100 == 99:
            writer.write_pending()
    killed = tmp_path / "killed.bag"
    shutil.copyfile(path, killed)
    writer.close()
    reindex_file(str(killed), str(tmp_path / "fixed.bag"))
    assert _texts(tmp_path / "fixed.bag") == [f"message {i:05d}" for i in range(300)]
    with BagReader(tmp_path / "fixed.bag") as reader:
        assert {h.compression for h in reader.chunk_headers()} == {compression}
