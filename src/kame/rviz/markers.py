"""rviz's Marker and MarkerArray displays: markers kept by (namespace, id), replaced by a newer
one, removed by DELETE, DELETEALL (all, or a namespace's in rviz's way: all) or when their
lifetime ends; each type drawn as rviz does (cube, sphere, cylinder, arrow, line strip/list,
cube/sphere lists, points, text, triangle list, STL/DAE mesh resource). Namespaces can be hidden ("Namespaces")."""

from __future__ import annotations

from typing import Any

import numpy as np

from kame.rviz.display import WARN, Display, Frames, Status
from kame.rviz.meshes import MeshLibrary, add_mesh
from kame.rviz.scene import (
    Scene,
    apply,
    arrow_triangles,
    box_triangles,
    cylinder_triangles,
    pose_matrix,
    sphere_triangles,
)

ARROW, CUBE, SPHERE, CYLINDER, LINE_STRIP, LINE_LIST, CUBE_LIST, SPHERE_LIST, POINTS, TEXT, MESH, TRIANGLES = range(12)
ADD, DELETE, DELETEALL = 0, 2, 3


def _rgba(color: Any) -> tuple[float, float, float, float]:
    return color.r, color.g, color.b, color.a


def _point_colors(marker: Any, count: int) -> np.ndarray:
    if len(marker.colors) == count:
        return np.array([_rgba(c) for c in marker.colors], dtype=np.float32)
    return np.tile(np.array(_rgba(marker.color), dtype=np.float32), (count, 1))


def draw_marker(scene: Scene, marker: Any, placed: np.ndarray, meshes: MeshLibrary | None = None) -> str:
    """Adds `marker` (whose frame is at `placed`) to the scene; says why not when it cannot."""
    matrix = placed @ pose_matrix(marker.pose)
    scale = (marker.scale.x, marker.scale.y, marker.scale.z)
    color = _rgba(marker.color)
    points = np.array([[p.x, p.y, p.z] for p in marker.points], dtype=float).reshape(-1, 3)
    kind = marker.type
    if kind in (CUBE, SPHERE, CYLINDER):
        shape = {CUBE: box_triangles, SPHERE: sphere_triangles, CYLINDER: cylinder_triangles}[kind](scale)
        scene.add("triangles", apply(matrix, shape), color)
    elif kind == ARROW:
        if len(points) >= 2:
            start, end = apply(matrix, points[:2])
            head_length = scale[2] if scale[2] > 0 else 0.23 * float(np.linalg.norm(end - start))
            triangles = arrow_triangles(start, end, scale[0], scale[1], head_length)
        else:
            start, end = apply(matrix, [[0, 0, 0], [scale[0], 0, 0]])
            triangles = arrow_triangles(start, end, scale[1], scale[1] * 2, scale[0] * 0.23)
        scene.add("triangles", triangles, color)
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
    defaults = {"Topic": "/visualization_marker", "Queue Size": 100, "Namespaces": {}}
    keeps_every_message = True

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.markers: dict[tuple[str, int], tuple[Any, float]] = {}
        self.meshes = MeshLibrary()  # the window gives it kame's package finder

    def reset(self) -> None:
        super().reset()
        self.markers = {}

    def receive(self, messages: Any, now: float) -> None:
        for message in messages:
            self.message = message
            self.version += 1
            for marker in self.unpack(message):
                self.apply(marker, now)

    def time_dependent(self) -> bool:
        return any(m.lifetime.secs or m.lifetime.nsecs for m, _ in self.markers.values())

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

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        problems = []
        for key, (marker, received) in list(self.markers.items()):
            lifetime = marker.lifetime.secs + marker.lifetime.nsecs * 1e-9
            if lifetime > 0 and now - received > lifetime:
                del self.markers[key]
                continue
            if not self.namespace_shown(marker.ns):
                continue
            found = frames.transform(marker.header.frame_id)
            if isinstance(found, str):
                problems.append(f"{marker.ns}/{marker.id}: {found}")
                continue
            problem = draw_marker(scene, marker, found, self.meshes)
            if problem:
                problems.append(f"{marker.ns}/{marker.id}: {problem}")
        if problems:
            self.status = Status(WARN, "; ".join(problems[:3]) + (" ..." if len(problems) > 3 else ""))

    def namespaces(self) -> list[str]:
        return sorted({ns for ns, _ in self.markers})


class MarkerArray(Marker):
    class_name = "rviz/MarkerArray"
    message_types = ("visualization_msgs/MarkerArray",)
    defaults = {"Topic": "/visualization_marker_array", "Queue Size": 100, "Namespaces": {}}

    def unpack(self, message: Any) -> list[Any]:
        return list(message.markers)
