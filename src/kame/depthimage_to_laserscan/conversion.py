"""DepthImageToLaserScan::convert_msg without ROS: a depth image (32FC1 in metres or 16UC1 in
millimetres) and its camera's projection in, a laser scan's angles and ranges out.

Upstream's rules, kept because users' maps depend on them:
- one beam per image column; angle_max is the angle between the left column's ray and the
  optical axis, angle_min minus the right column's (a scan turns the other way from image x);
- each column's range is the nearest valid range among the `scan_height` rows centred on cy,
  where a pixel's range is hypot(x, z) in the optical frame (not the depth z);
- a pixel's beam index is computed from its own angle, so neighbouring columns may share one;
- out of [range_min, range_max] a finite range is dropped; a beam with no valid pixel stays NaN,
  or +-Inf when an infinite depth was seen (more information than NaN);
- a 16UC1 depth of 0 means no reading.
The camera is taken as rectified (its D ignored), as simulated and registered depth images are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


class ConversionError(ValueError):
    """An image or setting that cannot be made into a scan; the text is upstream's."""


@dataclass(frozen=True)
class Projection:
    """The pinhole of a CameraInfo: P's fx, fy, cx, cy and its Tx, Ty (image_geometry's
    PinholeCameraModel, which reads P)."""

    fx: float
    fy: float
    cx: float
    cy: float
    tx: float = 0.0
    ty: float = 0.0

    @classmethod
    def from_p(cls, p: list[float] | tuple[float, ...]) -> Projection:
        if len(p) != 12 or p[0] == 0.0:
            raise ConversionError("Camera info has no projection matrix P: the depth camera is not calibrated")
        return cls(fx=p[0], fy=p[5], cx=p[2], cy=p[6], tx=p[3], ty=p[7])

    def ray(self, u: float, v: float) -> tuple[float, float, float]:
        """projectPixelTo3dRay: the ray through a pixel, in the optical frame (z forward)."""
        return ((u - self.cx - self.tx) / self.fx, (v - self.cy - self.ty) / self.fy, 1.0)


@dataclass(frozen=True)
class Settings:
    """The node's parameters, with upstream's defaults."""

    scan_height: int = 1
    scan_time: float = 0.033
    range_min: float = 0.45
    range_max: float = 10.0
    output_frame_id: str = "camera_depth_frame"


@dataclass(frozen=True)
class Scan:
    angle_min: float
    angle_max: float
    angle_increment: float
    ranges: np.ndarray  # float32, one beam per image column


def _angle_between(a: tuple[float, float, float], b: tuple[float, float, float]) -> float:
    dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    return math.acos(max(-1.0, min(1.0, dot / (math.hypot(*a) * math.hypot(*b)))))


def depth_in_meters(data: bytes, width: int, height: int, step: int, encoding: str,
                    bigendian: bool = False) -> np.ndarray:
    """An Image's pixels as float metres, NaN where a 16UC1 image has no reading (0)."""
    order = ">" if bigendian else "<"
    if encoding == "32FC1":
        kind, size = np.dtype(order + "f4"), 4
    elif encoding == "16UC1":
        kind, size = np.dtype(order + "u2"), 2
    else:
        raise ConversionError(f"Depth image has unsupported encoding: {encoding}")
    if step < width * size or len(data) < step * height:
        raise ConversionError(f"Depth image of {width}x{height} needs {step * height} bytes with step {step}, "
                              f"has {len(data)}")
    rows = np.frombuffer(data, dtype=np.uint8, count=step * height).reshape(height, step)
    pixels = rows[:, :width * size].copy().view(kind).reshape(height, width)
    metres: np.ndarray = pixels.astype(np.float64)
    if encoding == "16UC1":
        metres = np.where(pixels == 0, np.nan, metres * 0.001)
    return metres


def convert(depth: np.ndarray, projection: Projection, settings: Settings) -> Scan:
    """The scan of a depth image in metres (height x width, NaN or Inf where there is no reading)."""
    height, width = depth.shape
    if width < 2:
        raise ConversionError("Depth image must be at least two pixels wide")
    center = projection.ray(projection.cx, projection.cy)
    angle_max = _angle_between(projection.ray(0, projection.cy), center)
    angle_min = -_angle_between(center, projection.ray(width - 1, projection.cy))
    increment = (angle_max - angle_min) / (width - 1)
    half = settings.scan_height // 2  # upstream's integer division
    if settings.scan_height < 1 or half > projection.cy or half > height - projection.cy:
        raise ConversionError(f"scan_height ( {settings.scan_height} pixels) is too large for the image height.")
    offset = int(projection.cy - half)
    rows = depth[offset:offset + settings.scan_height]
    columns = np.arange(width, dtype=np.float64)
    x_per_depth = (columns - projection.cx) / projection.fx
    angles = -np.arctan2(x_per_depth, 1.0)
    # C++'s truncation toward zero; the clip keeps the edge columns' rounding inside the scan
    index = np.clip(((angles - angle_min) / increment).astype(np.int64), 0, width - 1)
    valid = np.isfinite(rows)
    ranges_of = np.where(valid, rows * np.hypot(x_per_depth, 1.0), rows)  # NaN and Inf pass through
    ranges = np.full(width, np.nan, dtype=np.float64)
    within = valid & (ranges_of >= settings.range_min) & (ranges_of <= settings.range_max)
    beams = np.broadcast_to(index, rows.shape)
    # the nearest in-range reading of each beam
    np.fmin.at(ranges, beams[within], ranges_of[within])
    # a beam without one keeps an infinity it saw (upstream: Inf is worth more than NaN)
    infinite = np.isinf(rows)
    unset = np.isnan(ranges)
    for beam, value in zip(beams[infinite], ranges_of[infinite], strict=True):
        if unset[beam]:
            ranges[beam] = value
    return Scan(angle_min, angle_max, increment, ranges.astype(np.float32))
