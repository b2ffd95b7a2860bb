"""image_transport's camera publisher, as a driver has it: `<base>` (sensor_msgs/Image),
`<base>/compressed` (its compressed transport, parameters and dynamic_reconfigure server as
compressed_image_transport's) and `camera_info` beside them. Each transport is made only while
someone subscribes to it, so a camera nobody watches costs its capture and little more."""

from __future__ import annotations

from typing import Any

from kame.client import log
from kame.client.core import resolve_name
from kame.client.topics import Publisher
from kame.image_transport.compressed import CompressionError
from kame.image_transport.republish import CompressedOutput
from sensor_msgs.msg import CameraInfo, Image


class CameraPublisher:
    def __init__(self, base_topic: str, info_topic: str | None = None) -> None:
        base = resolve_name(base_topic)
        self.raw = Publisher(base, Image, queue_size=1)
        self.compressed = CompressedOutput(base)
        info = info_topic if info_topic is not None else base.rsplit("/", 1)[0] + "/camera_info"
        self.info = Publisher(resolve_name(info), CameraInfo, queue_size=1)

    def wanted(self) -> bool:
        return bool(self.raw.get_num_connections() or self.compressed.publisher.get_num_connections()
                    or self.info.get_num_connections())

    def publish(self, image: Any, info: Any) -> None:
        if self.raw.get_num_connections():
            self.raw.publish(image)
        if self.compressed.publisher.get_num_connections():
            try:
                self.compressed.publisher.publish(self.compressed.convert(image))
            except CompressionError as exc:
                log.emit_throttle(5.0, log.ERROR, "%s", (exc,))
        if self.info.get_num_connections():
            self.info.publish(info)
