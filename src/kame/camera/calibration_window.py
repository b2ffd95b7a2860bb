"""camera_calibration's window (Qt): shows the display the node renders (calibration_display),
at its own size, and hands clicks and keys back to the node. The node wakes it through
`display_ready` (a queued signal) when a new display waits."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QImage, QKeyEvent, QMouseEvent, QPixmap
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget


class CalibrationWindow(QWidget):
    display_ready = Signal()

    def __init__(self, take: Callable[[], np.ndarray | None], click: Callable[[int, int], None],
                 key: Callable[[str], None]) -> None:
        super().__init__()
        self.setWindowTitle("display")
        self.take = take
        self.click = click
        self.key = key
        self.picture = QLabel()
        self.picture.setAlignment(Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignTop)
        self.picture.setMinimumSize(740, 480)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.picture)
        self.shown: QImage | None = None
        self.display_ready.connect(self.take_display)

    def take_display(self) -> None:
        display = self.take()
        if display is None:
            return
        height, width = display.shape[:2]
        rgb = np.ascontiguousarray(display[..., ::-1])
        self.shown = QImage(rgb.tobytes(), width, height, width * 3, QImage.Format.Format_RGB888).copy()
        if self.picture.size().toTuple() != (width, height):
            self.picture.setFixedSize(width, height)
            self.adjustSize()
        self.picture.setPixmap(QPixmap.fromImage(self.shown))

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            point = self.picture.mapFrom(self, event.position().toPoint())
            self.click(point.x(), point.y())
        super().mousePressEvent(event)

    def keyPressEvent(self, event: QKeyEvent) -> None:
        if event.key() == Qt.Key.Key_Escape:
            self.key("\x1b")
        elif event.text():
            self.key(event.text())
        super().keyPressEvent(event)
