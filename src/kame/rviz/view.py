"""rviz's 3-D view: draws the model's Scene through a Camera with OpenGL (PyOpenGL) in a native
window of its own (QOpenGLWindow, embedded in the main window by a container), and turns the
mouse into camera moves or the tools' clicks, drags and picks as rviz does.

A native window swaps its frames straight to the screen: a QOpenGLWidget's would first be
composed with the whole main window's (its panels too) into one frame, every frame, which under
Mesa's software rendering costs about as much as drawing 2,000 markers (12 ms of a frame at
1604x769). Where Qt can make no OpenGL context (offscreen Qt without a display) the view paints
nothing, and its camera and tools still work."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from OpenGL import GL
from PySide6.QtCore import QEvent, QPointF, QRectF, Qt, Signal
from PySide6.QtGui import (
    QColor,
    QExposeEvent,
    QImage,
    QMouseEvent,
    QOpenGLContext,
    QPainter,
    QResizeEvent,
    QSurfaceFormat,
    QWheelEvent,
)
from PySide6.QtOpenGL import QOpenGLWindow

from kame.rviz.camera import TOP_DOWN, Camera
from kame.rviz.gpu_batches import GpuBatches
from kame.rviz.scene import Scene

PRIMITIVES = {"lines": GL.GL_LINES, "points": GL.GL_POINTS, "triangles": GL.GL_TRIANGLES}
INTERACT, POSE_ESTIMATE, NAV_GOAL, PUBLISH_POINT = "Interact", "2D Pose Estimate", "2D Nav Goal", "Publish Point"
SELECT, MEASURE = "Select", "Measure"


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


def _opengl_available() -> bool:
    """Whether Qt can make an OpenGL context here (a QOpenGLWindow painted without one crashes)."""
    return QOpenGLContext().create()


class RenderView(QOpenGLWindow):
    """Draws a Scene through a Camera; the mouse moves the camera as rviz's does, or drives a tool."""

    clicked = Signal(object, object)  # ground point pressed, ground point released (numpy arrays)
    picked = Signal(object)  # Measure: the point under a left click (on the geometry there, else the ground)
    unpicked = Signal()  # Measure: a right click
    area = Signal(object, object)  # Select: the corners (x, y pixels) of the rectangle dragged

    def __init__(self) -> None:
        super().__init__()
        surface = QSurfaceFormat()
        surface.setDepthBufferSize(24)  # a window's own buffer has no depth unless asked (a QOpenGLWidget's had)
        surface.setStencilBufferSize(8)  # Qt's painter clips the labels with it
        self.setFormat(surface)
        self.drawable = _opengl_available()
        self.camera = Camera()
        self.scene = Scene()
        self.background = (48 / 255, 48 / 255, 48 / 255, 1.0)
        self.tool = INTERACT
        self.lighting: Callable[[], None] = _headlight  # lights the scene (rviz: one at the eye; gzclient: the world's)
        self._textures: dict[int, tuple[np.ndarray, int]] = {}  # GL textures by their image's id, kept while drawn
        self._gpu = GpuBatches()
        self._last: QPointF | None = None
        self._pressed_at: np.ndarray | None = None
        self._band: tuple[QPointF, QPointF] | None = None  # Select's rectangle while dragged
        self.interact: Callable[..., bool] | None = None  # the Interact tool's mouse
        self._interacting = False  # a control is being dragged

    # -------------------------------------------------------------- without OpenGL: no painting

    def event(self, event: QEvent) -> bool:
        if not self.drawable and event.type() in (QEvent.Type.UpdateRequest, QEvent.Type.Paint):
            return True
        return super().event(event)

    def exposeEvent(self, event: QExposeEvent) -> None:
        if self.drawable:
            super().exposeEvent(event)

    def resizeEvent(self, event: QResizeEvent) -> None:
        if self.drawable:  # QOpenGLWindow makes its context here
            super().resizeEvent(event)

    # -------------------------------------------------------------- drawing

    def show_scene(self, scene: Scene) -> None:
        """Draw `scene` from now on; repaint only when it differs from the one shown (the same
        batch, label and texture objects: every display reused its cached scene), so a still
        scene costs no drawing at the frame rate. The mouse and resizes repaint on their own."""
        if not (_same(scene.batches, self.scene.batches) and _same(scene.labels, self.scene.labels)
                and _same(scene.textures, self.scene.textures)):
            self.scene = scene
            self.update()

    def grabFramebuffer(self) -> QImage:
        """The scene as drawn now, read back (QOpenGLWindow's own would read the back buffer of a
        frame already swapped to the screen); empty without OpenGL."""
        if not self.drawable:
            return QImage()
        self.makeCurrent()
        self._paint(overlays=True)
        image = super().grabFramebuffer()
        self.doneCurrent()
        return image

    def paintGL(self) -> None:
        self._paint(overlays=True)

    def _paint(self, overlays: bool) -> None:
        """The scene, into the view's context (current); with `overlays`, the labels and Select's
        rectangle over it with Qt's painter (a pick draws the scene alone, for its depth)."""
        ratio = self.devicePixelRatio()
        width, height = int(self.width() * ratio), int(self.height() * ratio)
        GL.glViewport(0, 0, width, height)
        GL.glClearColor(*self.background)
        GL.glClear(GL.GL_COLOR_BUFFER_BIT | GL.GL_DEPTH_BUFFER_BIT)
        GL.glEnable(GL.GL_DEPTH_TEST)  # set each frame: the labels' QPainter leaves GL as it likes
        GL.glEnable(GL.GL_BLEND)  # translucent colours; the frame buffer's own alpha stays 1 (opaque to a compositor)
        GL.glBlendFuncSeparate(GL.GL_SRC_ALPHA, GL.GL_ONE_MINUS_SRC_ALPHA, GL.GL_ONE, GL.GL_ONE_MINUS_SRC_ALPHA)
        GL.glUseProgram(0)
        GL.glMatrixMode(GL.GL_PROJECTION)
        GL.glLoadMatrixd(self.camera.projection_matrix(width, height).T.astype(np.float64))
        GL.glMatrixMode(GL.GL_MODELVIEW)
        GL.glLoadIdentity()
        self.lighting()  # rviz's is set in eye space: it moves with the camera, as rviz's default light
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
            ratio = self.devicePixelRatio()
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


