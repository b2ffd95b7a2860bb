"""rqt_image_view's pixels (pure): a sensor_msgs/Image's bytes as rows of 8-bit pixels a window
can draw, for the encodings rqt_image_view shows.

Rules: rgb8/rgba8 are drawn as they are; bgr8/bgra8 have their channels swapped; mono8 is
grey; mono16 keeps its high byte; depth images (16UC1, millimetres, and 32FC1, metres) are
scaled from their smallest to their largest finite non-zero value onto 0..255, with unknown
depth (0, NaN, inf) black, as rqt_image_view's display of depth does. Rows may be padded
(`step` beyond width * pixel size); 16- and 32-bit values honour `is_bigendian`. A message
whose sizes do not add up is an ImageError naming what is wrong, never a crash.
"""

from __future__ import annotations

import numpy as np

# encoding -> (bytes per pixel, channels shown)
ENCODINGS = {"rgb8": (3, 3), "bgr8": (3, 3), "rgba8": (4, 4), "bgra8": (4, 4), "mono8": (1, 1), "8UC1": (1, 1),
             "mono16": (2, 1), "16UC1": (2, 1), "32FC1": (4, 1)}


class ImageError(ValueError):
    """An encoding not shown here, or sizes that do not fit the data."""


def to_display(encoding: str, width: int, height: int, step: int, data: bytes, is_bigendian: bool = False
               ) -> np.ndarray:
    """(height, width, channels) uint8: 1 channel grey, 3 RGB, 4 RGBA."""
    if encoding not in ENCODINGS:
        raise ImageError(f"encoding {encoding!r} is not shown (only {', '.join(ENCODINGS)})")
    size, channels = ENCODINGS[encoding]
    if width <= 0 or height <= 0:
        raise ImageError(f"an empty image ({width}x{height})")
    if step < width * size:
        raise ImageError(f"step {step} is less than width {width} x {size} bytes")
    if len(data) < step * height:
        raise ImageError(f"{len(data)} bytes of data, {step * height} needed for {height} rows of {step}")
    rows = np.frombuffer(data, np.uint8, step * height).reshape(height, step)[:, :width * size]
    if size == 1:
        grey: np.ndarray = rows.reshape(height, width, 1).copy()
        return grey
    if channels in (3, 4):
        pixels = rows.reshape(height, width, channels)
        order = {"bgr8": [2, 1, 0], "bgra8": [2, 1, 0, 3]}.get(encoding)
        colour: np.ndarray = np.ascontiguousarray(pixels[..., order] if order is not None else pixels)
        return colour
    kind = {"mono16": "u2", "16UC1": "u2", "32FC1": "f4"}[encoding]
    values: np.ndarray = rows.copy().view(np.dtype(kind).newbyteorder(">" if is_bigendian else "<"))
    values = values.reshape(height, width)
    if encoding == "mono16":
        high: np.ndarray = (values >> 8).astype(np.uint8).reshape(height, width, 1)
        return high
    return scale_depth(values.astype(np.float64)).reshape(height, width, 1)


def scale_depth(depth: np.ndarray) -> np.ndarray:
    known = np.isfinite(depth) & (depth != 0)
    out = np.zeros(depth.shape, np.uint8)
    if not known.any():
        return out
    low, high = float(depth[known].min()), float(depth[known].max())
    span = high - low
    scaled = (depth[known] - low) * (255.0 / span) if span > 0 else np.full(int(known.sum()), 255.0)
    out[known] = np.clip(np.rint(scaled), 0, 255).astype(np.uint8)
    return out

