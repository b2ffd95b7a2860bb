"""The panels of rviz's Image and Camera displays: one dock each, named after its display,
showing the newest image scaled to fit; a Camera panel draws the 3-D scene over the image as
the camera sees it (kame.rviz.sensors.Camera.project), at the display's Overlay Alpha."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from PySide6.QtCore import QPointF, Qt
from PySide6.QtGui import QColor, QImage, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import QDockWidget, QMainWindow, QWidget

from kame.rviz.display import Display
from kame.rviz.scene import Scene
from kame.rviz.sensors import Camera, Image

MAX_OVERLAY_TRIANGLES = 20_000  # beyond this the overlay draws the first ones only: painting is per triangle


def decode_compressed(data: bytes) -> np.ndarray:
    """A CompressedImage's JPEG or PNG bytes as H x W x 4 RGBA (Qt decodes them, as
    rqt_image_view does); ValueError when Qt cannot."""
    image = QImage.fromData(data)
    if image.isNull():
        raise ValueError("not a JPEG or PNG image Qt can read")
    image = image.convertToFormat(QImage.Format.Format_RGBA8888)
    rows = np.frombuffer(image.constBits(), np.uint8, image.sizeInBytes()).reshape(image.height(), -1)
    pixels: np.ndarray = rows[:, :4 * image.width()].reshape(image.height(), image.width(), 4).copy()
    return pixels


class ImagePanel(QWidget):
    def __init__(self, display: Image) -> None:
        super().__init__()
        self.display = display
        self.painted: Callable[[], None] | None = None  # after each paint: images reach the screen here
        self.scene = Scene()
        self.setMinimumSize(160, 120)

    def show_scene(self, scene: Scene) -> None:
        self.scene = scene
        self.update()

    def placement(self, width: int, height: int) -> tuple[float, float, float]:
        """Where an image of that size is drawn: left, top and pixels of the panel per image pixel."""
        scale = min(self.width() / width, self.height() / height)
        return (self.width() - width * scale) / 2, (self.height() - height * scale) / 2, scale

    def paintEvent(self, event: object) -> None:
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor(0, 0, 0))
        pixels = self.display.pixels
        if pixels is None:
            painter.setPen(QColor(200, 200, 200))
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, "No Image")
            painter.end()
            return
        height, width = pixels.shape[:2]
        left, top, scale = self.placement(width, height)
        image = QImage(pixels.data, width, height, 4 * width, QImage.Format.Format_RGBA8888)
        painter.save()
        painter.translate(left, top)
        painter.scale(scale, scale)
        painter.drawImage(0, 0, image)
        painter.restore()
        if isinstance(self.display, Camera):
            self._overlay(painter, self.display, left, top, scale)
        painter.end()
        if self.painted is not None:
            self.painted()

    def _overlay(self, target: QPainter, camera: Camera, left: float, top: float, scale: float) -> None:
        """The scene drawn opaque on a layer of its own, laid over the image at Overlay Alpha (as
        rviz blends its rendered scene): overlapping faces do not add up. No antialiasing: it would
        show the seams between a surface's triangles."""
        layer = QImage(self.width(), self.height(), QImage.Format.Format_ARGB32_Premultiplied)
        layer.fill(Qt.GlobalColor.transparent)
        painter = QPainter(layer)
        for batch in (batch.unindexed() for batch in self.scene.batches):
            pixels, in_front = camera.project(batch.vertices)
            spots = pixels * scale + (left, top)
            colors = np.clip(batch.float_colors() * 255, 0, 255).astype(int).tolist()
            if batch.kind == "triangles":
                painter.setPen(Qt.PenStyle.NoPen)
                count = min(len(spots) // 3, MAX_OVERLAY_TRIANGLES)
                for i in range(0, 3 * count, 3):
                    if in_front[i:i + 3].all():
                        painter.setBrush(QColor(*colors[i]))
                        painter.drawPolygon(QPolygonF([QPointF(*spots[i + k]) for k in range(3)]))
            elif batch.kind == "lines":
                for i in range(0, len(spots) - 1, 2):
                    if in_front[i] and in_front[i + 1]:
                        painter.setPen(QPen(QColor(*colors[i]), batch.size))
                        painter.drawLine(QPointF(*spots[i]), QPointF(*spots[i + 1]))
            else:
                painter.setPen(Qt.PenStyle.NoPen)
                for spot, color, front in zip(spots, colors, in_front, strict=True):
                    if not front:
                        continue
                    painter.setBrush(QColor(*color))
                    painter.drawEllipse(QPointF(*spot), batch.size / 2, batch.size / 2)
        painter.end()
        target.setOpacity(camera.number("Overlay Alpha", 0.5))
        target.drawImage(0, 0, layer)
        target.setOpacity(1.0)


class ImagePanels:
    """A dock per Image or Camera display of the window, made and removed as displays come and go."""

    def __init__(self, window: QMainWindow) -> None:
        self.window = window
        self.docks: dict[int, tuple[QDockWidget, ImagePanel]] = {}
        self.painted: Callable[[], None] | None = None  # each panel's paint (rviz's KAME_RVIZ_STATS)

    def sync(self, displays: list[Display], scene: Scene) -> None:
        shown = {id(d): d for d in displays if isinstance(d, Image) and d.enabled}
        for key in [k for k in self.docks if k not in shown]:
            dock, _ = self.docks.pop(key)
            self.window.removeDockWidget(dock)
            dock.deleteLater()
        for key, display in shown.items():
            if key not in self.docks:
                assert isinstance(display, Image)
                panel = ImagePanel(display)
                dock = QDockWidget(display.name, self.window)
                dock.setWidget(panel)
                self.window.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, dock)
                self.docks[key] = (dock, panel)
            self.docks[key][1].painted = self.painted
            self.docks[key][1].show_scene(scene)

    def panel(self, display: Display) -> ImagePanel | None:
        found = self.docks.get(id(display))
        return found[1] if found is not None else None
