"""depthimage_to_laserscan's node: `rosrun depthimage_to_laserscan depthimage_to_laserscan
image:=/camera/depth/image_raw`, as the TurtleBot's Gazebo launch runs it.

Subscribes `image` (sensor_msgs/Image, 32FC1 or 16UC1) and its CameraInfo beside it
(`<image's namespace>/camera_info`, as image_transport's camera subscriber names it), publishes
`scan`. Parameters as upstream's: ~scan_height, ~scan_time, ~range_min, ~range_max,
~output_frame_id. An image is converted with the newest CameraInfo (a depth camera's projection
does not change while it runs) and only while someone subscribes to the scan; an image that
cannot be converted is one error line, and the node runs on.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Any

from kame.client import log
from kame.client.core import resolve_name
from kame.client.process import get_param, init_node, spin
from kame.client.topics import Publisher, Subscriber
from kame.depthimage_to_laserscan.conversion import ConversionError, Projection, Settings, convert, depth_in_meters
from sensor_msgs.msg import CameraInfo, Image, LaserScan


def settings_from_parameters() -> Settings:
    defaults = Settings()
    return Settings(scan_height=int(get_param("~scan_height", defaults.scan_height)),
                    scan_time=float(get_param("~scan_time", defaults.scan_time)),
                    range_min=float(get_param("~range_min", defaults.range_min)),
                    range_max=float(get_param("~range_max", defaults.range_max)),
                    output_frame_id=str(get_param("~output_frame_id", defaults.output_frame_id)))


def info_topic(image_topic: str) -> str:
    """image_transport::getCameraInfoTopic: camera_info beside the image topic."""
    namespace = image_topic.rsplit("/", 1)[0]
    return f"{namespace}/camera_info"


class DepthImageToLaserScan:
    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.projection: Projection | None = None
        self.scan = Publisher("scan", LaserScan, queue_size=10)
        image_topic = resolve_name("image")
        self.info = Subscriber(info_topic(image_topic), CameraInfo, self._take_info, queue_size=1)
        self.image = Subscriber(image_topic, Image, self._convert, queue_size=1)

    def _take_info(self, info: Any) -> None:
        try:
            self.projection = Projection.from_p(list(info.P))
        except ConversionError as exc:
            log.emit(log.ERROR, "%s", (exc,))

    def _convert(self, image: Any) -> None:
        if self.projection is None or self.scan.get_num_connections() == 0:
            return
        try:
            depth = depth_in_meters(bytes(image.data), image.width, image.height, image.step, image.encoding,
                                    bool(image.is_bigendian))
            result = convert(depth, self.projection, self.settings)
        except ConversionError as exc:
            log.emit(log.ERROR, "Could not convert depth image to laserscan: %s", (exc,))
            return
        scan = LaserScan()
        scan.header.stamp = image.header.stamp
        scan.header.frame_id = self.settings.output_frame_id or image.header.frame_id
        scan.angle_min, scan.angle_max = result.angle_min, result.angle_max
        scan.angle_increment = result.angle_increment
        scan.time_increment = 0.0
        scan.scan_time = self.settings.scan_time
        scan.range_min, scan.range_max = self.settings.range_min, self.settings.range_max
        scan.ranges = result.ranges.tolist()
        self.scan.publish(scan)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    init_node("depthimage_to_laserscan", argv)
    DepthImageToLaserScan(settings_from_parameters())
    spin()
    return 0
