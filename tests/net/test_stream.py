"""Sender, Flusher and Receiver: direct writes, bounded backlogs that drop the oldest, hang-ups."""

from __future__ import annotations

import socket
import threading
import time

from kame.net.stream import Flusher, Receiver, Sender


def wait_until(condition, timeout: float = 5.0) -> bool:  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.005)
    return False


def read_all(sock: socket.socket, size: int) -> bytes:
    data = bytearray()
    sock.settimeout(5)
    while len(data) < size:
        chunk = sock.recv(size - len(data))
        if not chunk:
            break
        data += chunk
    return bytes(data)


def test_direct_send_and_parts() -> None:
    flusher = Flusher()
    a, b = socket.socketpair()
    try:
        sender = Sender(a, flusher, 10, lambda exc: None)
        sender.send(b"hello")
        sender.send_parts([b"a", memoryview(b"bc"), bytearray(b"d")])
        assert read_all(b, 9) == b"helloabcd"
        assert sender.frames_sent == 2 and sender.bytes_sent == 9
    finally:
        flusher.close()
        a.close()
        b.close()


def test_a_full_socket_keeps_only_the_newest_frames_and_never_blocks() -> None:
    flusher = Flusher()
    a, b = socket.socketpair()
    a.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    b.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    try:
        sender = Sender(a, flusher, 5, lambda exc: None)
        frame_size = 1000
        started = time.monotonic()
        for i in range(2000):
            sender.send(i.to_bytes(4, "little") * (frame_size // 4))
        assert time.monotonic() - started < 2.0  # the reader never read: sending did not wait
        assert sender.dropped > 0
        received = bytearray()
        b.settimeout(0.5)
        while True:
            try:
                chunk = b.recv(65536)
            except TimeoutError:
                break
            if not chunk:
                break
            received += chunk
        assert len(received) % frame_size == 0  # whole frames only: dropping never splits one
        frames = [bytes(received[i:i + frame_size]) for i in range(0, len(received), frame_size)]
        assert all(f == f[:4] * (frame_size // 4) for f in frames)
        numbers = [int.from_bytes(f[:4], "little") for f in frames]
        assert numbers[-1] == 1999  # the newest frame always arrives
        assert numbers == sorted(numbers)  # in order, gaps only where old frames were dropped
        assert len(numbers) < 2000
    finally:
        flusher.close()
        a.close()
        b.close()


def test_a_peer_hang_up_is_noticed_without_sending() -> None:
    flusher = Flusher()
    a, b = socket.socketpair()
    broken = threading.Event()
    try:
        Sender(a, flusher, 5, lambda exc: broken.set())
        b.close()
        assert broken.wait(5)
    finally:
        flusher.close()
        a.close()


class _Collect:
    def __init__(self) -> None:
        self.data = bytearray()
        self._buf = bytearray(7)

    def get_buffer(self, sizehint: int) -> memoryview:
        return memoryview(self._buf)

    def buffer_updated(self, nbytes: int) -> None:
        self.data += self._buf[:nbytes]


def test_receiver_reads_until_the_peer_closes() -> None:
    a, b = socket.socketpair()
    ended: list[BaseException | None] = []
    done = threading.Event()
    consumer = _Collect()

    def on_end(exc: BaseException | None) -> None:
        ended.append(exc)
        done.set()

    receiver = Receiver(a, consumer, on_end, name="test-receiver")
    receiver.start()
    b.sendall(b"0123456789abcdef")
    b.close()
    assert done.wait(5)
    assert bytes(consumer.data) == b"0123456789abcdef"
    assert ended == [None]
    receiver.close()
    a.close()


def test_closing_a_receiver_ourselves_reports_nothing() -> None:
    a, b = socket.socketpair()
    ended: list[BaseException | None] = []
    receiver = Receiver(a, _Collect(), ended.append, name="test-receiver")
    receiver.start()
    receiver.close()
    assert ended == []
    a.close()
    b.close()
