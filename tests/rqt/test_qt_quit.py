"""A Qt tool ends on Ctrl-C and SIGTERM whenever the signal comes: also before its loop runs, as
when a loaded machine is still building the window (joint_state_publisher_gui was SIGKILLed by
a test that pressed Ctrl-C as soon as its first message was out: the signal's quit() found no
loop to end, and the loop then ran for ever)."""

from __future__ import annotations

import subprocess
import sys

import pytest

pytest.importorskip("PySide6.QtWidgets")

TOOL = """
import os, signal, sys
from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication, QWidget
from kame.qt_quit import quit_on_signals
app = QApplication(["tool"])
quit_on_signals(app)
window = QWidget()
os.kill(os.getpid(), signal.{name})  # handled here, before the window is shown and the loop runs
window.show()
QTimer.singleShot(30_000, lambda: sys.exit(3))  # the signal was lost: not a hang, a failure
app.exec()
"""


@pytest.mark.parametrize("name", ["SIGINT", "SIGTERM"])
def test_a_signal_before_the_loop_runs_still_ends_it(name: str) -> None:
    done = subprocess.run([sys.executable, "-c", TOOL.format(name=name)], capture_output=True, text=True,
                          env={"QT_QPA_PLATFORM": "offscreen", "PATH": "/usr/bin:/bin"}, timeout=60)
    assert done.returncode == 0, (done.returncode, done.stderr)
