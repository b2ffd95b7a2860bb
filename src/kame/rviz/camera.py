"""rviz's three views as numbers: the orbit camera (a focal point, distance, yaw and pitch; left
drag rotates, middle drag pans, the wheel zooms), the top-down orthographic one (a centre and a
scale) and the first-person one (rviz/FPS: an eye position, yaw and pitch; left drag turns the
head, middle drag moves sideways and up, the wheel moves forward). Each gives the 4x4 view and
projection matrices OpenGL takes and projects a point of the fixed frame to a pixel, so a test
can say where geometry must appear."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

ORBIT = "rviz/Orbit"
TOP_DOWN = "rviz/TopDownOrtho"
FPS = "rviz/FPS"
MIN_DISTANCE = 0.01
PITCH_LIMIT = math.pi / 2 - 0.001


def _look_at(eye: np.ndarray, target: np.ndarray, up: np.ndarray) -> np.ndarray:
    forward = target - eye
    forward /= np.linalg.norm(forward)
    side = np.cross(forward, up)
    side /= np.linalg.norm(side)
    true_up = np.cross(side, forward)
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = side, true_up, -forward
    view[:3, 3] = -view[:3, :3] @ eye
    return view


@dataclass
class Camera:
    kind: str = ORBIT
    focal_point: np.ndarray = field(default_factory=lambda: np.zeros(3))
    distance: float = 10.0
    yaw: float = 0.785398  # rviz's defaults
    pitch: float = 0.785398
    fov_y: float = 0.785398
    scale: float = 10.0  # top-down: pixels per metre
    angle: float = 0.0  # top-down: the view's rotation about z
    near: float = 0.01
    far: float = 1000.0
    position: np.ndarray = field(default_factory=lambda: np.array([-10.0, 0.0, 10.0]))  # first-person: the eye

    def become(self, kind: str) -> None:
        """Switch to view `kind` seeing what this one sees, as rviz's view chooser does (the
        top-down view keeps its own centre and scale)."""
        if kind == self.kind:
            return
        if kind == FPS and self.kind == ORBIT:  # from the orbit's eye towards its focal point
            self.position = self.eye()
            self.yaw, self.pitch = self.yaw + math.pi, self.pitch
        elif kind == ORBIT and self.kind == FPS:  # the focal point `distance` ahead of the eye
            self.focal_point = np.asarray(self.position, dtype=float) + self.distance * self.forward()
            self.yaw = self.yaw - math.pi
        self.kind = kind

    def forward(self) -> np.ndarray:
        """First-person: the unit vector the eye looks along (a positive pitch looks down)."""
        cp = math.cos(self.pitch)
        return np.array([cp * math.cos(self.yaw), cp * math.sin(self.yaw), -math.sin(self.pitch)])

    # -------------------------------------------------------------- mouse

    def rotate(self, dx: float, dy: float) -> None:
        """A left drag of (dx, dy) pixels, as rviz's orbit view turns (0.005 rad a pixel)."""
        if self.kind == TOP_DOWN:
            self.angle += dx * 0.005
            return
        if self.kind == FPS:  # rviz's FPS view: the head turns the other way up and down
            self.yaw -= dx * 0.005
            self.pitch = min(PITCH_LIMIT, max(-PITCH_LIMIT, self.pitch + dy * 0.005))
            return
        self.yaw -= dx * 0.005
        self.pitch = min(PITCH_LIMIT, max(-PITCH_LIMIT, self.pitch + dy * 0.005))

    def pan(self, dx: float, dy: float, height: int) -> None:
        """A middle drag: the focal point follows the mouse in the view's plane."""
        if self.kind == TOP_DOWN:
            c, s = math.cos(self.angle), math.sin(self.angle)
            mx, my = -dx / self.scale, dy / self.scale
            self.focal_point = self.focal_point + np.array([c * mx - s * my, s * mx + c * my, 0.0])
            return
        if self.kind == FPS:  # rviz's: 1 cm a pixel, right and up
            view = self.view_matrix()
            self.position = np.asarray(self.position, dtype=float) + (dx * view[0, :3] - dy * view[1, :3]) * 0.01
            return
        metres_per_pixel = 2 * self.distance * math.tan(self.fov_y / 2) / max(1, height)
        view = self.view_matrix()
        right, up = view[0, :3], view[1, :3]
        self.focal_point = self.focal_point + (-dx * right + dy * up) * metres_per_pixel

    def zoom(self, steps: float) -> None:
        """Wheel steps (one notch = 1; forward zooms in), 10 % a notch as rviz does."""
        factor = 0.9 ** steps
        if self.kind == FPS:  # rviz's: 1.2 m forward a notch
            self.position = np.asarray(self.position, dtype=float) + 1.2 * steps * self.forward()
            return
        if self.kind == TOP_DOWN:
            self.scale /= factor
        else:
            self.distance = max(MIN_DISTANCE, self.distance * factor)

    # -------------------------------------------------------------- matrices

    def eye(self) -> np.ndarray:
        if self.kind == FPS:
            return np.asarray(self.position, dtype=float)
        cp = math.cos(self.pitch)
        offset = np.array([cp * math.cos(self.yaw), cp * math.sin(self.yaw), math.sin(self.pitch)])
        return np.asarray(self.focal_point, dtype=float) + self.distance * offset

    def view_matrix(self) -> np.ndarray:
        if self.kind == TOP_DOWN:
            c, s = math.cos(self.angle), math.sin(self.angle)
            rotation = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
            view = np.eye(4)
            view[:3, :3] = rotation
            view[:3, 3] = -rotation @ (np.asarray(self.focal_point, dtype=float) + np.array([0.0, 0.0, 500.0]))
            return view
        if self.kind == FPS:
            return _look_at(self.eye(), self.eye() + self.forward(), np.array([0.0, 0.0, 1.0]))
        return _look_at(self.eye(), np.asarray(self.focal_point, dtype=float), np.array([0.0, 0.0, 1.0]))

    def projection_matrix(self, width: int, height: int) -> np.ndarray:
        aspect = max(1, width) / max(1, height)
        if self.kind == TOP_DOWN:
            # a view not yet laid out is 0 pixels wide
            half_w, half_h = max(1, width) / (2 * self.scale), max(1, height) / (2 * self.scale)
            projection = np.eye(4)
            projection[0, 0], projection[1, 1] = 1 / half_w, 1 / half_h
            projection[2, 2], projection[2, 3] = -2 / self.far, -1.0
            return projection
        f = 1 / math.tan(self.fov_y / 2)
        projection = np.zeros((4, 4))
        projection[0, 0], projection[1, 1] = f / aspect, f
        projection[2, 2] = (self.far + self.near) / (self.near - self.far)
        projection[2, 3] = 2 * self.far * self.near / (self.near - self.far)
        projection[3, 2] = -1.0
        return projection

    def project(self, points: np.ndarray, width: int, height: int) -> np.ndarray:
        """Pixels (x right, y down from the top-left) of N points (N x 3); NaN for points behind."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        homogeneous = np.hstack([points, np.ones((len(points), 1))])
        clip = homogeneous @ (self.projection_matrix(width, height) @ self.view_matrix()).T
        w = clip[:, 3:4]
        with np.errstate(divide="ignore", invalid="ignore"):
            ndc = np.where(w > 0, clip[:, :3] / w, np.nan)
        return np.column_stack([(ndc[:, 0] + 1) * width / 2, (1 - ndc[:, 1]) * height / 2])

    def unproject(self, x: float, y: float, depth: float, width: int, height: int) -> np.ndarray:
        """The fixed-frame point at pixel (x, y) whose depth buffer value (0 near .. 1 far) is `depth`."""
        inverse = np.linalg.inv(self.projection_matrix(width, height) @ self.view_matrix())
        point = inverse @ np.array([2 * x / max(1, width) - 1, 1 - 2 * y / max(1, height), 2 * depth - 1, 1.0])
        found: np.ndarray = point[:3] / point[3]
        return found

    def ground_point(self, x: float, y: float, width: int, height: int) -> np.ndarray | None:
        """Where the ray through pixel (x, y) meets the fixed frame's z = 0 plane (the tools'
        click), or None when it does not (looking away from the ground)."""
        inverse = np.linalg.inv(self.projection_matrix(width, height) @ self.view_matrix())
        ndc_x, ndc_y = 2 * x / max(1, width) - 1, 1 - 2 * y / max(1, height)
        near, far = (inverse @ np.array([ndc_x, ndc_y, depth, 1.0]) for depth in (-1.0, 1.0))
        near, far = near[:3] / near[3], far[:3] / far[3]
        direction = far - near
        if abs(direction[2]) < 1e-12:
            return None
        t = -near[2] / direction[2]
        if t < 0:
            return None
        hit: np.ndarray = near + t * direction
        return hit
