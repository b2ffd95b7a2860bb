"""rviz's RobotModel display: the robot_description URDF's visuals (box, cylinder, sphere and
STL/DAE meshes), each placed at its link's tf frame and the visual's origin, in the material's
colour (a mesh's own colours without one; rviz's default red when neither gives one). The
URDF is parsed by urdf_parser_py; the window reads the parameter and hands its text to
`describe`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.rviz.display import WARN, Display, Frames, Status
from kame.rviz.meshes import DEFAULT_COLOR, MeshLibrary, add_mesh
from kame.rviz.scene import Color, Scene, apply, box_triangles, cylinder_triangles, sphere_triangles

SHAPES = {"box": box_triangles, "cylinder": cylinder_triangles, "sphere": sphere_triangles}


@dataclass
class Visual:
    link: str
    origin: np.ndarray  # 4x4, in the link's frame
    shape: str  # box, cylinder, sphere, mesh
    size: tuple[float, float, float]  # the shape's scale (diameters and heights; a mesh's scale)
    color: Color | None  # None: the URDF gives none
    mesh: str = ""


def origin_matrix(xyz: Any, rpy: Any) -> np.ndarray:
    x, y, z = (float(v) for v in (xyz or (0.0, 0.0, 0.0)))
    roll, pitch, yaw = (float(v) for v in (rpy or (0.0, 0.0, 0.0)))
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    matrix = np.eye(4)
    matrix[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                      [-sp, cp * sr, cp * cr]]
    matrix[:3, 3] = (x, y, z)
    return matrix


def _color(material: Any, named: dict[str, Color]) -> Color | None:
    if material is None:
        return None
    own = getattr(material, "color", None)
    if own is not None and own.rgba is not None:
        r, g, b, a = (float(v) for v in own.rgba)
        return r, g, b, a
    return named.get(str(material.name or ""))


def parse_urdf(text: str) -> list[Visual]:
    """The visuals of a URDF document; ValueError when it is not one."""
    from xml.etree.ElementTree import ParseError

    from urdf_parser_py.urdf import URDF

    try:
        robot = URDF.from_xml_string(text.encode())
    except ParseError as exc:
        raise ValueError(f"not XML: {exc}") from None
    except Exception as exc:  # urdf_parser_py's own (a missing attribute, a wrong root)
        raise ValueError(f"not a URDF: {exc}") from None
    named: dict[str, Color] = {}
    for material in robot.materials or []:
        found = _color(material, {})
        if found is not None:
            named[str(material.name)] = found
    visuals = []
    for link in robot.links:
        for visual in link.visuals or []:
            geometry = visual.geometry
            if geometry is None:
                continue
            kind = type(geometry).__name__.lower()
            size: tuple[float, float, float] = (1.0, 1.0, 1.0)
            mesh = ""
            if kind == "box":
                sx, sy, sz = (float(v) for v in geometry.size)
                size = (sx, sy, sz)
            elif kind == "cylinder":
                size = (2 * float(geometry.radius), 2 * float(geometry.radius), float(geometry.length))
            elif kind == "sphere":
                size = (2 * float(geometry.radius),) * 3
            elif kind == "mesh":
                mesh = str(geometry.filename)
                if geometry.scale is not None:
                    sx, sy, sz = (float(v) for v in geometry.scale)
                    size = (sx, sy, sz)
            origin = visual.origin
            visuals.append(Visual(str(link.name), origin_matrix(origin.xyz if origin else None,
                                                                origin.rpy if origin else None),
                                  kind, size, _color(visual.material, named), mesh))
    return visuals


class RobotModel(Display):
    class_name = "rviz/RobotModel"
    defaults = {"Robot Description": "robot_description", "Alpha": 1, "TF Prefix": ""}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.visuals: list[Visual] = []
        self.problem = "no robot description yet"
        self.meshes = MeshLibrary()  # the window gives it kame's package finder

    def describe(self, text: str | None) -> None:
        """The parameter's text (None: the parameter is not set)."""
        self.version += 1
        if text is None:
            self.visuals, self.problem = [], f"parameter {self.options.get('Robot Description')} is not set"
            return
        try:
            self.visuals, self.problem = parse_urdf(text), ""
        except ValueError as exc:
            self.visuals, self.problem = [], f"robot description: {exc}"

    def draw(self, scene: Scene, frames: Frames, now: float) -> None:
        if self.problem:
            self.status = Status(WARN, self.problem)
            return
        alpha = self.number("Alpha", 1.0)
        prefix = str(self.options.get("TF Prefix") or "")
        problems = []
        for visual in self.visuals:
            placed = frames.transform(f"{prefix}/{visual.link}" if prefix else visual.link)
            if isinstance(placed, str):
                problems.append(f"{visual.link}: {placed}")
                continue
            matrix = placed @ visual.origin
            color = visual.color or DEFAULT_COLOR
            if visual.shape == "mesh":
                mesh = self.meshes.load(visual.mesh)
                if isinstance(mesh, str):
                    problems.append(f"{visual.link}: {mesh}")
                    continue
                add_mesh(scene, mesh, matrix, visual.size, visual.color, alpha)
            elif visual.shape in SHAPES:
                scene.add("triangles", apply(matrix, SHAPES[visual.shape](visual.size)),
                          (*color[:3], color[3] * alpha))
            else:
                problems.append(f"{visual.link}: {visual.shape} is not drawn")
        if problems:
            self.status = Status(WARN, "; ".join(sorted(set(problems))[:3]))

