"""image_view's window (Qt): draws the model's newest picture, saves it on a right click or the
`s` key. The node wakes it through `frame_ready` (a queued signal) only when it had nothing
waiting, so a fast camera costs one redraw per turn of the window's loop."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QImage, QKeyEvent, QMouseEvent, QPixmap, QResizeEvent
from PySide6.QtWidgets import QLabel, QSizePolicy, QVBoxLayout, QWidget

from kame.camera.pictures import to_rgb
from kame.camera.viewer_model import ViewerModel


def qimage(picture: np.ndarray) -> QImage:
    rgb = to_rgb(picture)
    height, width = rgb.shape[:2]
    if rgb.ndim == 2:
        return QImage(rgb.tobytes(), width, height, width, QImage.Format.Format_Grayscale8).copy()
    return QImage(rgb.tobytes(), width, height, width * 3, QImage.Format.Format_RGB888).copy()


class ImageViewWindow(QWidget):
    frame_ready = Signal()

    def __init__(self, model: ViewerModel, take: Callable[[], np.ndarray | None], save: Callable[[], None],
                 warn: Callable[[str], None]) -> None:
        super().__init__()
        self.model = model
        self.take = take
        self.save = save
        self.warn = warn
        self.setWindowTitle(model.settings.title)
        self.picture = QLabel()
        self.picture.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.picture.setMinimumSize(32, 24)
        if not model.settings.autosize:
            self.picture.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Ignored)
            self.resize(640, 480)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.picture)
        self.image: QImage | None = None
        self.frame_ready.connect(self.take_frame)

    def take_frame(self) -> None:
        picture = self.take()
        if picture is None:
            return
        self.image = qimage(picture)
        if self.model.settings.autosize and self.size() != self.image.size():
            self.picture.setFixedSize(self.image.size())
            self.adjustSize()
        self._draw()

    def _draw(self) -> None:
        if self.image is None:
            return
        if self.model.settings.autosize:
            self.picture.setPixmap(QPixmap.fromImage(self.image))
        else:
            self.picture.setPixmap(QPixmap.fromImage(self.image).scaled(
                self.picture.size(), Qt.AspectRatioMode.KeepAspectRatio, Qt.TransformationMode.SmoothTransformation))

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        self._draw()

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.RightButton:
            self.save()
        elif event.button() == Qt.MouseButton.LeftButton:
            warning = self.model.left_click()
            if warning is not None:
                self.warn(warning)
        super().mousePressEvent(event)

    def keyPressEvent(self, event: QKeyEvent) -> None:
        if event.text() == "s":
            self.save()
        super().keyPressEvent(event)
