"""image_view's image_saver: `rosrun image_view image_saver image:=/usb_cam/image_raw` saves the
topic's images as left0000.jpg, left0001.jpg... (image_view 1.16's parameters: filename_format,
encoding, save_all_image, stamped_filename, request_start_end; services ~save, ~start, ~end).

With save_all_image false, each call of ~save saves the next image. When the camera publishes
camera_info beside the image, each image's calibration is written next to it (.ini), as
upstream's camera subscriber does; images are then saved only with their camera_info (same
stamp), and the first images, before any camera_info came, without.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Sequence
from typing import Any

from kame.camera.calibration_files import Calibration, dump
from kame.camera.image_feed import image_topic, subscribe_image, transport_argument
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.pictures import PictureError, format_filename, to_bgr
from kame.client import clock, core, log
from kame.client.process import get_param, init_node, myargv, spin
from kame.client.services import Service
from kame.client.topics import Subscriber
from sensor_msgs.msg import CameraInfo
from std_srvs.srv import Empty, EmptyResponse, Trigger, TriggerResponse


def in_encoding(cv2: Any, picture: Any, encoding: str) -> Any:
    """The picture as cv_bridge's toCvShare(image, encoding) gives it to imwrite."""
    grey = picture.ndim == 2
    if encoding == "bgr8":
        return cv2.cvtColor(picture, cv2.COLOR_GRAY2BGR) if grey else picture
    if encoding == "rgb8":
        return cv2.cvtColor(picture, cv2.COLOR_GRAY2RGB if grey else cv2.COLOR_BGR2RGB)
    if encoding == "mono8":
        return picture if grey else cv2.cvtColor(picture, cv2.COLOR_BGR2GRAY)
    raise PictureError(f"encoding {encoding} is not one image_saver converts to (bgr8, rgb8, mono8)")


class ImageSaver:
    def __init__(self, cv2: Any, topic: str, transport: str) -> None:
        self.cv2 = cv2
        self.format = str(get_param("~filename_format", "left%04i.%s"))
        self.stamped_filename = bool(get_param("~stamped_filename", False))
        self.encoding = str(get_param("~encoding", "bgr8"))
        self.save_all_image = bool(get_param("~save_all_image", True))
        self.request_start_end = bool(get_param("~request_start_end", False))
        if self.request_start_end and not self.save_all_image:
            log.emit(log.WARN, "'request_start_end' is true, so overwriting 'save_all_image' as true", ())
            self.save_all_image = True
        self.count = 0
        self.save_requested = False
        self.start_time: Any = None
        self.end_time: Any = None
        self.infos: dict[tuple[int, int], Any] = {}  # newest camera_info by stamp, to pair with its image
        self.images: dict[tuple[int, int], Any] = {}  # images waiting for their camera_info
        self.has_camera_info = False
        self.lock = threading.Lock()
        self.subscriber = subscribe_image(topic, transport, self._image, queue_size=5)
        self.info_subscriber = Subscriber(topic.rsplit("/", 1)[0] + "/camera_info", CameraInfo, self._info,
                                          queue_size=5)
        self.services = [Service("~save", Empty, self._save), Service("~start", Trigger, self._start),
                         Service("~end", Trigger, self._end)]

    def _save(self, _request: Any) -> Any:
        with self.lock:
            self.save_requested = True
        return EmptyResponse()

    def _start(self, _request: Any) -> Any:
        log.emit(log.INFO, "Received start saving request", ())
        with self.lock:
            self.start_time, self.end_time = clock.get_rostime(), None
        return TriggerResponse(success=True)

    def _end(self, _request: Any) -> Any:
        log.emit(log.INFO, "Received end saving request", ())
        with self.lock:
            self.end_time = clock.get_rostime()
        return TriggerResponse(success=True)

    @staticmethod
    def _key(message: Any) -> tuple[int, int]:
        return message.header.stamp.secs, message.header.stamp.nsecs

    def _info(self, info: Any) -> None:
        with self.lock:
            self.has_camera_info = True
            image = self.images.pop(self._key(info), None)
            if image is None:
                self.infos = {self._key(info): info}
                return
            self._save_one(image, info)

    def _image(self, image: Any) -> None:
        with self.lock:
            if not self.has_camera_info:
                self._save_one(image, None)
                return
            info = self.infos.pop(self._key(image), None)
            if info is None:
                self.images = {self._key(image): image}
                return
            self._save_one(image, info)

    def _wanted(self, image: Any) -> bool:
        if self.save_requested or not self.request_start_end:
            return self.save_all_image or self.save_requested
        stamp = image.header.stamp
        return (self.start_time is not None and stamp >= self.start_time
                and (self.end_time is None or stamp <= self.end_time))

    def _save_one(self, image: Any, info: Any) -> None:
        if not self._wanted(image):
            return
        try:
            picture = in_encoding(self.cv2, to_bgr(image, "image_saver"), self.encoding)
        except PictureError:
            log.emit(log.ERROR, "Unable to convert %s image to %s", (image.encoding, self.encoding))
            return
        filename = format_filename(self.format, self.count, "jpg")
        if self.stamped_filename:
            filename = str(time.time_ns()) + filename
        if not self.cv2.imwrite(filename, picture):
            log.emit(log.ERROR, "Could not save image %s (does its folder exist?)", (filename,))
            return
        log.emit(log.INFO, "Saved image %s", (filename,))
        self.save_requested = False
        if info is not None:
            stem = filename[:filename.rfind(".")] if "." in filename else filename
            with open(stem + ".ini", "w") as calibration:
                calibration.write(dump(Calibration("camera", info), "ini"))
        self.count += 1


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        cv2 = cv2_for("image_saver")
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    init_node("image_saver", argv, anonymous=True)
    try:
        ImageSaver(cv2, image_topic("image_saver"), transport_argument(myargv(argv)))
    except ValueError as exc:
        log.emit(log.FATAL, "%s", (exc,))
        core.signal_shutdown(str(exc))
        return 1
    spin()
    return 0
