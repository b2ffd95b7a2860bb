"""rqt_graph's window (PySide6): draws a graph_layout.Layout and lets the user choose what to show.

Rules: the window only draws; what to draw comes from kame.rqt.graph_model and
graph_layout. Refreshing asks the graph on a thread the window owns (one at a time), and the
snapshot comes back through a queued signal, so a slow graph never freezes the window.
Hovering a node or topic highlights it, its edges and its neighbours.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QPointF, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import (
    QBrush,
    QCloseEvent,
    QColor,
    QFont,
    QFontMetricsF,
    QImage,
    QPainter,
    QPainterPath,
    QPen,
    QPolygonF,
    QResizeEvent,
    QWheelEvent,
)
from PySide6.QtWidgets import (
    QApplication,
    QCheckBox,
    QComboBox,
    QFileDialog,
    QGraphicsEllipseItem,
    QGraphicsItem,
    QGraphicsPathItem,
    QGraphicsRectItem,
    QGraphicsScene,
    QGraphicsSceneHoverEvent,
    QGraphicsSimpleTextItem,
    QGraphicsView,
    QLabel,
    QLineEdit,
    QPushButton,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from kame.rqt.flow_layout import FlowLayout
from kame.rqt.graph_export import to_dot, to_svg
from kame.rqt.graph_layout import FONT_SIZE, Layout, cubic_segments, layout
from kame.rqt.graph_model import GraphOptions, GraphSnapshot, Kind, Mode, Scene, build_scene

INK = QColor("#000000")
HIGHLIGHT_NODE = QColor("#1f6fd1")
HIGHLIGHT_TOPIC = QColor("#d12f1f")
HIGHLIGHT_EDGE = QColor("#2a9d3a")
FADED = QColor("#b8b8b8")
UNREACHABLE = QColor("#cc0000")
CLUSTER = QColor("#6b7a8f")


def graph_font() -> QFont:
    font = QFont("sans-serif")
    font.setPixelSize(int(FONT_SIZE))
    return font


def measure_with(font: QFont) -> Callable[[str], float]:
    metrics = QFontMetricsF(font)
    return lambda text: float(metrics.horizontalAdvance(text))


class _Shape:
    """What a drawn vertex tells the scene when the mouse enters or leaves it."""

    def __init__(self, vertex_id: str, on_hover: Callable[[str | None], None]) -> None:
        self.vertex_id = vertex_id
        self.on_hover = on_hover


class _Ellipse(QGraphicsEllipseItem):
    shape_info: _Shape

    def hoverEnterEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.shape_info.on_hover(self.shape_info.vertex_id)

    def hoverLeaveEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.shape_info.on_hover(None)


class _Rect(QGraphicsRectItem):
    shape_info: _Shape

    def hoverEnterEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.shape_info.on_hover(self.shape_info.vertex_id)

    def hoverLeaveEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.shape_info.on_hover(None)


class GraphScene(QGraphicsScene):
    """The drawing of one layout; `highlight(vertex_id)` colours a neighbourhood, None clears."""

    def __init__(self, drawn: Layout, font: QFont, on_hover: Callable[[str | None], None] | None = None) -> None:
        super().__init__()
        self.layout_model = drawn
        self.setSceneRect(QRectF(0, 0, drawn.width, drawn.height))
        self.setBackgroundBrush(QBrush(QColor("#ffffff")))
        self.vertex_items: dict[str, QGraphicsItem] = {}
        self.edge_items: list[tuple[QGraphicsPathItem, QGraphicsPathItem]] = []
        hover = on_hover or self.highlight
        for namespace, box in drawn.groups.items():
            rect = self.addRect(QRectF(box.x, box.y, box.w, box.h), QPen(CLUSTER, 1, Qt.PenStyle.DashLine),
                                QBrush(QColor("#f4f6fa")))
            rect.setZValue(-1)
            title = QGraphicsSimpleTextItem(namespace, rect)
            title.setFont(font)
            title.setBrush(QBrush(CLUSTER))
            title.setPos(box.x + 6, box.y + 2)
        scene = drawn.scene
        for index, edge in enumerate(scene.edges):
            points = drawn.paths[index]
            path = QPainterPath(QPointF(*points[0]))
            for c1, c2, end in cubic_segments(points):
                path.cubicTo(QPointF(*c1), QPointF(*c2), QPointF(*end))
            line = self.addPath(path, QPen(INK, 1.2))
            head = self.addPath(_arrowhead(points[-2], points[-1]), QPen(INK, 1), QBrush(INK))
            self.edge_items.append((line, head))
            if edge.label:
                label = self.addSimpleText(edge.label, font)
                box = drawn.labels[index]
                label.setPos(box.x + (box.w - label.boundingRect().width()) / 2, box.y)
        for vertex in scene.vertices:
            box = drawn.boxes[vertex.id]
            item: _Ellipse | _Rect = (_Ellipse if vertex.kind is Kind.NODE else _Rect)(
                QRectF(box.x, box.y, box.w, box.h))
            item.shape_info = _Shape(vertex.id, hover)
            item.setAcceptHoverEvents(True)
            item.setPen(QPen(UNREACHABLE if vertex.unreachable else INK, 1.2))
            item.setBrush(QBrush(QColor("#ffffff")))
            item.setToolTip(vertex.name + (" (unreachable)" if vertex.unreachable else ""))
            self.addItem(item)
            text = QGraphicsSimpleTextItem(vertex.name, item)
            text.setFont(font)
            bounds = text.boundingRect()
            text.setPos(box.x + (box.w - bounds.width()) / 2, box.y + (box.h - bounds.height()) / 2)
            self.vertex_items[vertex.id] = item
        self.highlighted: str | None = None

    def highlight(self, vertex_id: str | None) -> None:
        self.highlighted = vertex_id
        scene = self.layout_model.scene
        lit_vertices, lit_edges = scene.neighbourhood(vertex_id) if vertex_id else (set(), set())
        for vid, item in self.vertex_items.items():
            vertex = scene.vertex(vid)
            colour = UNREACHABLE if vertex.unreachable else INK
            if vertex_id is not None:
                colour = (HIGHLIGHT_NODE if vertex.kind is Kind.NODE else HIGHLIGHT_TOPIC) if vid in lit_vertices \
                    else FADED
            assert isinstance(item, (_Ellipse, _Rect))
            item.setPen(QPen(colour, 2.4 if vid in lit_vertices else 1.2))
        for index, (line, head) in enumerate(self.edge_items):
            colour = INK if vertex_id is None else (HIGHLIGHT_EDGE if index in lit_edges else FADED)
            line.setPen(QPen(colour, 2.4 if index in lit_edges else 1.2))
            head.setPen(QPen(colour, 1))
            head.setBrush(QBrush(colour))


def _arrowhead(before: tuple[float, float], tip: tuple[float, float]) -> QPainterPath:
    dx, dy = tip[0] - before[0], tip[1] - before[1]
    length = (dx * dx + dy * dy) ** 0.5 or 1.0
    ux, uy = dx / length, dy / length
    back = (tip[0] - ux * 9, tip[1] - uy * 9)
    path = QPainterPath()
    path.addPolygon(QPolygonF([QPointF(*tip), QPointF(back[0] - uy * 4, back[1] + ux * 4),
                               QPointF(back[0] + uy * 4, back[1] - ux * 4), QPointF(*tip)]))
    return path


def render_image(drawn: Layout, font: QFont, scale: float = 1.0) -> QImage:
    """The graph as a picture (needs a QApplication)."""
    scene = GraphScene(drawn, font)
    image = QImage(max(1, int(drawn.width * scale)), max(1, int(drawn.height * scale)), QImage.Format.Format_RGB32)
    image.fill(QColor("#ffffff"))
    painter = QPainter(image)
    painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
    painter.setRenderHint(QPainter.RenderHint.TextAntialiasing, True)
    scene.render(painter, QRectF(0, 0, image.width(), image.height()), scene.sceneRect())
    painter.end()
    return image


def save_drawing(path: Path, drawn: Layout, font: QFont | None = None) -> None:
    """`.svg`, `.dot` or an image format Qt writes (`.png`, `.jpg`, ...), by the file's suffix."""
    suffix = path.suffix.lower()
    if suffix == ".svg":
        path.write_text(to_svg(drawn))
    elif suffix in (".dot", ".gv"):
        path.write_text(to_dot(drawn.scene))
    elif not render_image(drawn, font or graph_font()).save(str(path)):
        raise OSError(f"cannot write an image to {path}")


class _ZoomView(QGraphicsView):
    """The graph's view: the wheel zooms. Until the user zooms, the view keeps the graph fitted
    as it is resized (a docked window is laid out after its first drawing)."""

    def __init__(self) -> None:
        super().__init__()
        self.fitted = True

    def fit(self) -> None:
        scene = self.scene()
        if scene is not None:
            self.fitInView(scene.sceneRect(), Qt.AspectRatioMode.KeepAspectRatio)
        self.fitted = True

    def wheelEvent(self, event: QWheelEvent) -> None:
        factor = 1.15 if event.angleDelta().y() > 0 else 1 / 1.15
        self.scale(factor, factor)
        self.fitted = False

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        if self.fitted:
            self.fit()


class GraphWindow(QWidget):
    """The rqt_graph window. `fetch` returns a snapshot (it runs on the window's worker thread)."""

    snapshot_ready = Signal(object)  # a GraphSnapshot, or the error text
    refreshed = Signal()

    def __init__(self, fetch: Callable[[], GraphSnapshot], options: GraphOptions | None = None) -> None:
        super().__init__()
        self.fetch = fetch
        self.setWindowTitle("rqt_graph")
        self.font_ = graph_font()
        self.snapshot: GraphSnapshot | None = None
        self.scene_model: Scene | None = None
        self.layout_model: Layout | None = None
        self.graphics: GraphScene | None = None
        self._worker: threading.Thread | None = None
        self._again = False
        options = options or GraphOptions()

        self.refresh_button = QPushButton("Refresh")
        self.mode_box = QComboBox()
        for mode in Mode:
            self.mode_box.addItem(mode.value, mode)
        self.mode_box.setCurrentIndex(list(Mode).index(options.mode))
        self.node_filter = QLineEdit(options.node_filter)
        self.node_filter.setPlaceholderText("node filter: a, -b (regex)")
        self.topic_filter = QLineEdit(options.topic_filter)
        self.topic_filter.setPlaceholderText("topic filter")
        self.auto_refresh = QCheckBox("Auto refresh (s)")
        self.auto_period = QSpinBox()
        self.auto_period.setRange(1, 60)
        self.auto_period.setValue(2)
        self.fit_button = QPushButton("Fit")
        self.save_button = QPushButton("Save...")
        self.group_box = QCheckBox("Group namespaces")
        self.group_box.setChecked(options.group_namespaces)
        self.actions_box = QCheckBox("Group actions")
        self.actions_box.setChecked(options.group_actions)
        self.debug_box = QCheckBox("Hide debug")
        self.debug_box.setChecked(options.hide_debug)
        self.dead_box = QCheckBox("Hide dead sinks")
        self.dead_box.setChecked(options.hide_dead_sinks)
        self.leaf_box = QCheckBox("Hide leaf topics")
        self.leaf_box.setChecked(options.hide_leaf_topics)
        self.unreachable_box = QCheckBox("Hide unreachable")
        self.unreachable_box.setChecked(options.hide_unreachable)
        self.highlight_box = QCheckBox("Highlight")
        self.highlight_box.setChecked(True)
        self.status = QLabel("")
        self.view = _ZoomView()
        self.view.setRenderHint(QPainter.RenderHint.Antialiasing, True)
        self.view.setDragMode(QGraphicsView.DragMode.ScrollHandDrag)

        # rows that wrap: in a narrow dock every control stays on screen (Fit and Save were cut off)
        first = FlowLayout()
        first.add_widgets(self.refresh_button, self.mode_box, self.node_filter, self.topic_filter, self.auto_refresh,
                          self.auto_period, self.fit_button, self.save_button)
        second = FlowLayout()
        second.add_widgets(self.group_box, self.actions_box, self.debug_box, self.dead_box, self.leaf_box,
                           self.unreachable_box, self.highlight_box, self.status)
        column = QVBoxLayout(self)
        column.addLayout(first)
        column.addLayout(second)
        column.addWidget(self.view, 1)
        self.resize(1000, 640)

        self.timer = QTimer(self)
        self.timer.timeout.connect(self.refresh)
        self.snapshot_ready.connect(self._on_snapshot)
        self.refresh_button.clicked.connect(self.refresh)
        self.fit_button.clicked.connect(self.fit)
        self.save_button.clicked.connect(self._ask_save)
        self.auto_refresh.toggled.connect(self._auto_changed)
        self.auto_period.valueChanged.connect(self._auto_changed)
        # another mode, filter or option draws another graph: fitted, or it may lie off-screen
        self.mode_box.currentIndexChanged.connect(self._restyled)
        for line in (self.node_filter, self.topic_filter):
            line.editingFinished.connect(self._restyled)
        for box in (self.group_box, self.actions_box, self.debug_box, self.dead_box, self.leaf_box,
                    self.unreachable_box):
            box.toggled.connect(self._restyled)
        self.highlight_box.toggled.connect(self._highlight_toggled)

    def options(self) -> GraphOptions:
        return GraphOptions(mode=self.mode_box.currentData(), group_namespaces=self.group_box.isChecked(),
                            hide_debug=self.debug_box.isChecked(), hide_dead_sinks=self.dead_box.isChecked(),
                            hide_leaf_topics=self.leaf_box.isChecked(),
                            hide_unreachable=self.unreachable_box.isChecked(),
                            node_filter=self.node_filter.text(), topic_filter=self.topic_filter.text(),
                            group_actions=self.actions_box.isChecked())

    # ---------------------------------------------------------------- refreshing

    def refresh(self) -> None:
        """Ask the graph again, on the worker thread; a refresh asked meanwhile runs after it."""
        if self._worker is not None and self._worker.is_alive():
            self._again = True
            return
        self.refresh_button.setEnabled(False)
        self._worker = threading.Thread(target=self._fetch, name="rqt-graph-refresh", daemon=True)
        self._worker.start()

    def _fetch(self) -> None:
        try:
            result: object = self.fetch()
        except Exception as exc:  # shown in the window: the master may be gone
            result = f"cannot reach the master: {exc}"
        self.snapshot_ready.emit(result)

    def _on_snapshot(self, result: object) -> None:
        self.refresh_button.setEnabled(True)
        if isinstance(result, GraphSnapshot):
            self.snapshot = result
            self.redraw()
        else:
            self.status.setText(str(result))
        if self._again:
            self._again = False
            self.refresh()
        self.refreshed.emit()

    def _auto_changed(self) -> None:
        if self.auto_refresh.isChecked():
            self.timer.start(self.auto_period.value() * 1000)
        else:
            self.timer.stop()

    # ---------------------------------------------------------------- drawing

    def redraw(self) -> None:
        if self.snapshot is None:
            return
        first = self.graphics is None
        self.scene_model = build_scene(self.snapshot, self.options())
        self.layout_model = layout(self.scene_model, measure_with(self.font_))
        self.graphics = GraphScene(self.layout_model, self.font_, self._hover)
        self.view.setScene(self.graphics)
        nodes = len(self.scene_model.names(Kind.NODE))
        topics = len(self.scene_model.names(Kind.TOPIC))
        text = f"{nodes} nodes, {topics} topics, {len(self.scene_model.edges)} edges"
        if self.snapshot.unreachable:
            text += f"; unreachable: {', '.join(sorted(self.snapshot.unreachable))}"
        self.status.setText(text)
        if first:
            self.fit()

    def _restyled(self, *_: object) -> None:
        self.redraw()
        self.fit()

    def _hover(self, vertex_id: str | None) -> None:
        if self.graphics is not None and self.highlight_box.isChecked():
            self.graphics.highlight(vertex_id)

    def _highlight_toggled(self, on: bool) -> None:
        if self.graphics is not None and not on:
            self.graphics.highlight(None)

    def fit(self) -> None:
        self.view.fit()

    def _ask_save(self) -> None:
        if self.layout_model is None:
            return
        name, _ = QFileDialog.getSaveFileName(self, "Save graph", "rosgraph.svg",
                                              "SVG (*.svg);;PNG (*.png);;Graphviz dot (*.dot)")
        if name:
            try:
                save_drawing(Path(name), self.layout_model, self.font_)
            except OSError as exc:
                self.status.setText(str(exc))

    def closeEvent(self, event: QCloseEvent) -> None:
        self.timer.stop()
        if self._worker is not None:
            self._worker.join()  # bounded: every call it makes has a timeout
        super().closeEvent(event)


def application() -> QApplication:
    app = QApplication.instance()
    if isinstance(app, QApplication):
        return app
    return QApplication(["rqt_graph"])
