"""The turtles' drawing surface: an RGB raster the size of the window, trails painted into it.

Rules: pure (no clock, no I/O, no GUI); coordinates are pixels in the window's frame (x right,
y down). A line is painted as Qt paints an aliased pen with square caps: every pixel whose
integer point lies in the stroke's rectangle (width across, half a width beyond each end).
Each row of a line is one slice assignment, so long and wide lines stay cheap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Rgb:
    r: int
    g: int
    b: int

    def __bytes__(self) -> bytes:
        return bytes((self.r & 0xFF, self.g & 0xFF, self.b & 0xFF))


class Canvas:
    """A width x height RGB888 raster, rows top to bottom. `revision` counts the changes, so a
    reader can tell that its copy of the pixels is still the picture."""

    def __init__(self, width: int, height: int, fill: Rgb) -> None:
        self.width = width
        self.height = height
        self.pixels = bytearray(bytes(fill) * (width * height))
        self.revision = 0

    def fill(self, color: Rgb) -> None:
        self.pixels[:] = bytes(color) * (self.width * self.height)
        self.revision += 1

    def pixel(self, x: int, y: int) -> Rgb:
        if not (0 <= x < self.width and 0 <= y < self.height):
            return Rgb(0, 0, 0)  # QImage::pixel outside the image
        i = (y * self.width + x) * 3
        return Rgb(self.pixels[i], self.pixels[i + 1], self.pixels[i + 2])

    def line(self, x0: float, y0: float, x1: float, y1: float, color: Rgb, width: int) -> None:
        """Paint a line of `width` pixels (at least 1) from (x0, y0) to (x1, y1)."""
        if not all(math.isfinite(v) for v in (x0, y0, x1, y1)):
            return
        h = max(width, 1) / 2.0
        dx, dy = x1 - x0, y1 - y0
        length = math.hypot(dx, dy)
        ux, uy = (dx / length, dy / length) if length > 1e-12 else (1.0, 0.0)
        nx, ny = -uy, ux
        ys = [y0 + uy * a + ny * b for a in (-h, length + h) for b in (-h, h)]
        top = max(0, math.ceil(min(ys) - 1e-9))
        bottom = min(self.height - 1, math.floor(max(ys) + 1e-9))
        ink = bytes(color)
        self.revision += 1
        # The stroke: -h <= n.(p - p0) <= h and -h <= u.(p - p0) <= length + h.
        limits = ((nx, ny, -h, h), (ux, uy, -h, length + h))
        for row in range(top, bottom + 1):
            lo, hi = -math.inf, math.inf
            for a, b, c_lo, c_hi in limits:
                rest = b * (row - y0)
                if abs(a) < 1e-12:
                    if not (c_lo - 1e-9 <= rest <= c_hi + 1e-9):
                        lo, hi = 1.0, 0.0
                        break
                    continue
                t1, t2 = x0 + (c_lo - rest) / a, x0 + (c_hi - rest) / a
                lo, hi = max(lo, min(t1, t2)), min(hi, max(t1, t2))
            if hi < lo:
                continue
            first = max(0, math.ceil(lo - 1e-9))
            last = min(self.width - 1, math.floor(hi + 1e-9))
            if first <= last:
                start = (row * self.width + first) * 3
                self.pixels[start:start + (last - first + 1) * 3] = ink * (last - first + 1)
