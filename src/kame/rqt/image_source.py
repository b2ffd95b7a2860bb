"""rqt_image_view's feed: the image topics (sensor_msgs/Image and CompressedImage), and the one
being shown, whose newest message's bytes are kept until the window takes them. As rqt_console's
feed, the subscriber wakes the window (`on_ready`) only when nothing was waiting, so a fast
camera costs one redraw per window turn, not one per frame."""

from __future__ import annotations

import threading
from collections.abc import Callable

from kame.node.node import Node

IMAGE = "sensor_msgs/Image"
COMPRESSED = "sensor_msgs/CompressedImage"


class ImageSource:
    def __init__(self, node: Node, on_ready: Callable[[], None]) -> None:
        self.node = node
        self.on_ready = on_ready
        self.topic = ""
        self.type_name = ""
        self._newest: bytes | None = None
        self._lock = threading.Lock()

    def image_topics(self) -> list[tuple[str, str]]:
        topics = self.node.master.call("getTopicTypes")
        return sorted((str(t), str(ty)) for t, ty in topics if ty in (IMAGE, COMPRESSED))

    def show(self, topic: str, type_name: str) -> None:
        from sensor_msgs.msg import CompressedImage, Image

        self.stop()
        cls = Image if type_name == IMAGE else CompressedImage
        self.topic, self.type_name = topic, cls._type
        self.node.subscribe(topic, cls._type, cls._md5sum, cls._full_text, self._deliver)

    def _deliver(self, frames: list[memoryview], header: dict[str, str]) -> None:
        if not frames:
            return
        with self._lock:
            was_empty = self._newest is None
            self._newest = bytes(frames[-1])
        if was_empty:
            self.on_ready()

    def take(self) -> bytes | None:
        with self._lock:
            data, self._newest = self._newest, None
        return data

    def stop(self) -> None:
        if self.topic:
            self.node.unsubscribe(self.topic)
            self.topic = self.type_name = ""
        with self._lock:
            self._newest = None
