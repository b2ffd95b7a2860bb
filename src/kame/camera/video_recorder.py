"""image_view's video_recorder: `rosrun image_view video_recorder image:=/usb_cam/image_raw`
writes the topic's images to a video file through OpenCV's VideoWriter (image_view 1.16's
parameters: filename output.avi, fps 15, codec MJPG, encoding bgr8, stamped_filename).

The file is opened with the first image's size; an image less than 1/fps after the last one
written (by their stamps) is skipped, as upstream's. The file is closed at shutdown
("Video saved as ...").
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Sequence
from typing import Any

from kame.camera.image_feed import image_topic, subscribe_image, transport_argument
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.camera.pictures import PictureError, to_bgr
from kame.client import core, log
from kame.client.clock import Duration
from kame.client.process import get_param, init_node, myargv, spin


class VideoRecorder:
    def __init__(self, cv2: Any, topic: str, transport: str) -> None:
        self.cv2 = cv2
        filename = str(get_param("~filename", "output.avi"))
        if bool(get_param("~stamped_filename", False)):
            folder, _, name = filename.rpartition("/")
            filename = (folder + "/" if folder else "") + str(time.time_ns()) + name
        self.filename = filename
        self.fps = int(get_param("~fps", 15))
        self.codec = str(get_param("~codec", "MJPG"))
        self.encoding = str(get_param("~encoding", "bgr8"))
        if len(self.codec) != 4:
            raise ValueError("The video codec must be a FOURCC identifier (4 chars)")
        self.writer: Any = None
        self.last_written: Any = None
        self.frames = 0
        self.lock = threading.Lock()
        self.subscriber = subscribe_image(topic, transport, self._image, queue_size=1)

    def _image(self, image: Any) -> None:
        with self.lock:
            self._record(image)

    def _record(self, image: Any) -> None:
        if self.last_written is not None and image.header.stamp - self.last_written < Duration.from_sec(1.0 / self.fps):
            return
        try:
            picture = to_bgr(image, "video_recorder")
        except PictureError:
            log.emit(log.ERROR, "Unable to convert %s image to %s", (image.encoding, self.encoding))
            return
        if picture.ndim == 2:
            picture = self.cv2.cvtColor(picture, self.cv2.COLOR_GRAY2BGR)
        if self.writer is None:
            size = (picture.shape[1], picture.shape[0])
            self.writer = self.cv2.VideoWriter(self.filename, self.cv2.VideoWriter_fourcc(*self.codec), self.fps,
                                               size, True)
            if not self.writer.isOpened():
                log.emit(log.ERROR, "Could not create the output video! Check filename and/or support for codec.", ())
                core.signal_shutdown("no video file")
                return
            log.emit(log.INFO, "Starting to record %s video at [%d x %d]@%dfps. Press Ctrl+C to stop recording.",
                     (self.codec, size[0], size[1], self.fps))
        self.writer.write(picture)
        self.frames += 1
        self.last_written = image.header.stamp

    def close(self) -> None:
        with self.lock:
            if self.writer is not None:
                self.writer.release()
                self.writer = None
                log.emit(log.INFO, "Video saved as %s (%d frames)", (self.filename, self.frames))


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    try:
        cv2 = cv2_for("video_recorder")
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    init_node("video_recorder", argv, anonymous=True)
    try:
        recorder = VideoRecorder(cv2, image_topic("video_recorder"), transport_argument(myargv(argv)))
    except ValueError as exc:
        log.emit(log.FATAL, "%s", (exc,))
        core.signal_shutdown(str(exc))
        return 1
    try:
        spin()
    finally:
        recorder.subscriber.unregister()
        recorder.close()
    return 0
