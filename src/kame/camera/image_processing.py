"""image_proc's image processing (no ROS): debayering, rectification with a camera's
calibration, crop and decimation, resizing, each on numpy pictures with OpenCV, and the
CameraInfo each output goes with.

Rules (image_proc 1.16 and image_geometry's PinholeCameraModel):
- debayer: a Bayer image becomes bgr8 (algorithm 0 bilinear, 1 edge-aware, 2 edge-aware
  weighted: OpenCV's EA, 3 VNG); colour images are already colour; mono8/mono16 are already mono.
- rectify: the maps of initUndistortRectifyMap(K, D, R, P) in fixed point (CV_16SC2), made once
  per calibration and image size and reused; a camera with K[0] == 0 is uncalibrated and has no
  rectified image; remap with the interpolation asked for (0 nearest, 1 linear, 2 cubic, 3 area,
  4 Lanczos).
- crop_decimate: the region (x_offset, y_offset, width, height; 0 is "to the edge") then every
  decimation_x-th column and decimation_y-th row (nearest) or an interpolated resize; the
  CameraInfo's binning and roi say what was done, K and P stay the full sensor's.
- resize: by scale_width/scale_height (use_scale) or to width/height; K's and P's first two
  rows scale with the picture.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.camera.opencv import cv2_for

# OpenCV names a Bayer pattern by its second row's first two pixels, ROS by its first row's (as cv_bridge maps them)
BAYER_PATTERNS = {"bayer_rggb": "BayerBG", "bayer_bggr": "BayerRG", "bayer_gbrg": "BayerGR", "bayer_grbg": "BayerGB"}
DEBAYER_SUFFIXES = ("", "_EA", "_EA", "_VNG")  # OpenCV's names for image_proc's four algorithms
INTERPOLATIONS = ("INTER_NEAREST", "INTER_LINEAR", "INTER_CUBIC", "INTER_AREA", "INTER_LANCZOS4")


class ProcessingError(ValueError):
    """An input image_proc cannot process; the message is its log line."""


def interpolation(cv2: Any, number: int) -> int:
    if not 0 <= number < len(INTERPOLATIONS):
        raise ProcessingError(f"interpolation {number}: 0 to {len(INTERPOLATIONS) - 1}")
    value: int = getattr(cv2, INTERPOLATIONS[number])
    return value


def debayer(pixels: np.ndarray, encoding: str, algorithm: int = 0) -> np.ndarray:
    """The BGR picture of a Bayer image (8 or 16 bits)."""
    cv2 = cv2_for("image_proc's debayer")
    pattern = BAYER_PATTERNS.get(encoding[:len("bayer_rggb")])
    if pattern is None:
        raise ProcessingError(f"Raw image data from topic has unsupported encoding '{encoding}'")
    suffix = DEBAYER_SUFFIXES[algorithm] if 0 <= algorithm < len(DEBAYER_SUFFIXES) else ""
    if suffix == "_VNG" and pixels.dtype != np.uint8:
        suffix = ""  # OpenCV's VNG takes 8-bit images only; image_proc falls back to bilinear too
    converted: np.ndarray = cv2.cvtColor(pixels, getattr(cv2, f"COLOR_{pattern}2BGR{suffix}"))
    return converted


def is_calibrated(info: Any) -> bool:
    return bool(info.K[0] != 0.0)


@dataclass
class RectifyMaps:
    """The undistortion maps of one calibration and size, kept while they stay the same."""

    key: tuple[Any, ...] | None = None
    maps: tuple[np.ndarray, np.ndarray] | None = None

    def rectify(self, picture: np.ndarray, info: Any, interpolation_number: int = 1) -> np.ndarray:
        cv2 = cv2_for("image_proc's rectify")
        if not is_calibrated(info):
            raise ProcessingError("camera is uncalibrated")
        size = (picture.shape[1], picture.shape[0])
        key = (tuple(info.K), tuple(info.D), tuple(info.R), tuple(info.P), size)
        if key != self.key or self.maps is None:
            k = np.array(info.K, np.float64).reshape(3, 3)
            r = np.array(info.R, np.float64).reshape(3, 3)
            p = np.array(info.P, np.float64).reshape(3, 4)
            d = np.array(info.D, np.float64)
            self.maps = cv2.initUndistortRectifyMap(k, d, r, p, size, cv2.CV_16SC2)
            self.key = key
        rectified: np.ndarray = cv2.remap(picture, self.maps[0], self.maps[1], interpolation(cv2, interpolation_number))
        return rectified


@dataclass(frozen=True)
class CropDecimate:
    decimation_x: int = 1
    decimation_y: int = 1
    x_offset: int = 0
    y_offset: int = 0
    width: int = 0
    height: int = 0
    interpolation: int = 0

    def apply(self, picture: np.ndarray, info: Any) -> tuple[np.ndarray, Any]:
        """The cropped and decimated picture and its CameraInfo (a copy of `info`)."""
        cv2 = cv2_for("image_proc's crop_decimate")
        rows, cols = picture.shape[:2]
        x0, y0 = min(max(self.x_offset, 0), cols - 1), min(max(self.y_offset, 0), rows - 1)
        width = cols - x0 if self.width == 0 else min(self.width, cols - x0)
        height = rows - y0 if self.height == 0 else min(self.height, rows - y0)
        region = picture[y0:y0 + height, x0:x0 + width]
        dx, dy = max(self.decimation_x, 1), max(self.decimation_y, 1)
        if self.interpolation == 0:
            out = np.ascontiguousarray(region[::dy, ::dx])
        else:
            out = cv2.resize(region, (width // dx, height // dy), interpolation=interpolation(cv2, self.interpolation))
        binning_x, binning_y = max(int(info.binning_x), 1), max(int(info.binning_y), 1)
        result = copy.deepcopy(info)
        result.binning_x, result.binning_y = binning_x * dx, binning_y * dy
        result.roi.x_offset = int(info.roi.x_offset) + x0 * binning_x
        result.roi.y_offset = int(info.roi.y_offset) + y0 * binning_y
        result.roi.width, result.roi.height = width * binning_x, height * binning_y
        if self.width != 0 or self.height != 0:
            result.roi.do_rectify = True
        return out, result


@dataclass(frozen=True)
class Resize:
    interpolation: int = 1
    use_scale: bool = True
    scale_width: float = 1.0
    scale_height: float = 1.0
    width: int = -1
    height: int = -1

    def apply(self, picture: np.ndarray, info: Any | None) -> tuple[np.ndarray, Any | None]:
        cv2 = cv2_for("image_proc's resize")
        rows, cols = picture.shape[:2]
        if self.use_scale:
            width, height = int(cols * self.scale_width), int(rows * self.scale_height)
        else:
            width = self.width if self.width > 0 else cols
            height = self.height if self.height > 0 else rows
        width, height = max(width, 1), max(height, 1)
        out: np.ndarray = cv2.resize(picture, (width, height), interpolation=interpolation(cv2, self.interpolation))
        if info is None:
            return out, None
        scale_x, scale_y = width / cols, height / rows
        result = copy.deepcopy(info)
        result.width, result.height = width, height
        k, p = list(info.K), list(info.P)
        for index in (0, 1, 2):
            k[index] *= scale_x
            p[index] *= scale_x
            k[3 + index] *= scale_y
            p[4 + index] *= scale_y
        p[3] *= scale_x
        p[7] *= scale_y
        result.K, result.P = k, p
        return out, result
