"""image_transport's subscribers for kame's camera programs: an image topic in the transport
asked for (raw or compressed), a camera (image and camera_info paired by stamp), and for
image_view's window the newest picture, decoded on the subscription's thread and taken by the
window, which is woken (`on_ready`) only when nothing was waiting. Also the programs' `image`
topic and transport argument, as image_view's read them."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import numpy as np

from kame.camera.pictures import PictureError, to_bgr
from kame.camera.stamp_pairs import StampPairs
from kame.client import log
from kame.client.core import get_namespace, resolve_name
from kame.client.process import get_param
from kame.client.topics import Subscriber
from kame.image_transport.compressed import CompressionError, decompress
from sensor_msgs.msg import CameraInfo, CompressedImage, Image

TRANSPORTS = ("raw", "compressed")


def subscribe_image(topic: str, transport: str, callback: Callable[[Any], None], queue_size: int = 1) -> Subscriber:
    """image_transport's subscriber: `callback(Image)` from `topic` in `transport`."""
    if transport not in TRANSPORTS:
        raise ValueError(f"Unable to load plugin for transport '{transport}': kame's image_transport has "
                         f"{' and '.join(TRANSPORTS)}")
    if transport == "raw":
        return Subscriber(topic, Image, callback, queue_size=queue_size)

    def decoded(message: Any) -> None:
        try:
            image = decompress(message)
        except CompressionError as exc:
            log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
            return
        callback(image)

    return Subscriber(topic + "/compressed", CompressedImage, decoded, queue_size=queue_size)


class ImageFeed:
    def __init__(self, topic: str, transport: str, on_ready: Callable[[], None]) -> None:
        self.on_ready = on_ready
        self._newest: np.ndarray | None = None
        self._lock = threading.Lock()
        self.subscriber = subscribe_image(topic, transport, self._deliver)

    def _deliver(self, image: Any) -> None:
        try:
            picture = to_bgr(image)
        except PictureError as exc:
            log.emit_throttle(5.0, log.ERROR, "Unable to convert '%s' image for display: '%s'", (image.encoding, exc))
            return
        with self._lock:
            was_empty = self._newest is None
            self._newest = picture
        if was_empty:
            self.on_ready()

    def take(self) -> np.ndarray | None:
        with self._lock:
            picture, self._newest = self._newest, None
        return picture


def image_topic(program: str) -> str:
    """The resolved `image` topic, with image_view's programs' warning when it was not remapped."""
    topic = resolve_name("image")
    if topic == get_namespace().rstrip("/") + "/image":
        log.emit(log.WARN, "Topic 'image' has not been remapped! Typical command-line usage:\n"
                           "\t$ rosrun image_view %s image:=<image topic> [transport]", (program,))
    return topic


def transport_argument(args: list[str]) -> str:
    """The transport named after the program's name (`image_view image:=... compressed`), else
    the ~image_transport parameter, else raw, as image_transport's TransportHints read it."""
    return args[1] if len(args) > 1 else str(get_param("~image_transport", "raw"))


class CameraSubscriber:
    """image_transport's subscribeCamera: `callback(image, info)` for each image of `topic` and the
    camera_info beside it (same namespace) with the same stamp."""

    def __init__(self, topic: str, transport: str, callback: Callable[[Any, Any], None], queue_size: int = 5) -> None:
        self.callback = callback
        self.pairs = StampPairs()
        self.lock = threading.Lock()
        self.image = subscribe_image(topic, transport, self._image, queue_size=queue_size)
        self.info = Subscriber(topic.rsplit("/", 1)[0] + "/camera_info", CameraInfo, self._info, queue_size=queue_size)

    def _image(self, image: Any) -> None:
        with self.lock:
            pair = self.pairs.add_image(image)
        if pair is not None:
            self.callback(*pair)

    def _info(self, info: Any) -> None:
        with self.lock:
            pair = self.pairs.add_info(info)
        if pair is not None:
            self.callback(*pair)

    def unregister(self) -> None:
        self.image.unregister()
        self.info.unregister()
