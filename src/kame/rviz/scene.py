"""What the 3-D view draws, in the fixed frame: batches of line segments, points and
triangles with a colour per vertex (RGBA floats), and text labels. The displays fill a Scene
each frame; the window only uploads its arrays to OpenGL and paints the labels."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

Color = tuple[float, float, float, float]


@dataclass
class Batch:
    """One draw call: `kind` is "lines" (vertex pairs), "points" or "triangles" (vertex triples).
    `colors` is N x 4: float32 0..1, or uint8 0..255 (a cloud's packed rgb: a quarter of the
    bytes); one colour for every vertex is a broadcast view (stride 0), drawn without a colour
    array at all. `closed` triangles wind counter-clockwise seen from outside a closed surface,
    so the faces turned away from the camera need not be drawn; `normals` (N x 3 float32, one a
    vertex) spare the window working them out from the triangles. `metres`: points `size`
    metres wide where they are (rviz's Squares styles), smaller as they are farther away.
    `overlay`: drawn over everything, hidden by nothing (the tools' marks). `indices`: the
    primitives' vertices as indices into `vertices` (uint32), where solids share their corners:
    a third to a sixth of the vertices to place, upload and light (such a batch has normals)."""
    kind: str
    vertices: np.ndarray  # N x 3 float32, fixed frame
    colors: np.ndarray  # N x 4 float32 or uint8
    size: float = 1.0  # line width or point size in pixels
    closed: bool = False
    normals: np.ndarray | None = None
    metres: bool = False
    overlay: bool = False
    indices: np.ndarray | None = None

    @property
    def uniform(self) -> bool:
        return len(self.colors) > 0 and self.colors.strides[0] == 0

    def float_colors(self) -> np.ndarray:
        """N x 4 float32 0..1, whatever the batch keeps."""
        if self.colors.dtype == np.uint8:
            return self.colors.astype(np.float32) / 255
        return np.asarray(self.colors, dtype=np.float32)

    def unindexed(self) -> Batch:
        """The same primitives with each vertex written out where it is used (an indexed
        batch's shared ones repeated): what works on the triangles, not the GPU, reads."""
        if self.indices is None:
            return self
        normals = None if self.normals is None else self.normals[self.indices]
        return Batch(self.kind, self.vertices[self.indices], self.colors[self.indices], self.size, self.closed,
                     normals, self.metres, self.overlay)


@dataclass
class Label:
    position: np.ndarray
    text: str
    color: Color


@dataclass
class Texture:
    """An image laid on a quad (a map): `corners` are the fixed-frame points of pixel row 0's
    first and last column and then of the last row's last and first column."""
    corners: np.ndarray  # 4 x 3
    rgba: np.ndarray  # H x W x 4 uint8, row 0 at corners[0..1]


@dataclass
class Scene:
    batches: list[Batch] = field(default_factory=list)
    labels: list[Label] = field(default_factory=list)
    textures: list[Texture] = field(default_factory=list)

    def texture(self, corners: Any, rgba: np.ndarray) -> None:
        self.textures.append(Texture(np.asarray(corners, dtype=np.float32).reshape(4, 3), rgba))

    def add(self, kind: str, vertices: Any, colors: Any, size: float = 1.0, closed: bool = False,
            normals: np.ndarray | None = None, metres: bool = False, overlay: bool = False,
            indices: np.ndarray | None = None) -> None:
        vertices = np.asarray(vertices, dtype=np.float32).reshape(-1, 3)
        if not len(vertices):
            return
        colors = np.asarray(colors)
        if colors.dtype != np.uint8:
            colors = colors.astype(np.float32, copy=False)
        if colors.ndim == 1:
            colors = np.broadcast_to(colors, (len(vertices), 4))
        else:
            colors = np.ascontiguousarray(colors)
        if normals is not None:
            normals = np.ascontiguousarray(normals, dtype=np.float32).reshape(-1, 3)
        if indices is not None:
            if normals is None:  # the window works out a triangle soup's normals, not shared vertices'
                raise ValueError("indexed triangles need their normals")
            indices = np.ascontiguousarray(indices, dtype=np.uint32).reshape(-1)
        self.batches.append(Batch(kind, np.ascontiguousarray(vertices), colors, size, closed, normals, metres,
                                  overlay, indices))

    def merged(self) -> Scene:
        """The same scene with batches of one kind, size and closedness joined: one draw call
        for 2,000 markers (colours stay bytes when all are)."""
        groups: dict[tuple[str, float, bool, bool, bool, bool], list[Batch]] = {}
        for batch in self.batches:
            key = (batch.kind, batch.size, batch.closed, batch.metres, batch.overlay, batch.indices is not None)
            groups.setdefault(key, []).append(batch)
        batches = []
        for (kind, size, closed, metres, overlay, indexed), group in groups.items():
            if len(group) == 1:
                batches.append(group[0])
                continue
            as_bytes = all(b.colors.dtype == np.uint8 for b in group)
            colors = np.concatenate([b.colors if as_bytes else b.float_colors() for b in group])
            normals = (np.concatenate([b.normals for b in group if b.normals is not None])
                       if all(b.normals is not None for b in group) else None)
            indices = None
            if indexed:  # each batch's indices moved past the vertices of those before it
                starts = np.cumsum([0] + [len(b.vertices) for b in group[:-1]])
                indices = np.concatenate([b.indices + np.uint32(start) for b, start in zip(group, starts, strict=True)
                                          if b.indices is not None])
            batches.append(Batch(kind, np.concatenate([b.vertices for b in group]), colors, size, closed, normals,
                                 metres, overlay, indices))
        return Scene(batches, self.labels, self.textures)

    def extend(self, other: Scene) -> None:
        self.batches += other.batches
        self.labels += other.labels
        self.textures += other.textures

    def label(self, position: Any, text: str, color: Color) -> None:
        self.labels.append(Label(np.asarray(position, dtype=float), text, color))


# ------------------------------------------------------------------ poses as matrices

def quaternion_matrix(x: float, y: float, z: float, w: float) -> np.ndarray:
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    if norm < 1e-12:  # rviz treats an all-zero quaternion as identity (and warns)
        return np.eye(3)
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def quaternion_matrices(quaternions: np.ndarray) -> np.ndarray:
    """quaternion_matrix for N quaternions (N x 4, x y z w) at once: N x 3 x 3."""
    q = np.asarray(quaternions, dtype=float)
    norm = np.sqrt((q * q).sum(axis=1))
    zero = norm < 1e-12
    q = np.where(zero[:, None], (0.0, 0.0, 0.0, 1.0), q / np.where(zero, 1.0, norm)[:, None])
    x, y, z, w = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=-1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=-1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=-1),
    ], axis=1)


def pose_matrix(pose: Any) -> np.ndarray:
    """A geometry_msgs/Pose (or Transform: translation/rotation) as a 4x4 matrix."""
    position = getattr(pose, "position", None) or pose.translation
    orientation = getattr(pose, "orientation", None) or pose.rotation
    matrix = np.eye(4)
    matrix[:3, :3] = quaternion_matrix(orientation.x, orientation.y, orientation.z, orientation.w)
    matrix[:3, 3] = (position.x, position.y, position.z)
    return matrix


def apply(matrix: np.ndarray, points: Any) -> np.ndarray:
    """`points` (N x 3) moved by the 4x4 `matrix` (float32 points give float32). Written out per
    row of the matrix: a BLAS matmul of a tall N x 3 array is many times slower here (thread
    start-up on a busy machine)."""
    points = np.asarray(points)
    # float32 stays float32 (a cloud's 300k points: half the bytes to move and to upload)
    points = points.astype(np.float32 if points.dtype == np.float32 else float, copy=False).reshape(-1, 3)
    x, y, z = points[:, 0], points[:, 1], points[:, 2]
    result: np.ndarray = np.empty_like(points)
    for row in range(3):
        r = matrix[row]
        result[:, row] = x * r[0] + y * r[1] + z * r[2] + r[3]
    return result


def spatial_order(points: np.ndarray, cells: int = 40) -> np.ndarray:
    """An order of `points` (N x 3) that visits them box by box of a cells^3 grid over their
    bounds. llvmpipe rasterises a point cloud twice as fast in it as in a random one (300k
    points: 28 against 59 ms of CPU): each screen tile's points sit together in memory. About
    5 ms for 300k points (a radix sort of 16-bit box numbers)."""
    low = np.array([points[:, axis].min() for axis in range(3)], dtype=np.float32)  # per column: 20x faster
    high = np.array([points[:, axis].max() for axis in range(3)], dtype=np.float32)
    boxes = ((points - low) * ((cells - 1) / np.maximum(high - low, np.float32(1e-9)))).astype(np.uint16)
    key = (boxes[:, 0] * cells + boxes[:, 1]) * cells + boxes[:, 2]  # < 40^3: 16 bits
    order: np.ndarray = np.argsort(key, kind="stable")
    return order


# ------------------------------------------------------------------ shapes

def axes_lines(scene: Scene, matrix: np.ndarray, length: float, alpha: float = 1.0, width: float = 3.0) -> None:
    """rviz's axes: x red, y green, z blue."""
    ends = apply(matrix, np.array([[0, 0, 0], [length, 0, 0], [0, 0, 0], [0, length, 0], [0, 0, 0], [0, 0, length]]))
    colors = np.array([[1, 0, 0, alpha]] * 2 + [[0, 1, 0, alpha]] * 2 + [[0, 0, 1, alpha]] * 2)
    scene.add("lines", ends, colors, width)


def arrow_triangles(start: np.ndarray, end: np.ndarray, shaft_diameter: float, head_diameter: float,
                    head_length: float, sides: int = 8) -> np.ndarray:
    """An arrow from `start` to `end` as triangles (shaft cylinder and head cone)."""
    direction = np.asarray(end, float) - np.asarray(start, float)
    length = float(np.linalg.norm(direction))
    if length < 1e-9:
        return np.zeros((0, 3))
    axis = direction / length
    head_length = min(head_length, length)
    helper = np.array([0.0, 0.0, 1.0]) if abs(axis[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    angles = np.linspace(0, 2 * math.pi, sides + 1)
    ring = np.outer(np.cos(angles), u) + np.outer(np.sin(angles), v)
    shaft_end = np.asarray(start, float) + axis * (length - head_length)
    triangles: list[np.ndarray] = []
    for i in range(sides):
        a0, a1 = ring[i] * shaft_diameter / 2, ring[i + 1] * shaft_diameter / 2
        triangles += [start + a0, start + a1, shaft_end + a1, start + a0, shaft_end + a1, shaft_end + a0]
        h0, h1 = ring[i] * head_diameter / 2, ring[i + 1] * head_diameter / 2
        triangles += [shaft_end + h0, shaft_end + h1, np.asarray(end, float)]
        triangles += [shaft_end + h0, shaft_end + h1, shaft_end]
    return np.array(triangles)


BOX_FACES = np.array([
    [0, 1, 2, 0, 2, 3], [4, 6, 5, 4, 7, 6], [0, 4, 5, 0, 5, 1],
    [1, 5, 6, 1, 6, 2], [2, 6, 7, 2, 7, 3], [3, 7, 4, 3, 4, 0],
]).reshape(-1)


def box_triangles(scale: Sequence[float]) -> np.ndarray:
    """A box centred on the origin with sides `scale` (x, y, z), as 36 vertices."""
    hx, hy, hz = (abs(s) / 2 for s in scale)
    corners = np.array([[-hx, -hy, -hz], [hx, -hy, -hz], [hx, hy, -hz], [-hx, hy, -hz],
                        [-hx, -hy, hz], [hx, -hy, hz], [hx, hy, hz], [-hx, hy, hz]])
    faces: np.ndarray = corners[BOX_FACES]
    return faces


def sphere_triangles(scale: Sequence[float], rings: int = 8, segments: int = 12) -> np.ndarray:
    theta = np.linspace(0, math.pi, rings + 1)
    phi = np.linspace(0, 2 * math.pi, segments + 1)
    grid = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                     np.outer(np.cos(theta), np.ones_like(phi))], axis=-1) * (np.asarray(scale, float) / 2)
    a, b, c, d = grid[:-1, :-1], grid[:-1, 1:], grid[1:, 1:], grid[1:, :-1]
    return np.stack([a, b, c, a, c, d], axis=2).reshape(-1, 3)


def cylinder_triangles(scale: Sequence[float], segments: int = 16) -> np.ndarray:
    """A cylinder along z, as rviz's CYLINDER marker (diameters x, y; height z)."""
    phi = np.linspace(0, 2 * math.pi, segments + 1)
    rx, ry, hz = scale[0] / 2, scale[1] / 2, scale[2] / 2
    ring = np.column_stack([rx * np.cos(phi), ry * np.sin(phi)])
    triangles: list[list[float]] = []
    for i in range(segments):
        (x0, y0), (x1, y1) = ring[i], ring[i + 1]
        triangles += [[x0, y0, -hz], [x1, y1, -hz], [x1, y1, hz], [x0, y0, -hz], [x1, y1, hz], [x0, y0, hz]]
        triangles += [[0, 0, hz], [x0, y0, hz], [x1, y1, hz], [0, 0, -hz], [x1, y1, -hz], [x0, y0, -hz]]
    return np.array(triangles)


def face_normals(vertices: np.ndarray) -> np.ndarray:
    """Each triangle's unit normal, once per vertex (N x 3 float32); a degenerate one's is z."""
    corners = vertices.reshape(-1, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    flat = lengths < 1e-12
    normals[flat] = (0.0, 0.0, 1.0)
    normals[~flat] /= lengths[~flat, None]
    return np.repeat(normals.astype(np.float32), 3, axis=0)
