"""The bridge's topics on the ROS side: a client's subscriptions and publishers, and their pacing.

- A client's subscription to a topic is one kame.client Subscriber (they share the topic's one
  connection per publisher, and a latched message is replayed to each new one, as rospy does);
  the frames a message becomes are made once per message and encoding (`Encodings`), whatever
  the number of clients.
- A client's publisher is one kame.client Publisher (they share the topic's one publication).
- Throttled subscriptions with a queue wait in one `Pacer` thread, owned by the bridge, which
  sends each queued message when its time comes.
"""

from __future__ import annotations

import collections
import io
import itertools
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from kame.client.clock import get_rostime
from kame.client.topics import Subscriber
from kame.msg.message import Message
from kame.rosbridge import conversion, protocol
from kame.rosbridge.pacing import Pacing

Send = Callable[[str | bytes], bool]  # a client's send: False once it is gone


@dataclass(frozen=True)
class SubscribeOptions:
    throttle_rate: float = 0.0
    queue_length: int = 0
    fragment_size: int = 0
    compression: str = "none"


def merge(options: list[SubscribeOptions]) -> SubscribeOptions:
    """Several subscribe ops on one topic as one subscription (rosbridge's rules)."""
    compressions = {o.compression for o in options}
    compression = next((c for c in ("cbor-raw", "cbor", "png") if c in compressions), "none")
    fragments = [o.fragment_size for o in options if o.fragment_size > 0]
    return SubscribeOptions(min(o.throttle_rate for o in options), max(o.queue_length for o in options),
                            min(fragments) if fragments else 0, compression)


class Encodings:
    """The frames one message becomes, each made the first time a client needs it."""

    _ids = itertools.count(1)

    def __init__(self, topic: str, msg: Message, received: float) -> None:
        self.topic = topic
        self.msg = msg
        self.received = received
        self._frames: dict[tuple[str, int], list[str | bytes]] = {}
        self._lock = threading.Lock()

    def frames(self, compression: str, fragment_size: int) -> list[str | bytes]:
        key = (compression, fragment_size if compression in ("none", "png") else 0)
        with self._lock:
            frames = self._frames.get(key)
            if frames is None:
                frames = self._frames[key] = self._make(compression, fragment_size)
            return frames

    def _make(self, compression: str, fragment_size: int) -> list[str | bytes]:
        if compression == "cbor":
            value = conversion.to_cbor_value(self.msg, protocol.cbor_tag)
            return [protocol.encode_cbor({"op": "publish", "topic": self.topic, "msg": value})]
        if compression == "cbor-raw":
            buffer = io.BytesIO()
            self.msg.serialize(buffer)
            secs = int(self.received)
            raw = {"secs": secs, "nsecs": int((self.received - secs) * 1e9), "bytes": buffer.getvalue()}
            return [protocol.encode_cbor({"op": "publish", "topic": self.topic, "msg": raw})]
        text = protocol.encode_json({"op": "publish", "topic": self.topic, "msg": conversion.to_json(self.msg)})
        if compression == "png":
            text = protocol.png_compress(text)
        return list(protocol.fragments(text, fragment_size, f"publish:{self.topic}:{next(self._ids)}"))


class Latest:
    """The Encodings of a topic's newest message: every client's callback for one message gets the
    same object from kame.client, so its frames are made once."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._by_topic: dict[str, Encodings] = {}
        self._holders: collections.Counter[str] = collections.Counter()

    def of(self, topic: str, msg: Message) -> Encodings:
        with self._lock:
            current = self._by_topic.get(topic)
            if current is None or current.msg is not msg:
                current = Encodings(topic, msg, time.time())
                if self._holders[topic]:
                    self._by_topic[topic] = current
            return current

    def hold(self, topic: str) -> None:
        """A subscription of `topic` begins: its newest message is kept while any is left."""
        with self._lock:
            self._holders[topic] += 1

    def release(self, topic: str) -> None:
        with self._lock:
            self._holders[topic] -= 1
            if self._holders[topic] <= 0:
                del self._holders[topic]
                self._by_topic.pop(topic, None)


class ClientSubscription:
    """One client's subscription to one topic: its subscribe ops (by id), pacing and Subscriber."""

    def __init__(self, topic: str, message_class: type[Message], send: Send, latest: Latest, pacer: Pacer) -> None:
        self.topic = topic
        self.message_class = message_class
        self._send = send
        self._latest = latest
        self._pacer = pacer
        self._lock = threading.Lock()
        self.requests: dict[Any, SubscribeOptions] = {}
        self.options = SubscribeOptions()
        self.pacing: Pacing[Encodings] = Pacing()
        latest.hold(topic)
        try:
            self.subscriber = Subscriber(topic, message_class, self._deliver, queue_size=1000)
        except BaseException:
            latest.release(topic)
            raise

    def add(self, op_id: Any, options: SubscribeOptions) -> None:
        with self._lock:
            self.requests[op_id] = options
            self._update()

    def remove(self, op_id: Any) -> bool:
        """Drop one subscribe op (all of them for None); True when none is left."""
        with self._lock:
            if op_id is None:
                self.requests.clear()
            else:
                self.requests.pop(op_id, None)
            if self.requests:
                self._update()
            return not self.requests

    def _update(self) -> None:
        self.options = merge(list(self.requests.values()))
        self.pacing.change(self.options.throttle_rate, self.options.queue_length)

    def _deliver(self, msg: Message) -> None:
        encodings = self._latest.of(self.topic, msg)
        with self._lock:
            ready = self.pacing.offer(encodings, time.monotonic())
            options = self.options
            queued = self.pacing.next_due() is not None
        for item in ready:
            self._emit(item, options)
        if queued:
            self._pacer.wake(self)

    def due(self, now: float) -> float | None:
        """Send what the pacing lets go at `now`; when to come back (None: nothing waits)."""
        with self._lock:
            ready = self.pacing.due(now)
            options = self.options
            when = self.pacing.next_due()
        for item in ready:
            self._emit(item, options)
        return when

    def _emit(self, encodings: Encodings, options: SubscribeOptions) -> None:
        for frame in encodings.frames(options.compression, options.fragment_size):
            self._send(frame)

    def close(self) -> None:
        self._pacer.forget(self)
        self.subscriber.unregister()
        self._latest.release(self.topic)


class Pacer:
    """The thread that sends throttled subscriptions' queued messages when their time comes."""

    def __init__(self) -> None:
        self._waiting: dict[ClientSubscription, float] = {}
        self._changed = threading.Condition()
        self._stopped = False
        self._thread = threading.Thread(target=self._run, name="kame-rosbridge-pacer", daemon=True)
        self._thread.start()

    def wake(self, subscription: ClientSubscription) -> None:
        with self._changed:
            self._waiting.setdefault(subscription, 0.0)
            self._changed.notify()

    def forget(self, subscription: ClientSubscription) -> None:
        with self._changed:
            self._waiting.pop(subscription, None)

    def _run(self) -> None:
        while True:
            with self._changed:
                while not self._stopped:
                    now = time.monotonic()
                    due = [s for s, when in self._waiting.items() if when <= now]
                    if due:
                        break
                    timeout = min(self._waiting.values()) - now if self._waiting else None
                    self._changed.wait(timeout)
                if self._stopped:
                    return
            for subscription in due:
                when = subscription.due(time.monotonic())
                with self._changed:
                    if subscription in self._waiting:
                        if when is None:
                            del self._waiting[subscription]
                        else:
                            self._waiting[subscription] = when

    def close(self) -> None:
        with self._changed:
            self._stopped = True
            self._changed.notify()
        self._thread.join()


def ros_now() -> Any:
    """The time a message's "now" stands for: the node's ROS time."""
    return get_rostime()
