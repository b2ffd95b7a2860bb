"""gzclient's window as values, no Qt: the scene graph (each visual's triangles in its link's
frame, each link's pose as /gazebo/link_states last said), what it draws through rviz's Scene,
the selection, the ray picking a model under the mouse, the translate and rotate drags that
become set_model_state requests, and the camera moved by Gazebo's mouse.

Gazebo 11's mouse (its OrbitViewController): a left drag pans, a middle drag or Shift and a left
drag orbit about the point under the mouse at the press, a right drag zooms (up: nearer), the
wheel zooms towards the point under the mouse. The translate mode drags a model
over the horizontal plane through its origin (Gazebo's default, no axis key held); the rotate mode
turns it about the vertical axis through its origin (the ring Gazebo shows around z)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from kame.gzclient.scene_message import LightMessage, Quaternion, SceneMessage, Vector3, VisualMessage
from kame.rviz.camera import Camera
from kame.rviz.scene import (
    Scene,
    apply,
    box_triangles,
    cylinder_triangles,
    quaternion_matrix,
    sphere_triangles,
)

SELECT, TRANSLATE, ROTATE = "select", "translate", "rotate"
GRID_CELLS, GRID_CELL_SIZE = 20, 1.0  # Gazebo's default grid: 20 cells of 1 m on the ground
GRID_COLOR = (0.45, 0.45, 0.45, 1.0)
SELECTION_COLOR = (1.0, 1.0, 1.0, 1.0)
LIGHT_COLOR = (1.0, 0.85, 0.2, 1.0)
PAN, ORBIT, ZOOM = "pan", "orbit", "zoom"
MAX_LIGHTS = 8  # OpenGL's fixed pipeline lights at least so many; a world's further lights are left out


@dataclass(frozen=True)
class GlLight:
    """A world light as OpenGL's fixed pipeline takes it: a position in the world frame, w = 0 for
    a directional light (then x y z point towards the light), and its diffuse colour. Spot lights
    light as point lights (no cone), and no light fades with distance."""
    position: tuple[float, float, float, float]
    diffuse: tuple[float, float, float, float]


def gazebo_camera() -> Camera:
    """gzclient's first view: the eye at (5, -5, 2) looking at the origin."""
    eye = np.array([5.0, -5.0, 2.0])
    distance = float(np.linalg.norm(eye))
    return Camera(focal_point=np.zeros(3), distance=distance, yaw=math.atan2(eye[1], eye[0]),
                  pitch=math.asin(eye[2] / distance))


def drag_action(left: bool, middle: bool, right: bool, shift: bool) -> str | None:
    """What a drag with these buttons does to the camera, as Gazebo's orbit view controller says."""
    if middle or (left and shift):
        return ORBIT
    if left:
        return PAN
    if right:
        return ZOOM
    return None


def move_camera(camera: Camera, action: str, dx: float, dy: float, height: int) -> None:
    if action == ORBIT:
        camera.rotate(dx, dy)
    elif action == PAN:
        camera.pan(dx, dy, height)
    elif action == ZOOM:
        camera.zoom(-dy / 20)  # up brings the eye nearer, as Gazebo's right drag


def focus_on(camera: Camera, point: np.ndarray) -> None:
    """Make `point` the orbit's focal point without moving the eye (Gazebo orbits and zooms about
    what is under the mouse)."""
    offset = camera.eye() - point
    distance = float(np.linalg.norm(offset))
    if distance < 1e-6:
        return
    camera.focal_point = np.asarray(point, dtype=float)
    camera.distance = distance
    camera.yaw = math.atan2(offset[1], offset[0])
    camera.pitch = math.asin(max(-1.0, min(1.0, offset[2] / distance)))


def view_ray(camera: Camera, x: float, y: float, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """The ray from the eye through pixel (x, y): its origin and unit direction."""
    near = camera.unproject(x, y, 0.0, width, height)
    far = camera.unproject(x, y, 1.0, width, height)
    direction = far - near
    return near, direction / np.linalg.norm(direction)


def pose_matrix(position: Vector3, orientation: Quaternion) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, :3] = quaternion_matrix(*orientation)
    matrix[:3, 3] = position
    return matrix


def yaw_quaternion(angle: float) -> Quaternion:
    return 0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2)


def multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def shape_triangles(visual: VisualMessage) -> np.ndarray:
    """The visual's triangles in its own frame (3N x 3)."""
    size = visual.size
    if visual.kind == "box" and len(size) == 3:
        return box_triangles(size)
    if visual.kind == "sphere" and size:
        return sphere_triangles((2 * size[0],) * 3, rings=12, segments=24)
    if visual.kind == "cylinder" and len(size) == 2:
        return cylinder_triangles((2 * size[0], 2 * size[0], size[1]), segments=32)
    if visual.kind == "plane" and len(size) == 2:
        hx, hy = size[0] / 2, size[1] / 2
        return np.array([[-hx, -hy, 0], [hx, -hy, 0], [hx, hy, 0], [-hx, -hy, 0], [hx, hy, 0], [-hx, hy, 0]],
                        dtype=float)
    if visual.kind == "mesh" and visual.triangles is not None:
        return visual.triangles.astype(float)
    return np.zeros((0, 3))


def ray_triangles(origin: np.ndarray, direction: np.ndarray, triangles: np.ndarray) -> float | None:
    """The distance along the ray to the nearest of `triangles` (3N x 3) it meets (Möller and
    Trumbore's test, both faces), or None."""
    if not len(triangles):
        return None
    corners = triangles.reshape(-1, 3, 3)
    edge1, edge2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    p = np.cross(direction, edge2)
    det = np.einsum("ij,ij->i", edge1, p)
    usable = np.abs(det) > 1e-12
    inverse = np.where(usable, 1.0 / np.where(usable, det, 1.0), 0.0)
    t_vec = origin - corners[:, 0]
    u = np.einsum("ij,ij->i", t_vec, p) * inverse
    q = np.cross(t_vec, edge1)
    v = (q @ direction) * inverse
    t = np.einsum("ij,ij->i", edge2, q) * inverse
    hit = usable & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9)
    return float(t[hit].min()) if hit.any() else None


def horizontal_hit(origin: np.ndarray, direction: np.ndarray, height: float) -> np.ndarray | None:
    """Where the ray meets the horizontal plane z = height, or None (parallel, or behind the eye)."""
    if abs(direction[2]) < 1e-9:
        return None
    t = (height - origin[2]) / direction[2]
    if t <= 0:
        return None
    hit: np.ndarray = origin + t * direction
    return hit


@dataclass(frozen=True)
class ModelMove:
    """A set_model_state request's values: the model's new pose in the world frame, at rest."""
    model: str
    position: Vector3
    orientation: Quaternion


@dataclass
class _LinkVisual:
    link: str
    model: str
    triangles: np.ndarray  # in the link's frame
    color: tuple[float, float, float, float]
    plane: bool


@dataclass
class _Drag:
    model: str
    mode: str
    grabbed: np.ndarray  # where the ray met the drag plane at the press
    position: Vector3  # the model's pose at the press
    orientation: Quaternion


@dataclass
class ClientModel:
    """What the window draws and how the mouse works it."""

    camera: Camera = field(default_factory=gazebo_camera)
    mode: str = SELECT
    selected: str | None = None
    background: tuple[float, float, float, float] = (0.7, 0.7, 0.7, 1.0)
    ambient: tuple[float, float, float, float] = (0.4, 0.4, 0.4, 1.0)
    lights: list[GlLight] = field(default_factory=list)
    _visuals: list[_LinkVisual] = field(default_factory=list)
    _light_markers: list[tuple[np.ndarray, np.ndarray, str]] = field(default_factory=list)  # position, direction, type
    _links: dict[str, np.ndarray] = field(default_factory=dict)  # link -> 4x4 pose
    _models: dict[str, tuple[Vector3, Quaternion]] = field(default_factory=dict)
    _drag: _Drag | None = None
    _scene: Scene | None = None  # drawn for the poses and selection now; None once they change

    # -------------------------------------------------------------- what the server says

    def set_scene(self, message: SceneMessage) -> None:
        self.background = message.background
        self.ambient = message.ambient
        self.lights = [gl_light(light) for light in message.lights][:MAX_LIGHTS]
        self._visuals = []
        for visual in message.visuals:
            local = apply(pose_matrix(visual.position, visual.orientation), shape_triangles(visual))
            self._visuals.append(_LinkVisual(visual.link, visual.model, local, visual.color, visual.kind == "plane"))
        self._light_markers = []
        for light in message.lights:
            rotation = quaternion_matrix(*light.orientation)
            self._light_markers.append((np.array(light.position), rotation @ np.array(light.direction), light.type))
        if self.selected is not None and self.selected not in self.model_names():
            self.selected = None
        self._scene = None

    def set_link_poses(self, poses: dict[str, tuple[Vector3, Quaternion]]) -> None:
        self._links = {link: pose_matrix(*pose) for link, pose in poses.items()}
        self._scene = None

    def set_model_poses(self, poses: dict[str, tuple[Vector3, Quaternion]]) -> None:
        self._models = dict(poses)

    def model_names(self) -> list[str]:
        return sorted({visual.model for visual in self._visuals} | set(self._models))

    def drawn_models(self) -> list[str]:
        """The models with a visual drawn where its link is (its link's pose known)."""
        return sorted({visual.model for visual in self._visuals if visual.link in self._links})

    def model_pose(self, model: str) -> tuple[Vector3, Quaternion] | None:
        return self._models.get(model)

    # -------------------------------------------------------------- drawing

    def _world_triangles(self, visual: _LinkVisual) -> np.ndarray | None:
        """The visual's triangles where its link is now; None before the link's first pose."""
        pose = self._links.get(visual.link)
        return None if pose is None else apply(pose, visual.triangles)

    def render(self) -> Scene:
        """The scene to draw: the same object while nothing changed, so the view need not repaint."""
        if self._scene is not None:
            return self._scene
        scene = Scene()
        selected: list[np.ndarray] = []
        for visual in self._visuals:
            triangles = self._world_triangles(visual)
            if triangles is None:
                continue
            scene.add("triangles", triangles, visual.color)
            if visual.model == self.selected:
                selected.append(triangles)
        half = GRID_CELLS * GRID_CELL_SIZE / 2
        ticks = np.linspace(-half, half, GRID_CELLS + 1)
        lift = 0.002  # just above the ground plane's own triangles, so the lines are not hidden in them
        grid = [[(t, -half, lift), (t, half, lift)] for t in ticks] + [[(-half, t, lift), (half, t, lift)]
                                                                          for t in ticks]
        scene.add("lines", grid, GRID_COLOR, 1.0)
        for position, direction, kind in self._light_markers:  # Gazebo's light markers: where and which way
            tip = position + 0.5 * direction / max(1e-9, float(np.linalg.norm(direction)))
            scene.add("lines", [position, tip], LIGHT_COLOR, 2.0)
            if kind != "directional":
                scene.add("points", [position], LIGHT_COLOR, 8.0)
        if selected:
            scene.add("lines", bounding_box_lines(np.concatenate(selected)), SELECTION_COLOR, 2.0)
        self._scene = scene.merged()
        return self._scene

    # -------------------------------------------------------------- the mouse on models

    def pick(self, origin: np.ndarray, direction: np.ndarray) -> str | None:
        """The model whose visual the ray meets first; the ground plane is not picked (a click on
        the ground clears the selection, and a drag on it never moves the whole ground)."""
        nearest: tuple[float, str] | None = None
        for visual in self._visuals:
            if visual.plane:
                continue
            triangles = self._world_triangles(visual)
            if triangles is None:
                continue
            distance = ray_triangles(origin, direction, triangles)
            if distance is not None and (nearest is None or distance < nearest[0]):
                nearest = (distance, visual.model)
        return None if nearest is None else nearest[1]

    def surface_point(self, origin: np.ndarray, direction: np.ndarray) -> np.ndarray | None:
        """The first point the ray meets on any visual, the ground plane's too; else on z = 0."""
        nearest: float | None = None
        for visual in self._visuals:
            triangles = self._world_triangles(visual)
            if triangles is None:
                continue
            distance = ray_triangles(origin, direction, triangles)
            if distance is not None and (nearest is None or distance < nearest):
                nearest = distance
        if nearest is not None:
            hit: np.ndarray = origin + nearest * direction
            return hit
        return horizontal_hit(origin, direction, 0.0)

    def select(self, model: str | None) -> None:
        if model != self.selected:
            self.selected = model
            self._scene = None

    def press(self, origin: np.ndarray, direction: np.ndarray) -> bool:
        """A left press: selects what is under the mouse; in translate or rotate mode on a model,
        starts dragging it (True: the camera must not move)."""
        model = self.pick(origin, direction)
        self.select(model)
        if model is None or self.mode == SELECT:
            return False
        pose = self._models.get(model)
        if pose is None:
            return False
        grabbed = horizontal_hit(origin, direction, pose[0][2])
        if grabbed is None:
            return False
        self._drag = _Drag(model, self.mode, grabbed, pose[0], pose[1])
        return True

    def drag(self, origin: np.ndarray, direction: np.ndarray) -> ModelMove | None:
        """Where the dragged model goes for the mouse's ray now (None: not dragging, or the ray
        misses its plane)."""
        drag = self._drag
        if drag is None:
            return None
        hit = horizontal_hit(origin, direction, drag.position[2])
        if hit is None:
            return None
        if drag.mode == TRANSLATE:
            x, y, z = drag.position
            return ModelMove(drag.model, (x + float(hit[0] - drag.grabbed[0]), y + float(hit[1] - drag.grabbed[1]), z),
                             drag.orientation)
        centre = np.array(drag.position)
        before, after = drag.grabbed - centre, hit - centre
        turn = math.atan2(after[1], after[0]) - math.atan2(before[1], before[0])
        return ModelMove(drag.model, drag.position, multiply(yaw_quaternion(turn), drag.orientation))

    def release(self) -> None:
        self._drag = None

    @property
    def dragging(self) -> bool:
        return self._drag is not None

    # -------------------------------------------------------------- inserting shapes

    def insert_point(self, width: int, height: int) -> Vector3:
        """Where an inserted shape goes: on the ground under the view's centre, else the focal point."""
        ground = self.camera.ground_point(width / 2, height / 2, width, height)
        point = ground if ground is not None else self.camera.focal_point
        return float(point[0]), float(point[1]), 0.0


def gl_light(light: LightMessage) -> GlLight:
    if light.type == "directional":
        towards = -(quaternion_matrix(*light.orientation) @ np.array(light.direction))
        length = float(np.linalg.norm(towards)) or 1.0
        return GlLight((float(towards[0] / length), float(towards[1] / length), float(towards[2] / length), 0.0),
                       light.diffuse)
    return GlLight((*light.position, 1.0), light.diffuse)


def bounding_box_lines(points: np.ndarray) -> np.ndarray:
    """The 12 edges of the axis-aligned box around `points`, as line vertex pairs (Gazebo marks a
    selected model with its bounding box)."""
    low, high = points.min(axis=0), points.max(axis=0)
    corners = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1]) for z in (low[2], high[2])])
    edges = [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)]
    lines: np.ndarray = corners[np.array(edges).reshape(-1)]
    return lines


def unique_name(base: str, taken: list[str]) -> str:
    """Gazebo's names for inserted shapes: unit_box, then unit_box_0, unit_box_1..."""
    if base not in taken:
        return base
    number = 0
    while f"{base}_{number}" in taken:
        number += 1
    return f"{base}_{number}"
