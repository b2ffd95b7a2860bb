"""The installed Qt binding keeps None alive through Python paint overrides: PySide6 6.12.0 on
Python < 3.12 drops a reference per call and aborts the process after a few thousand frames
(pyproject excludes it; this test catches a binding with the same fault)."""

from __future__ import annotations

import sys

import pytest

pytest.importorskip("PySide6.QtWidgets")


@pytest.mark.skipif(sys.version_info >= (3, 12), reason="None is immortal from Python 3.12 on")
def test_painting_from_python_does_not_leak_none(qapp) -> None:  # type: ignore[no-untyped-def]
    from PySide6.QtCore import QRectF
    from PySide6.QtGui import QImage, QPainter, QPaintEvent
    from PySide6.QtWidgets import QGraphicsRectItem, QGraphicsScene, QWidget

    class Painted(QWidget):
        def paintEvent(self, event: QPaintEvent) -> None:
            painter = QPainter(self)
            painter.drawRect(0, 0, 5, 5)
            painter.end()

    class Item(QGraphicsRectItem):
        def paint(self, painter: QPainter, *args: object) -> None:
            painter.drawRect(self.boundingRect())

    widget = Painted()
    widget.resize(20, 20)
    scene = QGraphicsScene()
    scene.addItem(Item(QRectF(0, 0, 10, 10)))
    image = QImage(20, 20, QImage.Format.Format_RGB32)
    before = sys.getrefcount(None)
    for _ in range(300):
        widget.grab()
        painter = QPainter(image)
        scene.render(painter)
        painter.end()
    assert sys.getrefcount(None) > before - 100  # 6.12.0 loses about 1,000 here
