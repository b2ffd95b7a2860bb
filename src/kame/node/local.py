"""Intra-process topics: a node's subscription to its own publication gets the published objects.

Rules:
- When the master lists this node among a topic's publishers, the subscription links to the
  publication directly (roscpp's intra-process links, nodelets' rule): no socket, and a
  message published as an object reaches each callback as that very object, never
  serialized. Subscribers must not modify a message they receive, and a publisher must not
  modify a message after publishing it: every subscriber in the node shares it (and later
  publishes of a changed object would change what a queued delivery sees).
- Messages of another class than the subscription's (an AnyMsg or numpy_msg subscriber) and
  frames published as bytes (a bag's, a relayed message) go as bytes, deserialized on the
  subscriber's side as over TCPROS.
- Each link has a queue of at most queue_size messages (the publisher's, else the
  subscriber's, else LOCAL_UNQUEUED) that drops the oldest, and one thread the node owns
  that runs the callbacks: a slow callback never slows the publisher, as over TCPROS.
- KAME_INTRAPROCESS=0 turns it off (subscriptions then connect to their own node over TCPROS,
  or shared memory).
"""

from __future__ import annotations

import collections
import logging
import os
import threading
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from kame.node.topics import SubscriberLink, serialize_payload
from kame.protocol import tcpros

if TYPE_CHECKING:
    from kame.net.stream import Buffer
    from kame.node.topics import Publication, Subscription

log = logging.getLogger("kame.topics")

LOCAL_UNQUEUED = 1000  # messages a link keeps when neither side gave a queue_size
TRANSPORT = "INTRAPROCESS"  # what getBusInfo says, as roscpp


def enabled() -> bool:
    return os.environ.get("KAME_INTRAPROCESS", "1").strip().lower() not in ("0", "off", "false", "no")


class LocalSender:
    """A publication's sending side to a subscription in the same node (see the rules)."""

    def __init__(self, link: LocalPublisherLink, max_items: int) -> None:
        self._link = link
        self._takes = link.subscription.message_class if link.subscription.deliver_messages is not None else None
        self._items: collections.deque[tuple[bool, Any]] = collections.deque()  # (is an object, message)
        self._max_items = max(1, max_items)
        self._ready = threading.Condition()
        self.closed = False
        self.bytes_sent = 0
        self.frames_sent = 0
        self.dropped = 0

    def start(self) -> None:
        node = self._link.subscription.node
        node.spawn(self._run, f"kame-local{self._link.subscription.topic}")

    def takes(self, msg: Any) -> bool:
        """Whether `msg` goes as the object (else publish it as bytes)."""
        return type(msg) is self._takes

    def send_message(self, msg: Any) -> None:
        self._put((True, msg))

    def send(self, frame: Buffer) -> None:
        self.send_parts((frame,))

    def send_parts(self, parts: Sequence[Buffer], borrowed: bool = False) -> None:
        """A TCPROS frame (length prefix first): its payload is copied (the caller may reuse it)."""
        payload = b"".join(parts)[4:]
        self.bytes_sent += len(payload) + 4
        self._put((False, payload))

    def _put(self, item: tuple[bool, Any]) -> None:
        with self._ready:
            if self.closed:
                return
            self.frames_sent += 1
            self._items.append(item)
            if len(self._items) > self._max_items:
                self._items.popleft()
                self.dropped += 1
            self._ready.notify()

    def _run(self) -> None:
        link = self._link
        while True:
            with self._ready:
                self._ready.wait_for(lambda: self._items or self.closed)
                if self.closed:
                    break
                items, self._items = self._items, collections.deque()
            try:
                link.deliver(items)
            except Exception:
                log.exception("delivering %s in the node failed", link.subscription.topic)
        link.ended_by_publisher()

    def close(self) -> None:
        with self._ready:
            self.closed = True
            self._items.clear()
            self._ready.notify()


class LocalPublisherLink:
    """A subscription's link to a publication of its own node (PublisherLink's shape)."""

    transport = TRANSPORT

    def __init__(self, subscription: Subscription, publisher_uri: str, connection_id: int) -> None:
        self.subscription = subscription
        self.publisher_uri = publisher_uri
        self.connection_id = connection_id
        self.callerid = subscription.node.name
        self.header: dict[str, str] = {}
        self.bytes_received = 0
        self.messages_received = 0
        self.dropped = 0
        self.closed = False
        self.connected = False
        self.ended = False  # the publication closed: a new one needs a new link
        self.latching = False
        self.latched: bytes | None = None
        self.latched_object: Any = None
        self._sender: LocalSender | None = None
        self._publication: tuple[Publication, SubscriberLink] | None = None
        self._lock = threading.Lock()

    def run(self) -> None:
        sub = self.subscription
        node = sub.node
        pub = node.publications.get(sub.topic)
        if pub is None:
            self.ended = True
            return
        asked = tcpros.subscriber_header_fields(callerid=node.name, topic=sub.topic, type=sub.type,
                                                md5sum=sub.md5sum, message_definition=sub.definition)
        accepted = tcpros.accept_subscriber(asked, callerid=node.name, publications={sub.topic: pub.spec})
        if isinstance(accepted, tcpros.Rejected):
            log.error("%s refused our subscription to %s: %s", self.publisher_uri, sub.topic, accepted.error)
            self.ended = True
            return
        self.header = {**accepted.reply, **pub.extra_headers}
        self.latching = pub.latch
        sender = LocalSender(self, pub.queue_size or sub.queue_size or LOCAL_UNQUEUED)
        link = SubscriberLink(node.next_connection_id(), node.name, sender, TRANSPORT.lower(), transport=TRANSPORT)
        link.local = sender
        with self._lock:
            if self.closed:
                return
            self._sender = sender
            self._publication = (pub, link)
        sender.start()
        if not pub.add_link(link, sender.send_message if sender._takes is not None else None):
            return
        # connected once the publication sends to us, not before: a waiter that saw it earlier
        # (actionlib's wait_for_server) could publish into the gap and lose the message
        with self._lock:
            self.connected = not (self.closed or self.ended)
        for callback in sub.on_connect:
            callback(self)

    def deliver(self, items: collections.deque[tuple[bool, Any]]) -> None:
        sub = self.subscription
        if sub.queue_size and len(items) > sub.queue_size:
            excess = len(items) - sub.queue_size
            self.messages_received += excess
            self.dropped += excess
            items = collections.deque(list(items)[-sub.queue_size:])
        objects: list[Any] = []
        frames: list[memoryview] = []
        for is_object, item in items:  # in order: a run of objects, then a run of frames, ...
            if is_object:
                if frames:
                    sub.deliver(frames, self.header, self)
                    frames = []
                objects.append(item)
            else:
                if objects:
                    sub.deliver_objects(objects, self.header, self)
                    objects = []
                self.bytes_received += len(item) + 4
                frames.append(memoryview(item))
        if objects:
            sub.deliver_objects(objects, self.header, self)
        if frames:
            sub.deliver(frames, self.header, self)

    def latched_payload(self) -> bytes | None:
        if self.latched_object is not None:
            return serialize_payload(self.latched_object)
        return self.latched

    def ended_by_publisher(self) -> None:
        self.connected = False
        self.ended = True

    def close(self) -> None:
        with self._lock:
            self.closed = True
            sender, publication = self._sender, self._publication
        if publication is not None:
            pub, link = publication
            pub.drop_link(link)  # the publication forgets us (and closes the sender)
        elif sender is not None:
            sender.close()
