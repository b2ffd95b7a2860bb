"""joint_state_publisher_gui's window: a slider and a value for each free joint, Randomize
and Center buttons. The positions live in kame.robot.model.JointPositions (no Qt); the window
only moves them and shows them."""

from __future__ import annotations

import random
import threading
from typing import Any

from PySide6 import QtCore, QtWidgets

from kame.qt_quit import quit_on_signals
from kame.robot.joint_states import JointStatePublisher


class SliderWindow(QtWidgets.QWidget):
    def __init__(self, publisher: JointStatePublisher) -> None:
        super().__init__()
        self.publisher = publisher
        self.setWindowTitle("Joint State Publisher")
        layout = QtWidgets.QVBoxLayout(self)
        grid = QtWidgets.QGridLayout()
        layout.addLayout(grid)
        self.sliders: dict[str, QtWidgets.QSlider] = {}
        self.values: dict[str, QtWidgets.QLineEdit] = {}
        positions = publisher.positions
        for row, name in enumerate(positions.free):
            grid.addWidget(QtWidgets.QLabel(name), 2 * row, 0)
            value = QtWidgets.QLineEdit()
            value.setReadOnly(True)
            value.setMaximumWidth(90)
            grid.addWidget(value, 2 * row, 1)
            slider = QtWidgets.QSlider(QtCore.Qt.Orientation.Horizontal)
            slider.setRange(0, positions.SLIDER_STEPS)
            slider.valueChanged.connect(lambda steps, joint=name: self._moved(joint, steps))
            grid.addWidget(slider, 2 * row + 1, 0, 1, 2)
            self.sliders[name], self.values[name] = slider, value
        if not positions.free:
            layout.addWidget(QtWidgets.QLabel("This robot has no movable joints."))
        buttons = QtWidgets.QHBoxLayout()
        randomize, center = QtWidgets.QPushButton("Randomize"), QtWidgets.QPushButton("Center")
        randomize.clicked.connect(self.randomize)
        center.clicked.connect(self.center)
        buttons.addWidget(randomize)
        buttons.addWidget(center)
        layout.addLayout(buttons)
        self.show_positions()

    def _moved(self, joint: str, steps: int) -> None:
        with self.publisher.lock:
            positions = self.publisher.positions
            positions.set(joint, positions.from_slider(joint, steps))
            self.values[joint].setText(f"{positions.free[joint].position:.2f}")

    def show_positions(self) -> None:
        with self.publisher.lock:
            shown = {name: (self.publisher.positions.slider_value(name), joint.position)
                     for name, joint in self.publisher.positions.free.items()}
        for name, (steps, position) in shown.items():
            slider = self.sliders[name]
            slider.blockSignals(True)  # the model already holds the exact position
            slider.setValue(steps)
            slider.blockSignals(False)
            self.values[name].setText(f"{position:.2f}")

    def randomize(self) -> None:
        with self.publisher.lock:
            self.publisher.positions.randomize(random.uniform)
        self.show_positions()

    def center(self) -> None:
        with self.publisher.lock:
            self.publisher.positions.center()
        self.show_positions()


def run_window(publisher: JointStatePublisher, stop: Any) -> int:
    """The window until it is closed, Ctrl-C, or `stop` is set (the master's shutdown request)."""
    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication(["joint_state_publisher_gui"])
    quit_on_signals(app)
    window = SliderWindow(publisher)
    window.show()

    def quit_when_stopped() -> None:
        stop.wait()
        QtCore.QMetaObject.invokeMethod(app, "quit", QtCore.Qt.ConnectionType.QueuedConnection)

    watcher = threading.Thread(target=quit_when_stopped, name="stop_watch")
    watcher.start()
    try:
        app.exec()
    finally:
        stop.set()
        watcher.join()
    return 0
