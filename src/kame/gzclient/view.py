"""gzclient's 3-D view: rviz's RenderView drawing the model's scene, with Gazebo's mouse instead
of rviz's (kame.gzclient.model says which button does what): an orbit and the wheel first take the
point under the mouse as the focal point, as Gazebo does. A left click that lands on a model
selects it; in the translate or rotate mode its drag moves the model instead of the camera."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from OpenGL import GL
from PySide6.QtCore import QPointF, Qt
from PySide6.QtGui import QMouseEvent, QWheelEvent

from kame.gzclient.model import MAX_LIGHTS, ORBIT, ClientModel, ModelMove, drag_action, focus_on, move_camera, view_ray
from kame.rviz.view import RenderView


class GazeboView(RenderView):
    def __init__(self, model: ClientModel, moved: Callable[[ModelMove], None]) -> None:
        super().__init__()
        self.model = model
        self.camera = model.camera
        self._moved = moved
        self._previous: QPointF | None = None
        self.lighting = self._world_lights

    def _ray(self, event: QMouseEvent) -> tuple[np.ndarray, np.ndarray]:
        p = event.position()
        return view_ray(self.camera, p.x(), p.y(), self.width(), self.height())

    def _world_lights(self) -> None:
        """The world's lights, fixed in the world as the camera moves (rviz lights from the eye), and
        its ambient light; called in the paint with the view's context current."""
        GL.glLoadMatrixd(self.camera.view_matrix().T.astype(np.float64))
        for slot in range(MAX_LIGHTS):
            light = GL.GL_LIGHT0 + slot
            if slot >= len(self.model.lights):
                GL.glDisable(light)
                continue
            GL.glLightfv(light, GL.GL_POSITION, self.model.lights[slot].position)
            GL.glLightfv(light, GL.GL_DIFFUSE, self.model.lights[slot].diffuse)
            GL.glLightfv(light, GL.GL_AMBIENT, (0.0, 0.0, 0.0, 1.0))
            GL.glLightfv(light, GL.GL_SPECULAR, (0.0, 0.0, 0.0, 1.0))
            GL.glEnable(light)
        GL.glLightModelfv(GL.GL_LIGHT_MODEL_AMBIENT, self.model.ambient)
        GL.glLightModeli(GL.GL_LIGHT_MODEL_TWO_SIDE, GL.GL_TRUE)  # shapes are not all wound one way
        GL.glEnable(GL.GL_COLOR_MATERIAL)
        GL.glColorMaterial(GL.GL_FRONT_AND_BACK, GL.GL_AMBIENT_AND_DIFFUSE)

    def refresh(self) -> None:
        self.background = self.model.background
        self.show_scene(self.model.render())

    def _focus_under(self, event: QMouseEvent | QWheelEvent) -> None:
        p = event.position()
        point = self.model.surface_point(*view_ray(self.camera, p.x(), p.y(), self.width(), self.height()))
        if point is not None:
            focus_on(self.camera, point)

    def mousePressEvent(self, event: QMouseEvent) -> None:
        self._previous = event.position()
        shift = bool(event.modifiers() & Qt.KeyboardModifier.ShiftModifier)
        left, middle = event.button() == Qt.MouseButton.LeftButton, event.button() == Qt.MouseButton.MiddleButton
        if drag_action(left, middle, False, shift) == ORBIT:
            self._focus_under(event)
        elif left and self.model.press(*self._ray(event)):
            self.refresh()

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if self._previous is None:
            return
        if self.model.dragging:
            move = self.model.drag(*self._ray(event))
            if move is not None:
                self._moved(move)
            return
        buttons = event.buttons()
        action = drag_action(bool(buttons & Qt.MouseButton.LeftButton), bool(buttons & Qt.MouseButton.MiddleButton),
                             bool(buttons & Qt.MouseButton.RightButton),
                             bool(event.modifiers() & Qt.KeyboardModifier.ShiftModifier))
        dx, dy = event.position().x() - self._previous.x(), event.position().y() - self._previous.y()
        self._previous = event.position()
        if action is not None:
            move_camera(self.camera, action, dx, dy, self.height())
            self.update()

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        self.model.release()
        self._previous = None

    def wheelEvent(self, event: QWheelEvent) -> None:
        self._focus_under(event)
        self.camera.zoom(event.angleDelta().y() / 120)
        self.update()
