"""/tf and /tf_static on a kame Node, for kame's own programs (tf_echo, the static publisher,
the demo nodes): a listener feeding a Buffer, and the two broadcasters. rospy programs get the
same through the tf2_ros facade, which builds on rospy's Publisher and Subscriber instead.

One static broadcaster per node: /tf_static is latched and a latch holds one message, so every
static transform the node sends is merged into that one message (a newer transform for the
same child frame replaces the older)."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable
from typing import Any

from kame.node.node import Node
from kame.node.topics import serialize_frame
from kame.tf_ros.buffer import Buffer

TF_TOPIC = "/tf"
TF_STATIC_TOPIC = "/tf_static"


def _tf_message() -> type[Any]:
    from tf2_msgs.msg import TFMessage
    return TFMessage  # type: ignore[no-any-return]


class TransformListener:
    """Subscribes `node` to /tf and /tf_static and feeds `buffer`; `now` is the node's ROS time
    in ns (a jump back clears the buffer)."""

    def __init__(self, node: Node, buffer: Buffer, now: Callable[[], int] | None = None,
                 on_message: Callable[[Any, str, bool], None] | None = None) -> None:
        """`on_message(msg, authority, is_static)` sees each TFMessage too (tf_monitor's statistics)."""
        self.node = node
        self.buffer = buffer
        self._now = now
        self._on_message = on_message
        message = _tf_message()
        self._message = message
        for topic, is_static in ((TF_TOPIC, False), (TF_STATIC_TOPIC, True)):
            node.subscribe(node.resolve(topic), message._type, message._md5sum, message._full_text,
                           self._deliverer(is_static), queue_size=None, tcp_nodelay=True)

    def _deliverer(self, is_static: bool) -> Callable[[list[memoryview], dict[str, str]], None]:
        def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
            authority = header.get("callerid", "default_authority")
            for frame in frames:
                try:
                    msg = self._message._from_buffer(frame)
                except Exception as exc:  # a bad frame is skipped; the connection stays
                    self.buffer.warn(f"cannot deserialize a tf2_msgs/TFMessage from {authority}: {exc}")
                    continue
                if self._now is None:
                    self.buffer.receive(msg.transforms, authority, is_static)
                else:
                    self.buffer.receive_at(msg.transforms, authority, is_static, self._now)
                if self._on_message is not None:
                    self._on_message(msg, authority, is_static)
        return deliver

    def unregister(self) -> None:
        for topic in (TF_TOPIC, TF_STATIC_TOPIC):
            self.node.unsubscribe(self.node.resolve(topic))


class TransformBroadcaster:
    def __init__(self, node: Node, queue_size: int = 100) -> None:
        message = _tf_message()
        self._message = message
        self._publication = node.advertise(node.resolve(TF_TOPIC), message._type, message._md5sum,
                                           message._full_text, queue_size=queue_size)

    def send_transform(self, transforms: Any) -> None:
        """Publish one TransformStamped or a list of them."""
        items = list(transforms) if isinstance(transforms, (list, tuple)) else [transforms]
        self._publication.publish_frame(serialize_frame(self._message(transforms=items)))


class StaticTransformBroadcaster:
    def __init__(self, node: Node) -> None:
        message = _tf_message()
        self._message = message
        self._lock = threading.Lock()
        self._by_child: dict[str, Any] = {}
        self._publication = node.advertise(node.resolve(TF_STATIC_TOPIC), message._type, message._md5sum,
                                           message._full_text, latch=True, queue_size=100)

    def send_transform(self, transforms: Any) -> None:
        items: Iterable[Any] = transforms if isinstance(transforms, (list, tuple)) else [transforms]
        with self._lock:
            for transform in items:
                self._by_child[transform.child_frame_id] = transform
            frame = serialize_frame(self._message(transforms=list(self._by_child.values())))
            self._publication.publish_frame(frame)
