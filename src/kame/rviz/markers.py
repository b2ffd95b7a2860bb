"""rviz's Marker and MarkerArray displays: markers kept by (namespace, id), replaced by a newer
one, removed by DELETE, DELETEALL (all, or a namespace's in rviz's way: all) or when their
lifetime ends; each type drawn as rviz does (cube, sphere, cylinder, arrow, line strip/list,
cube/sphere lists, points, text, triangle list, STL/DAE mesh resource). Namespaces can be hidden ("Namespaces")."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from kame.rviz.display import WARN, Display, Frames, Selectable, Status, coordinates
from kame.rviz.meshes import MeshLibrary, add_mesh
from kame.rviz.scene import (
    Scene,
    apply,
    arrow_triangles,
    box_triangles,
    cylinder_triangles,
    pose_matrix,
    quaternion_matrices,
    sphere_triangles,
)

ARROW, CUBE, SPHERE, CYLINDER, LINE_STRIP, LINE_LIST, CUBE_LIST, SPHERE_LIST, POINTS, TEXT, MESH, TRIANGLES = range(12)
ADD, DELETE, DELETEALL = 0, 2, 3
TYPE_NAMES = dict(enumerate(("Arrow", "Cube", "Sphere", "Cylinder", "Line Strip", "Line List", "Cube List",
                             "Sphere List", "Points", "Text View Facing", "Mesh Resource", "Triangle List")))


def _rgba(color: Any) -> tuple[float, float, float, float]:
    return color.r, color.g, color.b, color.a


def _point_colors(marker: Any, count: int) -> np.ndarray:
    if len(marker.colors) == count:
        return np.array([_rgba(c) for c in marker.colors], dtype=np.float32)
    return np.tile(np.array(_rgba(marker.color), dtype=np.float32), (count, 1))


SOLIDS = (CUBE, SPHERE, CYLINDER, ARROW)


def _solid_triangles(kind: int) -> tuple[np.ndarray, np.ndarray]:
    """The kind's shape at scale 1 (an arrow: length 1 along x, shaft 1 and head 2 wide, its
    shaft's end closed) as a closed surface: its triangles (T x 3 x 3) wound counter-clockwise
    seen from outside, and their normals (T x 3)."""
    if kind == ARROW:
        triangles = arrow_triangles(np.zeros(3), np.array([1.0, 0.0, 0.0]), 1.0, 2.0, 0.23).reshape(-1, 3, 3)
        rim = triangles[0::4, :2]  # each side's shaft triangle begins with two points of the start's rim
        cap = np.stack([np.zeros_like(rim[:, 0]), rim[:, 1], rim[:, 0]], axis=1)
        triangles = np.concatenate([triangles, cap])
        flat = np.ptp(triangles[:, :, 0], axis=1) < 1e-9  # the caps: facing back along x
        centres = triangles.mean(axis=1)
        outward = np.where(flat[:, None], (-1.0, 0.0, 0.0), centres * (0.0, 1.0, 1.0))
    else:
        shape = {CUBE: box_triangles, SPHERE: sphere_triangles, CYLINDER: cylinder_triangles}[kind]
        triangles = shape((1.0, 1.0, 1.0)).reshape(-1, 3, 3)
        outward = triangles.mean(axis=1)  # centred on the origin and convex
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    solid = np.linalg.norm(normals, axis=1) > 1e-12  # a sphere's rows at its poles have corners in one point
    triangles, normals, outward = triangles[solid], normals[solid], outward[solid]
    inward = (normals * outward).sum(axis=1) < 0
    triangles[inward] = triangles[inward][:, ::-1]
    normals[inward] = -normals[inward]
    return triangles, normals / np.linalg.norm(normals, axis=1, keepdims=True)


@functools.cache
def solid_template(kind: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The kind's shape at scale 1 (see _solid_triangles) as vertices and their normals (V x 3
    float32) and its triangles as indices into them (T x 3 uint32). A sphere and the round
    sides of a cylinder or an arrow's shaft are shaded smooth, as rviz's meshes are (a vertex's
    normal points away from the axis), so their triangles share vertices; flat faces share
    the corners they have in common."""
    triangles, faces = _solid_triangles(kind)
    corners = triangles.reshape(-1, 3)
    normals = np.repeat(faces, 3, axis=0)
    axis = {SPHERE: None, CYLINDER: 2, ARROW: 0}.get(kind, -1)
    if axis != -1:
        # a sphere's every face, a round side's (its normal across the axis): from the axis out
        round_side = np.ones(len(corners), bool) if axis is None else np.abs(normals[:, axis]) < 1e-9
        away = corners.copy()
        if axis is not None:
            away[:, axis] = 0.0
        lengths = np.linalg.norm(away, axis=1, keepdims=True)
        normals = np.where(round_side[:, None] & (lengths > 1e-12), away / np.maximum(lengths, 1e-12), normals)
    welded = np.round(np.hstack([corners, normals]), 6)
    _, first, inverse = np.unique(welded, axis=0, return_index=True, return_inverse=True)
    return (corners[first].astype(np.float32), normals[first].astype(np.float32),
            inverse.reshape(-1, 3).astype(np.uint32))


def _solid_arrays(kind: int, placed: list[tuple[Any, np.ndarray]]) -> tuple[np.ndarray, ...]:
    """Markers of one solid kind (each with the matrix of its frame) as arrays: rotations
    (N x 3 x 3), origins and scales (N x 3) in float32 and colours (N x 4 bytes)."""
    count = len(placed)
    fields = np.empty((count, 14))
    for row, (marker, _) in enumerate(placed):
        p, q, s, c = marker.pose.position, marker.pose.orientation, marker.scale, marker.color
        fields[row] = (p.x, p.y, p.z, q.x, q.y, q.z, q.w, s.x, s.y, s.z, c.r, c.g, c.b, c.a)
    frames = np.stack([matrix for _, matrix in placed])
    rotations = frames[:, :3, :3] @ quaternion_matrices(fields[:, 3:7])
    origins = np.einsum("nij,nj->ni", frames[:, :3, :3], fields[:, :3]) + frames[:, :3, 3]
    scales = fields[:, 7:10].copy()
    if kind == ARROW:  # as draw_marker: length x, both diameters from y
        scales[:, 2] = scales[:, 1]
    else:
        scales = np.abs(scales)
    colors = np.clip(fields[:, 10:14] * 255 + 0.5, 0, 255).astype(np.uint8)
    return rotations.astype(np.float32), origins.astype(np.float32), scales.astype(np.float32), colors


def draw_solids(scene: Scene, solids: dict[int, list[tuple[Any, np.ndarray]]]) -> None:
    """Solid markers (by kind, each with the matrix of its frame) in one batch: their poses,
    scales and colours gathered into arrays and every vertex placed by numpy straight into the
    batch's arrays, the same geometry draw_marker gives each alone. A marker mirrored by a
    negative scale turns its winding over: those go in a batch drawn from both sides."""
    pieces = []
    for kind, placed in solids.items():
        rotations, origins, scales, colors = _solid_arrays(kind, placed)
        closed = (scales > 0).all(axis=1)
        for mask, is_closed in ((closed, True), (~closed, False)):
            if mask.any():
                pieces.append((is_closed, kind, rotations[mask], origins[mask], scales[mask], colors[mask]))
    for is_closed in (True, False):
        chosen = [piece for piece in pieces if piece[0] == is_closed]
        if not chosen:
            continue
        total = sum(len(piece[4]) * len(solid_template(piece[1])[0]) for piece in chosen)
        vertices = np.empty((total, 3), dtype=np.float32)
        normals = np.empty((total, 3), dtype=np.float32)
        colors = np.empty((total, 4), dtype=np.uint8)
        indices = []
        start = 0
        for _, kind, rotations, origins, scales, piece_colors in chosen:
            template, template_normals, template_indices = solid_template(kind)
            count, size = len(scales), len(template)
            rows = slice(start, start + count * size)
            block = _placed(template, scales, rotations, vertices[rows].reshape(count, size, 3))
            block += origins[:, None, :]
            # a normal goes through the inverse of the scaling (a flattened sphere's stay perpendicular)
            inverse = 1 / np.where(np.abs(scales) > 1e-12, scales, np.float32(1e-12))
            turned = _placed(template_normals, inverse, rotations, normals[rows].reshape(count, size, 3))
            turned /= np.sqrt(np.maximum((turned * turned).sum(axis=2, keepdims=True), np.float32(1e-24)))
            colors[rows].reshape(count, size, 4)[...] = piece_colors[:, None, :]
            firsts = np.arange(start, start + count * size, size, dtype=np.uint32)
            indices.append((template_indices.reshape(1, -1) + firsts[:, None]).reshape(-1))
            start += count * size
        scene.add("triangles", vertices, colors, closed=is_closed, normals=normals, indices=np.concatenate(indices))


def _placed(points: np.ndarray, scales: np.ndarray, rotations: np.ndarray, out: np.ndarray | None = None,
            ) -> np.ndarray:
    """`points` (V x 3) scaled and turned by each of N scales (N x 3) and rotations (N x 3 x 3):
    N x V x 3 float32 (into `out` when given), written out per row (a batched matmul is slower
    here, as in scene.apply)."""
    scaled = [points[None, :, axis] * scales[:, axis, None] for axis in range(3)]  # N x V each
    if out is None:
        out = np.empty((len(scales), len(points), 3), dtype=np.float32)
    for row in range(3):
        r = rotations[:, row, :, None]
        out[:, :, row] = r[:, 0] * scaled[0] + r[:, 1] * scaled[1] + r[:, 2] * scaled[2]
    return out


def draw_marker(scene: Scene, marker: Any, placed: np.ndarray, meshes: MeshLibrary | None = None) -> str:
    """Adds `marker` (whose frame is at `placed`) to the scene; says why not when it cannot."""
    matrix = placed @ pose_matrix(marker.pose)
    scale = (marker.scale.x, marker.scale.y, marker.scale.z)
    color = _rgba(marker.color)
    points = np.array([[p.x, p.y, p.z] for p in marker.points], dtype=float).reshape(-1, 3)
    kind = marker.type
    if kind in SOLIDS and (kind != ARROW or len(points) < 2):
        draw_solids(scene, {kind: [(marker, placed)]})
    elif kind == ARROW:  # from the first point to the second
        start, end = apply(matrix, points[:2])
        head_length = scale[2] if scale[2] > 0 else 0.23 * float(np.linalg.norm(end - start))
        scene.add("triangles", arrow_triangles(start, end, scale[0], scale[1], head_length), color)
    elif kind in (LINE_STRIP, LINE_LIST):
        if len(points) < 2:
            return ""
        colors = _point_colors(marker, len(points))
        world = apply(matrix, points)
        if kind == LINE_STRIP:
            world, colors = np.repeat(world, 2, axis=0)[1:-1], np.repeat(colors, 2, axis=0)[1:-1]
        else:
            even = len(points) // 2 * 2
            world, colors = world[:even], colors[:even]
        scene.add("lines", world, colors, max(1.0, scale[0] * 100))
    elif kind == POINTS:
        scene.add("points", apply(matrix, points), _point_colors(marker, len(points)), max(1.0, scale[0] * 100))
    elif kind in (CUBE_LIST, SPHERE_LIST):
        shape = box_triangles(scale) if kind == CUBE_LIST else sphere_triangles(scale, 4, 6)
        centers = apply(matrix, points)
        colors = _point_colors(marker, len(points))
        triangles = (centers[:, None, :] + shape[None, :, :] @ matrix[:3, :3].T).reshape(-1, 3)
        scene.add("triangles", triangles, np.repeat(colors, len(shape), axis=0))
    elif kind == TEXT:
        scene.label(matrix[:3, 3], marker.text, color)
    elif kind == TRIANGLES:
        even = len(points) // 3 * 3
        scene.add("triangles", apply(matrix, points[:even]), _point_colors(marker, len(points))[:even])
    elif kind == MESH:
        mesh = (meshes or MeshLibrary()).load(marker.mesh_resource)
        if isinstance(mesh, str):
            return mesh
        # rviz: the marker's colour, unless it asks for the file's own and the file has some
        add_mesh(scene, mesh, matrix, scale, None if marker.mesh_use_embedded_materials else color)
    else:
        return f"unknown marker type {kind}"
    return ""


class Marker(Display):
    class_name = "rviz/Marker"
    message_types = ("visualization_msgs/Marker",)
    defaults = {"Marker Topic": "/visualization_marker", "Queue Size": 100, "Namespaces": {}}
    keeps_every_message = True

    topic_key = "Marker Topic"

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.markers: dict[tuple[str, int], tuple[Any, float]] = {}
        self.meshes = MeshLibrary()  # the window gives it kame's package finder
        self._drawn: list[tuple[Any, np.ndarray]] = []  # (marker, its frame's matrix) as last drawn

    def reset(self) -> None:
        super().reset()
        self.markers = {}
        self._drawn = []

    def receive(self, messages: Any, now: float) -> None:
        for message in messages:
            self.message = message
            self.version += 1
            for marker in self.unpack(message):
                self.apply(marker, now)

    def unpack(self, message: Any) -> list[Any]:
        return [message]

    def apply(self, marker: Any, now: float) -> None:
        key = (marker.ns, marker.id)
        if marker.action == DELETEALL:
            self.markers = {}
        elif marker.action == DELETE:
            self.markers.pop(key, None)
        else:  # ADD and MODIFY (the same value)
            self.markers[key] = (marker, now)

    def namespace_shown(self, namespace: str) -> bool:
        shown = self.options.get("Namespaces") or {}
        return bool(shown.get(namespace, True)) if isinstance(shown, dict) else True

    def selectable(self) -> Selectable | None:
        """Each marker drawn, at its pose: "<ns>/<id>" and what rviz's Selection panel shows of it."""
        drawn = self._drawn
        if not drawn:
            return None

        def describe(i: int) -> tuple[str, dict[str, str]]:
            marker, _ = drawn[i]
            q, s, c = marker.pose.orientation, marker.scale, marker.color
            return f"{marker.ns}/{marker.id}", {
                "Type": TYPE_NAMES.get(marker.type, str(marker.type)), "Frame": marker.header.frame_id,
                "Position": coordinates(positions[i]), "Orientation": coordinates((q.x, q.y, q.z, q.w)),
                "Scale": coordinates((s.x, s.y, s.z)), "Color": coordinates((c.r, c.g, c.b, c.a))}

        positions = np.array([(placed @ [m.pose.position.x, m.pose.position.y, m.pose.position.z, 1.0])[:3]
                              for m, placed in drawn])
        return Selectable(positions, describe)

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        problems = []
        self._drawn = []
        solids: dict[int, list[tuple[Any, np.ndarray]]] = {}  # drawn together, by kind
        placements: dict[str, np.ndarray | str] = {}
        for key, (marker, received) in list(self.markers.items()):
            lifetime = marker.lifetime.secs + marker.lifetime.nsecs * 1e-9
            if lifetime > 0 and now - received > lifetime:
                del self.markers[key]
                continue
            if lifetime > 0:
                self.expires_at = min(self.expires_at, received + lifetime)
            if not self.namespace_shown(marker.ns):
                continue
            found = placements.get(marker.header.frame_id)
            if found is None:  # one lookup a frame, not one a marker: 2,000 markers share a few frames
                found = placements[marker.header.frame_id] = frames.transform(marker.header.frame_id)
            if isinstance(found, str):
                problems.append(f"{marker.ns}/{marker.id}: {found}")
                continue
            self._drawn.append((marker, found))
            if marker.type in SOLIDS and (marker.type != ARROW or len(marker.points) < 2):
                solids.setdefault(marker.type, []).append((marker, found))
                continue
            problem = draw_marker(scene, marker, found, self.meshes)
            if problem:
                problems.append(f"{marker.ns}/{marker.id}: {problem}")
        if solids:
            draw_solids(scene, solids)
        if problems:
            self.status = Status(WARN, "; ".join(problems[:3]) + (" ..." if len(problems) > 3 else ""))

    def namespaces(self) -> list[str]:
        return sorted({ns for ns, _ in self.markers})


class MarkerArray(Marker):
    class_name = "rviz/MarkerArray"
    message_types = ("visualization_msgs/MarkerArray",)
    defaults = {"Marker Topic": "/visualization_marker_array", "Queue Size": 100, "Namespaces": {}}

    def unpack(self, message: Any) -> list[Any]:
        return list(message.markers)
