"""A sensor_msgs/Image as the picture OpenCV writes (BGR, 8-bit or 16-bit) and a window shows
(RGB or grey, 8-bit), for image_view, image_saver, video_recorder and extract_images.

Rules (cv_bridge's toCvShare(..., "bgr8") as image_view uses it): rgb8/rgba8/bgra8 lose alpha
and become BGR; mono8 stays grey; 16-bit mono and depth are scaled onto 0..255 for viewing as
image_view's dynamic scaling does; Bayer images are demosaiced; yuv422 is converted. Also
boost::format's file names ("frame%04i.jpg", "left%04i.%s") as image_view's programs fill them.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from kame.camera.opencv import cv2_for
from kame.image_transport.compressed import to_array

# OpenCV names a Bayer pattern by its second row's first two pixels, ROS by its first row's (as cv_bridge maps them)
BAYER = {"bayer_rggb8": "BayerBG", "bayer_bggr8": "BayerRG", "bayer_gbrg8": "BayerGR", "bayer_grbg8": "BayerGB"}


class PictureError(ValueError):
    """An image whose encoding cannot be shown or saved."""


def to_bgr(image: Any, feature: str = "image_view") -> np.ndarray:
    """(height, width, 3) uint8 BGR, or (height, width) uint8 for grey images."""
    cv2 = cv2_for(feature)
    encoding = image.encoding
    try:
        pixels = to_array(image)
    except ValueError as exc:
        raise PictureError(str(exc)) from None
    if encoding in ("rgb8", "rgba8"):
        converted: np.ndarray = cv2.cvtColor(pixels, cv2.COLOR_RGB2BGR if encoding == "rgb8" else cv2.COLOR_RGBA2BGR)
        return converted
    if encoding == "bgra8":
        return np.ascontiguousarray(pixels[..., :3])
    if encoding in ("bgr8", "mono8", "8UC1", "8UC3"):
        return np.ascontiguousarray(pixels)
    if encoding in BAYER:
        return np.ascontiguousarray(cv2.cvtColor(pixels, getattr(cv2, f"COLOR_{BAYER[encoding]}2BGR")))
    if encoding in ("yuv422", "yuv422_yuy2"):
        code = cv2.COLOR_YUV2BGR_UYVY if encoding == "yuv422" else cv2.COLOR_YUV2BGR_YUY2
        return np.ascontiguousarray(cv2.cvtColor(pixels.reshape(image.height, image.width, 2), code))
    if pixels.ndim == 2 and pixels.dtype != np.uint8:
        return scaled(pixels.astype(np.float64))
    if pixels.ndim == 3 and pixels.dtype == np.uint16 and pixels.shape[2] >= 3:
        order = [2, 1, 0] if encoding.startswith("rgb") else [0, 1, 2]
        return np.ascontiguousarray((pixels[..., order] >> 8).astype(np.uint8))
    raise PictureError(f"cannot show or save an image of encoding {encoding!r}")


def scaled(values: np.ndarray) -> np.ndarray:
    """Finite non-zero values from their least to their greatest onto 0..255; the rest black."""
    known = np.isfinite(values) & (values != 0)
    out = np.zeros(values.shape, np.uint8)
    if known.any():
        low, high = float(values[known].min()), float(values[known].max())
        span = high - low or 1.0
        out[known] = np.clip((values[known] - low) * 255.0 / span, 0, 255).astype(np.uint8)
    return out


def to_rgb(bgr: np.ndarray) -> np.ndarray:
    """What a window draws: RGB for colour, grey as it is."""
    return bgr if bgr.ndim == 2 else np.ascontiguousarray(bgr[..., ::-1])


_SPEC = re.compile(r"%[-+ #0]*\d*(?:\.\d+)?[diouxXeEfFgGcrsa%]")


def format_filename(pattern: str, *values: Any) -> str:
    """boost::format's `pattern % values...` for image_view's filename_format: as many values as
    it has specifiers are used (image_saver gives the count and the extension; a pattern with
    only %04i takes the count)."""
    wanted = [spec for spec in _SPEC.findall(pattern) if spec != "%%"]
    try:
        return pattern % tuple(values[:len(wanted)])
    except (TypeError, ValueError) as exc:
        raise ValueError(f"filename_format {pattern!r}: {exc}") from None
