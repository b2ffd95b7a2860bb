"""gzclient's window in a process of its own on the display its environment names, as
`rosrun gazebo_ros gzclient` runs it, for the live test: each time its status bar changes it
prints `status <button> | <label> | ...`, and it presses its own buttons as stdin asks: "pause"
and "play" (the play/pause button), "step", "close" (the window closes; the node ends).

    python -m tests.gzclient.window_child   (ROS_MASTER_URI and DISPLAY from the environment)
"""

from __future__ import annotations

import os
import sys

from kame.gzclient.main import WINDOW_SIZE, forget_mujocos_platform


def main() -> int:
    forget_mujocos_platform(os.environ)  # before PyOpenGL loads, as gzclient's main does
    from PySide6.QtCore import QSocketNotifier, QTimer
    from PySide6.QtWidgets import QApplication

    from kame.client import core, process
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
        line = " | ".join([window.play_button.text()] + [label.text() for label in window.status_labels])
        if line != said[0]:
            said[0] = line
            print(f"status {line}", flush=True)

    def command() -> None:
        word = sys.stdin.readline().strip()
        if word in ("pause", "play") and window.play_button.text().lower() == word:
            window.play_button.click()
        elif word == "step":
            window.step_button.click()
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
