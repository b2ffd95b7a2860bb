"""rviz's window: the Displays panel (Global Options and each display with its options and
status), the 3-D view (kame.rviz.view: OpenGL in a window of its own, drawing the model's Scene),
the tool bar (Interact, Select, Measure, 2D Pose Estimate, 2D Nav Goal, Publish Point), the
Selection panel and the view chooser.
A frame (kame.rviz.pacing: at the Frame Rate, and soon after a message arrives) takes the waiting
messages, rebuilds the scene and repaints; the displays and the camera are kame.rviz's Qt-free
model."""

from __future__ import annotations

import functools
import math
import os
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QActionGroup, QBrush, QColor
from PySide6.QtWidgets import (
    QComboBox,
    QDockWidget,
    QFileDialog,
    QMainWindow,
    QMenu,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from kame.rviz import config as rviz_config
from kame.rviz.camera import FPS, ORBIT, TOP_DOWN
from kame.rviz.display import ERROR, OK, WARN, Display, Status, edited_option, format_color, parse_color
from kame.rviz.image_panels import ImagePanels, decode_compressed
from kame.rviz.interact_view import InteractRouter
from kame.rviz.interactive import InteractiveMarkers
from kame.rviz.markers import Marker
from kame.rviz.meshes import MeshLibrary
from kame.rviz.pacing import FramePacer
from kame.rviz.robot import RobotModel
from kame.rviz.scene import Scene
from kame.rviz.sensors import Image
from kame.rviz.shown_log import from_environment
from kame.rviz.source import RvizSource
from kame.rviz.stats import FrameStats
from kame.rviz.tools import Measure, Selection
from kame.rviz.view import INTERACT, MEASURE, NAV_GOAL, POSE_ESTIMATE, PUBLISH_POINT, SELECT, RenderView
from visualization_msgs.msg import InteractiveMarkerFeedback

# the topics of rviz's default tools (SetInitialPose, SetGoal, PublishPoint)
INITIAL_POSE_TOPIC, GOAL_TOPIC, CLICKED_POINT_TOPIC = "/initialpose", "/move_base_simple/goal", "/clicked_point"
STATUS_COLOURS = {WARN: (205, 153, 51), ERROR: (192, 32, 32)}  # as Debian's rviz 1.14 draws them


def _yaw_quaternion(yaw: float) -> tuple[float, float, float, float]:
    return 0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)


class RvizWindow(QMainWindow):
    def __init__(self, config: rviz_config.Config, source: RvizSource | None, config_path: str = "") -> None:
        super().__init__()
        self.config = config
        self.source = source
        self.meshes = MeshLibrary(source.find_package if source is not None else None)
        self.config_path = config_path
        self.setWindowTitle(rviz_config.window_title(config_path))
        self.view = RenderView()
        # the view's native window in the main one: the container is what the layout and the mouse's focus see
        self.view_widget = QWidget.createWindowContainer(self.view)
        self.view_widget.setMinimumSize(320, 240)
        self.view_widget.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self.view.camera = config.camera
        self.view.background = config.background
        self.view.clicked.connect(self._tool_used)
        self.measure, self.selection = Measure(), Selection()
        self._displays_scene = Scene()  # what the displays drew last, without the tools' marks
        self.view.picked.connect(self._measured)
        self.view.unpicked.connect(self._measure_reset)
        self.view.area.connect(self._select)
        self.view.interact = InteractRouter(self.view, lambda: self.config.displays,
                                            source.publish if source is not None else None,
                                            source.node.name if source is not None else "/rviz",
                                            lambda: self.draw(time.monotonic()))
        self.setCentralWidget(self.view_widget)
        self.selected_tree = QTreeWidget()
        self.selected_tree.setHeaderLabels(["Property", "Value"])
        self.selection_dock = QDockWidget("Selection")
        self.selection_dock.setObjectName("Selection")
        self.selection_dock.setWidget(self.selected_tree)
        self.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, self.selection_dock)
        self.selection_dock.hide()  # rviz's Selection panel shows once Select is used
        self.image_panels = ImagePanels(self)
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(["Property", "Value"])
        self.tree.setColumnWidth(0, 150)
        self.tree.setMinimumWidth(300)
        self.tree.itemChanged.connect(self._edited)
        self._items: dict[int, QTreeWidgetItem] = {}
        panel = QWidget()
        layout = QVBoxLayout(panel)
        layout.addWidget(self.tree)
        add = QPushButton("Add")
        menu = QMenu(add)
        for class_name in rviz_config.DISPLAY_CLASSES:
            menu.addAction(class_name, functools.partial(self.add_display, class_name))
        self.by_topic = menu.addMenu("By topic")  # filled with the master's topics as it opens
        self.by_topic.aboutToShow.connect(self._offer_topics)
        add.setMenu(menu)
        remove = QPushButton("Remove")
        remove.clicked.connect(self._remove_selected)
        layout.addWidget(add)
        layout.addWidget(remove)
        dock = QDockWidget("Displays")
        dock.setObjectName("Displays")
        dock.setWidget(panel)
        self.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, dock)
        self._tools()
        self.statusBar()  # there from the start, as rviz's: the view keeps its size when a tool says something
        if source is not None:  # rviz's tools advertise their topics as it starts: a first goal is heard
            self._advertise_tools(source)
        self._menus()
        self._topic_errors: dict[int, str] = {}
        self.rebuild_tree()
        self.pacer = FramePacer(self, self.frame, config.frame_rate)
        self.timer = self.pacer.timer  # stopped, the window draws when told to (the tests, the bench)
        if source is not None:
            source.on_ready = self.pacer.ready.emit
        self.shown_log = from_environment(os.environ)  # KAME_RVIZ_STATS: when each message reached the screen
        if self.shown_log is not None:
            self.view.frameSwapped.connect(self.shown_log.swapped)
            self.image_panels.painted = self.shown_log.swapped  # Image and Camera displays show in their panels
        self.started = time.monotonic()
        self.stats = FrameStats(self.started)
        self.view.frameSwapped.connect(self.stats.frame_shown)  # drawn and shown: a grab is neither

    # -------------------------------------------------------------- building

    def _tools(self) -> None:
        bar = self.addToolBar("Tools")
        bar.setObjectName("Tools")
        group = QActionGroup(self)
        self.tool_actions: dict[str, QAction] = {}
        for name in (INTERACT, SELECT, MEASURE, POSE_ESTIMATE, NAV_GOAL, PUBLISH_POINT):
            action = QAction(name, self, checkable=True)
            action.setChecked(name == INTERACT)
            action.triggered.connect(lambda _checked=False, tool=name: self.set_tool(tool))
            group.addAction(action)
            bar.addAction(action)
            self.tool_actions[name] = action
        self.views = QComboBox()
        self.views.addItems([ORBIT, TOP_DOWN, FPS])
        self.views.setCurrentText(self.config.camera.kind)
        self.views.currentTextChanged.connect(self.set_view)
        bar.addWidget(self.views)

    @staticmethod
    def _advertise_tools(source: RvizSource) -> None:
        from geometry_msgs.msg import PointStamped, PoseStamped, PoseWithCovarianceStamped

        source.advertise(INITIAL_POSE_TOPIC, PoseWithCovarianceStamped)
        source.advertise(GOAL_TOPIC, PoseStamped)
        source.advertise(CLICKED_POINT_TOPIC, PointStamped)

    def _menus(self) -> None:
        file_menu = self.menuBar().addMenu("&File")
        file_menu.addAction("Open Config", self._open)
        file_menu.addAction("Save Config", self._save)
        file_menu.addAction("Save Config As", self._save_as)
        file_menu.addAction("Quit", self.close)

    def _open(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Open Config", "", "RViz config (*.rviz)")
        if path:
            self.load(path)

    def _save(self) -> None:
        if self.config_path:
            self.save(self.config_path)
        else:
            self._save_as()

    def _save_as(self) -> None:
        path, _ = QFileDialog.getSaveFileName(self, "Save Config", self.config_path, "RViz config (*.rviz)")
        if path:
            self.save(path)

    def load(self, path: str) -> None:
        self.config = rviz_config.load(path)
        self.config_path = path
        self.view.camera, self.view.background = self.config.camera, self.config.background
        self.views.setCurrentText(self.config.camera.kind)
        self.pacer.set_rate(self.config.frame_rate)
        self.rebuild_tree()

    def save(self, path: str) -> None:
        self.config.camera = self.view.camera
        rviz_config.save(self.config, path)
        self.config_path = path
        self.setWindowTitle(rviz_config.window_title(path))

    def set_view(self, kind: str) -> None:
        self.view.camera.become(kind)
        self.view.update()

    def set_tool(self, tool: str) -> None:
        self.view.tool = tool
        self.tool_actions[tool].setChecked(True)
        if tool == SELECT:
            self.selection_dock.show()
        self.statusBar().showMessage(self.measure.status() if tool == MEASURE else "")

    def add_display(self, class_name: str) -> Display:
        display = rviz_config.DISPLAY_CLASSES[class_name]()
        self.config.displays.append(display)
        self.rebuild_tree()
        return display

    def _offer_topics(self) -> None:
        self.by_topic.clear()
        topics = self.source.published_topics() if self.source is not None else []
        for topic, class_name in rviz_config.displays_by_topic(topics):
            self.by_topic.addAction(f"{topic} ({class_name})", functools.partial(self.add_topic, class_name, topic))

    def add_topic(self, class_name: str, topic: str) -> Display:
        display = rviz_config.display_for_topic(class_name, topic)
        self.config.displays.append(display)
        self.rebuild_tree()
        return display

    def _remove_selected(self) -> None:
        item = self.tree.currentItem()
        while item is not None and item.parent() is not None:
            item = item.parent()
        index = self.tree.indexOfTopLevelItem(item) - 1 if item is not None else -1
        if 0 <= index < len(self.config.displays):
            del self.config.displays[index]
            self.rebuild_tree()

    # -------------------------------------------------------------- the tree

    def rebuild_tree(self) -> None:
        self.tree.blockSignals(True)
        self.tree.clear()
        self._items.clear()
        options = QTreeWidgetItem(self.tree, ["Global Options"])
        fixed = QTreeWidgetItem(options, ["Fixed Frame", ""])
        self.fixed_frames = QComboBox()  # tf's frames, refreshed as the tree grows; any name can be typed
        self.fixed_frames.setEditable(True)
        self.fixed_frames.addItem(self.config.fixed_frame)
        self.fixed_frames.currentTextChanged.connect(lambda text: self.set_global("Fixed Frame", text))
        self.tree.setItemWidget(fixed, 1, self.fixed_frames)
        for key, value in (("Background Color", format_color(self.config.background)),
                           ("Frame Rate", str(self.config.frame_rate))):
            child = QTreeWidgetItem(options, [key, value])
            child.setFlags(child.flags() | Qt.ItemFlag.ItemIsEditable)
        for display in self.config.displays:
            item = QTreeWidgetItem(self.tree, [display.name, display.class_name])
            item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
            item.setCheckState(0, Qt.CheckState.Checked if display.enabled else Qt.CheckState.Unchecked)
            QTreeWidgetItem(item, ["Status", display.status.level])
            for key, value in display.options.items():
                if isinstance(value, dict):
                    continue
                child = QTreeWidgetItem(item, [key, str(value)])
                child.setFlags(child.flags() | Qt.ItemFlag.ItemIsEditable)
            self._items[id(display)] = item
        self.tree.expandToDepth(0)
        self.tree.blockSignals(False)
        self._rewatch()

    def _edited(self, item: QTreeWidgetItem, column: int) -> None:
        parent = item.parent()
        if parent is None:
            index = self.tree.indexOfTopLevelItem(item) - 1
            if 0 <= index < len(self.config.displays):
                self.config.displays[index].enabled = item.checkState(0) == Qt.CheckState.Checked
            return
        key, value = item.text(0), item.text(1)
        if parent.text(0) == "Global Options":
            self.set_global(key, value)
            return
        display = self.config.displays[self.tree.indexOfTopLevelItem(parent) - 1]
        display.options[key] = edited_option(display.options.get(key), value)
        if key in ("Topic", "Marker Topic", "Image Topic", "Update Topic"):
            display.reset()
            self._rewatch()

    def _offer_frames(self, names: list[str]) -> None:
        known = [self.fixed_frames.itemText(i) for i in range(self.fixed_frames.count())]
        wanted = sorted(set(names) | {self.config.fixed_frame})
        if known != wanted:
            self.fixed_frames.blockSignals(True)
            self.fixed_frames.clear()
            self.fixed_frames.addItems(wanted)
            self.fixed_frames.setCurrentText(self.config.fixed_frame)
            self.fixed_frames.blockSignals(False)

    def set_global(self, key: str, value: str) -> None:
        if key == "Fixed Frame" and value:  # nothing to reset: every frame is placed through tf as it is drawn
            self.config.fixed_frame = value
        elif key == "Background Color":
            self.config.background = self.view.background = parse_color(value, self.config.background)
            self.view.update()
        elif key == "Frame Rate" and _is_number(value):
            self.config.frame_rate = max(1, int(float(value)))
            self.pacer.set_rate(self.config.frame_rate)

    def _rewatch(self) -> None:
        """Subscribes to what the displays show, and leaves what none shows any more."""
        for display in self.config.displays:
            if isinstance(display, (RobotModel, Marker, InteractiveMarkers)):
                display.meshes = self.meshes  # one cache of mesh files for the window
            if isinstance(display, Image):
                display.decode_compressed = decode_compressed
        if self.source is None:
            return
        self._topic_errors.clear()
        wanted = {}
        for display in self.config.displays:
            subscription = display.subscription()
            if subscription is not None:
                topic, type_name = subscription
                problem = self.source.watch(topic, type_name, display.keeps_every_message)
                if problem:
                    self._topic_errors[id(display)] = problem
                wanted[self.source.node.resolve(topic)] = display
            if isinstance(display, InteractiveMarkers) and display.topic:  # its feedback: connected before a drag
                self.source.advertise(display.feedback_topic(), InteractiveMarkerFeedback)
            for topic, type_name in display.side_topics().items():
                problem = self.source.watch(topic, type_name, False)
                if problem:
                    self._topic_errors[id(display)] = problem
                wanted[self.source.node.resolve(topic)] = display
        for topic in self.source.watched() - set(wanted):
            self.source.unwatch(topic)
        for display in self.config.displays:
            if isinstance(display, RobotModel):
                display.describe(self.source.param(str(display.options.get("Robot Description", ""))))

    # -------------------------------------------------------------- each frame

    def frame(self) -> bool:
        """Takes the waiting messages and draws; True when there were any."""
        now = time.monotonic()
        self.stats.turned(now)
        taken: dict[str, list[Any]] = {}
        if self.source is not None:
            taken = self.source.take()
            if self.shown_log is not None:
                self.shown_log.taken(taken)
            for display in self.config.displays:
                subscription = display.subscription()
                if subscription is not None:
                    display.receive(taken.get(self.source.node.resolve(subscription[0]), []), now)
                for topic in display.side_topics():
                    display.receive_side(topic, taken.get(self.source.node.resolve(topic), []), now)
        self.draw(now)
        return any(taken.values())

    def draw(self, now: float, frames: Any = None) -> None:
        """Rebuilds the scene from the displays (`frames`: the tf tree; the source's by default)."""
        if frames is None and self.source is not None:
            frames = self.source.frames(self.config.fixed_frame)
        if frames is not None:
            self._offer_frames(frames.names())
        scene = Scene()
        for display in self.config.displays:
            if frames is None:
                display.status = Status(ERROR, "no tf: rviz has no node")
                continue
            if isinstance(display, InteractiveMarkers):  # its VIEW_FACING controls turn to the camera
                display.face(self.view.camera.view_matrix())
            try:
                display.build(scene, frames, now)
            except Exception as exc:  # a message the display cannot draw must not stop the window
                display.status = Status(ERROR, f"cannot draw: {exc}")
            if id(display) in self._topic_errors:
                display.status = Status(ERROR, self._topic_errors[id(display)])
            self._show_status(display)
        self._displays_scene = scene
        self._show_with_tools()
        self.image_panels.sync(self.config.displays, scene)

    def _show_with_tools(self) -> None:
        scene = Scene()
        for part in (self._displays_scene, self.measure.overlay, self.selection.overlay):
            scene.extend(part)
        self.view.show_scene(scene)

    def _show_status(self, display: Display) -> None:
        item = self._items.get(id(display))
        if item is None or item.childCount() == 0:
            return
        status = item.child(0)
        if status is None:
            return
        text = display.status.level if display.status.level == OK else f"{display.status.level}: {display.status.text}"
        if status.text(1) != text:
            self.tree.blockSignals(True)
            status.setText(1, text)
            # rviz writes a flagged display's name and status in its warning or error colour
            colour = STATUS_COLOURS.get(display.status.level)
            for row in (item, status):
                row.setData(0, Qt.ItemDataRole.ForegroundRole, QBrush(QColor(*colour)) if colour else None)
            self.tree.blockSignals(False)

    def frame_names(self) -> list[str]:
        return self.source.frames(self.config.fixed_frame).names() if self.source is not None else []

    # -------------------------------------------------------------- tools

    def _tool_used(self, pressed: np.ndarray, released: np.ndarray) -> None:
        """2D Pose Estimate, 2D Nav Goal or Publish Point, used: its message sent, and Interact
        the tool again, as rviz's tools finish after one use."""
        publish: Callable[[str, Any], None] | None = self.source.publish_stamped if self.source is not None else None
        if publish is None or self.view.tool in (INTERACT, SELECT, MEASURE):
            return
        self._publish_tool_message(publish, pressed, released)
        self.set_tool(INTERACT)

    def _publish_tool_message(self, publish: Callable[[str, Any], None], pressed: np.ndarray,
                              released: np.ndarray) -> None:
        from geometry_msgs.msg import PointStamped, PoseStamped, PoseWithCovarianceStamped

        yaw = math.atan2(released[1] - pressed[1], released[0] - pressed[0]) if np.linalg.norm(
            released[:2] - pressed[:2]) > 1e-6 else 0.0
        if self.view.tool == PUBLISH_POINT:
            point = PointStamped()
            point.header.frame_id = self.config.fixed_frame
            point.point.x, point.point.y, point.point.z = (float(v) for v in released)
            publish(CLICKED_POINT_TOPIC, point)
            return
        pose: Any = PoseWithCovarianceStamped() if self.view.tool == POSE_ESTIMATE else PoseStamped()
        pose.header.frame_id = self.config.fixed_frame
        target = pose.pose.pose if self.view.tool == POSE_ESTIMATE else pose.pose
        target.position.x, target.position.y = float(pressed[0]), float(pressed[1])
        (target.orientation.x, target.orientation.y, target.orientation.z,
         target.orientation.w) = _yaw_quaternion(yaw)
        if self.view.tool == POSE_ESTIMATE:  # rviz's: 0.5 m in x and y, pi/12 in yaw
            covariance = [0.0] * 36
            covariance[0] = covariance[7] = 0.25
            covariance[35] = (math.pi / 12) ** 2
            pose.pose.covariance = covariance
            publish(INITIAL_POSE_TOPIC, pose)
        else:
            publish(GOAL_TOPIC, pose)

    def _measured(self, point: np.ndarray) -> None:
        self.measure.click(point)
        self.statusBar().showMessage(self.measure.status())
        self._show_with_tools()

    def _measure_reset(self) -> None:
        self.measure.reset()
        self.statusBar().showMessage(self.measure.status())
        self._show_with_tools()

    def _select(self, corner: tuple[float, float], other: tuple[float, float]) -> None:
        self.selection.select(self.config.displays, self.view.camera, self.view.width(), self.view.height(),
                              corner, other)
        self.selected_tree.clear()
        for selected in self.selection.selected:
            item = QTreeWidgetItem(self.selected_tree, [selected.name, selected.display])
            for key, value in selected.properties.items():
                QTreeWidgetItem(item, [key, value])
        if self.selection.total > len(self.selection.selected):
            QTreeWidgetItem(self.selected_tree, [f"... {self.selection.total - len(self.selection.selected)} more", ""])
        self.selected_tree.expandToDepth(0)
        self._show_with_tools()

    def closeEvent(self, event: Any) -> None:
        self.pacer.stop()
        super().closeEvent(event)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
