"""turtlesim's window: draws world snapshots with Qt (PySide6, the optional `kame[gui]` extra).

Rules: knows only the world (kame.turtlesim.world's Snapshot), never ROS. It runs in a process
of its own (`python -m kame.turtlesim.gui --window TITLE IMAGES`), fed frames on its stdin by the
node, so that a window that dies (its X server gone, Qt aborting) leaves the simulation running. The background and
trails come from the world's raster as they are; the turtles are the PNG images of turtlesim's
images/ folder (kame's own drawings, head up), one per turtle as the world picked it, rotated
to its heading as turtlesim's TurtleFrame does: replace a file and that turtle changes. The
window is fixed at the world's size and repaints only when the snapshot changed.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from pathlib import Path

from PySide6.QtCore import QPointF
from PySide6.QtGui import QImage, QPainter, QPaintEvent, QTransform
from PySide6.QtWidgets import QWidget

from kame.fed_window import application, show_fed_frames
from kame.turtlesim.frame_codec import FrameDecoder
from kame.turtlesim.world import Snapshot, Sprite


class TurtleImageError(Exception):
    """The images folder has no turtle image Qt can read."""


def load_turtle_images(folder: Path) -> tuple[QImage, ...]:
    """The turtle images (PNG, head up, as turtlesim's images/ holds them), sorted by name;
    files Qt cannot read are left out."""
    images = tuple(image for image in (QImage(str(path)) for path in sorted(folder.glob("*.png")))
                   if not image.isNull())
    if not images:
        raise TurtleImageError(f"no turtle image (*.png) that Qt can read in {folder}")
    return images


def draw_turtle(painter: QPainter, sprite: Sprite, images: Sequence[QImage]) -> None:
    """One of the turtle images centred on the turtle's position, rotated from head-up to theta
    (as turtlesim's TurtleFrame places them).

    The transform is set whole (setTransform) and reset after, never save()/restore(): every
    call of a void Qt method costs PySide6 6.12.0 a reference to None, and save/restore is two
    more of them per turtle per frame (see paint())."""
    image = images[sprite.image % len(images)]
    place = QTransform()
    place.translate(sprite.x, sprite.y)
    place.rotate(90.0 - math.degrees(sprite.theta))  # from head-up; window y points down, so CCW is negative
    painter.setTransform(place)
    painter.drawImage(QPointF(-image.width() / 2, -image.height() / 2), image)
    painter.resetTransform()


def paint(painter: QPainter, snapshot: Snapshot, images: Sequence[QImage]) -> None:
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
    painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform, True)
    for sprite in snapshot.turtles:
        draw_turtle(painter, sprite, images)


def render(snapshot: Snapshot, images: Sequence[QImage]) -> QImage:
    """The frame the window would show (needs a QGuiApplication)."""
    image = QImage(snapshot.width, snapshot.height, QImage.Format.Format_RGB32)
    painter = QPainter(image)
    paint(painter, snapshot, images)
    painter.end()
    return image


class TurtleWindow(QWidget):
    def __init__(self, snapshot: Snapshot, title: str, images: Sequence[QImage]) -> None:
        super().__init__()
        self.snapshot = snapshot
        self.images = images
        self.setWindowTitle(title)
        self.setFixedSize(snapshot.width, snapshot.height)
        self.frames_painted = 0

    def show_snapshot(self, snapshot: Snapshot) -> None:
        if snapshot.version != self.snapshot.version or snapshot is not self.snapshot:
            self.snapshot = snapshot
            self.update()

    def paintEvent(self, event: QPaintEvent) -> None:
        painter = QPainter(self)
        paint(painter, self.snapshot, self.images)
        painter.end()
        self.frames_painted += 1


def show_frames(fd: int, title: str, images_folder: Path) -> int:
    """The window process: draw the frames (kame.turtlesim.frame_codec) that arrive on `fd`
    with the turtle images of `images_folder` (kame.fed_window says how it ends)."""
    try:
        images = load_turtle_images(images_folder)
    except TurtleImageError as e:
        print(f"turtlesim_node: {e}", file=sys.stderr, flush=True)
        return 1
    return show_fed_frames(fd, FrameDecoder(), "turtlesim_node", lambda first: TurtleWindow(first, title, images),
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
    """`python -m kame.turtlesim.gui`: the probe; `... --window TITLE IMAGES`: the window process."""
    if argv[:1] == ["--window"] and len(argv) == 3:
        return show_frames(sys.stdin.fileno(), argv[1], Path(argv[2]))
    return probe()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
