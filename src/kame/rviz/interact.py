"""rviz's Interact tool without Qt: the control under the mouse (the nearest of its surfaces
the ray through the pixel meets), the drag of its marker by the control's interaction mode,
and the InteractiveMarkerFeedback rviz publishes for it on <ns>/feedback:

- As rviz 1.14: a left press on a control sends POSE_UPDATE (the pose as it is) then MOUSE_DOWN;
  the release BUTTON_CLICK (a BUTTON control's), POSE_UPDATE and MOUSE_UP; the marker's menu opens
  on the release of a right click, or of a left one on a MENU control; MENU_SELECT carries the
  entry chosen from it.
- POSE_UPDATE as the marker is dragged. The drag works in the control's frame (its x axis,
  the control's orientation on the marker's): MOVE_AXIS slides the marker along the axis to
  the point of the axis nearest the mouse's ray; MOVE_PLANE moves it with the point where the
  ray meets the plane (normal: the axis) through the grabbed point; ROTATE_AXIS turns it about
  the axis through its origin by the angle the mouse went round it in that plane; MOVE_ROTATE
  turns it so and moves it along so that the grabbed point stays under the mouse.
- The 3-D modes as rviz 1.14 drags them by the camera's axes: MOVE_3D keeps the grabbed point
  under the mouse in the plane facing the camera, and with Shift moves the marker along the ray
  it was grabbed by (rviz's metres a pixel: the control's y-z plane's at the grabbed point; the
  larger of the mouse's x and y moves, down or left bringing it nearer); ROTATE_3D turns it about
  the camera's up axis by x and its right axis by y (300 pixels a turn), with Shift about the
  view's direction; MOVE_ROTATE_3D moves as MOVE_3D and with Ctrl rotates as ROTATE_3D. A change
  of Shift or Ctrl mid-drag restarts the relative motion, as rviz's does; the wheel turned during
  a MOVE_3D or MOVE_ROTATE_3D drag moves the marker along the grabbing ray (away: forward).
Every pose is the marker's in its header frame, as rviz sends it."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from kame.rviz.camera import Camera
from kame.rviz.interactive import Handle
from kame.tf.transformations import quaternion_from_matrix
from visualization_msgs.msg import InteractiveMarkerControl, InteractiveMarkerFeedback

NONE, MENU, BUTTON = InteractiveMarkerControl.NONE, InteractiveMarkerControl.MENU, InteractiveMarkerControl.BUTTON
MOVE_AXIS, MOVE_PLANE = InteractiveMarkerControl.MOVE_AXIS, InteractiveMarkerControl.MOVE_PLANE
ROTATE_AXIS, MOVE_ROTATE = InteractiveMarkerControl.ROTATE_AXIS, InteractiveMarkerControl.MOVE_ROTATE
MOVE_3D, ROTATE_3D = InteractiveMarkerControl.MOVE_3D, InteractiveMarkerControl.ROTATE_3D
MOVE_ROTATE_3D = InteractiveMarkerControl.MOVE_ROTATE_3D
THREE_D = (MOVE_3D, ROTATE_3D, MOVE_ROTATE_3D)
PARALLEL = 1e-9
TURN_PER_PIXEL = 2 * 3.14 / 300  # rviz's: 300 pixels a turn
Z_SCALE_DEFAULT = 0.001  # rviz's metres a pixel when the control's plane gives none
WHEEL_TO_METRES = (1 / 8) * (2 / 15)  # rviz's: 2 m along the ray a notch (an angle delta of 120)


def mouse_ray(camera: Camera, x: float, y: float, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """The ray (origin, unit direction; fixed frame) through pixel (x, y)."""
    near, far = (camera.unproject(x, y, depth, width, height) for depth in (0.0, 1.0))
    direction = far - near
    return near, direction / np.linalg.norm(direction)


@dataclass
class Pointer:
    """What the 3-D modes need of a mouse event beyond its ray: its pixel, the keys held, the
    camera's axes (fixed frame) and the ray 10 pixels below (rviz's metres a pixel)."""
    x: float
    y: float
    right: np.ndarray
    up: np.ndarray
    forward: np.ndarray
    below: tuple[np.ndarray, np.ndarray]
    shift: bool = False
    control: bool = False


def pointer(camera: Camera, x: float, y: float, width: int, height: int,
            shift: bool = False, control: bool = False) -> Pointer:
    view = camera.view_matrix()
    return Pointer(x, y, view[0, :3].copy(), view[1, :3].copy(), -view[2, :3],
                   mouse_ray(camera, x, y + 10, width, height), shift, control)


def ray_triangles(origin: np.ndarray, direction: np.ndarray, triangles: np.ndarray) -> float | None:
    """How far along the ray it first meets one of the triangles (T x 3 x 3), None: it meets none
    (Moller-Trumbore over all of them at once)."""
    if not len(triangles):
        return None
    a, edge1, edge2 = triangles[:, 0], triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    p = np.cross(direction, edge2)
    det = (edge1 * p).sum(axis=1)
    usable = np.abs(det) > 1e-12
    inverse = np.where(usable, 1 / np.where(usable, det, 1.0), 0.0)
    s = origin - a
    u = (s * p).sum(axis=1) * inverse
    q = np.cross(s, edge1)
    v = (q @ direction) * inverse
    t = (q * edge2).sum(axis=1) * inverse
    hit = usable & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
    return float(t[hit].min()) if hit.any() else None


def pick(handles: list[Handle], origin: np.ndarray, direction: np.ndarray) -> tuple[Handle, np.ndarray] | None:
    """The control nearest along the ray that it meets, and the point met (fixed frame)."""
    best: tuple[float, Handle] | None = None
    for handle in handles:
        if handle.control.interaction_mode == NONE and not handle.marker.menu_entries:
            continue
        t = ray_triangles(origin, direction, handle.triangles)
        if t is not None and (best is None or t < best[0]):
            best = (t, handle)
    return None if best is None else (best[1], origin + best[0] * direction)


def _plane_point(origin: np.ndarray, direction: np.ndarray, point: np.ndarray, normal: np.ndarray) -> np.ndarray | None:
    across = float(normal @ direction)
    if abs(across) < PARALLEL:
        return None
    hit: np.ndarray = origin + float(normal @ (point - origin)) / across * direction
    return hit


def _turn(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation by `angle` about the unit `axis` (3x3, Rodrigues)."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    turn: np.ndarray = np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)
    return turn


def _angle_about(axis: np.ndarray, start: np.ndarray, end: np.ndarray) -> float:
    start, end = start - (start @ axis) * axis, end - (end @ axis) * axis
    return math.atan2(float(axis @ np.cross(start, end)), float(start @ end))


def dragged(mode: int, start: np.ndarray, frame: np.ndarray, grab: np.ndarray,
            origin: np.ndarray, direction: np.ndarray) -> np.ndarray | None:
    """The marker's new pose (4x4, fixed frame) when the mouse's ray is (origin, direction),
    the drag having begun with the marker at `start`, the control's frame at `frame` and the
    control grabbed at `grab`; None: the ray gives no position (parallel to the plane)."""
    axis = frame[:3, 0] / np.linalg.norm(frame[:3, 0])
    pose: np.ndarray = start.copy()
    if mode == MOVE_AXIS:
        across = float(axis @ direction)
        denominator = 1 - across * across
        if denominator < PARALLEL:
            return None
        w = grab - origin
        along = (across * float(direction @ w) - float(axis @ w)) / denominator
        pose[:3, 3] += along * axis
        return pose
    if mode == MOVE_PLANE:
        hit = _plane_point(origin, direction, grab, axis)
        if hit is None:
            return None
        pose[:3, 3] += hit - grab
        return pose
    if mode in (ROTATE_AXIS, MOVE_ROTATE):
        centre = start[:3, 3]
        hit = _plane_point(origin, direction, centre, axis)
        if hit is None:
            return None
        grab_in_plane = grab - float(axis @ (grab - centre)) * axis
        turn = _turn(axis, _angle_about(axis, grab_in_plane - centre, hit - centre))
        pose[:3, :3] = turn @ start[:3, :3]
        if mode == MOVE_ROTATE:  # the grabbed point follows the mouse
            pose[:3, 3] = hit - turn @ (grab_in_plane - centre)
        return pose
    return None


def z_scale(frame: np.ndarray, grab: np.ndarray, ray: tuple[np.ndarray, np.ndarray],
            below: tuple[np.ndarray, np.ndarray]) -> float:
    """rviz's metres a pixel for Shift's move along the ray: how far apart the rays through the
    pixel and 10 pixels below meet the control's y-z plane through the grabbed point, over 10."""
    normal = frame[:3, 0] / np.linalg.norm(frame[:3, 0])
    at, at_below = _plane_point(*ray, grab, normal), _plane_point(*below, grab, normal)
    if at is None or at_below is None:
        return Z_SCALE_DEFAULT
    scale = float(np.linalg.norm(at_below - at)) / 10
    return scale if scale > 1e-30 else Z_SCALE_DEFAULT


@dataclass
class Drag:
    handle: Handle
    start: np.ndarray  # the marker's pose (fixed frame) when pressed
    frame: np.ndarray  # the control's frame then
    grab: np.ndarray  # the point pressed (fixed frame)
    moved: bool = False
    # the 3-D modes': the pixel the relative motion is from, the keys then, the ray's direction
    # then, the marker's position the view plane moves from, and metres a pixel along the ray
    last: tuple[float, float] = (0.0, 0.0)
    keys: tuple[bool, bool] = (False, False)
    ray: np.ndarray = field(default_factory=lambda: np.zeros(3))
    anchor: np.ndarray = field(default_factory=lambda: np.zeros(3))
    metres_per_pixel: float = Z_SCALE_DEFAULT

    def step_3d(self, pose: np.ndarray, origin: np.ndarray, direction: np.ndarray, at: Pointer) -> np.ndarray | None:
        """The marker's new pose (from `pose`, its present one) in a 3-D mode; None: no change."""
        mode = self.handle.control.interaction_mode
        if (at.shift, at.control) != self.keys:  # rviz restarts the relative motion
            self.keys, self.last, self.ray = (at.shift, at.control), (at.x, at.y), direction
        dx, dy = at.x - self.last[0], at.y - self.last[1]
        self.last = (at.x, at.y)
        moved: np.ndarray = pose.copy()
        if mode == ROTATE_3D or (mode == MOVE_ROTATE_3D and at.control):
            if at.shift:
                angle = (dy if abs(dy) > abs(dx) else dx) * TURN_PER_PIXEL
                turn = _turn(at.forward, angle)
            else:
                turn = _turn(at.up, dx * TURN_PER_PIXEL) @ _turn(at.right, dy * TURN_PER_PIXEL)
            if dx == 0 and dy == 0:
                return None
            moved[:3, :3] = turn @ pose[:3, :3]
            return moved
        offset = self.grab - self.start[:3, 3]  # rviz's parent_to_grab_position_
        if at.shift:
            pixels = -dx if abs(dx) > abs(dy) else dy
            if pixels == 0:
                return None
            moved[:3, 3] = pose[:3, 3] - pixels * self.metres_per_pixel * self.ray
            self.anchor = moved[:3, 3].copy()
            return moved
        hit = _plane_point(origin, direction, self.anchor + offset, at.forward)
        if hit is None:
            return None
        moved[:3, 3] = hit - offset
        return moved


@dataclass
class Pressed:
    feedback: list[Any] = field(default_factory=list)
    consumed: bool = False  # False: nothing interactive there (the camera moves)


class Interaction:
    def __init__(self, node_name: str) -> None:
        self.node_name = node_name  # rviz's client_id: "<node name>/<display name>"
        self.drag: Drag | None = None
        self.right_pressed: Handle | None = None  # a marker with a menu, right-pressed
        self.menu: Handle | None = None  # a marker whose menu the last release opens

    def press(self, handles: list[Handle], origin: np.ndarray, direction: np.ndarray, right: bool = False,
              at: Pointer | None = None) -> Pressed:
        found = pick(handles, origin, direction)
        if found is None:
            return Pressed()
        handle, point = found
        if right:  # a marker without a menu leaves the right button to the camera
            self.right_pressed = handle if handle.marker.menu_entries else None
            return Pressed(consumed=self.right_pressed is not None)
        self.drag = Drag(handle, handle.pose, handle.control_frame(), point)
        if at is not None:
            self.drag.last, self.drag.keys, self.drag.ray = (at.x, at.y), (at.shift, at.control), direction
            self.drag.anchor = handle.pose[:3, 3]
            self.drag.metres_per_pixel = z_scale(self.drag.frame, point, (origin, direction), at.below)
        return Pressed([self.feedback(handle, InteractiveMarkerFeedback.POSE_UPDATE, point),
                        self.feedback(handle, InteractiveMarkerFeedback.MOUSE_DOWN, point)], consumed=True)

    def move(self, origin: np.ndarray, direction: np.ndarray, at: Pointer | None = None) -> list[Any]:
        drag = self.drag
        if drag is None:
            return []
        mode = drag.handle.control.interaction_mode
        if mode in THREE_D:
            pose = drag.step_3d(drag.handle.pose, origin, direction, at) if at is not None else None
        else:
            pose = dragged(mode, drag.start, drag.frame, drag.grab, origin, direction)
        if pose is None:
            return []
        drag.moved = True
        _set_pose(drag.handle.marker.pose, np.linalg.inv(drag.handle.reference) @ pose)
        return [self.feedback(drag.handle, InteractiveMarkerFeedback.POSE_UPDATE, None)]

    def wheel(self, delta: float) -> list[Any]:
        """The wheel turned by `delta` (Qt's angle delta) while dragging."""
        drag = self.drag
        if drag is None or drag.handle.control.interaction_mode not in (MOVE_3D, MOVE_ROTATE_3D) or not delta:
            return []
        pose = drag.handle.pose
        pose[:3, 3] += delta * WHEEL_TO_METRES * drag.ray
        drag.anchor = pose[:3, 3].copy()
        drag.moved = True
        _set_pose(drag.handle.marker.pose, np.linalg.inv(drag.handle.reference) @ pose)
        return [self.feedback(drag.handle, InteractiveMarkerFeedback.POSE_UPDATE, None)]

    def release(self) -> list[Any]:
        """The feedback of a release; `menu`: the marker whose menu it opens, if any."""
        drag, self.drag = self.drag, None
        self.menu, self.right_pressed = self.right_pressed, None
        if drag is None:
            return []
        if drag.handle.control.interaction_mode == MENU and drag.handle.marker.menu_entries:
            self.menu = drag.handle
        sent = [self.feedback(drag.handle, InteractiveMarkerFeedback.BUTTON_CLICK, drag.grab)] \
            if drag.handle.control.interaction_mode == BUTTON else []
        return [*sent, self.feedback(drag.handle, InteractiveMarkerFeedback.POSE_UPDATE, drag.grab),
                self.feedback(drag.handle, InteractiveMarkerFeedback.MOUSE_UP, drag.grab)]

    def menu_select(self, handle: Handle, entry_id: int) -> Any:
        feedback = self.feedback(handle, InteractiveMarkerFeedback.MENU_SELECT, None)
        feedback.menu_entry_id = entry_id
        return feedback

    def feedback(self, handle: Handle, event_type: int, point: np.ndarray | None) -> Any:
        marker = handle.marker
        feedback = InteractiveMarkerFeedback(client_id=f"{self.node_name}/{handle.display_name}",
                                             marker_name=marker.name, control_name=handle.control.name,
                                             event_type=event_type)
        stamp = marker.header.stamp
        # rviz: a marker stamped 0 is locked to its frame and answered in it; a stamped one in the fixed frame
        locked = stamp.secs == 0 and stamp.nsecs == 0
        into = np.linalg.inv(handle.reference) if locked else np.eye(4)
        feedback.header.frame_id = marker.header.frame_id if locked else handle.fixed_frame
        feedback.header.stamp = stamp
        _set_pose(feedback.pose, into @ handle.pose)
        if point is not None:
            local = into @ np.append(point, 1.0)
            feedback.mouse_point.x, feedback.mouse_point.y, feedback.mouse_point.z = (float(v) for v in local[:3])
            feedback.mouse_point_valid = True
        return feedback


def _set_pose(target: Any, matrix: np.ndarray) -> None:
    """A geometry_msgs/Pose set to the 4x4 `matrix`."""
    target.position.x, target.position.y, target.position.z = (float(v) for v in matrix[:3, 3])
    q = quaternion_from_matrix(matrix)
    target.orientation.x, target.orientation.y, target.orientation.z, target.orientation.w = (float(v) for v in q)


def menu_tree(entries: list[Any]) -> dict[int, list[Any]]:
    """A marker's menu entries by their parent's id (0: the top level), in their order."""
    tree: dict[int, list[Any]] = {}
    for entry in entries:
        tree.setdefault(entry.parent_id, []).append(entry)
    return tree
