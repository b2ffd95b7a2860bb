"""rviz's window on a live graph, as `rviz -d FILE` opens it (its node, tf, subscriptions), on
whatever display Qt is given (a private Xvfb in the tests). Every 200 ms it prints where the TF
display puts each frame it names on the command line, whether the view's pixel there is drawn,
and each display's status; with --click it also uses the Publish Point tool on the ground point
(X, Y) of the fixed frame each time (its subscriber may connect after the first click); with
--colour it also counts the view's pixels of that colour, lit or not (a display's, to see it
drawn); with --drag it drags once, with the Interact tool, from the fixed frame's ground point
(X0, Y0) to (X1, Y1), once something of the --colour is drawn.

    python -m tests.rviz.live_child MASTER_URI FILE.rviz FRAME... [--click X,Y] [--colour R,G,B]
        [--drag X0,Y0,X1,Y1]
"""

from __future__ import annotations

import sys

import numpy as np
from PySide6.QtCore import QPoint, Qt, QTimer
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication

from kame.node.node import Node, NodeConfig
from kame.rviz import config
from kame.rviz.source import RvizSource
from kame.rviz.window import INTERACT, PUBLISH_POINT, RvizWindow


def _shades_of(pixels: np.ndarray, colour: tuple[int, ...]) -> int:
    """How many pixels are `colour` as the headlight shades it: k * colour for k in 0.3..1."""
    wanted = np.asarray(colour, dtype=float)
    found = pixels.astype(float)
    k = found @ wanted / float(wanted @ wanted)
    close = np.all(np.abs(found - k[:, None] * wanted) <= 3, axis=1)
    return int((close & (k >= 0.3) & (k <= 1.01)).sum())


def main() -> int:
    args = sys.argv[1:]
    click = None
    if "--click" in args:
        at = args.index("--click")
        click = np.array([float(v) for v in args[at + 1].split(",")] + [0.0])
        del args[at:at + 2]
    colour = None
    if "--colour" in args:
        at = args.index("--colour")
        colour = tuple(int(v) for v in args[at + 1].split(","))
        del args[at:at + 2]
    drag = None
    if "--drag" in args:
        at = args.index("--drag")
        drag = [float(v) for v in args[at + 1].split(",")]
        del args[at:at + 2]
    master_uri, path, *frames = args
    app = QApplication(["rviz"])
    node = Node(NodeConfig("/rviz_test", master_uri, "127.0.0.1", "127.0.0.1"))
    source = RvizSource(node, lambda: None)
    window = RvizWindow(config.load(path), source, path)
    window.resize(900, 600)
    window.show()
    if not QTest.qWaitForWindowExposed(window, 10_000):
        print("never exposed", flush=True)
        return 1
    view = window.view
    dragged = []

    def pixel(x: float, y: float) -> QPoint:
        at = view.camera.project([[x, y, 0.0]], view.width(), view.height())[0]
        return QPoint(round(float(at[0])), round(float(at[1])))

    def report() -> None:
        image = view.grabFramebuffer()
        ratio = image.width() / max(1, view.width())
        background = tuple(round(c * 255) for c in window.config.background[:3])
        placed = {label.text: label.position for label in view.scene.labels}
        parts = []
        for frame in frames:
            if frame not in placed:
                parts.append(f"{frame}=none")
                continue
            x, y = view.camera.project([placed[frame]], view.width(), view.height())[0] * ratio
            drawn = any(image.pixelColor(round(float(x)) + dx, round(float(y)) + dy).getRgb()[:3] != background
                        for dx in range(-1, 2) for dy in range(-1, 2))
            parts.append(f"{frame}={placed[frame][0]:.3f},{placed[frame][1]:.3f},{'drawn' if drawn else 'blank'}")
        statuses = ";".join(f"{d.name}:{d.status.level}" for d in window.config.displays)
        counted = ""
        if colour is not None:
            pixels = image.convertToFormat(image.Format.Format_RGB888)
            rgb = np.frombuffer(pixels.constBits(), np.uint8, pixels.sizeInBytes())
            rows = rgb.reshape(pixels.height(), pixels.bytesPerLine())[:, : pixels.width() * 3]
            count = _shades_of(rows.reshape(-1, 3), colour)
            counted = f" colour {count}"
            if drag is not None and count and not dragged:
                dragged.append(True)
                window.set_tool(INTERACT)
                left, none = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
                QTest.mousePress(view, left, none, pixel(drag[0], drag[1]))
                for step in range(1, 6):
                    QTest.mouseMove(view, pixel(drag[0] + (drag[2] - drag[0]) * step / 5,
                                                drag[1] + (drag[3] - drag[1]) * step / 5))
                QTest.mouseRelease(view, left, none, pixel(drag[2], drag[3]))
        print("frames", " ".join(parts), "status", statuses + counted, flush=True)
        if click is not None:
            window.set_tool(PUBLISH_POINT)
            x, y = view.camera.project([click], view.width(), view.height())[0]
            point = QPoint(round(float(x)), round(float(y)))
            QTest.mousePress(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, point)
            QTest.mouseRelease(view, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, point)

    timer = QTimer()
    timer.timeout.connect(report)
    timer.start(200)
    try:
        return int(app.exec())
    finally:
        source.close()
        node.shutdown("test over")


if __name__ == "__main__":
    sys.exit(main())
