"""BagWriter's recorder paths: large messages handed over (`owned=True`) and written from where
they lie, page-cache drop-behind, and short writes; the bytes must not depend on any of them."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import rosbag
from kame.bag import writer as writer_module
from kame.bag.writer import BagWriter

HEADER = {"type": "std_msgs/String", "md5sum": "992ce8a1687cec8c8bd883ec73ca41d1",
          "message_definition": "string data\n"}


def _string(payload: bytes) -> bytes:
    return len(payload).to_bytes(4, "little") + payload


def _messages() -> list[tuple[int, int, bytes]]:
    """Small and large (above the kept-by-reference size) messages on two connections."""
    out = []
    for i in range(60):
        out.append((0, i, _string(b"small %d" % i)))
        if i % 7 == 0:
            out.append((1, i, _string(bytes([i % 251]) * (200_000 + i))))
    return out


def _write(path: Path, compression: str, owned: bool, drop_behind: bool, threshold: int = 300_000) -> None:
    w = BagWriter(path, "w", compression, threshold, drop_behind=drop_behind)
    conns = [w.add_connection("/small", HEADER), w.add_connection("/big", HEADER)]
    for conn, i, data in _messages():
        w.write(conns[conn], 10 + i, 5, data, owned=owned)
    w.close()


@pytest.mark.parametrize("compression", ["none", "lz4", "bz2"])
def test_owned_and_drop_behind_write_the_same_bytes(tmp_path: Path, compression: str,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(writer_module, "_DROP_WINDOW", 256 * 1024)  # advise often on a small bag
    _write(tmp_path / "plain.bag", compression, owned=False, drop_behind=False)
    _write(tmp_path / "fast.bag", compression, owned=True, drop_behind=True)
    assert (tmp_path / "plain.bag").read_bytes() == (tmp_path / "fast.bag").read_bytes()
    with rosbag.Bag(tmp_path / "fast.bag") as bag:
        got = [(t, m.data) for t, m, _ in bag.read_messages(raw=False)]
    expected = [("/small" if conn == 0 else "/big", data[4:].decode("latin-1")) for conn, _, data in _messages()]
    assert got == expected


def test_drop_behind_advises_only_what_is_written_and_backs_off_when_slow(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[tuple[int, int]] = []
    slow = [False]
    clock = [0.0]

    def fadvise(fd: int, offset: int, length: int, advice: int) -> None:
        assert advice == os.POSIX_FADV_DONTNEED
        calls.append((offset, offset + length))
        if slow[0]:
            clock[0] += 1.0

    monkeypatch.setattr(writer_module.os, "posix_fadvise", fadvise, raising=False)
    monkeypatch.setattr(writer_module.time, "monotonic", lambda: clock[0])
    monkeypatch.setattr(writer_module, "_DROP_WINDOW", 1 << 20)
    monkeypatch.setattr(writer_module, "_BACKOFF", 4 << 20)
    w = BagWriter(tmp_path / "d.bag", "w", chunk_threshold=100_000, drop_behind=True)
    conn = w.add_connection("/big", HEADER)
    big = _string(bytes(300_000))
    for i in range(20):  # ~6 MB
        w.write(conn, 1, i, big, owned=True)
    assert len(calls) >= 4
    for k in range(2, len(calls)):  # each range is advised twice: write-back starts, then it is dropped
        assert calls[k][0] == calls[k - 2][1]
    assert all(end <= os.path.getsize(tmp_path / "d.bag") for _, end in calls)
    # A slow call (the disk is behind): the next 4 MB are left to the kernel.
    slow[0] = True
    n = len(calls)
    written = 20
    while len(calls) == n:
        w.write(conn, 2, 0, big, owned=True)
        written += 1
    slow[0] = False
    pos_after_slow = calls[-1][1]
    for i in range(10):  # 3 MB: inside the back-off
        w.write(conn, 3, i, big, owned=True)
    assert len(calls) == n + 1
    for i in range(20):
        w.write(conn, 4, i, big, owned=True)
    assert len(calls) > n + 1 and calls[n + 1][0] >= pos_after_slow + (4 << 20)
    w.close()
    with rosbag.Bag(tmp_path / "d.bag") as bag:
        assert bag.get_message_count() == written + 30


def test_short_writes_are_continued(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    real_writev = os.writev

    def short_writev(fd: int, buffers: list[bytes]) -> int:  # at most 1000 bytes a call
        taken: list[bytes] = []
        room = 1000
        for b in buffers:
            piece = bytes(memoryview(b)[:room])
            taken.append(piece)
            room -= len(piece)
            if not room:
                break
        return real_writev(fd, taken)

    _write(tmp_path / "plain.bag", "none", owned=True, drop_behind=False)
    monkeypatch.setattr(writer_module.os, "writev", short_writev)
    _write(tmp_path / "short.bag", "none", owned=True, drop_behind=False)
    assert (tmp_path / "plain.bag").read_bytes() == (tmp_path / "short.bag").read_bytes()
