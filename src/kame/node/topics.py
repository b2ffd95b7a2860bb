"""Topics over TCPROS: a node's publications and subscriptions and their connections.

Publishing serializes a message once, frames it, and hands the same bytes to every
subscriber connection's Sender (kame.net.stream): no thread hop while sockets take the
bytes, a queue_size-bounded backlog per connection that drops its oldest frames, so a slow
subscriber never slows the publisher or the other subscribers.

Subscribing connects to each publisher the master names (requestTopic, then a TCPROS
handshake), reads frames on one thread per publisher and runs the callbacks there, in
order, one subscription's callbacks never concurrently. When a publisher goes away but is
still registered, the link is retried with a growing delay, waiting on an event that
closing the link (and so the node's shutdown) sets: no retry outlives its subscription.

What a publisher can make a subscriber hold is bounded: a frame longer than the message type
can be (its size, for a type without variable-length fields; else `max_frame`, 1 GiB by
default) and a frame that stops arriving half-way (no byte for STALL_TIMEOUT) both drop the
connection with one error line, without a retry (the peer would do the same again).
"""

from __future__ import annotations

import io
import itertools
import logging
import struct
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from kame.msg.size import fixed_size
from kame.net.address import DOES_NOT_RESOLVE, unreachable_reason
from kame.net.handshake import HandshakeError, read_header_and_rest, write_header
from kame.net.stream import Receiver, Sender, connect, peer_of, set_keepalive, set_nodelay, shut_down
from kame.net.xmlrpc_client import XmlRpcProxy
from kame.node.master_proxy import unwrap
from kame.node.unreachable import unreachable_message
from kame.protocol import shmros, tcpros

if TYPE_CHECKING:
    import socket
    from collections.abc import Sequence

    # imported where used: with ctypes and mmap, nearly a megabyte a node without a
    # shared-memory connection never needs
    from kame.net import shm
    from kame.net.stream import Buffer, Flusher
    from kame.node.master_proxy import MasterProxy
    from kame.node.unreachable import ReportedOnce

log = logging.getLogger("kame.topics")

SMALL_FRAME = 64 * 1024
MAX_FRAME = 1 << 30
READ_SIZE = 256 * 1024  # bytes a subscriber's read asks for when it names no buff_size
#: Bytes a publisher without a queue_size keeps for one subscriber that does not keep up.
UNQUEUED_BACKLOG = 256 << 20
#: Seconds a publisher may leave a frame half-sent before the connection is dropped.
STALL_TIMEOUT = 30.0


_pack_frame_length = struct.Struct("<I").pack


class TopicsNode(Protocol):
    """What publications, subscriptions and their links ask of their node: kame.node.node's
    Node, which makes them (typed here so that this module does not import it back)."""

    name: str
    uri: str
    is_shutdown: bool
    master: MasterProxy
    flusher: Flusher
    unreachable_reported: ReportedOnce
    publications: dict[str, Publication]

    def next_connection_id(self) -> int: ...

    def spawn(self, target: Callable[[], None], name: str) -> threading.Thread: ...

    def publisher_link(self, subscription: Subscription, uri: str) -> IncomingLink:
        """A new link of `subscription` to the publisher at `uri`: kame.node.local's to a
        publication of this node, else a PublisherLink."""
        ...


class FrameSender(Protocol):
    """Where a publication's frames go for one subscriber: a socket (kame.net.stream's Sender),
    shared memory (kame.net.shm's ShmSender) or this node (kame.node.local's LocalSender)."""

    bytes_sent: int
    frames_sent: int
    dropped: int  # frames its queue of queue_size dropped (the oldest) for a subscriber behind

    def send(self, frame: Buffer) -> None: ...

    def send_parts(self, parts: Sequence[Buffer], borrowed: bool = False) -> None: ...

    def close(self) -> None: ...


class LocalDelivery(FrameSender, Protocol):
    """A subscriber in this node (kame.node.local's LocalSender): published objects go to it as
    they are, when it takes their class."""

    def takes(self, msg: Any) -> bool: ...

    def send_message(self, msg: Any) -> None: ...


class IncomingLink(Protocol):
    """A subscription's link to one publisher: a PublisherLink (TCPROS or shared memory) or
    kame.node.local's LocalPublisherLink (a publication of this node)."""

    publisher_uri: str
    connection_id: int
    transport: str
    callerid: str
    header: dict[str, str]
    bytes_received: int
    messages_received: int
    dropped: int  # received, then dropped by the subscription's queue_size (its oldest)
    connected: bool
    ended: bool  # the publication is gone for good: a new one needs a new link
    latching: bool
    latched: bytes | None  # a latching publisher's last message, as bytes

    def run(self) -> None: ...

    def close(self) -> None: ...

    def latched_payload(self) -> bytes | None: ...


class ObjectLatch(Protocol):
    """A link that brings published objects (kame.node.local's): a latching publisher's last one."""

    latching: bool
    latched_object: Any
    messages_received: int


class _Chunks(list[Any]):
    """A write-only buffer for generated serializers: keeps the pieces, copies nothing."""

    write = list.append


def serialize_frame(msg: Any) -> list[Any]:
    """A message as TCPROS frame buffers: [length prefix + small data] or [prefix, *pieces]."""
    chunks = _Chunks()
    msg.serialize(chunks)
    if len(chunks) == 1:  # a message written in one piece (fixed-size ones, most small ones)
        size = len(chunks[0])
        if size <= SMALL_FRAME:
            return [_pack_frame_length(size) + chunks[0]]
    size = 0
    for chunk in chunks:
        size += len(chunk)
    prefix = tcpros.encode_frame_prefix(size)
    if size <= SMALL_FRAME:  # many small pieces: one joined buffer is cheaper than a long sendmsg
        chunks.insert(0, prefix)
        return [b"".join(chunks)]
    return [prefix, *chunks]


def serialize_payload(msg: Any) -> bytes:
    buff = io.BytesIO()
    msg.serialize(buff)
    return buff.getvalue()


class SubscriberLink:
    """One subscriber connected to one of our publications: over TCPROS (`Sender`), shared
    memory (`ShmSender`) or in this node (kame.node.local's `LocalSender`, no socket)."""

    __slots__ = ("callerid", "connection_id", "local", "peer", "sender", "sock", "transport")

    def __init__(self, connection_id: int, callerid: str, sender: FrameSender, peer: str,
                 sock: socket.socket | None = None, transport: str = "TCPROS") -> None:
        self.connection_id = connection_id
        self.callerid = callerid
        self.sender = sender
        self.peer = peer
        self.sock = sock
        self.transport = transport
        self.local: LocalDelivery | None = None  # a subscriber in this node: objects go here

    def close(self, shut: bool = False) -> None:
        self.sender.close()
        if self.sock is not None:
            try:
                if shut:
                    shut_down(self.sock)
                self.sock.close()
            except OSError:
                pass


class Publication:
    def __init__(self, node: TopicsNode, topic: str, type: str, md5sum: str, definition: str, latch: bool,
                 queue_size: int, extra_headers: dict[str, str] | None = None, tcp_nodelay: bool = False) -> None:
        self.node = node
        self.topic = topic
        self.type = type
        self.md5sum = md5sum
        self.definition = definition
        self.latch = latch
        self.queue_size = queue_size
        self.extra_headers = extra_headers or {}
        # TCP_NODELAY for subscribers whose header does not ask either way (rospy's Publisher option)
        self.tcp_nodelay = tcp_nodelay
        self.links: list[SubscriberLink] = []
        self.latched: list[Any] | None = None
        self.latched_object: Any = None  # the latched message as published, for subscribers in this node
        self.local_links = 0  # how many of links are subscribers in this node
        # next() of a count is one call that the interpreter does not interrupt: publishers on
        # several threads still number 1, 2, 3, ... without a lock's 100 ns on every publish
        self._seqs = itertools.count(1)
        self.on_connect: list[Callable[[SubscriberLink], None]] = []
        self.on_disconnect: list[Callable[[SubscriberLink], None]] = []
        self.closed = False
        self._lock = threading.Lock()

    def next_seq(self) -> int:
        """The header.seq of the next message with a header published here (1 first, as rospy)."""
        return next(self._seqs)

    def publish_frame(self, frame: list[Any], borrowed: bool = False) -> None:
        """Send one framed message (from serialize_frame or tcpros.frame_parts) to every
        subscriber. `borrowed`: the buffers are reused once this returns, so what has to wait
        for a slow socket, or be latched, is copied; the rest goes out without a copy."""
        if self.latch:
            self.latched = [b"".join(frame)] if borrowed else frame
            self.latched_object = None
        for link in self.links:
            if len(frame) == 1 and not borrowed:
                link.sender.send(frame[0])
            else:
                link.sender.send_parts(frame, borrowed)

    def publish_message(self, msg: Any) -> None:
        """Send a message object: as that object to subscribers in this node that take it
        (kame.node.local), serialized once for the others and for latching. A message that
        cannot be serialized raises before anyone gets it, when anyone needs its bytes."""
        if not self.local_links:  # the usual case: no subscriber in this node
            parts = serialize_frame(msg)
            if self.latch:
                self.latched = parts
                self.latched_object = msg
            if len(parts) == 1:
                data = parts[0]
                for link in self.links:
                    link.sender.send(data)
            else:
                for link in self.links:
                    link.sender.send_parts(parts)
            return
        links = self.links
        frame: list[Any] | None = None
        if self.latch or any(link.local is None or not link.local.takes(msg) for link in links):
            frame = serialize_frame(msg)
        if self.latch:
            self.latched = frame
            self.latched_object = msg
        for link in links:
            local = link.local
            if local is not None and local.takes(msg):
                local.send_message(msg)
            elif frame is not None:
                if len(frame) == 1:
                    link.sender.send(frame[0])
                else:
                    link.sender.send_parts(frame)

    def publish_payload(self, payload: bytes | memoryview, borrowed: bool = False) -> None:
        """Send a message serialized elsewhere (a bag's bytes, a relayed frame) as it is: framed
        by tcpros.frame_parts and written with the payload's own buffer (no copy)."""
        self.publish_frame(tcpros.frame_parts(payload), borrowed)

    @property
    def spec(self) -> tcpros.TopicSpec:
        return tcpros.TopicSpec(self.type, self.md5sum, self.definition, self.latch)

    def attach(self, sock: socket.socket, accepted: tcpros.SubscriberAccepted, use_shm: bool = False) -> None:
        """Finish the handshake of a subscriber our TCPROS server accepted for this topic;
        `use_shm`: it offered shared memory and may have it (kame.protocol.shmros)."""
        shm_reply = {shmros.HEADER_FIELD: shmros.ACCEPTED} if use_shm else {}
        write_header(sock, {**accepted.reply, **self.extra_headers, **shm_reply})
        set_nodelay(sock, self.tcp_nodelay if accepted.tcp_nodelay is None else accepted.tcp_nodelay)
        set_keepalive(sock)
        peer = peer_of(sock)
        link_box: list[SubscriberLink] = []

        def broken(exc: BaseException | None) -> None:
            if link_box:
                self.drop_link(link_box[0])

        kind: type[Sender | shm.ShmSender] = Sender
        if use_shm:
            from kame.net import shm

            kind = shm.ShmSender
        if self.queue_size:
            sender = kind(sock, self.node.flusher, self.queue_size, broken)
        else:  # no queue_size: any number of frames, within UNQUEUED_BACKLOG bytes
            sender = kind(sock, self.node.flusher, 1 << 62, broken, max_bytes=UNQUEUED_BACKLOG)
        link = SubscriberLink(self.node.next_connection_id(), accepted.callerid, sender, peer, sock)
        link_box.append(link)
        self.add_link(link)

    def add_link(self, link: SubscriberLink, latched_message: Callable[[Any], None] | None = None) -> bool:
        """Start sending to a connected subscriber, the latched message first; False (and the
        link closed) when the publication has closed meanwhile. `latched_message` takes the
        latched message as an object when there is one (a subscriber in this node)."""
        with self._lock:
            if self.closed:
                link.close()
                return False
            self.links = [*self.links, link]
            self.local_links += link.local is not None
            latched, latched_object = self.latched, self.latched_object
        if latched_message is not None and latched_object is not None:
            latched_message(latched_object)
        elif latched is not None:
            if len(latched) == 1:
                link.sender.send(latched[0])
            else:
                link.sender.send_parts(latched)
        for callback in self.on_connect:
            callback(link)
        return True

    def add_connect_callback(self, callback: Callable[[SubscriberLink], None]) -> None:
        """Called with each subscriber that connects from now on. The lists are replaced, never
        changed in place: a connection running the callbacks meanwhile sees the old list whole."""
        with self._lock:
            self.on_connect = [*self.on_connect, callback]

    def remove_connect_callback(self, callback: Callable[[SubscriberLink], None]) -> None:
        with self._lock:
            self.on_connect = [c for c in self.on_connect if c is not callback]

    def drop_link(self, link: SubscriberLink) -> None:
        """End the connection of one subscriber (it went away, or it was in this node and unsubscribed)."""
        with self._lock:
            if link not in self.links:
                return
            self.links = [other for other in self.links if other is not link]
            self.local_links -= link.local is not None
        link.close()
        for callback in self.on_disconnect:
            callback(link)

    def close(self) -> None:
        with self._lock:
            self.closed = True
            links, self.links = self.links, []
            self.local_links = 0
        for link in links:
            link.close(shut=True)

    @property
    def bytes_sent(self) -> int:
        return sum(link.sender.bytes_sent for link in self.links)


Callback = Callable[[list[memoryview], dict[str, str]], None]
MessagesCallback = Callable[[list[Any], dict[str, str]], None]


class PublisherLink:
    """Our connection to one publisher of a subscribed topic (plain TCPROS, or with shared memory)."""

    transport = "TCPROS"

    def __init__(self, subscription: Subscription, publisher_uri: str, connection_id: int,
                 reconnecting: bool = False) -> None:
        self.subscription = subscription
        self.publisher_uri = publisher_uri
        self.connection_id = connection_id
        # a publisher we were connected to and lost is no news: only a first connection's
        # failures say that the publisher's advertised address is unusable from here
        self._may_report = not reconnecting
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

    def latched_payload(self) -> bytes | None:
        return self.latched

    def run(self) -> None:
        """Connect, retrying while the publisher stays registered (runs on its own thread)."""
        delay = 0.1
        failures = 0
        while not self.closed and not self.subscription.node.is_shutdown:
            try:
                self._connect()
                return
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
            delay = min(delay * 2, 2.0)

    def _report_unreachable(self, exc: BaseException, failures: int) -> None:
        """One warning per publisher when its advertised address fails us: at once when its name
        does not resolve, else from the third failure on (a publisher that just exited also
        refuses, and the master's update then drops it)."""
        reason = unreachable_reason(exc)
        if not self._may_report or reason is None:
            return
        if failures < 3 and reason != DOES_NOT_RESOLVE:
            return
        self._may_report = False
        node = self.subscription.node
        if node.unreachable_reported.first(self.publisher_uri):
            log.warning(unreachable_message(self._publisher_name(), self.subscription.topic, self._target, reason))

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
            consumer = _Frames(self._deliver_shm, trailing, sub.queue_size, max(sub.max_frame + 1, 256))
        else:
            consumer = _Frames(self._deliver, trailing, sub.queue_size, sub.max_frame)
        with self._lock:  # close() either sees the receiver, or we see that it was closed
            if self.closed:
                sock.close()
                return
            self.receiver = Receiver(sock, consumer, self._ended, name=f"kame-sub{sub.topic}",
                                     chunk_size=sub.buff_size, stall_timeout=sub.stall_timeout,
                                     read_interval=sub.read_interval)
            self.connected = True
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
    """

    def __init__(self, deliver: Callable[[list[memoryview]], None], trailing: bytes, queue_size: int | None,
                 max_frame: int = MAX_FRAME) -> None:
        self._reader = tcpros.FrameReader(max_frame, reuse=True)  # deliver copies what it keeps
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
        frames = self._reader.buffer_updated(nbytes)
        if frames:
            # checks of the last frame and the count only: a smaller frame earlier in the read
            # shows as more frames than the read could hold
            if len(frames[-1]) < self._smallest or len(frames) > self._fits:
                self._resize(frames)
            self._deliver(frames)

    def _resize(self, frames: list[memoryview]) -> None:
        smallest = min(len(frame) for frame in frames)
        if smallest < self._smallest:
            self._smallest = smallest
            self._queue_bytes = max(_MIN_READ, self._queue_size * (smallest + 4))
            self._fits = self._queue_bytes // (smallest + 4) + 1


_MIN_READ = 4096


class Subscription:
    """One subscribed topic: its publisher links and the callback they deliver to.

    `tcp_nodelay` goes to each publisher in our connection header (`tcp_nodelay=1`), asking
    it to send without Nagle's delay, and is set on our side of the socket too. `buff_size`
    is how many bytes each read asks of the kernel, as rospy's (the default is kame's own);
    with a queue_size, a read asks for no more than queue_size of the smallest messages seen
    (4 KiB at least; see _Frames). A
    message larger than `buff_size` still arrives whole: once its length is known, the rest
    is read straight into its own buffer. `read_interval` (seconds, 0: none) is a pause after
    each read (stream.Receiver), for a subscriber that batches anyway: many small messages
    then cost one wake-up of the receiving thread instead of one each.
    """

    def __init__(self, node: TopicsNode, topic: str, type: str, md5sum: str, definition: str, queue_size: int | None,
                 tcp_nodelay: bool, deliver_frames: Callback, buff_size: int | None = None,
                 max_frame: int | None = None, message_class: type[Any] | None = None,
                 deliver_messages: MessagesCallback | None = None, shared_memory: bool = True,
                 read_interval: float = 0.0) -> None:
        self.node = node
        self.read_interval = read_interval
        # a publisher in this node hands messages of `message_class` to `deliver_messages` as
        # they were published (kame.node.local); without it, they come as bytes
        self.message_class = message_class
        self.deliver_messages = deliver_messages
        self.shared_memory = shared_memory  # offer shared memory to kame publishers on this host (kame.protocol.shmros)
        self.no_shm: set[str] = set()  # publishers whose segments we could not map
        # None: worked out at the first connection; parsing the definition in subscribe() nearly
        # doubled the time 100 subscriptions took to register (17 -> 31 ms)
        self._max_frame = max_frame
        self.stall_timeout = STALL_TIMEOUT
        self.topic = topic
        self.type = type
        self.md5sum = md5sum
        self.definition = definition
        self.queue_size = queue_size
        self.tcp_nodelay = tcp_nodelay
        self.buff_size = buff_size or READ_SIZE
        self.deliver_frames = deliver_frames
        self.links: dict[str, IncomingLink] = {}
        # called with each publisher link once its handshake is done (replaced, never changed in place)
        self.on_connect: list[Callable[[IncomingLink], None]] = []
        self.closed = False
        self._lock = threading.Lock()
        self.callback_lock = threading.Lock()
        # publisher lists are applied in the master's order: a publisherUpdate that arrives while
        # registerSubscriber is on its way is newer than that call's answer (the master notifies
        # only subscribers it has registered), so the answer must not undo it
        self._lists_lock = threading.Lock()
        self.updates = 0  # publisherUpdates applied

    @property
    def max_frame(self) -> int:
        """The largest frame a publisher may send: the type's size when it has no variable-length
        fields, else MAX_FRAME (or what subscribe() was given)."""
        if self._max_frame is None:
            exact = fixed_size(self.type, self.definition) if "*" not in (self.type, self.md5sum) else None
            self._max_frame = MAX_FRAME if exact is None else exact
        return self._max_frame

    def publisher_update(self, uris: list[str]) -> None:
        """A publisherUpdate's list: the master's newest."""
        with self._lists_lock:
            self.updates += 1
            self.set_publishers(uris)

    def registered(self, uris: list[str], updates_before: int) -> None:
        """registerSubscriber's answer, asked when `updates` was `updates_before`: applied unless a
        newer publisherUpdate came meanwhile (a publisher registering just then would otherwise
        be dropped again, and its latched message never heard)."""
        with self._lists_lock:
            if self.updates == updates_before:
                self.set_publishers(uris)

    def add_connect_callback(self, callback: Callable[[IncomingLink], None]) -> None:
        with self._lock:
            self.on_connect = [*self.on_connect, callback]

    def remove_connect_callback(self, callback: Callable[[IncomingLink], None]) -> None:
        with self._lock:
            self.on_connect = [c for c in self.on_connect if c is not callback]

    def deliver(self, frames: list[memoryview], header: dict[str, str], link: IncomingLink) -> None:
        link.messages_received += len(frames)
        if self.queue_size and len(frames) > self.queue_size:
            link.dropped += len(frames) - self.queue_size
            frames = frames[-self.queue_size:]  # a slow callback keeps the newest, as queue_size promises
        with self.callback_lock:
            if link.latching:
                link.latched = bytes(frames[-1])
            if not self.closed:
                self.deliver_frames(frames, header)

    def deliver_objects(self, msgs: list[Any], header: dict[str, str], link: ObjectLatch) -> None:
        """Messages from a publication of this node, as published (kame.node.local)."""
        deliver = self.deliver_messages
        assert deliver is not None
        link.messages_received += len(msgs)
        with self.callback_lock:
            if link.latching:
                link.latched_object = msgs[-1]
            if not self.closed:
                deliver(msgs, header)

    def latched_messages(self) -> list[tuple[bytes, dict[str, str]]]:
        """The last message of each connected latching publisher, with its connection header.
        Hold callback_lock while using them, so none is also delivered as new meanwhile."""
        with self._lock:
            links = list(self.links.values())
        latched = [(link.latched_payload(), link.header) for link in links if link.connected]
        return [(payload, header) for payload, header in latched if payload is not None]

    def set_publishers(self, uris: list[str]) -> None:
        """The master's complete list of publishers: connect to new ones, drop the gone."""
        wanted = set(uris)
        with self._lock:
            if self.closed:
                return
            gone = [link for uri, link in self.links.items() if uri not in wanted]
            for link in gone:
                del self.links[link.publisher_uri]
            new: list[IncomingLink] = []
            for uri in uris:
                old = self.links.get(uri)
                if old is None or old.ended:
                    fresh = self.node.publisher_link(self, uri)
                    self.links[uri] = fresh
                    new.append(fresh)
        for link in gone:
            link.close()
        for link in new:
            self.node.spawn(link.run, f"kame-connect{self.topic}")

    def reconnect(self, old: IncomingLink) -> None:
        with self._lock:
            if self.closed or self.links.get(old.publisher_uri) is not old:
                return
            link = PublisherLink(self, old.publisher_uri, self.node.next_connection_id(), reconnecting=True)
            self.links[old.publisher_uri] = link
        self.node.spawn(link.run, f"kame-reconnect{self.topic}")

    def close(self) -> None:
        with self._lock:
            self.closed = True
            links, self.links = list(self.links.values()), {}
        for link in links:
            link.close()

    @property
    def connection_count(self) -> int:
        return sum(1 for link in self.links.values() if link.connected)
