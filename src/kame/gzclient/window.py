"""gzclient's main window, as Gazebo 11 lays it out: the 3-D view, a tool bar above it (the
select, translate and rotate modes; a box, sphere and cylinder to insert), the Edit menu's resets and Delete (the
selected model),
and a bar below it with play/pause, step and the status figures. The window only draws the
model and passes what the user did to the source; a frame timer takes what arrived."""

from __future__ import annotations

from typing import Protocol

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QAction, QActionGroup, QCloseEvent, QKeySequence
from PySide6.QtWidgets import QLabel, QMainWindow, QToolBar, QToolButton, QWidget

from kame.gzclient.model import ROTATE, SELECT, TRANSLATE, ClientModel, ModelMove, unique_name
from kame.gzclient.scene_message import Vector3
from kame.gzclient.source import SHAPES, Update
from kame.gzclient.status import StatusFigures
from kame.gzclient.view import GazeboView

FRAME_PERIOD_MS = 33  # the window takes what arrived 30 times a second
PROBLEM_SHOWN_MS = 10_000  # how long a refused request stays said in the bar
TITLE = "Gazebo"


class Source(Protocol):
    """What the window asks of its ROS side (kame.gzclient.source.ClientSource)."""

    def take(self) -> Update: ...
    def set_paused(self, paused: bool) -> None: ...
    def step(self, iterations: int = 1) -> None: ...
    def reset_world(self) -> None: ...
    def reset_simulation(self) -> None: ...
    def move(self, move: ModelMove) -> None: ...
    def insert(self, shape: str, name: str, position: Vector3) -> None: ...
    def delete(self, model: str) -> None: ...


class GzClientWindow(QMainWindow):
    def __init__(self, source: Source) -> None:
        super().__init__()
        self.setWindowTitle(TITLE)
        self.source = source
        self.model = ClientModel()
        self.status = StatusFigures()
        self.view = GazeboView(self.model, source.move)
        self.view_widget = QWidget.createWindowContainer(self.view)
        self.view_widget.setMinimumSize(320, 240)
        self.setCentralWidget(self.view_widget)
        self._build_tools()
        self._build_menu()
        self._build_time_bar()
        self._timer = QTimer(self)
        self._timer.timeout.connect(self.take)
        self._timer.start(FRAME_PERIOD_MS)

    # -------------------------------------------------------------- layout

    def _build_tools(self) -> None:
        tools = QToolBar("Tools", self)
        tools.setObjectName("tools")
        tools.setMovable(False)
        modes = QActionGroup(self)
        self.mode_actions: dict[str, QAction] = {}
        for mode, text, key in ((SELECT, "Select", "Esc"), (TRANSLATE, "Translate", "T"), (ROTATE, "Rotate", "R")):
            action = QAction(text, self, checkable=True)
            action.setShortcut(QKeySequence(key))
            action.setToolTip(f"{text} mode ({key})")
            action.triggered.connect(lambda _checked=False, m=mode: self.set_mode(m))
            modes.addAction(action)
            tools.addAction(action)
            self.mode_actions[mode] = action
        self.mode_actions[SELECT].setChecked(True)
        tools.addSeparator()
        self.insert_actions: dict[str, QAction] = {}
        for shape in SHAPES:
            action = QAction(shape.capitalize(), self)
            action.setToolTip(f"Insert a {shape} where the view looks")
            action.triggered.connect(lambda _checked=False, s=shape: self.insert(s))
            tools.addAction(action)
            self.insert_actions[shape] = action
        self.addToolBar(tools)

    def _build_menu(self) -> None:
        edit = self.menuBar().addMenu("&Edit")
        self.reset_poses_action = edit.addAction("Reset Model Poses")
        self.reset_poses_action.setShortcut(QKeySequence("Ctrl+Shift+R"))
        self.reset_poses_action.triggered.connect(self.source.reset_world)
        self.reset_world_action = edit.addAction("Reset World")
        self.reset_world_action.setShortcut(QKeySequence("Ctrl+R"))
        self.reset_world_action.triggered.connect(self.source.reset_simulation)
        edit.addSeparator()
        self.delete_action = edit.addAction("Delete")
        self.delete_action.setShortcut(QKeySequence(QKeySequence.StandardKey.Delete))
        self.delete_action.triggered.connect(self.delete_selected)

    def _build_time_bar(self) -> None:
        bar = QToolBar("Time", self)
        bar.setObjectName("time")
        bar.setMovable(False)
        self.play_button = QToolButton(self)
        self.play_button.setText("Pause")
        self.play_button.setToolTip("Play or pause the simulation (/gazebo/pause_physics, unpause_physics)")
        self.play_button.clicked.connect(self.toggle_paused)
        bar.addWidget(self.play_button)
        self.step_button = QToolButton(self)
        self.step_button.setText("Step")
        self.step_button.setToolTip("One iteration while paused")
        self.step_button.clicked.connect(lambda: self.source.step(1))
        bar.addWidget(self.step_button)
        bar.addSeparator()
        self.status_labels = [QLabel(self) for _ in range(4)]
        for label in self.status_labels:
            label.setContentsMargins(8, 0, 8, 0)
            bar.addWidget(label)
        self.problem_label = QLabel(self)  # a refused request, said in the bar the user is looking at
        self.problem_label.setStyleSheet("color: #b00000")
        self.problem_label.setContentsMargins(8, 0, 8, 0)
        bar.addWidget(self.problem_label)
        self._problem_timer = QTimer(self)
        self._problem_timer.setSingleShot(True)
        self._problem_timer.timeout.connect(self.problem_label.clear)
        self.addToolBar(Qt.ToolBarArea.BottomToolBarArea, bar)
        self._show_status()

    # -------------------------------------------------------------- what the user does

    def set_mode(self, mode: str) -> None:
        self.model.mode = mode
        self.mode_actions[mode].setChecked(True)

    def toggle_paused(self) -> None:
        self.source.set_paused(not self.status.paused)

    def delete_selected(self) -> None:
        if self.model.selected is not None:
            self.source.delete(self.model.selected)
            self.model.select(None)

    def insert(self, shape: str) -> None:
        name = unique_name(SHAPES[shape], self.model.model_names())
        self.source.insert(shape, name, self.model.insert_point(self.view.width(), self.view.height()))

    # -------------------------------------------------------------- what arrived

    def take(self) -> None:
        update = self.source.take()
        if update.scene is not None:
            self.model.set_scene(update.scene)
        if update.links is not None:
            self.model.set_link_poses(update.links)
        if update.models is not None:
            self.model.set_model_poses(update.models)
        if update.stats is not None:
            self.status.update(update.stats)
            self._show_status()
        if update.problems:
            self.problem_label.setText(update.problems[-1])
            self._problem_timer.start(PROBLEM_SHOWN_MS)
        self.view.refresh()

    def _show_status(self) -> None:
        fields = self.status.fields()
        for label, text in zip(self.status_labels, fields + [""] * (len(self.status_labels) - len(fields)),
                               strict=True):
            label.setText(text)
        self.play_button.setText("Play" if self.status.paused else "Pause")
        self.step_button.setEnabled(self.status.paused)

    def closeEvent(self, event: QCloseEvent) -> None:
        self._timer.stop()
        super().closeEvent(event)
