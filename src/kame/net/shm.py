"""Shared-memory segments and the publisher's sender of shared-memory topics (kame.protocol.shmros).

Rules:
- A segment is a file in /dev/shm named `kame.<pid namespace>.<pid>.<random>`, created by the
  publisher (space reserved with posix_fallocate, so a full /dev/shm is an error now, never a
  SIGBUS later), mapped, and unlinked by the subscriber as soon as it has mapped it: from then
  on only the two mappings hold the memory, and the kernel frees it when both processes end,
  however they end. A name whose subscriber never took it (it died first, or the connection
  broke) is unlinked by the publisher when the connection ends. What a SIGKILL between
  creating and announcing a segment would leave, the next kame process to create one on this
  host sweeps: names of its pid namespace whose process is gone.
- A connection has one ring at a time: created for its first large message (four of it, 1 MiB
  at least), replaced by a larger one when a message outgrows it or when it fills up (doubling
  up to GROW_TO, 8 MiB, or four of the largest message): what loopback socket buffers would hold.
- `ShmSender` has `Sender`'s shape (kame.net.stream): sending never blocks and never waits on
  the subscriber; a message that finds no room in the ring waits in a backlog of at most
  max_frames messages (the publisher's queue_size) that drops the oldest, as over TCP. The
  ring's space comes back with the subscriber's acknowledgements, which the owner's Flusher
  reads when the socket becomes readable, and the publishing thread before it places a large
  message. The subscriber acknowledges a message of ACK_EACH bytes or more as soon as it has
  been delivered (smaller ones once per batch read): with the ring placing each message in
  the lowest gap (shmros.Ring), a subscriber that keeps up has its images copied through the
  same two or three slots, still in the CPU's cache, instead of the whole ring in turn.
- Deserializing from the ring allocates every message's arrays afresh; glibc's malloc gives
  a freed multi-megabyte block back to the kernel and faults it in again for the next one
  (a page fault per 4 KiB: that cost a 1080p image three quarters of its rate). A subscriber
  that maps a segment asks malloc to take blocks of up to half of it from its heap (at most
  32 MiB, M_MMAP_THRESHOLD) and to keep up to twice it freed there (M_TRIM_THRESHOLD).
- Opting out: KAME_SHM=0 (or off/false/no) in either process keeps plain TCPROS; KAME_SHM=always
  puts even small messages through the ring (the tests' forced mode); by default messages of
  INLINE_BELOW bytes or more go through the ring and smaller ones stay on the socket.
"""

from __future__ import annotations

import collections
import contextlib
import ctypes
import functools
import logging
import mmap
import os
import re
import socket
import threading
from collections.abc import Callable, Sequence

from kame.net.stream import Buffer, Flusher
from kame.protocol import shmros

log = logging.getLogger("kame.net.shm")

SHM_DIR = "/dev/shm"
INLINE_BELOW = 16 * 1024
ACK_EACH = 256 * 1024
MIN_CAPACITY = 1 << 20
#: A ring that fills up grows (doubling) up to this, or four of its largest message: what a
#: loopback socket's buffers would hold, so a subscriber's short stall costs no messages here
#: either.
GROW_TO = 8 << 20
MAX_CAPACITY = 1 << 31
_IOV_MAX = 512
_NAME = re.compile(r"kame\.(\d+)\.(\d+)\.[0-9a-f]+")
_OFF = ("0", "off", "false", "no")


def mode() -> str:
    """'off', 'on' or 'always', from KAME_SHM (read at each connection)."""
    value = os.environ.get("KAME_SHM", "1").strip().lower()
    if value in _OFF:
        return "off"
    return "always" if value == "always" else "on"


def local_token() -> str | None:
    """This process's shmros token, or None when shared memory is off or /dev/shm unusable."""
    if mode() == "off":
        return None
    return _host_token()


@functools.cache
def _host_token() -> str | None:
    try:
        with open("/proc/sys/kernel/random/boot_id") as f:
            boot_id = f.read().strip()
        shm = os.stat(SHM_DIR)
        if not os.access(SHM_DIR, os.W_OK | os.X_OK):
            return None
    except OSError:
        return None
    return shmros.token(os.getuid(), boot_id, shm.st_dev, shm.st_ino)


@functools.cache
def _pid_namespace() -> int:
    try:
        return os.stat("/proc/self/ns/pid").st_ino
    except OSError:
        return 0


class Segment:
    """One mapped segment: `view` is the whole of it (read-only for the subscriber)."""

    def __init__(self, name: str, memory: mmap.mmap, readonly: bool) -> None:
        self.name = name
        self.capacity = len(memory)
        self._memory = memory
        view = memoryview(memory)
        self.view = view.toreadonly() if readonly else view

    def close(self) -> None:
        """Unmap now if nothing else holds a view of it; else when the last view goes."""
        self.view.release()
        with contextlib.suppress(BufferError):
            self._memory.close()


def create_segment(capacity: int) -> Segment | None:
    """A new segment of `capacity` bytes, reserved in full; None when /dev/shm will not have it."""
    _sweep_once()
    name = f"kame.{_pid_namespace()}.{os.getpid()}.{os.urandom(8).hex()}"  # not secrets: it loads hashlib (footprint)
    path = os.path.join(SHM_DIR, name)
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o600)
    except OSError as exc:
        log.debug("cannot create %s: %s", path, exc)
        return None
    try:
        os.posix_fallocate(fd, 0, capacity)
        memory = mmap.mmap(fd, capacity)
    except OSError as exc:
        log.debug("cannot reserve %d bytes in %s: %s", capacity, SHM_DIR, exc)
        unlink(name)
        return None
    finally:
        os.close(fd)
    return Segment(name, memory, readonly=False)


def open_segment(name: str, capacity: int) -> Segment:
    """The subscriber's side: map the publisher's segment read-only, then unlink its name."""
    if not _NAME.fullmatch(name):
        raise OSError(f"not a kame segment name: {name!r}")
    path = os.path.join(SHM_DIR, name)
    fd = os.open(path, os.O_RDONLY | os.O_CLOEXEC)
    try:
        if os.fstat(fd).st_size < capacity:
            raise OSError(f"segment {name} is smaller than announced")
        memory = mmap.mmap(fd, capacity, prot=mmap.PROT_READ)
    finally:
        os.close(fd)
        unlink(name)
    return Segment(name, memory, readonly=True)


def unlink(name: str) -> None:
    with contextlib.suppress(OSError):
        os.unlink(os.path.join(SHM_DIR, name))


def sweep() -> list[str]:
    """Unlink the segments of this pid namespace whose creating process is gone; their names."""
    namespace = str(_pid_namespace())
    swept: list[str] = []
    try:
        names = os.listdir(SHM_DIR)
    except OSError:
        return swept
    for name in names:
        match = _NAME.fullmatch(name)
        if match is None or match.group(1) != namespace or _alive(int(match.group(2))):
            continue
        unlink(name)
        swept.append(name)
    return swept


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


_swept = threading.Event()


def _sweep_once() -> None:
    if not _swept.is_set():
        _swept.set()
        swept = sweep()
        if swept:
            log.debug("removed %d shared-memory segments left by ended processes", len(swept))


_M_TRIM_THRESHOLD = -1  # glibc's mallopt parameters
_M_MMAP_THRESHOLD = -3
_MMAP_THRESHOLD_MAX = 32 << 20  # the largest glibc accepts on 64-bit machines
_TRIM_THRESHOLD_MAX = 128 << 20


class _Heap:
    """The segment size malloc has been tuned for (it only grows)."""

    lock = threading.Lock()
    tuned_for = 0


@functools.cache
def _mallopt() -> Callable[[int, int], int] | None:
    try:
        function = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):  # not glibc (or no C library to ask): nothing to tune
        return None
    function.argtypes = (ctypes.c_int, ctypes.c_int)
    function.restype = ctypes.c_int
    return function


def keep_heap(capacity: int) -> None:
    """Tune malloc for messages from a segment of `capacity` bytes (see the module's rules)."""
    mallopt = _mallopt()
    with _Heap.lock:
        if mallopt is None or capacity <= _Heap.tuned_for:
            return
        _Heap.tuned_for = capacity
        mallopt(_M_MMAP_THRESHOLD, min(max(capacity // 2, 128 << 10), _MMAP_THRESHOLD_MAX))
        mallopt(_M_TRIM_THRESHOLD, min(2 * capacity, _TRIM_THRESHOLD_MAX))


def _capacity_for(length: int) -> int:
    """A ring that holds four messages of `length` (the next one is written while the
    subscriber reads the last), at least MIN_CAPACITY, at most MAX_CAPACITY."""
    want = max(MIN_CAPACITY, 4 * (length + shmros.ALIGN))
    capacity = 1 << (want - 1).bit_length()
    return min(capacity, MAX_CAPACITY)


class ShmSender:
    """The sending side of one shared-memory connection (see the module's rules)."""

    def __init__(self, sock: socket.socket, flusher: Flusher, max_frames: int,
                 on_broken: Callable[[BaseException | None], None], max_bytes: int | None = None) -> None:
        sock.setblocking(False)
        self.sock = sock
        self.closed = False
        self.max_frames = max(1, max_frames)
        self.max_bytes = max_bytes
        self.inline_below = 0 if mode() == "always" else INLINE_BELOW
        self.dropped = 0
        self.bytes_sent = 0
        self.frames_sent = 0
        self._flusher = flusher
        self._on_broken = on_broken
        self._lock = threading.Lock()
        self._segment: Segment | None = None
        self._ring: shmros.Ring | None = None
        # per DATA or MAP record sent and not yet acknowledged: the ring it used (None: a MAP)
        self._inflight: collections.deque[shmros.Ring | None] = collections.deque()
        self._acked = 0
        self._announced: dict[int, str] = {}  # MAP record number -> segment name the subscriber may not have taken
        self._records = 0
        self._backlog: collections.deque[tuple[list[Buffer], int]] = collections.deque()
        self._backlog_bytes = 0
        self._out: list[memoryview] = []  # committed records not yet taken by the socket
        self._acks = bytearray()
        self._pending_map: memoryview | None = None  # a new segment's MAP, sent before the next DATA
        self._failure: tuple[BaseException | None] | None = None
        flusher.watch(self)

    def send(self, frame: Buffer) -> None:
        self.send_parts((frame,))

    def send_parts(self, parts: Sequence[Buffer], borrowed: bool = False) -> None:
        """Queue one TCPROS frame (its 4-byte length prefix first, in the first buffer)."""
        if len(parts) == 1 and len(parts[0]) - 4 < self.inline_below:
            self._send_small(parts[0], borrowed)
            return
        payload = _payload(parts)
        length = sum(len(p) for p in payload)
        with self._lock:
            if self.closed:
                return
            self.frames_sent += 1
            waiting = False
            took_acks = bool(self._inflight) and length >= self.inline_below and self._take_acks()
            if self.closed:  # the acknowledgements said the subscriber is gone
                pass
            elif self._backlog or self._out:
                # behind others: the flusher already waits for the socket (out) or acks
                # (backlog), unless the acks it waits for were just taken here
                self._enqueue(payload, length, borrowed)
                if not took_acks or self._out:
                    return
                waiting = not self._pump()
            else:
                record = self._commit(payload, length)
                if record is None:
                    self._enqueue(payload, length, borrowed)
                    return
                self._out = record
                waiting = not self._write()
                if waiting and borrowed:
                    self._out = [memoryview(bytes(view)) for view in self._out]
        if self._failure is not None:
            self._report_failure()
        elif waiting:
            self._flusher.want_write(self)

    def _send_small(self, frame: Buffer, borrowed: bool) -> None:
        """A small message in one buffer (the usual case: a ping, a pose): straight onto the
        socket as an INLINE record, as Sender.send would, when nothing waits before it."""
        with self._lock:
            if self.closed:
                return
            self.frames_sent += 1
            if self._backlog or self._out:
                self._enqueue([memoryview(frame)[4:]], len(frame) - 4, borrowed)
                return
            record = shmros.inline_prefix(len(frame) - 4) + frame[4:]
            self.bytes_sent += len(frame)
            try:
                sent = self.sock.send(record)
            except (BlockingIOError, InterruptedError):
                sent = 0
            except OSError as exc:
                self._fail(exc)
                sent = len(record)
            if sent < len(record):
                self._out = [memoryview(record)[sent:]]
        if self._failure is not None:
            self._report_failure()
        elif sent < len(record):
            self._flusher.want_write(self)

    def _enqueue(self, payload: list[Buffer], length: int, borrowed: bool) -> None:
        if borrowed:
            payload = [bytes(p) for p in payload]
        backlog = self._backlog
        backlog.append((payload, length))
        self._backlog_bytes += length
        max_bytes = self.max_bytes
        while len(backlog) > self.max_frames or (max_bytes is not None and self._backlog_bytes > max_bytes
                                                 and len(backlog) > 1):
            _, dropped = backlog.popleft()
            self._backlog_bytes -= dropped
            self.dropped += 1

    def _commit(self, payload: list[Buffer], length: int) -> list[memoryview] | None:
        """The records that send one message (its bytes placed in the ring, or inline); None
        while the ring has no room for it."""
        self.bytes_sent += length + 4
        if length >= self.inline_below:
            ring = self._ring_for(length)
            if ring is not None:
                offset = ring.place(length)
                if offset is None and ring.capacity < max(GROW_TO, _capacity_for(length)):
                    ring = self._new_segment(2 * ring.capacity) or ring
                    offset = ring.place(length)
                if offset is None:
                    self.bytes_sent -= length + 4
                    return None
                assert self._segment is not None
                view = self._segment.view
                for part in payload:
                    end = offset + len(part)
                    view[offset:end] = part
                    offset = end
                self._inflight.append(ring)
                self._records += 1
                record = memoryview(shmros.data_record(offset - length, length))
                if self._pending_map is not None:
                    record_list = [self._pending_map, record]
                    self._pending_map = None
                    return record_list
                return [record]
        if len(payload) == 1 and length < 65536:
            return [memoryview(shmros.inline_prefix(length) + bytes(payload[0]))]
        return [memoryview(shmros.inline_prefix(length)), *(memoryview(p) for p in payload)]

    def _ring_for(self, length: int) -> shmros.Ring | None:
        """The ring this message goes to: a new, larger one when the current one cannot hold
        two of it; None (send it inline) when /dev/shm has no room for one."""
        ring = self._ring
        need = 2 * (length + shmros.ALIGN)
        if ring is not None and (ring.capacity >= need or ring.capacity >= MAX_CAPACITY):
            return ring if length + shmros.ALIGN <= ring.capacity else None
        fresh = self._new_segment(_capacity_for(length))
        if fresh is None:
            return ring if ring is not None and length + shmros.ALIGN <= ring.capacity else None
        return fresh

    def _new_segment(self, capacity: int) -> shmros.Ring | None:
        """Switch to a new segment (the subscriber maps it when the MAP record reaches it;
        messages still in the old one stay readable in its mapping)."""
        segment = create_segment(min(capacity, MAX_CAPACITY))
        if segment is None:
            return None
        if self._pending_map is not None:  # the last new segment was never announced: forget it
            self._pending_map = None
            self._records -= 1
            self._inflight.pop()
            unlink(self._announced.pop(self._records))
        if self._segment is not None:
            self._segment.close()  # the subscriber keeps its own mapping as long as it reads it
        self._segment = segment
        self._ring = shmros.Ring(segment.capacity)
        self._announced[self._records] = segment.name
        self._inflight.append(None)
        self._records += 1
        self._pending_map = memoryview(shmros.map_record(segment.name, segment.capacity))
        return self._ring

    def _write(self) -> bool:
        """Put committed records on the socket; True when all went."""
        out = self._out
        while out:
            try:
                sent = self.sock.sendmsg(out[:_IOV_MAX])
            except (BlockingIOError, InterruptedError):
                return False
            except OSError as exc:
                self._fail(exc)
                return True
            while sent:
                head = out[0]
                if sent >= len(head):
                    sent -= len(head)
                    out.pop(0)
                else:
                    out[0] = head[sent:]
                    sent = 0
        return True

    def _pump(self) -> bool:
        """Move backlog messages into the ring and records to the socket; True when nothing
        waits for the socket (messages may still wait for ring space: acks bring it)."""
        while True:
            if self._out and not self._write():
                return False
            if self.closed or not self._backlog:
                return True
            batch: list[memoryview] = []
            while self._backlog and len(batch) < _IOV_MAX:
                payload, length = self._backlog[0]
                record = self._commit(payload, length)
                if record is None:
                    break
                self._backlog.popleft()
                self._backlog_bytes -= length
                batch.extend(record)
            if not batch:
                return True
            self._out = batch

    def peer_hung_up(self) -> bool:
        """The socket is readable: acknowledgements (space to reuse), or the end of the stream."""
        waiting = False
        with self._lock:
            if not self.closed and self._take_acks():
                waiting = not self.closed and not self._pump()
        if self._failure is not None:
            self._report_failure()
            return True
        if waiting:
            self._flusher.want_write(self)
        return False

    def _take_acks(self) -> bool:
        """Read the acknowledgements that have arrived, without waiting; True when some did.
        The publishing thread does it too, before placing a message: the space the subscriber
        has just read goes to the next message while it is still in the CPU's cache, and the
        ring does not fill up while the flusher thread waits for its turn to read them."""
        try:
            data = self.sock.recv(65536, socket.MSG_DONTWAIT)
        except (BlockingIOError, InterruptedError):
            return False
        except OSError as exc:
            self._fail(exc)
            return False
        if not data:
            self._fail(None)
            return False
        self._acknowledged(data)
        return True

    def _acknowledged(self, data: bytes) -> None:
        acks = self._acks
        acks += data
        whole = len(acks) - len(acks) % shmros.ACK.size
        if not whole:
            return
        (count,) = shmros.ACK.unpack_from(acks, whole - shmros.ACK.size)
        del acks[:whole]
        if not self._acked <= count <= self._records:
            self._fail(shmros.ShmError(f"acknowledgement of {count} records, {self._records} sent"))
            return
        for number in range(self._acked, count):
            ring = self._inflight.popleft()
            if ring is None:
                self._announced.pop(number, None)  # the subscriber has it (and unlinked it)
            elif ring is self._ring:
                ring.release()
        self._acked = count

    def flush(self) -> bool:
        """Called by the flusher when the socket is writable; True when nothing waits for it."""
        with self._lock:
            done = True if self.closed else self._pump()
        self._report_failure()
        return done

    def _fail(self, exc: BaseException | None) -> None:
        if self.closed:
            return
        self._release()
        self._failure = (exc,)

    def _release(self) -> None:
        self.closed = True
        self._backlog.clear()
        self._backlog_bytes = 0
        self._out = []
        for name in self._announced.values():
            unlink(name)
        self._announced.clear()
        if self._segment is not None:
            self._segment.close()
            self._segment = None

    def _report_failure(self) -> None:
        failure, self._failure = self._failure, None
        if failure is not None:
            callback, self._on_broken = self._on_broken, _ignore
            callback(failure[0])

    def close(self) -> None:
        with self._lock:
            if not self.closed:
                self._release()
        self._on_broken = _ignore
        self._flusher.forget(self)


def _ignore(_exc: BaseException | None) -> None:
    return None


def _payload(parts: Sequence[Buffer]) -> list[Buffer]:
    """A TCPROS frame's buffers without its 4-byte length prefix."""
    first = parts[0]
    if len(first) > 4:
        return [memoryview(first)[4:], *parts[1:]]
    skip = 4 - len(first)
    rest = list(parts[1:])
    while skip and rest:
        head = rest[0]
        if len(head) <= skip:
            skip -= len(head)
            rest.pop(0)
        else:
            rest[0] = memoryview(head)[skip:]
            skip = 0
    return rest


class ShmReceiver:
    """The subscriber's side of the records: payload views in the mapped segment, handed on,
    and the acknowledgement count sent back once they have been delivered (a message of
    ACK_EACH bytes or more as soon as it has been, so its space goes back to the publisher
    while the next one is read: see ShmSender's take of acknowledgements)."""

    def __init__(self, max_frame: int, queue_size: int | None = None) -> None:
        self.max_frame = max_frame
        self.queue_size = queue_size
        self._segment: Segment | None = None
        self._done = 0  # DATA and MAP records taken
        self._acked = 0

    def deliver(self, frames: list[memoryview], deliver: Callable[[list[memoryview]], None],
                sock: socket.socket) -> int:
        """Hand the messages of `frames` to `deliver` (the newest queue_size of them, as
        over TCPROS) and acknowledge them; returns how many older ones were dropped."""
        entries = self._payloads(frames)
        dropped = 0
        if self.queue_size and len(entries) > self.queue_size:
            dropped = len(entries) - self.queue_size
            entries = entries[-self.queue_size:]  # the counts are running: a later one covers the dropped
        first = 0
        for index, (view, done) in enumerate(entries):
            if len(view) >= ACK_EACH:
                deliver([entry[0] for entry in entries[first:index + 1]])
                self._acknowledge(sock, done)
                first = index + 1
        if first < len(entries):
            deliver([entry[0] for entry in entries[first:]])
        self._acknowledge(sock, self._done)
        return dropped

    def _payloads(self, frames: list[memoryview]) -> list[tuple[memoryview, int]]:
        """Each message's bytes, with the record count to acknowledge once they have been read."""
        out: list[tuple[memoryview, int]] = []
        for frame in frames:
            if len(frame) and frame[0] == shmros.INLINE:  # the usual small message, decoded here
                out.append((frame[1:], self._done))
                continue
            record = shmros.decode(frame)
            if isinstance(record, memoryview):
                out.append((record, self._done))
                continue
            self._done += 1
            if isinstance(record, shmros.Map):
                if record.capacity > MAX_CAPACITY:
                    raise shmros.ShmError(f"a segment of {record.capacity} bytes announced")
                try:
                    mapped = open_segment(record.name, record.capacity)
                except OSError as exc:
                    raise ShmUnavailable(f"cannot map the publisher's segment {record.name}: {exc}") from exc
                if self._segment is not None:
                    self._segment.close()
                self._segment = mapped
                keep_heap(mapped.capacity)
                continue
            segment = self._segment
            if segment is None:
                raise shmros.ShmError("a message in shared memory before any segment")
            if record.length > self.max_frame:
                raise shmros.ShmError(f"message of {record.length} bytes refused (limit {self.max_frame})")
            end = record.offset + record.length
            if end > segment.capacity:
                raise shmros.ShmError(f"a message at {record.offset}+{record.length} outside the segment")
            out.append((segment.view[record.offset:end], self._done))
        return out

    def _acknowledge(self, sock: socket.socket, done: int) -> None:
        """Tell the publisher the first `done` records are done with (their views are not used again)."""
        if done > self._acked:
            self._acked = done
            sock.sendall(shmros.ACK.pack(done))

    def close(self) -> None:
        if self._segment is not None:
            self._segment.close()
            self._segment = None


class ShmUnavailable(Exception):
    """The publisher's segment cannot be mapped here: reconnect without shared memory."""
