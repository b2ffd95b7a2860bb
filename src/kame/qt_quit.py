"""A Qt tool (the rqt tools, rviz, joint_state_publisher_gui) ends on SIGINT (Ctrl-C) or SIGTERM
as its window's close does, as rqt's own tools do on Ctrl-C: its windows are closed and its Qt
loop quits, so its main's `finally` shuts its node down and its registrations leave the master (a
tool killed by the signal left them there, and rqt_graph showed a dead node). Qt's loop runs
in C, where a Python handler never runs: the signal also wakes the loop through a pipe Qt
watches (signal.set_wakeup_fd), and the handler runs as Python drains it. A signal that comes
before the loop runs (a tool still building its window, under load) must not be lost: quit() then
has no loop to end, so the handler also posts the quit, which the loop takes as it starts."""

from __future__ import annotations

import os
import signal

from PySide6.QtCore import QCoreApplication, QMetaObject, QSocketNotifier, Qt
from PySide6.QtWidgets import QApplication


def quit_on_signals(app: QCoreApplication) -> None:
    reader, writer = os.pipe()
    os.set_blocking(reader, False)
    os.set_blocking(writer, False)
    signal.set_wakeup_fd(writer)
    notifier = QSocketNotifier(reader, QSocketNotifier.Type.Read, app)
    notifier.activated.connect(lambda: os.read(reader, 512))

    def close(number: int, frame: object) -> None:
        QApplication.closeAllWindows()
        app.quit()
        QMetaObject.invokeMethod(app, "quit", Qt.ConnectionType.QueuedConnection)

    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, close)
