"""image_proc's nodelets as kame runs them (each on kame.client, in a process of its own):
debayer, rectify, crop_decimate and resize, with their dynamic_reconfigure parameters, and the
`image_proc` node that combines debayer with a rectify for image_mono and one for image_color,
as image_proc 1.16's (`ROS_NAMESPACE=camera rosrun image_proc image_proc`).

Topics are upstream's: debayer image_raw -> image_mono, image_color; rectify image_mono (with
camera_info) -> image_rect; crop_decimate camera/image_raw -> camera_out/image_raw (with their
camera_info); resize image (and camera_info) -> ~image, ~camera_info. As upstream's, a nodelet
subscribes to its inputs only while someone subscribes to one of its outputs (`LazyInput`), and
computes an output only while it has subscribers. Each nodelet's parameters live in its own namespace (the
standalone program's private one; image_proc's <node>_debayer, <node>_rectify_mono,
<node>_rectify_color), served by kame.reconfigure's Server.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from kame.camera.image_feed import CameraSubscriber, subscribe_image
from kame.camera.image_proc_configs import crop_decimate_config, debayer_config, rectify_config, resize_config
from kame.camera.image_processing import CropDecimate, ProcessingError, RectifyMaps, Resize, debayer, is_calibrated
from kame.camera.image_publisher import CameraPublisher, ImagePublisher
from kame.camera.opencv import cv2_for
from kame.camera.pictures import PictureError, to_bgr
from kame.client import log
from kame.client.core import resolve_name
from kame.client.topics import Publisher, SubscribeListener, Subscriber
from kame.image_transport.compressed import CompressionError, from_array, to_array
from kame.reconfigure.server import Server
from sensor_msgs.msg import CameraInfo

MONO = ("mono8", "mono16", "8UC1", "16UC1")


class LazyInput(SubscribeListener):
    """A nodelet's input subscriptions, made when its outputs get their first subscriber and
    dropped when they have none left (image_transport's connect callbacks)."""

    def __init__(self, subscribe: Callable[[], list[Any]], wanted: Callable[[], bool]) -> None:
        self.subscribe = subscribe
        self.wanted = wanted
        self.inputs: list[Any] = []
        self.lock = threading.Lock()

    def peer_subscribe(self, topic_name: str, topic_publish: Callable[[Any], None],
                       peer_publish: Callable[[Any], None]) -> None:
        with self.lock:
            if not self.inputs:
                self.inputs = self.subscribe()

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        with self.lock:
            if self.inputs and not self.wanted():
                for subscription in self.inputs:
                    subscription.unregister()
                self.inputs = []


def _is_colour(encoding: str) -> bool:
    return encoding in ("rgb8", "bgr8", "rgba8", "bgra8", "rgb16", "bgr16", "rgba16", "bgra16")


class Debayer:
    def __init__(self, namespace: str, parameters: str) -> None:
        self.algorithm = 0
        raw_topic = resolve_name(f"{namespace}image_raw")
        self.input = LazyInput(lambda: [subscribe_image(raw_topic, "raw", self._raw)],
                               lambda: self.mono.wanted() or self.color.wanted())
        self.mono = ImagePublisher(f"{namespace}image_mono", self.input)
        self.color = ImagePublisher(f"{namespace}image_color", self.input)
        self.server = Server(debayer_config(), self._configure, parameters)

    def _configure(self, config: Any, _level: int) -> Any:
        self.algorithm = int(config["debayer"])
        return config

    def _raw(self, raw: Any) -> None:
        if self.mono.wanted():
            self._publish_mono(raw)
        if self.color.wanted():
            self._publish_color(raw)

    def _publish_mono(self, raw: Any) -> None:
        if raw.encoding in MONO:
            self.mono.publish(raw)
            return
        try:
            pixels = self._colour(raw)
        except (ProcessingError, CompressionError) as exc:
            log.emit_throttle(10.0, log.ERROR, "%s", (exc,))
            return
        cv2 = cv2_for("image_proc's debayer")
        grey = cv2.cvtColor(pixels, cv2.COLOR_BGR2GRAY)
        self.mono.publish(from_array(grey, "mono16" if grey.dtype.itemsize == 2 else "mono8", raw.header))

    def _publish_color(self, raw: Any) -> None:
        if raw.encoding in MONO or _is_colour(raw.encoding):
            if raw.encoding in MONO:
                log.emit_throttle(30.0, log.WARN, "Color topic '%s' requested, but raw image data is grayscale",
                                  (self.color.raw.resolved_name,))
            self.color.publish(raw)
            return
        try:
            pixels = self._colour(raw)
        except (ProcessingError, CompressionError) as exc:
            log.emit_throttle(10.0, log.ERROR, "%s", (exc,))
            return
        self.color.publish(from_array(pixels, "bgr16" if pixels.dtype.itemsize == 2 else "bgr8", raw.header))

    def _colour(self, raw: Any) -> Any:
        """The BGR picture of a Bayer, YUV or colour image."""
        if raw.encoding.startswith("bayer"):
            return debayer(to_array(raw), raw.encoding, self.algorithm)
        try:
            return to_bgr(raw, "image_proc's debayer")
        except PictureError as exc:
            raise ProcessingError(f"Raw image data has unsupported encoding '{raw.encoding}'") from exc


class Rectify:
    def __init__(self, image_topic: str, rect_topic: str, parameters: str) -> None:
        self.interpolation = 1
        self.maps = RectifyMaps()
        self.lock = threading.Lock()  # the maps are made on one pair's thread at a time
        image = resolve_name(image_topic)
        self.info_topic = image.rsplit("/", 1)[0] + "/camera_info"
        self.input = LazyInput(lambda: [CameraSubscriber(image, "raw", self._pair)], lambda: self.publisher.wanted())
        self.publisher = ImagePublisher(rect_topic, self.input)
        self.server = Server(rectify_config(), self._configure, parameters)

    def _configure(self, config: Any, _level: int) -> Any:
        self.interpolation = int(config["interpolation"])
        return config

    def _pair(self, image: Any, info: Any) -> None:
        if not self.publisher.wanted():
            return
        if not is_calibrated(info):
            log.emit_throttle(30.0, log.ERROR, "Rectified topic '%s' requested but camera publishing '%s' is "
                              "uncalibrated", (self.publisher.raw.resolved_name, self.info_topic))
            return
        if not any(info.D):  # no distortion: the image is its own rectification
            self.publisher.publish(image)
            return
        try:
            with self.lock:
                rectified = self.maps.rectify(to_array(image), info, self.interpolation)
        except (ProcessingError, CompressionError) as exc:
            log.emit_throttle(10.0, log.ERROR, "%s", (exc,))
            return
        self.publisher.publish(from_array(rectified, image.encoding, image.header))


class CropDecimateNode:
    def __init__(self, parameters: str) -> None:
        self.settings = CropDecimate()
        image = resolve_name("camera/image_raw")
        self.input = LazyInput(lambda: [CameraSubscriber(image, "raw", self._pair)], lambda: self.publisher.wanted())
        self.publisher = CameraPublisher("camera_out/image_raw", "camera_out/camera_info", self.input)
        self.server = Server(crop_decimate_config(), self._configure, parameters)

    def _configure(self, config: Any, _level: int) -> Any:
        self.settings = CropDecimate(*(int(config[name]) for name in ("decimation_x", "decimation_y", "x_offset",
                                                                      "y_offset", "width", "height", "interpolation")))
        return config

    def _pair(self, image: Any, info: Any) -> None:
        if not self.publisher.wanted():
            return
        try:
            pixels, out_info = self.settings.apply(to_array(image), info)
        except (ProcessingError, CompressionError) as exc:
            log.emit_throttle(10.0, log.ERROR, "%s", (exc,))
            return
        out_info.header = image.header
        self.publisher.publish_camera(from_array(pixels, image.encoding, image.header), out_info)


class ResizeNode:
    def __init__(self, parameters: str) -> None:
        self.settings = Resize()
        self.info: Any = None
        image, info = resolve_name("image"), resolve_name("camera_info")
        self.input = LazyInput(lambda: [Subscriber(info, CameraInfo, self._info, queue_size=1),
                                        subscribe_image(image, "raw", self._image)],
                               lambda: self.image_publisher.wanted() or bool(self.info_publisher.get_num_connections()))
        self.image_publisher = ImagePublisher("~image", self.input)
        self.info_publisher = Publisher("~camera_info", CameraInfo, subscriber_listener=self.input, queue_size=1)
        self.server = Server(resize_config(), self._configure, parameters)

    def _configure(self, config: Any, _level: int) -> Any:
        self.settings = Resize(int(config["interpolation"]), bool(config["use_scale"]), float(config["scale_width"]),
                               float(config["scale_height"]), int(config["width"]), int(config["height"]))
        return config

    def _info(self, info: Any) -> None:
        self.info = info

    def _image(self, image: Any) -> None:
        info = self.info
        try:
            pixels, out_info = self.settings.apply(to_array(image), info)
        except (ProcessingError, CompressionError) as exc:
            log.emit_throttle(10.0, log.ERROR, "%s", (exc,))
            return
        self.image_publisher.publish(from_array(pixels, image.encoding, image.header))
        if out_info is not None and self.info_publisher.get_num_connections():
            self.info_publisher.publish(out_info)
