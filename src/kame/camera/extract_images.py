"""image_view's extract_images: `rosrun image_view extract_images image:=/camera/image_raw`
(often beside `rosbag play`) saves an image every sec_per_frame seconds of wall time as
frame0000.jpg, frame0001.jpg... (parameters filename_format, sec_per_frame), as image_view
1.16's."""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Sequence
from typing import Any

from kame.camera.image_feed import image_topic, subscribe_image, transport_argument
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.pictures import PictureError, format_filename, to_bgr
from kame.client import core, log
from kame.client.process import get_param, init_node, myargv, spin


class ExtractImages:
    def __init__(self, cv2: Any, topic: str, transport: str) -> None:
        self.cv2 = cv2
        self.format = str(get_param("~filename_format", "frame%04d.jpg"))
        self.sec_per_frame = float(get_param("~sec_per_frame", 0.1))
        self.count = 0
        self.last_saved: float | None = None
        self.lock = threading.Lock()
        self.subscriber = subscribe_image(topic, transport, self._image, queue_size=1)

    def _image(self, image: Any) -> None:
        with self.lock:
            now = time.monotonic()
            if self.last_saved is not None and now - self.last_saved < self.sec_per_frame:
                return
            try:
                picture = to_bgr(image, "extract_images")
            except PictureError:
                log.emit(log.ERROR, "Unable to convert %s image to bgr8", (image.encoding,))
                return
            filename = format_filename(self.format, self.count)
            if not self.cv2.imwrite(filename, picture):
                log.emit(log.ERROR, "Could not save image %s (does its folder exist?)", (filename,))
                return
            log.emit(log.INFO, "Saved image %s", (filename,))
            self.count += 1
            self.last_saved = now


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        cv2 = cv2_for("extract_images")
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    init_node("extract_images", argv, anonymous=True)
    try:
        ExtractImages(cv2, image_topic("extract_images"), transport_argument(myargv(argv)))
    except ValueError as exc:
        log.emit(log.FATAL, "%s", (exc,))
        core.signal_shutdown(str(exc))
        return 1
    spin()
    return 0
