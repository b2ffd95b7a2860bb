"""Byte streams over TCP for message transports: a listener, a receiver, a bounded sender.

Rules:
- Sending never blocks the caller and never hops threads while the socket can take the bytes:
  `Sender.send` writes straight to the (non-blocking) socket. Only what the kernel will not
  take now waits in a per-connection backlog, which one flusher thread per owner drains as
  the socket becomes writable, many frames per system call.
- A backlog holds at most `max_frames` frames (a publisher's queue_size) and, with
  `max_bytes`, at most that many bytes (a publisher without a queue_size: its frames are
  otherwise unbounded); when full, the oldest whole frame that has not started going out is
  dropped. One slow reader therefore costs its own connection frames, never the sender's
  time, memory beyond that bound, or other connections.
- Receiving is one thread per connection, blocking in recv_into a buffer its consumer hands
  out; the consumer may parse and act on many frames per read.
- Every thread has an owner that stops it: `close()` shuts the socket down, which wakes the
  thread blocked on it. "Closed by us" and "broken by the peer" reach the callbacks apart.
This module moves bytes; what the bytes mean is the caller's business.
"""

from __future__ import annotations

import collections
import errno
import logging
import selectors
import socket
import struct
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any, Protocol

from kame.net import peers
from kame.net.address import resolvable

log = logging.getLogger("kame.net.stream")

Buffer = bytes | bytearray | memoryview
_IOV_MAX = 512  # buffers per sendmsg call


def set_nodelay(sock: socket.socket, enabled: bool) -> None:
    if sock.family in (socket.AF_INET, socket.AF_INET6):
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1 if enabled else 0)


def set_keepalive(sock: socket.socket) -> None:
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_KEEPALIVE, 1)


class Flushable(Protocol):
    """What a Flusher drives: a connection's sender (Sender here, kame.net.shm's ShmSender)."""

    sock: socket.socket
    closed: bool

    def flush(self) -> bool: ...

    def peer_hung_up(self) -> bool: ...


class Flusher:
    """One thread watching the owner's senders: it drains the backlogs of those whose sockets
    were full, and notices peers that hung up (a reader of ours never sends after the
    handshake, so a readable socket means end of stream or garbage to discard)."""

    def __init__(self, name: str = "kame-flusher") -> None:
        self._selector = selectors.DefaultSelector()
        self._wake_r, self._wake_w = socket.socketpair()
        self._wake_r.setblocking(False)
        # a full wake-up socket already wakes the thread: never block on it (the thread itself
        # calls watch(), and would wait on itself)
        self._wake_w.setblocking(False)
        self._selector.register(self._wake_r, selectors.EVENT_READ, None)
        self._lock = threading.Lock()
        self._changes: dict[Flushable, int] = {}  # sender -> wanted events (0: forget it)
        self._events: dict[Flushable, int] = {}
        self._closed = False
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def watch(self, sender: Flushable) -> None:
        self._change(sender, selectors.EVENT_READ)

    def want_write(self, sender: Flushable) -> None:
        self._change(sender, selectors.EVENT_READ | selectors.EVENT_WRITE)

    def forget(self, sender: Flushable) -> None:
        self._change(sender, 0)

    def _change(self, sender: Flushable, events: int) -> None:
        with self._lock:
            if self._closed:
                return
            self._changes[sender] = events
        try:
            self._wake_w.send(b"\0")
        except OSError:
            pass

    def close(self) -> None:
        with self._lock:
            self._closed = True
        try:
            self._wake_w.send(b"\0")
        except OSError:
            pass
        if self._thread is not threading.current_thread():
            self._thread.join(timeout=2.0)
        self._wake_w.close()

    def _apply(self) -> None:
        with self._lock:
            changes, self._changes = self._changes, {}
        for sender, events in changes.items():
            current = self._events.get(sender, 0)
            if sender.closed:
                events = 0
            try:
                if events == current:
                    continue
                if not events:
                    self._selector.unregister(sender.sock)
                    del self._events[sender]
                elif not current:
                    self._selector.register(sender.sock, events, sender)
                    self._events[sender] = events
                else:
                    self._selector.modify(sender.sock, events, sender)
                    self._events[sender] = events
            except (KeyError, ValueError, OSError):
                self._events.pop(sender, None)

    def _run(self) -> None:
        try:
            while not self._closed:
                self._apply()
                for key, mask in self._selector.select():  # changes and close() wake it
                    sender = key.data
                    if sender is None:
                        try:
                            self._wake_r.recv(4096)
                        except OSError:
                            pass
                        continue
                    if mask & selectors.EVENT_READ and sender.peer_hung_up():
                        self.forget(sender)
                        continue
                    if mask & selectors.EVENT_WRITE and sender.flush():
                        self.watch(sender)
        finally:
            self._selector.close()
            self._wake_r.close()


class Sender:
    """The sending side of one connection: direct writes, a bounded backlog, drop-oldest."""

    def __init__(self, sock: socket.socket, flusher: Flusher, max_frames: int,
                 on_broken: Callable[[BaseException | None], None], max_bytes: int | None = None) -> None:
        sock.setblocking(False)
        self.sock = sock
        self.closed = False
        self.max_frames = max(1, max_frames)
        self.max_bytes = max_bytes
        self._backlog_bytes = 0
        self.dropped = 0
        self.bytes_sent = 0
        self.frames_sent = 0
        self._flusher = flusher
        self._on_broken = on_broken
        self._lock = threading.Lock()
        # Frames waiting, each as the buffers still to send; the first may be partly sent.
        self._backlog: collections.deque[list[memoryview]] = collections.deque()
        self._head_started = False
        self._failure: tuple[BaseException | None] | None = None
        flusher.watch(self)

    def send(self, frame: Buffer) -> None:
        """Queue one frame (bytes-like); it goes out now if the socket takes it."""
        # The usual case first, without send_parts' general bookkeeping (on a round trip's path
        # it is a noticeable part of the time): nothing waiting, and the socket takes it whole.
        sent = 0
        with self._lock:
            if not self._backlog and not self.closed:
                try:
                    sent = self.sock.send(frame)
                except OSError:  # would block, or broken: send_parts below sorts it out
                    sent = 0
                if sent == len(frame):
                    self.frames_sent += 1
                    self.bytes_sent += sent
                    return
                if sent:  # the rest waits for the flusher, as in send_parts
                    self.frames_sent += 1
                    self.bytes_sent += sent
                    self._backlog.append([memoryview(frame)[sent:]])
                    self._backlog_bytes += len(frame) - sent
                    self._head_started = True
        if sent:
            self._flusher.want_write(self)
        else:
            self.send_parts((frame,))

    def send_parts(self, parts: Sequence[Buffer], borrowed: bool = False) -> None:
        """Queue one frame given as one or more buffers (a large message: no joining copy).
        `borrowed`: the caller reuses the buffers once this returns, so what cannot go out now
        is copied into the backlog (only that part: the usual case copies nothing)."""
        keep = _copied if borrowed else memoryview
        with self._lock:
            if self.closed:
                return
            self.frames_sent += 1
            if self._backlog:
                self._append([keep(p) for p in parts])
                return
            try:
                sent = self.sock.send(parts[0]) if len(parts) == 1 else self.sock.sendmsg(parts[:_IOV_MAX])
            except (BlockingIOError, InterruptedError):
                sent = 0
            except OSError as exc:
                self._fail(exc)
                sent = -1
            rest: list[memoryview] = []
            if sent >= 0:
                self.bytes_sent += sent
                for part in parts:
                    size = len(part)  # buffers are byte-sized: len is their byte count
                    if sent >= size:
                        sent -= size
                        continue
                    view = memoryview(part)
                    rest.append(keep(view[sent:] if sent else view))
                    sent = 0
                if rest:
                    self._backlog.append(rest)
                    self._backlog_bytes += sum(len(view) for view in rest)
                    self._head_started = len(rest) < len(parts) or len(rest[0]) < len(parts[0])
        if sent < 0:
            self._report_failure()
        elif rest:
            self._flusher.want_write(self)

    def peer_hung_up(self) -> bool:
        """Called when the socket is readable: True (and the link is ended) at end of stream."""
        try:
            data = self.sock.recv(65536)
        except (BlockingIOError, InterruptedError):
            return False
        except OSError as exc:
            with self._lock:
                self._fail(exc)
            self._report_failure()
            return True
        if data:
            return False
        with self._lock:
            self._fail(None)
        self._report_failure()
        return True

    def _append(self, frame: list[memoryview]) -> None:
        backlog = self._backlog
        backlog.append(frame)
        self._backlog_bytes += sum(len(view) for view in frame)
        max_bytes = self.max_bytes
        while len(backlog) > self.max_frames or (max_bytes is not None and self._backlog_bytes > max_bytes
                                                 and len(backlog) > 1 + self._head_started):
            # The head may be partly on the wire: keep it, drop the next oldest.
            if self._head_started:
                head = backlog.popleft()
                dropped = backlog.popleft()
                backlog.appendleft(head)
            else:
                dropped = backlog.popleft()
            self._backlog_bytes -= sum(len(view) for view in dropped)
            self.dropped += 1

    def flush(self) -> bool:
        """Send what the socket takes; True when the backlog is empty (called by the flusher)."""
        try:
            return self._flush()
        finally:
            self._report_failure()

    def _flush(self) -> bool:
        with self._lock:
            if self.closed:
                return True
            backlog = self._backlog
            while backlog:
                batch: list[memoryview] = []
                for frame in backlog:
                    batch.extend(frame)
                    if len(batch) >= _IOV_MAX:
                        break
                try:
                    sent = self.sock.sendmsg(batch[:_IOV_MAX])
                except (BlockingIOError, InterruptedError):
                    return False
                except OSError as exc:
                    self._fail(exc)
                    return True
                self.bytes_sent += sent
                self._backlog_bytes -= sent
                while sent and backlog:
                    head = backlog[0]
                    while head and sent >= len(head[0]):
                        sent -= len(head.pop(0))
                    if head:
                        if sent:
                            head[0] = head[0][sent:]
                            sent = 0
                        self._head_started = True
                    else:
                        backlog.popleft()
                        self._head_started = False
                if backlog:
                    return False
            return True

    def _fail(self, exc: BaseException | None) -> None:
        """Mark the link broken (under the lock); the owner hears of it from _report_failure."""
        if self.closed:
            return
        self.closed = True
        self._backlog.clear()
        self._backlog_bytes = 0
        self._failure = (exc,)

    def _report_failure(self) -> None:
        """Tell the owner the link broke; called with the lock released (the owner closes us)."""
        failure, self._failure = self._failure, None
        if failure is not None:
            callback, self._on_broken = self._on_broken, _ignore
            callback(failure[0])

    def close(self) -> None:
        with self._lock:
            self.closed = True
            self._backlog.clear()
            self._backlog_bytes = 0
        self._on_broken = _ignore
        self._flusher.forget(self)


def _ignore(_exc: BaseException | None) -> None:
    return None


def _copied(buffer: Buffer) -> memoryview:
    return memoryview(bytes(buffer))


class Consumer(Protocol):
    """What a Receiver feeds, in asyncio.BufferedProtocol's shape: it hands out the buffer the
    next read goes into (for a large message, that message's own storage: one copy in all)
    and is told how many bytes arrived."""

    def get_buffer(self, sizehint: int) -> memoryview: ...

    def buffer_updated(self, nbytes: int) -> None: ...

    @property
    def mid_frame(self) -> bool:
        """Part of a message has arrived and the rest has not (a stall here is the peer's)."""
        ...

    def release(self) -> None:
        """The stream is over: drop the buffers now."""
        ...


class Stalled(Exception):
    """The peer stopped sending in the middle of a message."""


class Receiver:
    """A thread that reads a socket into a Consumer until the stream ends.

    `on_end(exc)` is called once: with None when the peer closed the stream, with the error
    when it broke (or the consumer raised), and not at all when we closed it ourselves.
    With `stall_timeout`, a peer that sends no byte for that long while the consumer is in the
    middle of a message ends the stream with Stalled (idle between messages is fine).
    With `read_interval`, the thread waits that long after each read: what arrives meanwhile
    gathers in the socket's buffer and comes in the next read, one wake-up for many small
    messages instead of one each. For a consumer that only looks at the data every so often (a
    plot drawn at a frame rate); the kernel's buffer (and TCP's flow control) bounds what waits.
    When the stream ends the consumer releases its buffers on the spot, and the receiver lets go
    of the consumer and `on_end`: an owner that holds the receiver while the consumer's callbacks
    hold the owner is a reference cycle, which kept a half-received frame (up to 64 MiB) until
    the cyclic collector happened to run.
    """

    def __init__(self, sock: socket.socket, consumer: Consumer, on_end: Callable[[BaseException | None], None],
                 name: str, chunk_size: int = 256 * 1024, stall_timeout: float | None = None,
                 read_interval: float = 0.0) -> None:
        self.sock = sock
        self._stall_timeout = stall_timeout
        self._read_interval = read_interval
        self._consumer: Consumer | None = consumer  # both let go of when the stream ends
        self._on_end: Callable[[BaseException | None], None] | None = on_end
        self._chunk_size = chunk_size
        self._closing = False
        self._closed = threading.Event()  # wakes a read_interval wait at close
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)

    def start(self) -> None:
        self._thread.start()

    def _run(self) -> None:
        consumer = self._consumer
        assert consumer is not None
        recv_into = self.sock.recv_into
        chunk_size = self._chunk_size
        error: BaseException | None = None
        stall = self._stall_timeout
        interval = self._read_interval
        closed = self._closed
        try:
            if stall is not None:
                _set_receive_timeout(self.sock, stall)
            while not self._closing:
                try:
                    n = recv_into(consumer.get_buffer(chunk_size))
                except BlockingIOError:  # SO_RCVTIMEO passed
                    if stall is not None and consumer.mid_frame:
                        raise Stalled(f"no byte for {stall:g} s in the middle of a message") from None
                    continue
                if n == 0:
                    break
                consumer.buffer_updated(n)
                if interval and closed.wait(interval):
                    break
        except OSError as exc:
            error = exc
        except Exception as exc:  # a protocol error or a bug in the consumer: end this stream only
            error = exc
        consumer.release()
        del consumer
        self._consumer = None
        on_end, self._on_end = self._on_end, None
        if not self._closing and on_end is not None:
            on_end(error)

    def close(self) -> None:
        self._closing = True
        self._closed.set()
        shut_down(self.sock)
        if self._thread.is_alive() and self._thread is not threading.current_thread():
            self._thread.join(timeout=1.0)


def _set_receive_timeout(sock: socket.socket, seconds: float) -> None:
    """A blocking socket whose reads fail with EAGAIN after `seconds` without a byte (SO_RCVTIMEO).
    Not settimeout(): Python then polls the socket before every read, one more system call
    per message on the path of every small one."""
    sock.settimeout(None)
    whole = int(seconds)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVTIMEO, _TIMEVAL.pack(whole, int((seconds - whole) * 1e6)))


_TIMEVAL = struct.Struct("@ll")  # struct timeval


class Listener:
    """Accepts TCP connections on a thread and hands each new socket to `on_accept`."""

    def __init__(self, host: str, port: int, on_accept: Callable[[socket.socket, Any], None],
                 name: str = "kame-listener") -> None:
        family = socket.AF_INET6 if ":" in host else socket.AF_INET
        self.sock = socket.socket(family, socket.SOCK_STREAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.bind((host, port))
        self.sock.listen(128)
        self.port: int = self.sock.getsockname()[1]
        self._on_accept = on_accept
        self._closing = False
        self._starved = AcceptStarvation(self.sock)
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        starved = self._starved
        while not self._closing:
            try:
                conn, addr = self.sock.accept()
            except OSError as exc:
                if self._closing:
                    return
                starved.failed(exc)
                continue
            starved.ok()
            if not peers.admit(addr, self._thread.name):
                conn.close()
                continue
            try:
                self._on_accept(conn, addr)
            except Exception:
                log.exception("error accepting a connection from %s", addr)
                conn.close()

    def close(self) -> None:
        self._closing = True
        self._starved.stop()
        shut_down(self.sock)
        self.sock.close()
        self._thread.join(timeout=1.0)


class AcceptStarvation:
    """What an accept loop does when accept() fails. Out of file descriptors (or memory), the
    pending connection stays queued and accept() fails again at once: retrying straight away
    spun a CPU at 100% and logged nothing. We log once per episode and pause before retrying;
    other failures (a client that reset before we got to it) retry at once, silently. The
    pause ends at once when the owner closes the server (`stop()`)."""

    PAUSE = 0.1

    def __init__(self, sock: socket.socket) -> None:
        self._sock = sock
        self._logged = False
        self._stopped = threading.Event()

    def stop(self) -> None:
        self._stopped.set()

    def failed(self, exc: OSError) -> None:
        if exc.errno not in _STARVED:
            return
        if not self._logged:
            self._logged = True
            log.error("cannot accept connections on %s: %s; retrying every %.1f s until it clears",
                      _local(self._sock), exc, self.PAUSE)
        self._stopped.wait(self.PAUSE)

    def ok(self) -> None:
        if self._logged:
            self._logged = False
            log.warning("accepting connections on %s again", _local(self._sock))


_STARVED = frozenset({errno.EMFILE, errno.ENFILE, errno.ENOBUFS, errno.ENOMEM})


def _local(sock: socket.socket) -> str:
    try:
        return str(sock.getsockname())
    except OSError:
        return "?"


def receive(sock: socket.socket, size: int, spin: float = 0.0) -> bytes:
    """sock.recv(size); with `spin`, polled without blocking for that long first. An answer that
    comes within tens of microseconds (a service call's) then costs no sleep and wake-up of a
    blocking read (half of a persistent call)."""
    if spin:
        deadline = time.perf_counter() + spin
        while True:
            try:
                return sock.recv(size, socket.MSG_DONTWAIT)
            except BlockingIOError:
                if time.perf_counter() >= deadline:
                    break
    return sock.recv(size)


def shut_down(sock: socket.socket) -> None:
    """End both directions now: a thread blocked reading `sock` wakes (closing alone would not
    wake it). The caller still closes the socket."""
    try:
        sock.shutdown(socket.SHUT_RDWR)
    except OSError:
        pass


def peer_of(sock: socket.socket) -> str:
    """`host:port` of the other end, for log lines ("?" once the socket is gone)."""
    try:
        host, port = sock.getpeername()[:2]
        return f"{host}:{port}"
    except OSError:
        return "?"


def connect(host: str, port: int, timeout: float) -> socket.socket:
    # typeshed says str; the address goes to getaddrinfo, which takes bytes as well (see resolvable)
    sock = socket.create_connection((resolvable(host), port), timeout=timeout)  # type: ignore[arg-type]
    sock.settimeout(None)
    return sock


def recv_exactly(sock: socket.socket, size: int, deadline: float | None = None) -> bytes:
    """Blocking read of exactly `size` bytes (handshakes); raises ConnectionError at EOF.
    With a `deadline` (time.monotonic()), TimeoutError once it passes: a peer that trickles a
    byte now and then cannot keep us reading, as a per-recv timeout would let it."""
    chunks: list[bytes] = []
    remaining = size
    while remaining:
        if deadline is not None:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"timed out with {remaining} of {size} bytes still to come")
            sock.settimeout(left)
        chunk = sock.recv(min(remaining, 1 << 20))
        if not chunk:
            raise ConnectionError("connection closed by the peer")
        chunks.append(chunk)
        remaining -= len(chunk)
    return b"".join(chunks)
