"""The window process of a simulation (turtlesim, stageros): frames read from a pipe, the
newest drawn by a Qt window.

Rules: knows frames only through its caller's decoder and window; never ROS. The first frame
opens the window; each read hands the newest whole frame to it. EOF (the simulation is gone or
closed us) and the user closing the window end it with status 0, a broken frame with status 3,
and Qt itself ends it when its display goes away.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from typing import TypeVar

from PySide6.QtCore import QSocketNotifier
from PySide6.QtWidgets import QApplication, QWidget

from kame.protocol.latest_frame import LatestFrameDecoder

F = TypeVar("F")
W = TypeVar("W", bound=QWidget)
READ_SIZE = 1 << 20


def application(program: str | None = None) -> QApplication:
    """This process's QApplication; `program` names it to the window system (WM_CLASS)."""
    app = QApplication.instance()
    if isinstance(app, QApplication):
        return app
    return QApplication([program] if program else sys.argv[:1])


def show_fed_frames(fd: int, decoder: LatestFrameDecoder[F], program: str, open_window: Callable[[F], W],
                    show: Callable[[W, F], None]) -> int:
    """Read frames from `fd` into `decoder`; `open_window(first)` makes the window, `show(window,
    frame)` hands it each newer one. Returns the process's exit status."""
    while (first := decoder.latest()) is None:
        data = os.read(fd, READ_SIZE)
        if not data:
            return 0
        decoder.feed(data)
    app = application(program)
    window = open_window(first)
    window.show()

    def on_readable() -> None:
        try:
            data = os.read(fd, READ_SIZE)
            if not data:
                app.exit(0)
                return
            decoder.feed(data)
        except (OSError, decoder.error) as exc:
            print(f"{program} window: {exc}", file=sys.stderr, flush=True)
            app.exit(3)
            return
        latest = decoder.latest()
        if latest is not None:
            show(window, latest)

    notifier = QSocketNotifier(fd, QSocketNotifier.Type.Read)
    notifier.activated.connect(on_readable)
    return int(app.exec())
