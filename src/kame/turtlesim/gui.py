"""turtlesim's window: draws world snapshots with Qt (PySide6, the optional `kame[gui]` extra).

Rules: knows only the world (kame.turtlesim.world's Snapshot), never ROS. It runs in a process
of its own (`python -m kame.turtlesim.gui --window TITLE`), fed frames on its stdin by the
node, so that a window that dies (its X server gone, Qt aborting) leaves the simulation running. The background and
trails come from the world's raster as they are; the turtles are kame's own drawings, made
with QPainter (no image files), one of IMAGE_COUNT shell colours per turtle, facing +x at
theta 0. The window is fixed at the world's size and repaints only when the snapshot changed.
"""

from __future__ import annotations

import functools
import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QImage, QPainter, QPaintEvent, QPen, QPolygonF, QTransform
from PySide6.QtWidgets import QWidget

from kame.fed_window import application, show_fed_frames
from kame.turtlesim.frame_codec import FrameDecoder
from kame.turtlesim.world import IMAGE_COUNT, Snapshot, Sprite

# (shell, shell pattern, skin): one per turtle image
PALETTE: tuple[tuple[str, str, str], ...] = (
    ("#2e8b57", "#1f5f3b", "#9acd32"),
    ("#8b5a2b", "#5c3a1a", "#c8b560"),
    ("#4169e1", "#27408b", "#87cefa"),
    ("#b22222", "#7a1616", "#f4a460"),
    ("#6a5acd", "#483d8b", "#d8bfd8"),
    ("#ff8c00", "#b35f00", "#ffd27f"),
    ("#008b8b", "#005f5f", "#7fffd4"),
    ("#556b2f", "#3a4a20", "#bdb76b"),
)
assert len(PALETTE) == IMAGE_COUNT


@dataclass(frozen=True)
class _Look:
    """One turtle image's pens, brushes and outlines, made once: a frame only places them."""
    outline: QPen
    no_pen: QPen
    skin: QBrush
    eyes: QBrush
    shell: QBrush
    pattern: QBrush
    tail: QPolygonF
    hexagon: QPolygonF


@functools.cache
def _look(image: int) -> _Look:
    shell, pattern, skin = (QColor(c) for c in PALETTE[image % len(PALETTE)])
    return _Look(
        outline=QPen(QColor("#1a1a1a"), 1.2), no_pen=QPen(Qt.PenStyle.NoPen), skin=QBrush(skin),
        eyes=QBrush(QColor("#111111")), shell=QBrush(shell), pattern=QBrush(pattern),
        tail=QPolygonF([QPointF(-13.0, -2.5), QPointF(-20.0, 0.0), QPointF(-13.0, 2.5)]),
        hexagon=QPolygonF([QPointF(5.0 * math.cos(k * math.pi / 3), 5.0 * math.sin(k * math.pi / 3))
                           for k in range(6)]))


def draw_turtle(painter: QPainter, sprite: Sprite) -> None:
    """A top view of a turtle about 45 px long, centred on its position, heading theta.

    The transform is set whole (setTransform) and reset after, never save()/restore(): every
    call of a void Qt method costs PySide6 6.12.0 a reference to None, and save/restore is two
    more of them per turtle per frame (see paint())."""
    look = _look(sprite.image)
    place = QTransform()
    place.translate(sprite.x, sprite.y)
    place.rotate(-math.degrees(sprite.theta))  # window y points down: CCW is negative
    painter.setTransform(place)
    painter.setPen(look.outline)
    painter.setBrush(look.skin)
    for fx, fy in ((9.0, 11.0), (9.0, -11.0), (-9.0, 11.0), (-9.0, -11.0)):  # flippers
        painter.drawEllipse(QPointF(fx, fy), 5.0, 3.5)
    painter.drawPolygon(look.tail)
    painter.drawEllipse(QPointF(16.0, 0.0), 6.0, 5.0)  # head
    painter.setPen(look.no_pen)
    painter.setBrush(look.eyes)
    painter.drawEllipse(QPointF(19.0, 2.2), 1.1, 1.1)
    painter.drawEllipse(QPointF(19.0, -2.2), 1.1, 1.1)
    painter.setPen(look.outline)
    painter.setBrush(look.shell)
    painter.drawEllipse(QRectF(-14.0, -11.0, 28.0, 22.0))  # shell
    painter.setPen(look.no_pen)
    painter.setBrush(look.pattern)
    painter.drawPolygon(look.hexagon)
    for k in range(6):
        a = k * math.pi / 3 + math.pi / 6
        painter.drawEllipse(QPointF(9.0 * math.cos(a), 7.0 * math.sin(a)), 2.4, 2.0)
    painter.resetTransform()


def paint(painter: QPainter, snapshot: Snapshot) -> None:
    """One frame: the world's raster as it is (QImage wraps the snapshot's bytes, no copy), then
    the turtles.

    PySide6-Essentials 6.12.0 decrements None's reference count on every call of a method that
    returns void (QPainter's setPen, drawEllipse, ..., QWidget.update, QTimer.start alike): on
    Python 3.10/3.11, where None is not immortal, a process aborts with `Fatal Python error:
    none_dealloc` after some thousands of calls, whatever the calls are. No way of painting
    avoids that, so pyproject.toml keeps 6.12.0 out and the node's start-up probe refuses a
    binding that loses references (the window stays shut, the simulation runs)."""
    image = QImage(snapshot.pixels, snapshot.width, snapshot.height, snapshot.width * 3,
                   QImage.Format.Format_RGB888)
    painter.drawImage(0, 0, image)
    painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
    for sprite in snapshot.turtles:
        draw_turtle(painter, sprite)


def render(snapshot: Snapshot) -> QImage:
    """The frame the window would show (needs a QGuiApplication)."""
    image = QImage(snapshot.width, snapshot.height, QImage.Format.Format_RGB32)
    painter = QPainter(image)
    paint(painter, snapshot)
    painter.end()
    return image


class TurtleWindow(QWidget):
    def __init__(self, snapshot: Snapshot, title: str) -> None:
        super().__init__()
        self.snapshot = snapshot
        self.setWindowTitle(title)
        self.setFixedSize(snapshot.width, snapshot.height)
        self.frames_painted = 0

    def show_snapshot(self, snapshot: Snapshot) -> None:
        if snapshot.version != self.snapshot.version or snapshot is not self.snapshot:
            self.snapshot = snapshot
            self.update()

    def paintEvent(self, event: QPaintEvent) -> None:
        painter = QPainter(self)
        paint(painter, self.snapshot)
        painter.end()
        self.frames_painted += 1


def show_frames(fd: int, title: str) -> int:
    """The window process: draw the frames (kame.turtlesim.frame_codec) that arrive on `fd`
    (kame.fed_window says how it ends)."""
    return show_fed_frames(fd, FrameDecoder(), "turtlesim_node", lambda first: TurtleWindow(first, title),
                           TurtleWindow.show_snapshot)


def references_lost_to_none(calls: int = 200) -> int:
    """How many references to None `calls` calls of a void Qt method lose (0 on a sound binding;
    always 0 on Python 3.12+, where None is immortal and cannot be freed)."""
    point = QPointF(0.0, 0.0)
    before = sys.getrefcount(None)
    for _ in range(calls):
        point.setX(1.0)
    return before - sys.getrefcount(None)


def probe() -> int:
    """The node's start-up check, run in a child process (Qt aborts a process whose platform
    plugin cannot load): can this binding draw for hours, and can Qt open its platform?"""
    from PySide6 import __version__

    from kame.turtlesim.window_probe import PROBE_LEAK, PROBE_OK

    if references_lost_to_none() > 0:
        print(f"{PROBE_LEAK} {__version__}", flush=True)
        return 2
    app = application()
    print(f"{PROBE_OK} {app.platformName()}", flush=True)
    return 0


def main(argv: Sequence[str]) -> int:
    """`python -m kame.turtlesim.gui`: the probe; `... --window TITLE`: the window process."""
    if argv[:1] == ["--window"]:
        return show_frames(sys.stdin.fileno(), argv[1] if len(argv) > 1 else "TurtleSim")
    return probe()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
