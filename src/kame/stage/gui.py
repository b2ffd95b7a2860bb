"""The simulator's window: the walls, the robots and their laser hits, drawn with Qt (PySide6,
the optional `kame[gui]` extra), as Stage's window shows its world from above.

Rules: knows only frames (kame.stage.view), never ROS. It runs in a process of its own
(`python -m kame.stage.gui --window TITLE`), fed frames on its stdin by stageros, so that a
window that dies leaves the simulation running. The map fills the window, keeping its aspect,
north up; a robot is a disc with a line to its heading, outlined red while its bumper is
pressed; its laser's hits are dots. The window repaints only when a new frame came.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence

import numpy as np
from PySide6.QtCore import QPointF, QRectF
from PySide6.QtGui import QBrush, QColor, QImage, QPainter, QPaintEvent, QPen, QTransform
from PySide6.QtWidgets import QWidget

from kame.fed_window import show_fed_frames
from kame.stage.view import Frame, FrameDecoder

LARGEST_SIDE = 800  # pixels: the window's first size for the map's longer side
SMALLEST_SIDE = 300
ROBOT_FILL = QColor("#2f6fd6")
ROBOT_OUTLINE = QColor("#102040")
BUMPED_OUTLINE = QColor("#e01010")
HIT_COLOUR = QColor(230, 40, 40, 200)


def first_size(frame: Frame) -> tuple[int, int]:
    """The window's opening size: the map scaled so its longer side is LARGEST_SIDE pixels,
    its shorter side never under SMALLEST_SIDE."""
    scale = LARGEST_SIDE / max(frame.columns, frame.rows)
    width, height = frame.columns * scale, frame.rows * scale
    return max(SMALLEST_SIDE, round(width)), max(SMALLEST_SIDE, round(height))


def world_to_window(frame: Frame, width: int, height: int) -> QTransform:
    """World metres to window pixels: the map centred, as large as fits, north up."""
    map_width, map_height = frame.columns * frame.resolution, frame.rows * frame.resolution
    scale = min(width / map_width, height / map_height)
    left = (width - map_width * scale) / 2
    top = (height - map_height * scale) / 2
    transform = QTransform()
    transform.translate(left, top + map_height * scale)
    transform.scale(scale, -scale)
    transform.translate(-frame.origin[0], -frame.origin[1])
    return transform


def paint(painter: QPainter, frame: Frame, width: int, height: int) -> None:
    painter.fillRect(0, 0, width, height, QColor("#808080"))
    place = world_to_window(frame, width, height)
    image = QImage(frame.raster, frame.columns, frame.rows, frame.columns, QImage.Format.Format_Grayscale8)
    corner = place.map(QPointF(frame.origin[0], frame.origin[1] + frame.rows * frame.resolution))
    scale = place.m11()  # pixels per metre
    cell = frame.resolution * scale
    painter.drawImage(QRectF(corner.x(), corner.y(), frame.columns * cell, frame.rows * cell), image)
    painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
    dot = max(1.5, 0.03 * scale)
    for robot in frame.robots:
        if robot.hits:
            points = np.frombuffer(robot.hits, dtype=np.float32).reshape(-1, 2)
            painter.setPen(QPen(HIT_COLOUR, dot))
            painter.drawPoints([place.map(QPointF(float(x), float(y))) for x, y in points])
        centre = place.map(QPointF(robot.x, robot.y))
        radius = robot.radius * scale
        painter.setPen(QPen(BUMPED_OUTLINE if robot.stalled else ROBOT_OUTLINE, 3.0 if robot.stalled else 1.5))
        painter.setBrush(QBrush(ROBOT_FILL))
        painter.drawEllipse(centre, radius, radius)
        nose = QPointF(centre.x() + radius * math.cos(robot.theta), centre.y() - radius * math.sin(robot.theta))
        painter.setPen(QPen(QColor("white"), max(1.5, radius / 6)))
        painter.drawLine(centre, nose)
        painter.setPen(QPen(QColor("black")))
        painter.drawText(QPointF(centre.x() + radius + 3, centre.y() - radius - 3), robot.name)


def render(frame: Frame, width: int, height: int) -> QImage:
    """The picture the window would show at that size (needs a QGuiApplication)."""
    image = QImage(width, height, QImage.Format.Format_RGB32)
    painter = QPainter(image)
    paint(painter, frame, width, height)
    painter.end()
    return image


class WorldWindow(QWidget):
    def __init__(self, frame: Frame, title: str) -> None:
        super().__init__()
        self.frame = frame
        self.setWindowTitle(title)
        self.resize(*first_size(frame))
        self.frames_painted = 0

    def show_frame(self, frame: Frame) -> None:
        if frame is not self.frame:
            self.frame = frame
            self.update()

    def paintEvent(self, event: QPaintEvent) -> None:
        painter = QPainter(self)
        paint(painter, self.frame, self.width(), self.height())
        painter.end()
        self.frames_painted += 1


def show_frames(fd: int, title: str) -> int:
    """The window process: draw the frames (kame.stage.view) that arrive on `fd` (kame.fed_window
    says how it ends)."""
    return show_fed_frames(fd, FrameDecoder(), "stageros", lambda first: WorldWindow(first, title),
                           WorldWindow.show_frame)


def main(argv: Sequence[str]) -> int:
    """`python -m kame.stage.gui --window TITLE`: the window process."""
    if argv[:1] != ["--window"]:
        print("usage: python -m kame.stage.gui --window TITLE", file=sys.stderr)
        return 2
    return show_frames(sys.stdin.fileno(), argv[1] if len(argv) > 1 else "Stage")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
