"""Topics over TCPROS: a node's publications and subscriptions and their connections.

Publishing serializes a message once, frames it, and hands the same bytes to every
subscriber connection's Sender (kame.net.stream): no thread hop while sockets take the
bytes, a queue_size-bounded backlog per connection that drops its oldest frames, so a slow
subscriber never slows the publisher or the other subscribers.

Subscribing connects to each publisher the master names through a link of its own
(kame.node.publisher_link), which reads frames on one thread per publisher and runs the
callbacks there, in order, one subscription's callbacks never concurrently.
"""

from __future__ import annotations

import io
import itertools
import struct
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from kame.msg.size import fixed_size
from kame.net.handshake import write_header
from kame.net.stream import Sender, peer_of, set_keepalive, set_nodelay, shut_down
from kame.node.publisher_link import MAX_FRAME, STALL_TIMEOUT, PublisherLink
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

SMALL_FRAME = 64 * 1024
READ_SIZE = 256 * 1024  # bytes a subscriber's read asks for when it names no buff_size
#: Bytes a publisher without a queue_size keeps for one subscriber that does not keep up.
UNQUEUED_BACKLOG = 256 << 20


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

    def add_publisher(self, uri: str) -> None:
        """Connect to the publisher at `uri` too (keeping the others), as rospy's create_transport."""
        with self._lock:
            uris = list(self.links)
        if uri not in uris:
            self.set_publishers([*uris, uri])

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

    def reconnect(self, old: PublisherLink) -> None:
        """A new link to the publisher `old` was connected to, which dropped it (TCPROS links
        only: a link in this node ends with its publication)."""
        with self._lock:
            if self.closed or self.links.get(old.publisher_uri) is not old:
                return
            link = PublisherLink(self, old.publisher_uri, self.node.next_connection_id(), after=old)
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
