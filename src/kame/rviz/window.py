"""rviz's window: the Displays panel (Global Options and each display with its options and
status), the 3-D view (OpenGL through PyOpenGL in a QOpenGLWidget, drawing the model's Scene),
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
from OpenGL import GL
from PySide6.QtCore import QPointF, QRectF, Qt, Signal
from PySide6.QtGui import QAction, QActionGroup, QBrush, QColor, QMouseEvent, QPainter, QWheelEvent
from PySide6.QtOpenGLWidgets import QOpenGLWidget
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
from kame.rviz.camera import FPS, ORBIT, TOP_DOWN, Camera
from kame.rviz.display import ERROR, OK, WARN, Display, Status, edited_option, format_color, parse_color
from kame.rviz.gpu_batches import GpuBatches
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
from visualization_msgs.msg import InteractiveMarkerFeedback

PRIMITIVES = {"lines": GL.GL_LINES, "points": GL.GL_POINTS, "triangles": GL.GL_TRIANGLES}
INTERACT, POSE_ESTIMATE, NAV_GOAL, PUBLISH_POINT = "Interact", "2D Pose Estimate", "2D Nav Goal", "Publish Point"
SELECT, MEASURE = "Select", "Measure"


STATUS_COLOURS = {WARN: (205, 153, 51), ERROR: (192, 32, 32)}  # as Debian's rviz 1.14 draws them


def _headlight() -> None:
    """One light at the eye, shining where it looks, lighting both sides of every face (the
    displays do not wind their triangles one way): a face turned to the camera shows its
    colour exactly, one seen edge-on the ambient 35 % of it."""
    GL.glLightfv(GL.GL_LIGHT0, GL.GL_POSITION, (0.0, 0.0, 1.0, 0.0))
    GL.glLightfv(GL.GL_LIGHT0, GL.GL_AMBIENT, (0.35, 0.35, 0.35, 1.0))
    GL.glLightfv(GL.GL_LIGHT0, GL.GL_DIFFUSE, (0.65, 0.65, 0.65, 1.0))
    GL.glLightfv(GL.GL_LIGHT0, GL.GL_SPECULAR, (0.0, 0.0, 0.0, 1.0))
    GL.glLightModelfv(GL.GL_LIGHT_MODEL_AMBIENT, (0.0, 0.0, 0.0, 1.0))
    GL.glLightModeli(GL.GL_LIGHT_MODEL_TWO_SIDE, GL.GL_TRUE)
    GL.glEnable(GL.GL_LIGHT0)
    GL.glEnable(GL.GL_COLOR_MATERIAL)
    GL.glColorMaterial(GL.GL_FRONT_AND_BACK, GL.GL_AMBIENT_AND_DIFFUSE)


def _same(these: list[Any], those: list[Any]) -> bool:
    return len(these) == len(those) and all(a is b for a, b in zip(these, those, strict=True))


def _keys(event: QMouseEvent) -> tuple[bool, bool]:
    """Shift and Ctrl held (the Interact tool's 3-D modes)."""
    held = event.modifiers()
    return bool(held & Qt.KeyboardModifier.ShiftModifier), bool(held & Qt.KeyboardModifier.ControlModifier)


class RenderView(QOpenGLWidget):
    """Draws a Scene through a Camera; the mouse moves the camera as rviz's does, or drives a tool."""

    clicked = Signal(object, object)  # ground point pressed, ground point released (numpy arrays)
    picked = Signal(object)  # Measure: the point under a left click (on the geometry there, else the ground)
    unpicked = Signal()  # Measure: a right click
    area = Signal(object, object)  # Select: the corners (x, y pixels) of the rectangle dragged

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.camera = Camera()
        self.scene = Scene()
        self.background = (48 / 255, 48 / 255, 48 / 255, 1.0)
        self.tool = INTERACT
        self._textures: dict[int, tuple[np.ndarray, int]] = {}  # GL textures by their image's id, kept while drawn
        self._gpu = GpuBatches()
        self._last: QPointF | None = None
        self._pressed_at: np.ndarray | None = None
        self._band: tuple[QPointF, QPointF] | None = None  # Select's rectangle while dragged
        self.interact: Callable[..., bool] | None = None  # the Interact tool's mouse
        self.setMouseTracking(True)  # moves without a button: the Interact tool's hover highlight
        self._interacting = False  # a control is being dragged
        self.setMinimumSize(320, 240)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)

    # -------------------------------------------------------------- drawing

    def show_scene(self, scene: Scene) -> None:
        """Draw `scene` from now on; repaint only when it differs from the one shown (the same
        batch, label and texture objects: every display reused its cached scene), so a still
        scene costs no drawing at the frame rate. The mouse and resizes repaint on their own."""
        if not (_same(scene.batches, self.scene.batches) and _same(scene.labels, self.scene.labels)
                and _same(scene.textures, self.scene.textures)):
            self.scene = scene
            self.update()

    def paintGL(self) -> None:
        self._paint(overlays=True)

    def _paint(self, overlays: bool) -> None:
        """The scene; with `overlays`, the labels and Select's rectangle over it (Qt's painter,
        only within a paint: a pick draws the scene alone, for its depth)."""
        ratio = self.devicePixelRatioF()
        width, height = int(self.width() * ratio), int(self.height() * ratio)
        GL.glViewport(0, 0, width, height)
        GL.glClearColor(*self.background)
        GL.glClear(GL.GL_COLOR_BUFFER_BIT | GL.GL_DEPTH_BUFFER_BIT)
        GL.glEnable(GL.GL_DEPTH_TEST)  # set each frame: the labels' QPainter leaves GL as it likes
        GL.glEnable(GL.GL_BLEND)  # the frame buffer's alpha stays 1: Qt composes the widget by it
        GL.glBlendFuncSeparate(GL.GL_SRC_ALPHA, GL.GL_ONE_MINUS_SRC_ALPHA, GL.GL_ONE, GL.GL_ONE_MINUS_SRC_ALPHA)
        GL.glUseProgram(0)
        GL.glMatrixMode(GL.GL_PROJECTION)
        GL.glLoadMatrixd(self.camera.projection_matrix(width, height).T.astype(np.float64))
        GL.glMatrixMode(GL.GL_MODELVIEW)
        GL.glLoadIdentity()
        _headlight()  # set in eye space: it moves with the camera, as rviz's default light
        GL.glLoadMatrixd(self.camera.view_matrix().T.astype(np.float64))
        GL.glDepthMask(GL.GL_FALSE)  # maps lie under what shares their plane (the grid), as in rviz
        drawn = set()
        for texture in self.scene.textures:
            self._draw_texture(texture.corners, texture.rgba)
            drawn.add(id(texture.rgba))
        for gone in set(self._textures) - drawn:
            GL.glDeleteTextures([self._textures.pop(gone)[1]])
        GL.glDepthMask(GL.GL_TRUE)
        GL.glEnableClientState(GL.GL_VERTEX_ARRAY)
        for slot, batch in enumerate(self.scene.batches):
            GL.glLineWidth(max(1.0, batch.size))
            GL.glPointSize(max(1.0, batch.size))
            if batch.metres:
                self._point_metres(batch.size, height)
            gpu = self._gpu.uploaded(slot, batch)
            GL.glBindBuffer(GL.GL_ARRAY_BUFFER, gpu.vertices)
            GL.glVertexPointer(3, GL.GL_FLOAT, 0, None)
            if batch.uniform:  # one colour for all: no colour array to upload or read
                GL.glColor4f(*(float(c) for c in batch.float_colors()[0]))
            else:
                GL.glEnableClientState(GL.GL_COLOR_ARRAY)
                GL.glBindBuffer(GL.GL_ARRAY_BUFFER, gpu.colors)
                GL.glColorPointer(4, GL.GL_UNSIGNED_BYTE if batch.colors.dtype == np.uint8 else GL.GL_FLOAT, 0, None)
            lit = batch.kind == "triangles"
            if batch.overlay:
                GL.glDisable(GL.GL_DEPTH_TEST)
            if batch.closed:  # the far side of a closed surface is hidden: llvmpipe need not fill it
                GL.glEnable(GL.GL_CULL_FACE)
            if lit:  # surfaces are shaded by their facing; lines, points and labels are not
                GL.glEnable(GL.GL_LIGHTING)
                GL.glEnableClientState(GL.GL_NORMAL_ARRAY)
                GL.glBindBuffer(GL.GL_ARRAY_BUFFER, gpu.normals)
                GL.glNormalPointer(GL.GL_FLOAT, 0, None)
            if batch.indices is None:
                GL.glDrawArrays(PRIMITIVES[batch.kind], 0, len(batch.vertices))
            else:
                GL.glBindBuffer(GL.GL_ELEMENT_ARRAY_BUFFER, gpu.indices)
                GL.glDrawElements(PRIMITIVES[batch.kind], len(batch.indices), GL.GL_UNSIGNED_INT, None)
                GL.glBindBuffer(GL.GL_ELEMENT_ARRAY_BUFFER, 0)
            GL.glDisable(GL.GL_CULL_FACE)
            GL.glEnable(GL.GL_DEPTH_TEST)
            if batch.metres:
                GL.glPointParameterfv(GL.GL_POINT_DISTANCE_ATTENUATION, (1.0, 0.0, 0.0))
            if lit:
                GL.glDisableClientState(GL.GL_NORMAL_ARRAY)
                GL.glDisable(GL.GL_LIGHTING)
            GL.glDisableClientState(GL.GL_COLOR_ARRAY)
        GL.glBindBuffer(GL.GL_ARRAY_BUFFER, 0)
        self._gpu.keep(len(self.scene.batches))
        GL.glDisableClientState(GL.GL_VERTEX_ARRAY)
        if not overlays:
            return
        self._draw_labels()
        if self._band is not None:
            painter = QPainter(self)
            painter.setPen(QColor(255, 90, 255))
            painter.drawRect(QRectF(*self._band).normalized())
            painter.end()

    def _point_metres(self, metres: float, height: int) -> None:
        """Points `metres` wide where they are: so many pixels in the top-down view; in a
        perspective one the pixels a metre covers 1 m from the eye, divided by each point's
        distance (GL's point distance attenuation, 1 / sqrt(d^2))."""
        camera = self.camera
        if camera.kind == TOP_DOWN:
            GL.glPointSize(max(1.0, metres * camera.scale * height / max(1, self.height())))
            return
        GL.glPointSize(max(1.0, metres * height / (2 * math.tan(camera.fov_y / 2))))
        GL.glPointParameterfv(GL.GL_POINT_DISTANCE_ATTENUATION, (0.0, 0.0, 1.0))

    def _draw_texture(self, corners: np.ndarray, rgba: np.ndarray) -> None:
        known = self._textures.get(id(rgba))
        if known is not None and known[0] is rgba:  # the same map as last frame: uploaded once
            GL.glBindTexture(GL.GL_TEXTURE_2D, known[1])
        else:
            texture = GL.glGenTextures(1)
            self._textures[id(rgba)] = (rgba, texture)
            GL.glBindTexture(GL.GL_TEXTURE_2D, texture)
            GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MIN_FILTER, GL.GL_NEAREST)
            GL.glTexParameteri(GL.GL_TEXTURE_2D, GL.GL_TEXTURE_MAG_FILTER, GL.GL_NEAREST)
            GL.glPixelStorei(GL.GL_UNPACK_ALIGNMENT, 1)
            height, width = rgba.shape[:2]
            GL.glTexImage2D(GL.GL_TEXTURE_2D, 0, GL.GL_RGBA, width, height, 0, GL.GL_RGBA, GL.GL_UNSIGNED_BYTE,
                            np.ascontiguousarray(rgba))
            GL.glPixelStorei(GL.GL_UNPACK_ALIGNMENT, 4)  # as Qt's glyph cache expects it
        GL.glEnable(GL.GL_TEXTURE_2D)
        GL.glColor4f(1, 1, 1, 1)
        GL.glBegin(GL.GL_QUADS)
        for (u, v), corner in zip(((0, 0), (1, 0), (1, 1), (0, 1)), corners, strict=True):
            GL.glTexCoord2f(u, v)
            GL.glVertex3f(*corner)
        GL.glEnd()
        GL.glDisable(GL.GL_TEXTURE_2D)
        GL.glBindTexture(GL.GL_TEXTURE_2D, 0)

    def _draw_labels(self) -> None:
        if not self.scene.labels:
            return
        positions = np.array([label.position for label in self.scene.labels])
        pixels = self.camera.project(positions, self.width(), self.height())
        GL.glDisable(GL.GL_DEPTH_TEST)  # Qt's paint engine draws text with GL: over the scene, untested,
        GL.glBlendFunc(GL.GL_ONE, GL.GL_ONE_MINUS_SRC_ALPHA)  # its glyphs' colours premultiplied
        GL.glColor4f(1, 1, 1, 1)
        GL.glMatrixMode(GL.GL_PROJECTION)
        GL.glLoadIdentity()
        GL.glMatrixMode(GL.GL_MODELVIEW)
        GL.glLoadIdentity()
        painter = QPainter(self)
        line_height = painter.fontMetrics().height()
        for label, (x, y) in zip(self.scene.labels, pixels, strict=True):
            if not (math.isfinite(x) and math.isfinite(y)):
                continue
            lines = label.text.split("\n")  # drawText keeps to one line: an interactive marker's description has more
            for row, line in enumerate(lines):
                below = y - 4 - (len(lines) - 1 - row) * line_height
                painter.setPen(QColor(0, 0, 0, 160))  # a shadow keeps white names readable on a free map
                painter.drawText(QPointF(x + 5, below + 1), line)
                painter.setPen(QColor.fromRgbF(*label.color))
                painter.drawText(QPointF(x + 4, below), line)
        painter.end()

    # -------------------------------------------------------------- mouse

    def _ground(self, event: QMouseEvent) -> np.ndarray | None:
        p = event.position()
        return self.camera.ground_point(p.x(), p.y(), self.width(), self.height())

    def pick(self, x: float, y: float) -> np.ndarray | None:
        """The fixed-frame point drawn at pixel (x, y): the scene is drawn again and its depth
        there read back; where nothing is drawn (or with no OpenGL), the ground's."""
        depth = 1.0
        context = self.context()
        if context is not None and context.isValid():
            self.makeCurrent()
            self._paint(overlays=False)  # the frame buffer's depth may have been discarded after it was shown
            ratio = self.devicePixelRatioF()
            row = int(self.height() * ratio) - 1 - int(y * ratio)
            value = GL.glReadPixels(int(x * ratio), row, 1, 1, GL.GL_DEPTH_COMPONENT, GL.GL_FLOAT)
            self.doneCurrent()
            depth = float(np.asarray(value, dtype=np.float32).reshape(-1)[0])
        if depth < 1.0:
            return self.camera.unproject(x, y, depth, self.width(), self.height())
        return self.camera.ground_point(x, y, self.width(), self.height())

    def mousePressEvent(self, event: QMouseEvent) -> None:
        self._last = event.position()
        left = event.button() == Qt.MouseButton.LeftButton
        right = event.button() == Qt.MouseButton.RightButton
        if self.tool == INTERACT and self.interact is not None and (left or right):
            self._interacting = self.interact("press", event.position().x(), event.position().y(), right,
                                              *_keys(event))
            if self._interacting:
                return
        if self.tool == SELECT and left:
            self._band = (event.position(), event.position())
        elif self.tool == MEASURE and left:
            point = self.pick(event.position().x(), event.position().y())
            if point is not None:
                self.picked.emit(point)
        elif self.tool == MEASURE and event.button() == Qt.MouseButton.RightButton:
            self.unpicked.emit()
        elif self.tool != INTERACT and left:
            self._pressed_at = self._ground(event)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if self._interacting and self.interact is not None:
            self.interact("move", event.position().x(), event.position().y(), False, *_keys(event))
            return
        if event.buttons() == Qt.MouseButton.NoButton:  # tracked: the control under the mouse is highlit
            if self.tool == INTERACT and self.interact is not None:
                self.interact("hover", event.position().x(), event.position().y(), False)
            return
        if self._band is not None:
            self._band = (self._band[0], event.position())
            self.update()
            return
        if self._last is None or self._pressed_at is not None:
            return
        if self.tool == MEASURE and event.buttons() & Qt.MouseButton.LeftButton:
            return
        dx, dy = event.position().x() - self._last.x(), event.position().y() - self._last.y()
        self._last = event.position()
        buttons = event.buttons()
        if buttons & Qt.MouseButton.LeftButton and not event.modifiers() & Qt.KeyboardModifier.ShiftModifier:
            self.camera.rotate(dx, dy)
        elif buttons & (Qt.MouseButton.MiddleButton | Qt.MouseButton.LeftButton):
            self.camera.pan(dx, dy, self.height())
        elif buttons & Qt.MouseButton.RightButton:
            self.camera.zoom(-dy / 20)
        self.update()

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        if self._interacting and self.interact is not None:
            self._interacting = False
            self.interact("release", event.position().x(), event.position().y(), False)
            self._last = None
            return
        if self._band is not None:
            start = self._band[0]
            self._band = None
            self.area.emit((start.x(), start.y()), (event.position().x(), event.position().y()))
            self.update()
        if self._pressed_at is not None:
            released = self._ground(event)
            self.clicked.emit(self._pressed_at, released if released is not None else self._pressed_at)
        self._pressed_at = None
        self._last = None

    def wheelEvent(self, event: QWheelEvent) -> None:
        if self._interacting and self.interact is not None:  # a 3-D drag: rviz moves the marker along the ray
            self.interact("wheel", event.position().x(), event.position().y(), False, wheel=event.angleDelta().y())
            return
        self.camera.zoom(event.angleDelta().y() / 120)
        self.update()


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
        self.setCentralWidget(self.view)
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
        self.started = time.monotonic()
        self.stats = FrameStats(self.started)
        self.view.frameSwapped.connect(self.stats.frame_shown)  # drawn and shown: a grab is neither

    # -------------------------------------------------------------- building

    def _tools(self) -> None:
        bar = self.addToolBar("Tools")
        bar.setObjectName("Tools")
        group = QActionGroup(self)
        for name in (INTERACT, SELECT, MEASURE, POSE_ESTIMATE, NAV_GOAL, PUBLISH_POINT):
            action = QAction(name, self, checkable=True)
            action.setChecked(name == INTERACT)
            action.triggered.connect(lambda _checked=False, tool=name: self.set_tool(tool))
            group.addAction(action)
            bar.addAction(action)
        self.views = QComboBox()
        self.views.addItems([ORBIT, TOP_DOWN, FPS])
        self.views.setCurrentText(self.config.camera.kind)
        self.views.currentTextChanged.connect(self.set_view)
        bar.addWidget(self.views)

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
        publish: Callable[[str, Any], None] | None = self.source.publish_stamped if self.source is not None else None
        if publish is None or self.view.tool == INTERACT:
            return
        from geometry_msgs.msg import PointStamped, PoseStamped, PoseWithCovarianceStamped

        yaw = math.atan2(released[1] - pressed[1], released[0] - pressed[0]) if np.linalg.norm(
            released[:2] - pressed[:2]) > 1e-6 else 0.0
        if self.view.tool == PUBLISH_POINT:
            point = PointStamped()
            point.header.frame_id = self.config.fixed_frame
            point.point.x, point.point.y, point.point.z = (float(v) for v in released)
            publish("/clicked_point", point)
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
            publish("/initialpose", pose)
        else:
            publish("/move_base_simple/goal", pose)

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
