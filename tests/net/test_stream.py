"""Sender, Flusher and Receiver: direct writes, bounded backlogs that drop the oldest, hang-ups."""

from __future__ import annotations

import re
import socket
import threading
import time

from kame.net.stream import Flusher, Receiver, Sender, Stalled


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


def test_a_borrowed_buffer_is_copied_only_when_it_has_to_wait() -> None:
    # A relay (rosout) sends straight from its receive buffer and reuses it at once: what the
    # socket does not take now must be a copy, or the reused buffer would go out instead.
    flusher = Flusher()
    a, b = socket.socketpair()
    a.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    try:
        sender = Sender(a, flusher, 100, lambda exc: None)
        scratch = bytearray(50_000)
        sent = []
        for i in range(5):
            scratch[:] = bytes([65 + i]) * len(scratch)
            sender.send_parts([b"%d" % i, memoryview(scratch)], borrowed=True)
            sent.append(b"%d" % i + bytes(scratch))
        scratch[:] = b"z" * len(scratch)
        assert read_all(b, 5 * 50_001) == b"".join(sent)
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
        self.released = False

    def get_buffer(self, sizehint: int) -> memoryview:
        return memoryview(self._buf)

    def buffer_updated(self, nbytes: int) -> None:
        self.data += self._buf[:nbytes]

    def release(self) -> None:
        self.released = True


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
    assert ended == [None] and consumer.released
    receiver.close()
    a.close()


class _Link:
    """An owner whose receiver's consumer and on_end call back into it: a reference cycle."""

    def __init__(self, sock: socket.socket, ended: threading.Event) -> None:
        consumer = _Collect()
        consumer.owner = self  # type: ignore[attr-defined]  # as a link's frames go to its deliver()
        self.ended = ended
        self.receiver = Receiver(sock, consumer, self.on_end, name="test-receiver")

    def on_end(self, exc: BaseException | None) -> None:
        self.ended.set()


def test_a_receiver_whose_stream_ended_holds_no_cycle_to_its_owner() -> None:
    # The owner (a subscriber's link) and its half-received frame stayed until the cyclic
    # collector ran: a subscriber reconnected to a dropping publisher grew to 1.6 GB.
    import gc
    import weakref

    a, b = socket.socketpair()
    ended = threading.Event()
    gc.disable()
    try:
        link = _Link(a, ended)
        gone = weakref.ref(link)
        link.receiver.start()
        b.close()
        assert ended.wait(5)
        link.receiver._thread.join(5)
        del link
        assert gone() is None  # freed by its reference count, at once
    finally:
        gc.enable()
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


class _Halves(_Collect):
    """Two-byte messages: in the middle of one after an odd count of bytes."""

    @property
    def mid_frame(self) -> bool:
        return len(self.data) % 2 == 1


def test_a_stall_timeout_ends_a_stream_stalled_mid_message_only() -> None:
    a, b = socket.socketpair()
    ended: list[BaseException | None] = []
    done = threading.Event()
    consumer = _Halves()

    def on_end(exc: BaseException | None) -> None:
        ended.append(exc)
        done.set()

    receiver = Receiver(a, consumer, on_end, name="test-receiver", stall_timeout=0.2)
    receiver.start()
    try:
        b.sendall(b"ab")
        assert not done.wait(0.7)  # idle between messages, several timeouts long: fine
        b.sendall(b"c")  # half a message, and then nothing
        assert done.wait(5)
        assert bytes(consumer.data) == b"abc"
        assert len(ended) == 1 and isinstance(ended[0], Stalled)
    finally:
        receiver.close()
        a.close()
        b.close()


class _CountReads(_Collect):
    def __init__(self) -> None:
        super().__init__()
        self._buf = bytearray(4096)
        self.reads = 0

    def buffer_updated(self, nbytes: int) -> None:
        self.reads += 1
        super().buffer_updated(nbytes)


def test_a_read_interval_gathers_what_arrives_meanwhile_into_one_read() -> None:
    a, b = socket.socketpair()
    consumer = _CountReads()
    receiver = Receiver(a, consumer, lambda exc: None, name="test-receiver", read_interval=3.0)
    receiver.start()
    try:
        b.sendall(b"a")
        assert wait_until(lambda: consumer.reads == 1)  # the first read is done: now the thread waits
        for byte in b"bcdefghijk":  # ten sends, each of which would wake a reader without the interval
            b.sendall(bytes([byte]))
        assert wait_until(lambda: len(consumer.data) == 11, timeout=10.0)
        assert bytes(consumer.data) == b"abcdefghijk" and consumer.reads == 2
        b.sendall(b"l")
    finally:
        receiver.close()  # wakes the wait: the thread is gone when close returns (it waits 1 s at most)
    assert not receiver._thread.is_alive()
    a.close()
    b.close()


_STARVED_SERVER = r'''
import logging, resource, socket, sys, threading, time
logging.basicConfig(stream=sys.stderr, level=logging.INFO, format="%(levelname)s %(message)s")
from kame.net.rpc_server import RpcServer
from kame.net.stream import Listener
held = []
accepted = threading.Event()
def accept(sock, addr):
    held.append(sock)
    accepted.set()
listener = Listener("127.0.0.1", 0, accept)
rpc = RpcServer("127.0.0.1", 0, lambda body: b"ok")
rpc.start()
resource.setrlimit(resource.RLIMIT_NOFILE, (48, 48))
print(listener.port, rpc.port, flush=True)
sys.stdin.readline()  # the client has filled our descriptor table
start = time.process_time()
time.sleep(1.0)
print(round(time.process_time() - start, 2), flush=True)
sys.stdin.readline()  # the client has let go
before = len(held)
accepted.clear()
for sock in held[:before]:
    sock.close()
accepted.wait(10.0)  # the loop's 0.1 s pause, however loaded the machine
print(len(held) - before, flush=True)
'''


def test_accept_loops_pause_when_out_of_file_descriptors() -> None:
    # Out of descriptors, accept() fails at once for as long as a connection is queued: the
    # accept loops retried in a tight loop (a whole CPU, nothing logged). Now they log once and pause.
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-c", _STARVED_SERVER], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    clients: list[socket.socket] = []
    try:
        assert proc.stdin is not None and proc.stdout is not None and proc.stderr is not None
        port, rpc_port = map(int, proc.stdout.readline().split())
        for target in [port] * 60 + [rpc_port] * 3:
            clients.append(socket.create_connection(("127.0.0.1", target), timeout=5))
        time.sleep(0.3)
        proc.stdin.write("\n")
        proc.stdin.flush()
        assert float(proc.stdout.readline()) < 0.5  # was ~1.0: a spinning accept loop
        for sock in clients[:30]:
            sock.close()
        proc.stdin.write("\n")
        proc.stdin.flush()
        assert int(proc.stdout.readline()) > 0  # accepting again once descriptors are free
        proc.stdin.close()
        proc.wait(5)
        err = proc.stderr.read()
        # once an episode, not once a retry: for each listener, "cannot accept" and "accepting again"
        # take turns (freed descriptors can be used up again by the queued connections: a new episode)
        last_said: dict[str, str] = {}
        for said, where in re.findall(r"(cannot accept|accepting) connections on (\('[^)]*\))", err):
            assert last_said.get(where) != said, err
            last_said[where] = said
        assert last_said, err
        assert "Too many open files" in err
    finally:
        for sock in clients:
            sock.close()
        if proc.poll() is None:
            proc.kill()
            proc.wait()


class _StuckSender:
    """A Flushable whose first flush waits until released (a flusher thread held up)."""

    def __init__(self) -> None:
        self.sock, self._other = socket.socketpair()
        self.closed = False
        self.in_flush = threading.Event()
        self.release = threading.Event()

    def flush(self) -> bool:
        self.in_flush.set()
        self.release.wait(10)
        return True

    def peer_hung_up(self) -> bool:
        return False


def test_requests_to_a_busy_flusher_never_block_the_caller() -> None:
    # The wake-up socket filled while the flusher thread was busy, and a send on it blocked the
    # publisher (and the flusher itself, when it asked to watch a sender: a deadlock).
    flusher = Flusher()
    sender = _StuckSender()
    try:
        flusher.want_write(sender)
        assert sender.in_flush.wait(5)
        requests = threading.Thread(target=lambda: [flusher.want_write(sender) for _ in range(300_000)])
        requests.start()
        requests.join(30)
        assert not requests.is_alive()
    finally:
        sender.release.set()
        flusher.close()
        sender.sock.close()
        sender._other.close()
