"""kame's test camera (`video_device:=testsrc`): a moving test pattern with a frame counter.

The picture is eight colour bars (white, yellow, cyan, green, magenta, red, blue, black) that
scroll left by `SCROLL` pixels a frame, over a grey ramp in the bottom quarter, with the frame's
number written in a black box at the top left. Frame n is always the same picture, so tests can
tell frames apart and read which one they got (`frame_number_box`).
"""

from __future__ import annotations

import numpy as np

from kame.camera.opencv import cv2_for

BARS = np.array([(255, 255, 255), (255, 255, 0), (0, 255, 255), (0, 255, 0),
                 (255, 0, 255), (255, 0, 0), (0, 0, 255), (0, 0, 0)], np.uint8)
SCROLL = 4  # pixels a frame


class TestPattern:
    """Frames of one size, made on request: `frame(n)` is frame n's RGB picture."""

    __test__ = False  # not a pytest test class, despite its name

    def __init__(self, width: int, height: int) -> None:
        if width < 8 or height < 8:
            raise ValueError(f"a test pattern of {width}x{height}: 8x8 at least")
        self.width, self.height = width, height
        self._cv2 = cv2_for("the test pattern (video_device:=testsrc)")
        columns = (np.arange(2 * width) * len(BARS) // width) % len(BARS)
        bars = BARS[columns]  # two periods wide, so any scroll offset is one slice
        ramp = np.repeat(np.tile(np.linspace(0, 255, width).astype(np.uint8), 2)[:, None], 3, axis=1)
        ramp_top = height - height // 4
        self._band = np.empty((height, 2 * width, 3), np.uint8)
        self._band[:ramp_top] = bars[None]
        self._band[ramp_top:] = ramp[None]
        self._scale = max(height / 480, 0.5)

    def frame(self, number: int) -> np.ndarray:
        offset = (number * SCROLL) % self.width
        picture = np.ascontiguousarray(self._band[:, offset:offset + self.width])
        x0, y0, x1, y1 = frame_number_box(self.width, self.height)
        picture[y0:y1, x0:x1] = 0
        self._cv2.putText(picture, f"{number:06d}", (x0 + 4, y1 - int(8 * self._scale)),
                          self._cv2.FONT_HERSHEY_SIMPLEX, self._scale, (255, 255, 255), max(1, int(2 * self._scale)))
        return picture


def frame_number_box(width: int, height: int) -> tuple[int, int, int, int]:
    """Where the counter is drawn, (x0, y0, x1, y1): black with white digits."""
    scale = max(height / 480, 0.5)
    return 0, 0, min(width, int(150 * scale)), min(height, int(40 * scale))
