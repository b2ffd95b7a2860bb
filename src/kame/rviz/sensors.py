"""rviz's sensor displays: Range (a cone), WrenchStamped (force and torque arrows), Image (the
newest image, shown in a panel of its own) and Camera (the image with the 3-D scene drawn over
it as the camera sees it, through its CameraInfo).

Rules (rviz 1.14):
- Range draws a cone from the sensor along its x axis, as long as the range and as wide as the
  field of view; a range outside [min_range, max_range] draws nothing, except a fixed-distance
  ranger (min == max) reporting -inf, which draws at that distance.
- WrenchStamped: the force as an arrow from the frame's origin, |f| * Force Arrow Scale long; the
  torque as an arrow |t| * Torque Arrow Scale long with a circle about it.
- Image and Camera read `Image Topic` (`/compressed` beside it, JPEG or PNG, with Transport
  Hint "compressed"); decoding (rqt_image_view's encodings) happens once per
  new message; Camera takes its CameraInfo from the image topic's namespace + /camera_info, and
  projects with its P matrix from the image's frame (the optical frame: z forward, x right).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from kame.rqt.image_model import ImageError, to_display
from kame.rviz.display import ERROR, WARN, Display, Frames, Status
from kame.rviz.scene import Scene, apply, arrow_triangles


class Range(Display):
    class_name = "rviz/Range"
    message_types = ("sensor_msgs/Range",)
    defaults = {"Topic": "/range", "Color": "255; 255; 255", "Alpha": 0.5, "Buffer Length": 1}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        message = self.message
        placed = self.placed(frames, message.header.frame_id)
        if placed is None:
            return
        distance = float(message.range)
        if message.min_range == message.max_range and distance < 0 and not math.isfinite(distance):
            distance = float(message.min_range)
        elif not message.min_range <= distance <= message.max_range:
            return
        radius = distance * math.tan(float(message.field_of_view) / 2)
        scene.add("triangles", apply(placed, cone_triangles(distance, radius)), self.color())


def cone_triangles(length: float, radius: float, segments: int = 24) -> np.ndarray:
    """A cone with its apex at the origin, opening along +x to a disc of `radius` at `length`."""
    angles = np.linspace(0, 2 * math.pi, segments + 1)
    rim = np.column_stack([np.full(segments + 1, length), radius * np.cos(angles), radius * np.sin(angles)])
    apex, centre = np.zeros(3), np.array([length, 0.0, 0.0])
    sides = np.stack([np.broadcast_to(apex, (segments, 3)), rim[:-1], rim[1:]], axis=1)
    cap = np.stack([np.broadcast_to(centre, (segments, 3)), rim[1:], rim[:-1]], axis=1)
    return np.concatenate([sides, cap]).reshape(-1, 3)


class WrenchStamped(Display):
    class_name = "rviz/WrenchStamped"
    message_types = ("geometry_msgs/WrenchStamped",)
    defaults = {"Topic": "/wrench", "Force Color": "204; 51; 51", "Torque Color": "204; 204; 51", "Alpha": 1,
                "Force Arrow Scale": 2, "Torque Arrow Scale": 2, "Arrow Width": 0.5, "History Length": 1}

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is None:
            return
        width = self.number("Arrow Width", 0.5)
        force, torque = self.message.wrench.force, self.message.wrench.torque
        for vector, scale_key, color_key in ((force, "Force Arrow Scale", "Force Color"),
                                             (torque, "Torque Arrow Scale", "Torque Color")):
            v = np.array([vector.x, vector.y, vector.z], dtype=float)
            length = float(np.linalg.norm(v))
            if not math.isfinite(length):
                self.status = Status(WARN, "the wrench has a NaN or infinite value")
                return
            if length < 1e-9:
                continue
            end = v * self.number(scale_key, 2.0)
            start_fixed, end_fixed = apply(placed, [[0, 0, 0], end])
            head = min(0.3 * float(np.linalg.norm(end)), 2 * width)
            scene.add("triangles", arrow_triangles(start_fixed, end_fixed, 0.2 * width, 0.4 * width, head),
                      self.color(color_key))
            if vector is torque:  # rviz's circle about the torque's axis, half way up the arrow
                scene.add("lines", apply(placed, _ring(end / 2, v / length, 0.5 * width)), self.color(color_key), 2.0)


def _ring(centre: np.ndarray, axis: np.ndarray, radius: float, segments: int = 24) -> np.ndarray:
    helper = np.array([0.0, 0.0, 1.0]) if abs(axis[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    angles = np.linspace(0, 2 * math.pi, segments + 1)
    points = centre + radius * (np.outer(np.cos(angles), u) + np.outer(np.sin(angles), w))
    return np.repeat(points, 2, axis=0)[1:-1]


class Image(Display):
    """The newest image as RGBA pixels (`pixels`), for the window's image panel."""
    class_name = "rviz/Image"
    message_types = ("sensor_msgs/Image",)
    defaults = {"Image Topic": "/image", "Transport Hint": "raw", "Queue Size": 2, "Normalize Range": True}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.pixels: np.ndarray | None = None  # H x W x 4 uint8
        # JPEG/PNG bytes -> H x W x 4 uint8 (ValueError when they are not an image); the window's
        self.decode_compressed: Callable[[bytes], np.ndarray] | None = None

    topic_key = "Image Topic"

    def subscription(self) -> tuple[str, str] | None:
        """image_transport's: Transport Hint "compressed" reads `<Image Topic>/compressed`."""
        if not self.topic:
            return None
        if self.options.get("Transport Hint") == "compressed":
            return f"{self.topic}/compressed", "sensor_msgs/CompressedImage"
        return self.topic, "sensor_msgs/Image"

    def reset(self) -> None:
        super().reset()
        self.pixels = None

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        message = self.message
        if message._type == "sensor_msgs/CompressedImage":
            if self.decode_compressed is None:
                self.pixels, self.status = None, Status(ERROR, "compressed images are decoded by the window")
                return
            try:
                self.pixels = self.decode_compressed(bytes(message.data))
            except ValueError as exc:
                self.pixels, self.status = None, Status(ERROR, f"cannot decode the {message.format} image: {exc}")
            return
        try:
            shown = to_display(message.encoding, message.width, message.height, message.step, bytes(message.data),
                               bool(message.is_bigendian))
        except ImageError as exc:
            self.pixels = None
            self.status = Status(ERROR, str(exc))
            return
        self.pixels = rgba(shown)


def rgba(shown: np.ndarray) -> np.ndarray:
    """rqt_image_view's grey, RGB or RGBA pixels as RGBA."""
    height, width = shown.shape[:2]
    channels = shown.shape[2] if shown.ndim == 3 else 1
    if channels == 4:
        return np.ascontiguousarray(shown)
    out = np.empty((height, width, 4), dtype=np.uint8)
    out[..., :3] = shown.reshape(height, width, -1)[..., :3] if channels == 3 else shown.reshape(height, width, 1)
    out[..., 3] = 255
    return out


def camera_info_topic(image_topic: str) -> str:
    """rviz's (and image_transport's) CameraInfo topic: the image topic's namespace + /camera_info."""
    return image_topic[:image_topic.rfind("/")] + "/camera_info"


class Camera(Image):
    """The image, and what the 3-D view shows, seen from the camera (`project`)."""
    class_name = "rviz/Camera"
    defaults = {"Image Topic": "/camera/image_raw", "Transport Hint": "raw", "Queue Size": 2,
                "Image Rendering": "background and overlay", "Overlay Alpha": 0.5, "Zoom Factor": 1}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.info: Any = None
        self.optical_from_fixed: np.ndarray | None = None

    def side_topics(self) -> dict[str, str]:
        return {camera_info_topic(self.topic): "sensor_msgs/CameraInfo"} if self.topic else {}

    def receive_side(self, topic: str, messages: list[Any], now: float) -> None:
        if messages:
            self.info = messages[-1]
            self.version += 1

    def reset(self) -> None:
        super().reset()
        self.info = None
        self.optical_from_fixed = None

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        super().draw(scene, frames, now)
        self.optical_from_fixed = None
        if self.pixels is None:
            return
        if self.info is None:
            self.status = Status(WARN, f"no CameraInfo received on {camera_info_topic(self.topic)}")
            return
        placed = self.placed(frames, self.message.header.frame_id)
        if placed is not None:
            self.optical_from_fixed = np.linalg.inv(placed)

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Fixed-frame points as image pixels (N x 2) and which of them are in front of the camera."""
        if self.optical_from_fixed is None or self.info is None:
            return np.zeros((len(points), 2)), np.zeros(len(points), dtype=bool)
        return project(points, self.optical_from_fixed, np.asarray(self.info.P, dtype=float).reshape(3, 4))


def project(points: np.ndarray, optical_from_fixed: np.ndarray, projection: np.ndarray,
            ) -> tuple[np.ndarray, np.ndarray]:
    """`points` (fixed frame) through a camera whose optical frame is at `optical_from_fixed`'s
    inverse and whose CameraInfo P is `projection`: pixels and an in-front mask."""
    optical = apply(optical_from_fixed, points)
    homogeneous = optical @ projection[:, :3].T + projection[:, 3]
    depth = homogeneous[:, 2]
    in_front = optical[:, 2] > 1e-6
    safe = np.where(np.abs(depth) > 1e-12, depth, 1.0)
    return homogeneous[:, :2] / safe[:, None], in_front
