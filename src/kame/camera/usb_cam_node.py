"""usb_cam's usb_cam_node (0.3.x, as the courses clone it): a camera's frames on `~image_raw`
(and its compressed transport) with `~camera_info`, `~start_capture` and `~stop_capture`.

Parameters and defaults are usb_cam 0.3.6's (video_device /dev/video0, 640x480, mjpeg, mmap,
30 fps, head_camera; brightness, contrast, saturation, sharpness, gain and focus -1 "leave
alone"; autofocus, autoexposure/exposure, auto_white_balance/white_balance). kame adds two
sources: `video_device:=testsrc` (a moving test pattern with a frame counter) and a video file's
path; both are converted from the pixel format as a camera's frames are and published at the
frame rate. The capture loop is the main thread's, as usb_cam's spin(): a device blocks until
its next frame, the other sources keep the rate with kame.client's Rate.
"""

from __future__ import annotations

import copy
import sys
from collections.abc import Sequence
from typing import Any

from kame.camera.image_publisher import CameraPublisher
from kame.camera.info_manager import CameraInfoManager
from kame.camera.pixel_formats import FORMATS, FrameError, decode, pixel_format
from kame.camera.sources import CameraError, FrameSource, Settings, V4L2Source, open_source
from kame.client import clock, core, log
from kame.client.process import get_param, init_node
from kame.client.services import Service
from kame.client.timer import Rate
from kame.net.signal_wake import SignalSafeEvent
from sensor_msgs.msg import CameraInfo, Image
from std_srvs.srv import Empty, EmptyResponse

DEFAULTS: dict[str, Any] = {
    "video_device": "/dev/video0", "brightness": -1, "contrast": -1, "saturation": -1, "sharpness": -1,
    "io_method": "mmap", "image_width": 640, "image_height": 480, "framerate": 30, "pixel_format": "mjpeg",
    "autofocus": False, "focus": -1, "autoexposure": True, "exposure": 100, "gain": -1,
    "auto_white_balance": True, "white_balance": 4000, "camera_frame_id": "head_camera",
    "camera_name": "head_camera", "camera_info_url": "",
}


def read_parameters() -> dict[str, Any]:
    return {name: get_param("~" + name, default) for name, default in DEFAULTS.items()}


def apply_controls(source: V4L2Source, params: dict[str, Any]) -> None:
    """usb_cam's set_v4l_parameter calls, in its order; a control the camera lacks is a warning."""
    settings: list[tuple[str, int]] = [(name, int(params[name])) for name in
                                       ("brightness", "contrast", "saturation", "sharpness", "gain")
                                       if int(params[name]) >= 0]
    if params["auto_white_balance"]:
        settings.append(("white_balance_temperature_auto", 1))
    else:
        settings += [("white_balance_temperature_auto", 0), ("white_balance_temperature", int(params["white_balance"]))]
    if not params["autoexposure"]:
        settings += [("exposure_auto", 1), ("exposure_absolute", int(params["exposure"]))]
    if params["autofocus"]:
        settings.append(("focus_auto", 1))
    else:
        settings.append(("focus_auto", 0))
        if int(params["focus"]) >= 0:
            settings.append(("focus_absolute", int(params["focus"])))
    for name, value in settings:
        if not source.set_control(name, value):
            log.emit(log.WARN, "Camera %s has no control '%s'", (source.settings.device, name))


class UsbCam:
    def __init__(self, params: dict[str, Any], source: FrameSource, settings: Settings) -> None:
        self.params = params
        self.source = source
        self.settings = settings
        self.frame_id = str(params["camera_frame_id"])
        self.publisher = CameraPublisher("~image_raw", "~camera_info")
        self.info = CameraInfoManager(str(params["camera_name"]), str(params["camera_info_url"]))
        if not self.info.is_calibrated():
            # upstream renames the camera after its device (which "/dev/video0", not a valid name,
            # leaves head_camera); kame's test pattern and video files keep camera_name, so that a
            # calibration COMMITted for them is found again under the same name
            if settings.device.startswith("/dev/"):
                self.info.set_camera_name(settings.device)
            self.info.set_camera_info(CameraInfo(width=settings.width, height=settings.height))
        self.capturing = SignalSafeEvent()
        self.capturing.set()
        self.services = [Service("~start_capture", Empty, self._start), Service("~stop_capture", Empty, self._stop)]

    def _start(self, _request: Any) -> Any:
        self.capturing.set()
        return EmptyResponse()

    def _stop(self, _request: Any) -> Any:
        self.capturing.clear()
        return EmptyResponse()

    def frame(self, raw: bytes) -> tuple[Any, Any]:
        pixels = decode(raw, self.settings.format, self.settings.width, self.settings.height)
        stamp = clock.get_rostime()
        image = Image(height=pixels.shape[0], width=pixels.shape[1], encoding=self.settings.format.encoding,
                      is_bigendian=0, step=pixels.shape[1] * (3 if pixels.ndim == 3 else 1), data=pixels.tobytes())
        image.header.stamp, image.header.frame_id = stamp, self.frame_id
        info = copy.deepcopy(self.info.get_camera_info())  # a published message is never changed after
        info.header.stamp, info.header.frame_id = stamp, self.frame_id
        return image, info

    def spin(self) -> None:
        rate = Rate(self.settings.framerate)
        while not core.is_shutdown():
            if not self.capturing.is_set():
                self.source.pause()  # here, not in the service's thread: this loop is the source's one reader
                with core.woken_at_shutdown(self.capturing):
                    self.capturing.wait()
                if core.is_shutdown():
                    break
                try:
                    self.source.resume()
                except CameraError as exc:
                    log.emit(log.ERROR, "%s", (exc,))
                    break
                continue
            try:
                raw = self.source.read()
                image, info = self.frame(raw)
            except (CameraError, FrameError) as exc:
                log.emit_throttle(5.0, log.WARN, "USB camera did not respond in time: %s", (exc,))
            else:
                self.publisher.publish_camera(image, info)
            if self.source.paced:
                rate.sleep()


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    init_node("usb_cam", argv)
    params = read_parameters()
    if int(params["framerate"]) <= 0:
        log.emit(log.FATAL, "bad framerate %d", (int(params["framerate"]),))
        return 1
    if params["pixel_format"] not in FORMATS:
        log.emit(log.FATAL, "Unknown pixel format '%s' (usb_cam has %s)", (params["pixel_format"], ", ".join(FORMATS)))
        core.signal_shutdown("unknown pixel format")
        return 1
    settings = Settings(str(params["video_device"]), int(params["image_width"]), int(params["image_height"]),
                        pixel_format(str(params["pixel_format"])), int(params["framerate"]), str(params["io_method"]))
    log.emit(log.INFO, "Starting '%s' (%s) at %dx%d via %s (%s) at %i FPS",
             (params["camera_name"], settings.device, settings.width, settings.height, settings.io_method,
              settings.format.name, settings.framerate))
    try:
        source = open_source(settings)
    except CameraError as exc:
        log.emit(log.FATAL, "%s", (exc,))
        core.signal_shutdown("no camera")
        return 1
    try:
        if isinstance(source, V4L2Source):
            apply_controls(source, params)
        UsbCam(params, source, settings).spin()
    finally:
        source.close()
    return 0
