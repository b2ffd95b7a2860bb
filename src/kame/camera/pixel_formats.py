"""usb_cam's pixel formats: what a camera sends in each, and the sensor_msgs/Image usb_cam 0.3.x
publishes from it.

Rules (usb_cam.cpp's process_image): yuyv, uyvy, mjpeg and rgb24 become rgb8; grey and
yuvmono10 (10-bit grey in 16-bit words, as usb_cam reads it, high bits kept) become mono8. kame
also takes `mono8` as another name for grey. The conversions are OpenCV's (BT.601, as usb_cam's
own YUV tables), so a frame costs a few milliseconds at 1080p. `encode` is the other way, what a
camera in that format would have sent for an RGB picture: the test pattern and video files go
through it so that pixel_format costs and looks the same as with a webcam.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.camera.opencv import cv2_for


@dataclass(frozen=True)
class PixelFormat:
    name: str
    fourcc: str  # the V4L2 pixel format usb_cam asks the device for
    encoding: str  # the published Image's encoding


FORMATS = {format.name: format for format in (
    PixelFormat("yuyv", "YUYV", "rgb8"),
    PixelFormat("uyvy", "UYVY", "rgb8"),
    PixelFormat("mjpeg", "MJPG", "rgb8"),
    PixelFormat("rgb24", "RGB3", "rgb8"),
    PixelFormat("grey", "GREY", "mono8"),
    PixelFormat("mono8", "GREY", "mono8"),
    PixelFormat("yuvmono10", "YUYV", "mono8"),
)}


class FrameError(ValueError):
    """A frame whose size does not fit its format, or jpeg data that does not decode."""


def pixel_format(name: str) -> PixelFormat:
    """The format usb_cam's pixel_format parameter names; KeyError for one it does not know."""
    return FORMATS[name]


def _cv2() -> Any:
    return cv2_for("usb_cam's pixel format conversions")


def encode(rgb: np.ndarray, format: PixelFormat) -> bytes:
    """The bytes a camera sends in `format` for an (height, width, 3) uint8 RGB picture."""
    cv2 = _cv2()
    if format.name in ("yuyv", "uyvy"):
        code = cv2.COLOR_RGB2YUV_YUYV if format.name == "yuyv" else cv2.COLOR_RGB2YUV_UYVY
        return bytes(cv2.cvtColor(rgb, code).data)
    if format.name == "mjpeg":
        _encoded, jpeg = cv2.imencode(".jpg", cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), [cv2.IMWRITE_JPEG_QUALITY, 90])
        return bytes(jpeg.data)
    if format.name == "rgb24":
        return bytes(np.ascontiguousarray(rgb).data)
    grey = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    if format.name == "yuvmono10":
        return bytes((grey.astype("<u2") << 2).data)
    return bytes(grey.data)


def decode(data: bytes | memoryview, format: PixelFormat, width: int, height: int) -> np.ndarray:
    """The published picture: (height, width, 3) RGB for rgb8, (height, width) for mono8."""
    cv2 = _cv2()
    raw = np.frombuffer(data, np.uint8)
    if format.name == "mjpeg":
        bgr = cv2.imdecode(raw, cv2.IMREAD_COLOR)
        if bgr is None:
            raise FrameError(f"an mjpeg frame of {len(raw)} bytes does not decode")
        if bgr.shape[:2] != (height, width):
            raise FrameError(f"an mjpeg frame of {bgr.shape[1]}x{bgr.shape[0]}, {width}x{height} expected")
        rgb: np.ndarray = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
        return rgb
    per_pixel = {"yuyv": 2, "uyvy": 2, "rgb24": 3, "grey": 1, "mono8": 1, "yuvmono10": 2}[format.name]
    needed = width * height * per_pixel
    if len(raw) < needed:
        raise FrameError(f"a {format.name} frame of {len(raw)} bytes, {width}x{height} needs {needed}")
    raw = raw[:needed]
    if format.name in ("yuyv", "uyvy"):
        code = cv2.COLOR_YUV2RGB_YUYV if format.name == "yuyv" else cv2.COLOR_YUV2RGB_UYVY
        colour: np.ndarray = cv2.cvtColor(raw.reshape(height, width, 2), code)
        return colour
    if format.name == "rgb24":
        return raw.reshape(height, width, 3)
    if format.name == "yuvmono10":
        return (raw.view("<u2").reshape(height, width) >> 2).astype(np.uint8)
    return raw.reshape(height, width)
