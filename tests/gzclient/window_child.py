"""gzclient's window in a process of its own on the display its environment names, as
`rosrun gazebo_ros gzclient` runs it, for the live test: each time its status bar changes it
prints `status <button> | <label> | ... | <problem> | drawn <models>`, and it works itself as
stdin asks: "pause" and "play" (the play/pause button), "step", "insert box", "delete MODEL", "drag MODEL X Y"
(the translate mode, and a left drag with the mouse from the model's origin to the pixel of
(X, Y) at its height), "close" (the window closes; the node ends).

    python -m tests.gzclient.window_child   (ROS_MASTER_URI and DISPLAY from the environment)
"""

from __future__ import annotations

import os
import sys

import numpy as np

from kame.gzclient.main import WINDOW_SIZE, forget_mujocos_platform


def main() -> int:
    forget_mujocos_platform(os.environ)  # before PyOpenGL loads, as gzclient's main does
    from PySide6.QtCore import QPoint, QSocketNotifier, Qt, QTimer
    from PySide6.QtTest import QTest
    from PySide6.QtWidgets import QApplication

    from kame.client import core, process
    from kame.gzclient.model import TRANSLATE
    from kame.gzclient.source import ClientSource
    from kame.gzclient.window import GzClientWindow

    process.init_node("gazebo_gui", argv=sys.argv)
    app = QApplication(["gzclient"])
    source = ClientSource()
    window = GzClientWindow(source)
    window.resize(*WINDOW_SIZE)
    window.show()
    said = [""]

    def report() -> None:
        line = " | ".join([window.play_button.text()] + [label.text() for label in window.status_labels]
                          + [window.problem_label.text(), "drawn " + ",".join(window.model.drawn_models())])
        if line != said[0]:
            said[0] = line
            print(f"status {line}", flush=True)

    def drag(model: str, x: float, y: float) -> None:
        pose = window.model.model_pose(model)
        if pose is None:
            print(f"no pose for {model}", flush=True)
            return
        window.mode_actions[TRANSLATE].trigger()
        view = window.view
        z = pose[0][2]
        start, end = view.camera.project(np.array([pose[0], (x, y, z)]), view.width(), view.height())
        left = Qt.MouseButton.LeftButton
        QTest.mousePress(view, left, Qt.KeyboardModifier.NoModifier, QPoint(round(start[0]), round(start[1])))
        for fraction in np.linspace(0.1, 1.0, 10):
            here = start + fraction * (end - start)
            QTest.mouseMove(view, QPoint(round(here[0]), round(here[1])))
        QTest.mouseRelease(view, left, Qt.KeyboardModifier.NoModifier, QPoint(round(end[0]), round(end[1])))
        print(f"dragged {model} selected {window.model.selected}", flush=True)

    def command() -> None:
        line = sys.stdin.readline().split()
        word = line[0] if line else ""
        if word in ("pause", "play") and window.play_button.text().lower() == word:
            window.play_button.click()
        elif word == "step":
            window.step_button.click()
        elif word == "insert":
            window.insert_actions[line[1]].trigger()
        elif word == "delete":  # as a click selects it and Edit > Delete
            window.model.select(line[1])
            window.delete_action.trigger()
        elif word == "drag":
            drag(line[1], float(line[2]), float(line[3]))
        elif word in ("close", ""):
            window.close()

    reporter = QTimer(window)
    reporter.timeout.connect(report)
    reporter.start(50)
    notifier = QSocketNotifier(sys.stdin.fileno(), QSocketNotifier.Type.Read, app)
    notifier.activated.connect(command)
    try:
        app.exec()
    finally:
        source.close()
        core.signal_shutdown("window closed")
    print("closed", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
