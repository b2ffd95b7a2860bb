"""rviz's InteractiveMarkers display: the markers of the servers on an update namespace
("Update Topic": <ns>/update, and the latched <ns>/update_full), kept in step as a client
does (kame.interactive_markers.client_state), each drawn where its pose puts it: every
control's markers, or, for a control without any, rviz's defaults (arrows for MOVE_AXIS, a
ring for ROTATE_AXIS, MOVE_PLANE and MOVE_ROTATE, coloured by the control's axis; a MENU
control's description as a white view-facing button above the marker, which a click opens
the menu on: its text's box facing the camera is what the Interact tool hits). A VIEW_FACING
control's frame turns as rviz's does to face the camera (its x axis the view's direction, its z
the camera's up), its markers with it unless independent_marker_orientation keeps them the
marker's. What each control covers is kept (Handle) for the Interact tool (kame.rviz.interact)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.interactive_markers.client_state import ClientState
from kame.rviz.display import WARN, Display, Frames, Status
from kame.rviz.markers import draw_marker
from kame.rviz.meshes import MeshLibrary
from kame.rviz.scene import Scene, pose_matrix, quaternion_matrix
from visualization_msgs.msg import InteractiveMarkerControl, Marker

MENU = InteractiveMarkerControl.MENU
MOVE_AXIS, MOVE_PLANE = InteractiveMarkerControl.MOVE_AXIS, InteractiveMarkerControl.MOVE_PLANE
ROTATE_AXIS, MOVE_ROTATE = InteractiveMarkerControl.ROTATE_AXIS, InteractiveMarkerControl.MOVE_ROTATE
RING_SEGMENTS = 36
GLYPH_ASPECT = 0.6  # a character's width to its height, about (rviz's MovableText in its default font)


@dataclass
class Handle:
    """One control as drawn: what the Interact tool needs to hit it and drag its marker."""
    server_id: str
    display_name: str  # rviz's client_id is the node's name, "/" and this
    feedback_topic: str  # <ns>/feedback
    marker: Any  # visualization_msgs/InteractiveMarker (the client's own copy)
    control: Any  # visualization_msgs/InteractiveMarkerControl
    reference: np.ndarray  # 4x4: the marker's header frame in the fixed frame
    fixed_frame: str
    triangles: np.ndarray  # T x 3 x 3: the control's surfaces in the fixed frame
    facing: np.ndarray | None = None  # VIEW_FACING: the frame's rotation (fixed frame) facing the camera

    @property
    def pose(self) -> np.ndarray:
        """The marker's pose in the fixed frame (4x4)."""
        pose: np.ndarray = self.reference @ pose_matrix(self.marker.pose)
        return pose

    def control_frame(self) -> np.ndarray:
        """The control's frame in the fixed frame: its orientation on the marker's (INHERIT), on
        the marker's header frame (FIXED), or on the rotation facing the camera (VIEW_FACING)."""
        q = self.control.orientation
        norm = float(np.sqrt(q.x ** 2 + q.y ** 2 + q.z ** 2 + q.w ** 2))
        turn = quaternion_matrix(q.x / norm, q.y / norm, q.z / norm, q.w / norm) if norm > 1e-9 else np.eye(3)
        pose = self.pose
        base = pose if self.control.orientation_mode == InteractiveMarkerControl.INHERIT else self.reference
        if self.facing is not None:
            base = np.eye(4)
            base[:3, :3] = self.facing
        frame: np.ndarray = pose.copy()
        frame[:3, :3] = base[:3, :3] @ turn
        return frame


def _rotation_to(start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """The shortest turn taking unit `start` to unit `end` (Ogre's getRotationTo)."""
    axis, cosine = np.cross(start, end), float(start @ end)
    if cosine < -1 + 1e-9:  # opposite: half a turn about any axis across them
        across = np.cross(start, [1.0, 0, 0] if abs(start[0]) < 0.9 else [0, 1.0, 0])
        across /= np.linalg.norm(across)
        turn: np.ndarray = 2 * np.outer(across, across) - np.eye(3)
        return turn
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    turn = np.eye(3) + k + (k @ k) / (1 + cosine)
    return turn


def view_facing(control: Any, view: np.ndarray) -> np.ndarray:
    """rviz's VIEW_FACING frame (3x3, fixed frame) for the camera's `view` matrix: the control's
    x axis turned onto the view's direction, then about it until the control's z is the camera's up."""
    q = control.orientation
    norm = float(np.sqrt(q.x ** 2 + q.y ** 2 + q.z ** 2 + q.w ** 2))
    turn = quaternion_matrix(q.x / norm, q.y / norm, q.z / norm, q.w / norm) if norm > 1e-9 else np.eye(3)
    forward, up = -view[2, :3], view[1, :3]
    onto_view = _rotation_to(turn[:3, 0], forward)
    upright = _rotation_to(onto_view @ turn[:3, 2], up)
    facing: np.ndarray = upright @ onto_view
    return facing


def _axis_color(turn: np.ndarray, alpha: float) -> tuple[float, float, float, float]:
    x = np.abs(turn[:3, 0])
    return float(x[0]), float(x[1]), float(x[2]), alpha


def default_markers(control: Any, scale: float) -> list[Any]:
    """rviz's markers for a control that has none, in the interactive marker's frame."""
    q = control.orientation
    norm = float(np.sqrt(q.x ** 2 + q.y ** 2 + q.z ** 2 + q.w ** 2))
    turn = quaternion_matrix(q.x / norm, q.y / norm, q.z / norm, q.w / norm) if norm > 1e-9 else np.eye(3)
    r, g, b, a = _axis_color(turn, 1.0)
    made = []
    if control.interaction_mode == MOVE_AXIS:
        for sign in (1.0, -1.0):
            arrow = Marker(type=Marker.ARROW)
            arrow.pose.orientation.w = 1.0
            start, end = turn[:3, 0] * sign * 0.55 * scale, turn[:3, 0] * sign * 1.0 * scale
            arrow.points = [_point(start), _point(end)]
            arrow.scale.x, arrow.scale.y, arrow.scale.z = 0.12 * scale, 0.25 * scale, 0.2 * scale
            arrow.color.r, arrow.color.g, arrow.color.b, arrow.color.a = r, g, b, a
            made.append(arrow)
    elif control.interaction_mode in (ROTATE_AXIS, MOVE_PLANE, MOVE_ROTATE):
        ring = Marker(type=Marker.TRIANGLE_LIST)
        ring.pose.orientation.w = 1.0
        ring.scale.x = ring.scale.y = ring.scale.z = 1.0
        angles = np.linspace(0, 2 * np.pi, RING_SEGMENTS + 1)
        inner, outer = 0.5 * scale, 0.6 * scale
        circle = np.stack([np.zeros_like(angles), np.cos(angles), np.sin(angles)], axis=1) @ turn[:3, :3].T
        for i in range(RING_SEGMENTS):
            a0, a1, b0, b1 = circle[i] * inner, circle[i + 1] * inner, circle[i] * outer, circle[i + 1] * outer
            ring.points += [_point(p) for p in (a0, b0, b1, a0, b1, a1)]
        ring.color.r, ring.color.g, ring.color.b, ring.color.a = r, g, b, 0.8
        made.append(ring)
    elif control.interaction_mode == MENU and control.description:  # interactive_markers' makeViewFacingButton
        button = Marker(type=Marker.TEXT_VIEW_FACING, text=control.description)
        size = 0.25 * scale
        button.pose.orientation.w = 1.0
        button.pose.position.x, button.pose.position.z = -0.1 * size, 1.2 * scale - 0.1 * size
        button.scale.x = button.scale.y = button.scale.z = size
        button.color.r = button.color.g = button.color.b = button.color.a = 1.0
        made.append(button)
    return made


def text_box(marker: Any, placed: np.ndarray, view: np.ndarray) -> np.ndarray:
    """Two triangles (2 x 3 x 3, fixed frame) covering a TEXT_VIEW_FACING marker's text as the
    camera (`view`) sees it: its lines' height and its longest line's width, about its centre."""
    lines = marker.text.split("\n")
    half_up = 0.5 * marker.scale.z * len(lines) * view[1, :3]
    half_right = 0.5 * GLYPH_ASPECT * marker.scale.z * max(len(line) for line in lines) * view[0, :3]
    centre = (placed @ pose_matrix(marker.pose))[:3, 3]
    corners = [centre - half_right - half_up, centre + half_right - half_up,
               centre + half_right + half_up, centre - half_right + half_up]
    return np.array([[corners[0], corners[1], corners[2]], [corners[0], corners[2], corners[3]]])


def _point(values: np.ndarray) -> Any:
    from geometry_msgs.msg import Point

    return Point(x=float(values[0]), y=float(values[1]), z=float(values[2]))


def _faces_camera(control: Any) -> bool:
    """Whether what the control draws, or the box of its text, turns with the camera."""
    return bool(control.orientation_mode == InteractiveMarkerControl.VIEW_FACING
                or (control.interaction_mode == MENU and not control.markers)
                or any(m.type == Marker.TEXT_VIEW_FACING for m in control.markers))


def update_namespace(topic: str) -> str:
    """The namespace of an update topic: rviz's "Update Topic" /basic_controls/update -> /basic_controls."""
    return topic[: -len("/update")] if topic.endswith("/update") else topic


class InteractiveMarkers(Display):
    class_name = "rviz/InteractiveMarkers"
    message_types = ("visualization_msgs/InteractiveMarkerUpdate",)
    defaults = {"Update Topic": "", "Show Descriptions": True, "Show Axes": False, "Show Visual Aids": False,
                "Enable Transparency": True}
    keeps_every_message = True
    topic_key = "Update Topic"

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        namespace = self.options.pop("Interactive Markers Namespace", None)  # rviz 1.13 on: the namespace
        if namespace and not self.options.get("Update Topic"):
            self.options["Update Topic"] = f"{namespace}/update"
        self.client = ClientState()
        self.meshes = MeshLibrary()
        self.handles: list[Handle] = []
        self.view = np.eye(4)  # the camera's view matrix, which VIEW_FACING controls face
        self.highlit: tuple[str, str, int, float] | None = None  # server, marker, control's index, how much

    def highlight(self, handle: Handle | None, amount: float) -> None:
        """Brighten `handle`'s control by `amount` as rviz does (0.3 under the mouse, 0.5 pressed),
        the others not."""
        highlit = None if handle is None else (
            handle.server_id, handle.marker.name,
            next((i for i, c in enumerate(handle.marker.controls) if c is handle.control), -1), amount)
        if highlit != self.highlit:
            self.highlit = highlit
            self.version += 1

    def face(self, view: np.ndarray) -> None:
        """The camera is now `view`: draw again if a control faces it and it turned."""
        if not np.allclose(view[:3, :3], self.view[:3, :3]) and any(
                _faces_camera(c) for m in self.client.markers.values() for c in m.controls):
            self.version += 1
        self.view = view

    def side_topics(self) -> dict[str, str]:
        topic = self.topic
        return {f"{update_namespace(topic)}/update_full": "visualization_msgs/InteractiveMarkerInit"} if topic else {}

    def feedback_topic(self) -> str:
        return f"{update_namespace(self.topic)}/feedback"

    def receive(self, messages: Any, now: float) -> None:
        for message in messages:
            self.message = message
            self.client.update(message)
        if messages:
            self.version += 1

    def receive_side(self, topic: str, messages: list[Any], now: float) -> None:
        for message in messages:
            self.message = self.message or message
            self.client.init(message)
        if messages:
            self.version += 1

    def reset(self) -> None:
        super().reset()
        self.client.reset()
        self.handles = []

    def moved(self) -> None:
        """A marker's pose was changed here (a drag): draw it again."""
        self.version += 1

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        self.handles = []
        problems = [self.client.problem] if self.client.problem else []
        for (server_id, name), marker in sorted(self.client.markers.items()):
            reference = frames.transform(marker.header.frame_id)
            if isinstance(reference, str):
                problems.append(f"{name}: {reference}")
                continue
            pose = reference @ pose_matrix(marker.pose)
            scale = marker.scale if marker.scale > 0 else 1.0
            for index, control in enumerate(marker.controls):
                own = Scene()
                texts: list[np.ndarray] = []
                facing = view_facing(control, self.view) \
                    if control.orientation_mode == InteractiveMarkerControl.VIEW_FACING else None
                markers_pose = pose.copy()
                if facing is not None and not control.independent_marker_orientation:
                    markers_pose[:3, :3] = facing
                for shown in control.markers or default_markers(control, scale):
                    placed = frames.transform(shown.header.frame_id) if shown.header.frame_id else markers_pose
                    if isinstance(placed, str):
                        problems.append(f"{name}: {placed}")
                        continue
                    problem = draw_marker(own, shown, placed, self.meshes)
                    if shown.type == Marker.TEXT_VIEW_FACING and shown.text:
                        texts.append(text_box(shown, placed, self.view))
                    if problem:
                        problems.append(f"{name}/{control.name}: {problem}")
                if self.highlit is not None and self.highlit[:3] == (server_id, name, index):
                    added = np.array([self.highlit[3]] * 3 + [0.0], dtype=np.float32)
                    for batch in own.batches:  # rviz adds the highlight to the lit colour
                        batch.colors = np.minimum(batch.float_colors() + added, np.float32(1.0))
                surfaces = [b.unindexed().vertices.reshape(-1, 3, 3) for b in own.batches if b.kind == "triangles"]
                surfaces += texts
                triangles = np.concatenate(surfaces) if surfaces else np.zeros((0, 3, 3))
                self.handles.append(Handle(server_id, self.name, self.feedback_topic(), marker,
                                           control, reference, frames.fixed_frame, triangles.astype(float),
                                           facing))
                scene.extend(own)
            if self.flag("Show Descriptions") and marker.description:
                scene.label(pose[:3, 3] + np.array([0.0, 0.0, 0.6 * scale]), marker.description, (1, 1, 1, 1))
        if problems:
            self.status = Status(WARN, "; ".join(problems[:3]) + (" ..." if len(problems) > 3 else ""))
