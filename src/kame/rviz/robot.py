"""rviz's RobotModel display: the robot_description URDF's visuals (box, cylinder, sphere; a
mesh is named in the status, not drawn yet), each placed at its link's tf frame and the
visual's origin, in the material's colour (rviz's default grey without one). The window reads
the parameter and hands its text to `describe`."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from typing import Any

import numpy as np

from kame.rviz.display import WARN, Display, Frames, Status
from kame.rviz.scene import Color, Scene, apply, box_triangles, cylinder_triangles, sphere_triangles

DEFAULT_COLOR: Color = (0.8, 0.8, 0.8, 1.0)


@dataclass
class Visual:
    link: str
    origin: np.ndarray  # 4x4, in the link's frame
    shape: str  # box, cylinder, sphere, mesh
    size: tuple[float, float, float]  # the shape's scale (diameters and heights)
    color: Color
    mesh: str = ""


def _floats(text: str | None, count: int, default: float = 0.0) -> list[float]:
    values = [float(v) for v in (text or "").split()]
    return (values + [default] * count)[:count]


def origin_matrix(element: ElementTree.Element | None) -> np.ndarray:
    x, y, z = _floats(element.get("xyz") if element is not None else None, 3)
    roll, pitch, yaw = _floats(element.get("rpy") if element is not None else None, 3)
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), \
        math.sin(yaw)
    matrix = np.eye(4)
    matrix[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                      [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                      [-sp, cp * sr, cp * cr]]
    matrix[:3, 3] = (x, y, z)
    return matrix


def parse_urdf(text: str) -> list[Visual]:
    """The visuals of a URDF document; ValueError when it is not one."""
    try:
        robot = ElementTree.fromstring(text)
    except ElementTree.ParseError as exc:
        raise ValueError(f"not XML: {exc}") from None
    if robot.tag != "robot":
        raise ValueError(f"a URDF's root is <robot>, not <{robot.tag}>")
    materials = {}
    for named in robot.findall("material"):
        rgba = named.find("color")
        if rgba is not None:
            materials[named.get("name", "")] = tuple(_floats(rgba.get("rgba"), 4, 1.0))
    visuals = []
    for link in robot.findall("link"):
        for visual in link.findall("visual"):
            geometry = visual.find("geometry")
            shape = geometry[0] if geometry is not None and len(geometry) else None
            if shape is None:
                continue
            color: Any = DEFAULT_COLOR
            material = visual.find("material")
            if material is not None:
                own = material.find("color")
                color = tuple(_floats(own.get("rgba"), 4, 1.0)) if own is not None else materials.get(
                    material.get("name", ""), DEFAULT_COLOR)
            size: tuple[float, float, float]
            if shape.tag == "box":
                sx, sy, sz = _floats(shape.get("size"), 3)
                size = (sx, sy, sz)
            elif shape.tag == "cylinder":
                radius, length = float(shape.get("radius", 0)), float(shape.get("length", 0))
                size = (2 * radius, 2 * radius, length)
            elif shape.tag == "sphere":
                diameter = 2 * float(shape.get("radius", 0))
                size = (diameter, diameter, diameter)
            else:
                size = (1.0, 1.0, 1.0)
            visuals.append(Visual(link.get("name", ""), origin_matrix(visual.find("origin")), shape.tag, size, color,
                                  shape.get("filename", "")))
    return visuals


class RobotModel(Display):
    class_name = "rviz/RobotModel"
    defaults = {"Robot Description": "robot_description", "Alpha": 1, "TF Prefix": ""}

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.visuals: list[Visual] = []
        self.problem = "no robot description yet"

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
            shapes = {"box": box_triangles, "cylinder": cylinder_triangles, "sphere": sphere_triangles}
            if visual.shape not in shapes:
                problems.append(f"{visual.link}: {visual.shape} {visual.mesh} not drawn yet")
                continue
            color = (*visual.color[:3], visual.color[3] * alpha)
            scene.add("triangles", apply(placed @ visual.origin, shapes[visual.shape](visual.size)), color)
        if problems:
            self.status = Status(WARN, "; ".join(sorted(set(problems))[:3]))
