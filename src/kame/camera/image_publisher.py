"""image_transport's publishers, as drivers and image_proc have them: `<base>` (sensor_msgs/Image)
and `<base>/compressed` (its compressed transport, with compressed_image_transport's parameters
and dynamic_reconfigure server), and for a camera `camera_info` beside them. Each transport is
made only while someone subscribes to it, so an output nobody watches costs little."""

from __future__ import annotations

from typing import Any

from kame.client import log
from kame.client.core import resolve_name
from kame.client.topics import Publisher, SubscribeListener
from kame.image_transport.compressed import CompressionError
from kame.image_transport.republish import CompressedOutput
from sensor_msgs.msg import CameraInfo, Image


class ImagePublisher:
    """`listener` hears each subscriber of either transport come and go (image_proc's lazy inputs)."""

    def __init__(self, base_topic: str, listener: SubscribeListener | None = None) -> None:
        base = resolve_name(base_topic)
        self.raw = Publisher(base, Image, subscriber_listener=listener, queue_size=1)
        self.compressed = CompressedOutput(base, listener)

    def wanted(self) -> bool:
        return bool(self.raw.get_num_connections() or self.compressed.publisher.get_num_connections())

    def publish(self, image: Any) -> None:
        if self.raw.get_num_connections():
            self.raw.publish(image)
        if self.compressed.publisher.get_num_connections():
            try:
                self.compressed.publisher.publish(self.compressed.convert(image))
            except CompressionError as exc:
                log.emit_throttle(5.0, log.ERROR, "%s", (exc,))


class CameraPublisher(ImagePublisher):
    def __init__(self, base_topic: str, info_topic: str | None = None, listener: SubscribeListener | None = None
                 ) -> None:
        super().__init__(base_topic, listener)
        info = info_topic if info_topic is not None else self.raw.resolved_name.rsplit("/", 1)[0] + "/camera_info"
        self.info = Publisher(resolve_name(info), CameraInfo, subscriber_listener=listener, queue_size=1)

    def wanted(self) -> bool:
        return super().wanted() or bool(self.info.get_num_connections())

    def publish_camera(self, image: Any, info: Any) -> None:
        self.publish(image)
        if self.info.get_num_connections():
            self.info.publish(info)
