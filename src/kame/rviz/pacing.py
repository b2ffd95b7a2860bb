"""When rviz's window takes its frames: a timer at the Frame Rate (tf moves frames with no message,
and a display's lifetimes end), and soon after the source has decoded a message, so a message
reaching an idle window is drawn within milliseconds instead of waiting for the next tick (up
to a whole period at 30 fps: 33 ms of its latency). At most one frame that took messages per
period whatever arrives: a message due sooner waits for that period's end, and every message
waiting then is taken by that one frame (the newest of each topic). The ticks between, which
find nothing new and paint nothing, hold no message back."""

from __future__ import annotations

import math
import time
from collections.abc import Callable

from PySide6.QtCore import QObject, QTimer, Signal


class FramePacer(QObject):
    # emitted from the source's decoding thread: queued into the window's thread
    ready = Signal()

    def __init__(self, parent: QObject, frame: Callable[[], bool], rate: int) -> None:
        """`frame` takes a frame; True when it took messages."""
        super().__init__(parent)
        self._frame = frame
        self.timer = QTimer(self)  # the frame rate's tick; stopped, the window draws only when told to
        self.timer.timeout.connect(self._tick)
        self._soon = QTimer(self)
        self._soon.setSingleShot(True)
        self._soon.timeout.connect(self._tick)
        self._last = -math.inf  # monotonic time of the last frame that took messages
        self.ready.connect(self._message_ready)
        self.set_rate(rate)
        self.timer.start()

    def set_rate(self, rate: int) -> None:
        self.timer.setInterval(max(1, 1000 // max(1, rate)))

    def stop(self) -> None:
        self.timer.stop()
        self._soon.stop()

    def _tick(self) -> None:
        self._soon.stop()
        started = time.monotonic()
        if self.timer.isActive():  # the next tick a whole period after this frame, however it came
            self.timer.start()
        if self._frame():
            self._last = started

    def _message_ready(self) -> None:
        if not self.timer.isActive() or self._soon.isActive():  # stopped, or a frame is already due
            return
        wait = self._last + self.timer.interval() / 1000 - time.monotonic()
        self._soon.start(math.ceil(max(0.0, wait) * 1000))
