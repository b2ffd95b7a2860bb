"""A subscription's TCPROS link to one publisher: requestTopic, the handshake, the reading thread.

A link connects to the publisher the master names (requestTopic, then a TCPROS handshake) and
reads its frames on a thread of its own (kame.net.stream's Receiver), handing them to its
Subscription (kame.node.topics) in batches. When a publisher goes away but is still
registered, the link is retried with a growing delay, waiting on an event that closing the link
(and so the node's shutdown) sets: no retry outlives its subscription.

What a publisher can make a subscriber hold is bounded: a frame longer than the message type
can be (its size, for a type without variable-length fields; else `max_frame`, 1 GiB by
default), a frame that stops arriving half-way (no byte for the subscription's stall timeout)
and one that arrives too slowly (a deadline scaled to its size, see _Frames) drop the connection
with one error line, without a retry (the peer would do the same again). A frame's buffer holds
what arrived (kame.protocol.tcpros's FrameReader) and is released when the connection ends. A
publisher that answers with what is not a connection header, or that drops the connection soon
after each handshake, is tried again ever more slowly (kame.net.backoff), with one line.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from kame.net.address import DOES_NOT_RESOLVE, REFUSED, is_local_address, unreachable_reason
from kame.net.backoff import RespawnBackoff
from kame.net.handshake import HandshakeError, MalformedHeader, read_header_and_rest, write_header
from kame.net.stream import Receiver, Stalled, connect, set_keepalive, set_nodelay, shut_down
from kame.net.xmlrpc_client import XmlRpcProxy
from kame.node.master_proxy import unwrap
from kame.node.unreachable import dead_publisher_message, unreachable_message
from kame.protocol import shmros, tcpros

if TYPE_CHECKING:
    import socket

    # imported where used: with ctypes and mmap, nearly a megabyte a node without a
    # shared-memory connection never needs
    from kame.net import shm
    from kame.node.topics import Subscription

log = logging.getLogger("kame.topics")

#: The largest frame a subscription takes by default: 1 GiB, roscpp's own sanity bound.
MAX_FRAME = 1 << 30
#: Seconds before the first retry of a publisher that could not be reached, doubled per
#: failure up to RETRY_CAP: a publisher just starting or just gone (the master's update drops it).
RETRY_DELAY = 0.1
RETRY_CAP = 2.0
#: Seconds a publisher may leave a frame half-sent before the connection is dropped (no byte
#: that long), and the base of a split frame's deadline.
STALL_TIMEOUT = 30.0
#: Bytes a second a frame that spans several reads must arrive at, on average, after
#: STALL_TIMEOUT: 16 KiB/s, a slow radio link's; a 6 MB image then has 6.4 min, a 64 MiB frame 68.
MIN_FRAME_RATE = 16 << 10


class PublisherLink:
    """Our connection to one publisher of a subscribed topic (plain TCPROS, or with shared memory)."""

    transport = "TCPROS"

    def __init__(self, subscription: Subscription, publisher_uri: str, connection_id: int,
                 after: PublisherLink | None = None) -> None:
        """`after`: the link to the same publisher that this one replaces, which it dropped."""
        self.subscription = subscription
        self.publisher_uri = publisher_uri
        self.connection_id = connection_id
        # a publisher we were connected to and lost is no news: only a first connection's
        # failures say that the publisher's advertised address is unusable from here
        self._may_report = after is None
        # a publisher that drops us soon after each handshake is reconnected to ever more slowly,
        # as a program that keeps crashing is respawned; the count lives across the links
        self.drops: RespawnBackoff = RespawnBackoff() if after is None else after.drops
        self._first_wait = 0.0 if after is None else after.reconnect_delay
        self.reconnect_delay: float = 0.0  # how long the link that replaces this one waits first
        self._connected_at = 0.0
        self._target = publisher_uri  # what _connect is trying to reach: its URI, then host:port
        self.callerid = ""
        self.header: dict[str, str] = {}
        self.receiver: Receiver | None = None
        self.sock: socket.socket | None = None
        self.bytes_received = 0
        self.messages_received = 0
        self.dropped = 0
        self.closed = False
        self._closing = threading.Event()  # set by close(): ends a retry's wait at once
        self._lock = threading.Lock()
        self.connected = False
        self.latching = False
        # With a latching publisher, its last message (a copy: frames are reused buffers), so a
        # callback added later still gets it, as rospy's add_callback does (#1852).
        self.latched: bytes | None = None
        self.ended = False  # always False: a TCPROS link retries by itself
        self._shm: shm.ShmReceiver | None = None
        # a publisher that answers with what is not a connection header is tried again ever
        # more slowly, as a program that keeps crashing is respawned
        self._garbled = RespawnBackoff()

    def latched_payload(self) -> bytes | None:
        return self.latched

    def run(self) -> None:
        """Connect, retrying while the publisher stays registered (runs on its own thread)."""
        if self._first_wait and self._closing.wait(self._first_wait):
            return
        delay = RETRY_DELAY
        failures = 0
        while not self.closed and not self.subscription.node.is_shutdown:
            try:
                self._connect()
                return
            except MalformedHeader as exc:
                if self.closed:
                    return
                wait, _ = self._garbled.delay(0.0, RETRY_DELAY)
                self._report_garbled(exc, wait)
                if self._closing.wait(wait):
                    return
                continue
            except (OSError, HandshakeError, ValueError) as exc:
                if self.closed:
                    return
                failures += 1
                log.debug("connecting to %s for %s failed: %s", self.publisher_uri, self.subscription.topic, exc)
                self._report_unreachable(exc, failures)
            except _Refused as exc:
                # A publisher on its way out (rospy answers "node shutting down") is no fault:
                # the master's next publisherUpdate drops it.
                level = logging.DEBUG if "shutting down" in str(exc) else logging.ERROR
                log.log(level, "%s refused our subscription to %s: %s", self.publisher_uri,
                        self.subscription.topic, exc)
                return
            if self._closing.wait(delay):
                return
            delay = min(delay * 2, RETRY_CAP)

    def _report_garbled(self, exc: MalformedHeader, wait: float) -> None:
        """One error line for a publisher whose reply is not a connection header; each retry
        after it is a debug line with its delay."""
        topic = self.subscription.topic
        if self._garbled.young_deaths == 1:
            who = self._publisher_name() or self.publisher_uri
            log.error("publisher %s of %s answered with a malformed connection header (%s): trying again "
                      "ever less often, up to every %g s", who, topic, exc, RespawnBackoff.CAP)
        log.debug("malformed connection header from %s for %s: %s; trying again in %g s",
                  self.publisher_uri, topic, exc, wait)

    def _report_unreachable(self, exc: BaseException, failures: int) -> None:
        """One warning per publisher when its advertised address fails us: at once when its name
        does not resolve, else from the third failure on (a publisher that just exited also
        refuses, and the master's update then drops it). A node API on this machine that refuses
        the connection is a dead publisher (kame.node.unreachable), not an address problem."""
        reason = unreachable_reason(exc)
        if not self._may_report or reason is None:
            return
        if failures < 3 and reason != DOES_NOT_RESOLVE:
            return
        self._may_report = False
        node = self.subscription.node
        if not node.unreachable_reported.first(self.publisher_uri):
            return
        if reason == REFUSED and self._target == self.publisher_uri and self._on_this_machine():
            log.warning(dead_publisher_message(self._publisher_name(), self.subscription.topic, self.publisher_uri))
        else:
            log.warning(unreachable_message(self._publisher_name(), self.subscription.topic, self._target, reason))

    def _on_this_machine(self) -> bool:
        """Whether the publisher's node API is an address of this machine (or its loopback)."""
        from urllib.parse import urlsplit

        host = urlsplit(self.publisher_uri).hostname or ""
        return bool(host) and is_local_address(host, ipv6=":" in host)

    def _publisher_name(self) -> str | None:
        """The node the master lists at our publisher's URI, if it says."""
        node, topic = self.subscription.node, self.subscription.topic
        try:
            publishers = dict(node.master.call("getSystemState")[0]).get(topic, [])
            for name in publishers:
                if node.master.call("lookupNode", name) == self.publisher_uri:
                    return str(name)
        except Exception:  # any failure: the warning names the URI anyway
            log.debug("could not name the publisher at %s", self.publisher_uri, exc_info=True)
        return None

    def _connect(self) -> None:
        sub = self.subscription
        node = sub.node
        self._target = self.publisher_uri
        proxy = XmlRpcProxy(self.publisher_uri, timeout=5.0)
        try:
            answer = unwrap(proxy.call("requestTopic", node.name, sub.topic, [["TCPROS"]]), "requestTopic")
        except Exception as exc:
            raise OSError(f"requestTopic: {exc}") from exc
        finally:
            proxy.close()
        if not isinstance(answer, list) or len(answer) < 3 or answer[0] != "TCPROS":
            raise _Refused(f"unsupported protocol parameters {answer!r}")
        host, port = str(answer[1]), int(answer[2])
        self._target = f"{host}:{port} (its TCPROS address)"
        sock = connect(host, port, timeout=5.0)
        with self._lock:  # from here close() ends the handshake too
            if self.closed:
                sock.close()
                return
            self.sock = sock
        from kame.net import shm

        try:
            may_share = sub.shared_memory and self.publisher_uri not in sub.no_shm
            offer = shmros.offer(shm.local_token() if may_share else None)
            write_header(sock, tcpros.subscriber_header_fields(
                callerid=node.name, topic=sub.topic, type=sub.type, md5sum=sub.md5sum,
                message_definition=sub.definition, tcp_nodelay=sub.tcp_nodelay, extra=offer))
            header, trailing = read_header_and_rest(sock, 5.0)
            sock.settimeout(None)
        except BaseException:
            sock.close()
            raise
        reply = tcpros.check_publisher_reply(header)
        if isinstance(reply, tcpros.Rejected):
            sock.close()
            raise _Refused(reply.error)
        if reply.md5sum != sub.md5sum and "*" not in (reply.md5sum, sub.md5sum):
            sock.close()
            raise _Refused(f"md5sum mismatch: we expect [{sub.type}/{sub.md5sum}], "
                           f"the publisher sends [{reply.type}/{reply.md5sum}]")
        set_nodelay(sock, sub.tcp_nodelay)
        set_keepalive(sock)
        self.header = header
        self.callerid = header.get("callerid", "")
        self.latching = reply.latching
        if offer and shmros.accepted(header):
            self._shm = shm.ShmReceiver(sub.max_frame, sub.queue_size)
            # records are one byte longer than the message, and a MAP names a segment
            consumer = _Frames(self._deliver_shm, trailing, sub.queue_size, max(sub.max_frame + 1, 256),
                               sub.stall_timeout)
        else:
            consumer = _Frames(self._deliver, trailing, sub.queue_size, sub.max_frame, sub.stall_timeout)
        with self._lock:  # close() either sees the receiver, or we see that it was closed
            if self.closed:
                sock.close()
                return
            self.receiver = Receiver(sock, consumer, self._ended, name=f"kame-sub{sub.topic}",
                                     chunk_size=sub.buff_size, stall_timeout=sub.stall_timeout,
                                     read_interval=sub.read_interval)
            self.connected = True
            self._connected_at = time.monotonic()
            self.receiver.start()
        for callback in sub.on_connect:
            callback(self)

    def _deliver(self, frames: list[memoryview]) -> None:
        for frame in frames:
            self.bytes_received += len(frame) + 4
        self.subscription.deliver(frames, self.header, self)

    def _deliver_shm(self, frames: list[memoryview]) -> None:
        receiver, sock = self._shm, self.sock
        assert receiver is not None and sock is not None
        dropped = receiver.deliver(frames, self._deliver, sock)
        if dropped:
            self.messages_received += dropped
            self.dropped += dropped

    def _ended(self, exc: BaseException | None) -> None:
        self.connected = False
        if self._shm is not None:
            self._shm.close()
        if self._shm is not None and isinstance(exc, _shm_unavailable()):
            log.warning("%s on %s; connecting again without shared memory", exc, self.subscription.topic)
            self.subscription.no_shm.add(self.publisher_uri)
            exc = OSError(str(exc))
        if exc is not None and not isinstance(exc, OSError):
            # The publisher sent something that is not TCPROS, or our consumer failed on what it
            # sent: one error, and no retry (it would send the same again). Never silent: a link
            # that ends without a word is a subscription that stops for no visible reason.
            detail = str(exc) if isinstance(exc, tcpros.TcprosError) else f"{type(exc).__name__}: {exc}"
            log.error("dropping the connection to %s on %s: %s", self.callerid, self.subscription.topic, detail)
            if self.sock is not None:
                self.sock.close()  # the peer learns it was dropped; nothing more is read
            return
        if exc is not None:
            log.warning("connection to %s on %s broke: %s", self.callerid or self.publisher_uri,
                        self.subscription.topic, exc)
        if self.closed or self.subscription.node.is_shutdown:
            return
        # The publisher went away; while the master still lists it, try again.
        lived = time.monotonic() - self._connected_at
        self.reconnect_delay, news = self.drops.delay(lived, 0.0)
        if news:
            log.warning("%s dropped the connection on %s %.1f s after it was made, %d times in a row: connecting "
                        "again in %g s", self.callerid or self.publisher_uri, self.subscription.topic, lived,
                        self.drops.young_deaths, self.reconnect_delay)
        self.subscription.reconnect(self)

    def close(self) -> None:
        with self._lock:
            self.closed = True
            receiver, sock = self.receiver, self.sock
        self._closing.set()
        if receiver is not None:
            receiver.close()
        if self._shm is not None:
            self._shm.close()
        if sock is not None:
            try:
                shut_down(sock)  # wakes a handshake read in progress
                sock.close()
            except OSError:
                pass


class _Refused(Exception):
    pass


def _shm_unavailable() -> type[Exception]:
    from kame.net import shm

    return shm.ShmUnavailable


class _Frames:
    """A Receiver consumer: TCPROS frames out of the stream, handed on in batches.

    With a queue_size N, a read asks the kernel for no more than N of the smallest frames seen
    (4 KiB at least): a read then never holds more than N frames, so what the subscription
    keeps of it (its newest N) is all of it, and a subscriber that falls behind leaves the rest
    in the socket's buffers, where TCP's flow control holds the publisher back until its own
    queue of queue_size drops the oldest (bench/RESULTS.md: kame's queue_size). A read sized by
    the mean frame dropped frames whenever the mean sat above the real size (1 % at full rate).
    Only a queue_size small enough for the 4 KiB floor to hold more (N = 1, say) keeps the newest
    N of each read and drops the others on the subscriber's side, as rospy does.

    A frame still incomplete after a second read must be whole within `stall_timeout` plus its
    size at MIN_FRAME_RATE from then, else the stream ends with Stalled: a frame dripped a byte
    at a time resets the stall timeout with every byte, and held its buffer (and the connection)
    for ever. The hot path pays one attribute read a read; a small frame split between two
    reads, two attribute writes; the clock is read only for a frame that spans three reads.
    """

    def __init__(self, deliver: Callable[[list[memoryview]], None], trailing: bytes, queue_size: int | None,
                 max_frame: int = MAX_FRAME, stall_timeout: float = STALL_TIMEOUT) -> None:
        self._reader = tcpros.FrameReader(max_frame, reuse=True)  # deliver copies what it keeps
        self._stall_timeout = stall_timeout
        self._partial = 0  # the reader's `partial` last seen
        self._deadline = 0.0  # monotonic seconds by which that frame must be whole; 0: not set yet
        self._started = 0.0
        self._deliver = deliver
        self._trailing = trailing
        self._queue_size = queue_size or 0
        # the smallest frame seen; 0 without a queue_size (reads are then buff_size, never resized)
        self._smallest = MAX_FRAME + 1 if queue_size else 0
        self._queue_bytes = _MIN_READ if queue_size else 1 << 62  # what a read may ask for
        self._fits = 1 << 62  # frames of the smallest size a read of _queue_bytes holds, plus a split one

    def get_buffer(self, sizehint: int) -> memoryview:
        if self._trailing:  # bytes that came with the publisher's header: a latched message, or
            # the start of a stream that was already flowing (up to 64 KiB): queue_size at a time
            frames = self._reader.feed(self._trailing)
            self._trailing = b""
            if frames and self._queue_size:
                self._resize(frames)
            step = self._queue_size or len(frames) or 1
            for start in range(0, len(frames), step):
                self._deliver(frames[start:start + step])
        return self._reader.get_buffer(min(sizehint, self._queue_bytes))

    @property
    def mid_frame(self) -> bool:
        return self._reader.pending > 0

    def buffer_updated(self, nbytes: int) -> None:
        reader = self._reader
        frames = reader.buffer_updated(nbytes)
        partial = reader.partial
        if partial:
            if partial != self._partial:  # begun in this read
                self._partial, self._deadline = partial, 0.0
            else:
                self._frame_deadline()
        if frames:
            # checks of the last frame and the count only: a smaller frame earlier in the read
            # shows as more frames than the read could hold
            if len(frames[-1]) < self._smallest or len(frames) > self._fits:
                self._resize(frames)
            self._deliver(frames)

    def _frame_deadline(self) -> None:
        """For a frame still incomplete after another read: set its deadline, or end the stream
        once the deadline has passed."""
        size = self._reader.frame_size
        now = time.monotonic()
        if not self._deadline:
            self._started = now
            self._deadline = now + self._stall_timeout + size / MIN_FRAME_RATE
        elif now > self._deadline:
            came = self._reader.pending - 4
            raise Stalled(f"a frame of {size} bytes is not whole {now - self._started:.1f} s into it ({came} bytes "
                          f"came); a frame must arrive at {MIN_FRAME_RATE >> 10} KiB/s at least")

    def release(self) -> None:
        self._reader.release()

    def _resize(self, frames: list[memoryview]) -> None:
        smallest = min(len(frame) for frame in frames)
        if smallest < self._smallest:
            self._smallest = smallest
            self._queue_bytes = max(_MIN_READ, self._queue_size * (smallest + 4))
            self._fits = self._queue_bytes // (smallest + 4) + 1


_MIN_READ = 4096
