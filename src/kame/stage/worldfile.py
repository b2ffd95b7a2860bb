"""Stage's .world files, for the shapes ROS worlds use: a floorplan bitmap, boxes, robots.

Pure: text in (included files through a `read` callback), values out. Understood:
- `include "file"`, `define NAME PARENT ( ... )`, top-level `resolution`, and instances
  `TYPE ( key value ... nested ( ... ) )`; `#` comments; values are numbers, words, "strings"
  and [ lists ]; everything else (window, interval_sim, colours, sensors...) is read and ignored.
- An instance with a `bitmap` is a floorplan: the image scaled to `size` [x y ...] metres,
  centred on `pose`, its dark pixels (channel average below 128) walls, `boundary 1` a wall
  around it. An instance of a type that derives from `position` is a robot. Any other instance
  with a `size` and a `pose` is a box (an obstacle), rotated by its yaw.
- pose is [x y z yaw] (Stage 4) or [x y yaw] (Stage 3), yaw in degrees.
Errors (unbalanced brackets, no floorplan, an unknown include) raise WorldFileError saying
where.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from kame.stage.mapfile import OCCUPIED, Grid

_TOKEN = re.compile(r'\s*(?:(#[^\n]*)|("[^"]*")|([()\[\]])|([^\s()\[\]"#]+))')
DARK = 128  # a bitmap pixel darker than this (channel average) is a wall


class WorldFileError(ValueError):
    """A .world file kame cannot read; the text says where and why."""


Value = float | str | list["Value"]


@dataclass
class Instance:
    kind: str
    properties: dict[str, Value] = field(default_factory=dict)


@dataclass(frozen=True)
class Floorplan:
    bitmap: str
    size: tuple[float, float]
    pose: tuple[float, float, float]  # x, y, yaw (radians)
    boundary: bool


@dataclass(frozen=True)
class Box:
    size: tuple[float, float]
    pose: tuple[float, float, float]


@dataclass(frozen=True)
class RobotPlacement:
    name: str
    pose: tuple[float, float, float]


@dataclass
class WorldSpec:
    resolution: float = 0.02
    floorplans: list[Floorplan] = field(default_factory=list)
    boxes: list[Box] = field(default_factory=list)
    robots: list[RobotPlacement] = field(default_factory=list)


def _tokens(text: str, source: str) -> list[str]:
    tokens = []
    position = 0
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None or match.end() == position:
            if text[position:].strip() == "":
                break
            line = text.count("\n", 0, position) + 1
            raise WorldFileError(f"{source}:{line}: cannot read {text[position:position + 20]!r}")
        position = match.end()
        if match.group(1) is None and match.lastindex is not None:
            tokens.append(match.group(match.lastindex))
    return tokens


class _Parser:
    def __init__(self, tokens: list[str], source: str) -> None:
        self.tokens = tokens
        self.at = 0
        self.source = source

    def peek(self) -> str | None:
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def take(self) -> str:
        token = self.peek()
        if token is None:
            raise WorldFileError(f"{self.source}: the file ends inside a bracket")
        self.at += 1
        return token

    def value(self) -> Value:
        token = self.take()
        if token == "[":
            items: list[Value] = []
            while self.peek() != "]":
                items.append(self.value())
            self.take()
            return items
        if token in "()]":
            raise WorldFileError(f"{self.source}: unexpected {token!r}")
        if token.startswith('"'):
            return token[1:-1]
        try:
            return float(token)
        except ValueError:
            return token

    def body(self) -> tuple[dict[str, Value], list[Instance]]:
        """key value pairs and nested instances up to the closing ')'."""
        properties: dict[str, Value] = {}
        nested: list[Instance] = []
        while self.peek() != ")":
            key = self.take()
            if self.peek() == "(":
                self.take()
                inner, _ = self.body()
                nested.append(Instance(key, inner))
            else:
                properties[key] = self.value()
        self.take()
        return properties, nested


def _numbers(value: Value | None, what: str) -> list[float]:
    if not isinstance(value, list) or not all(isinstance(v, float) for v in value):
        raise WorldFileError(f"{what} must be a list of numbers, not {value!r}")
    return [float(v) for v in value if isinstance(v, float)]


def _pose(value: Value | None) -> tuple[float, float, float]:
    if value is None:
        return 0.0, 0.0, 0.0
    numbers = _numbers(value, "pose")
    if len(numbers) == 4:
        return numbers[0], numbers[1], math.radians(numbers[3])
    if len(numbers) == 3:
        return numbers[0], numbers[1], math.radians(numbers[2])
    raise WorldFileError(f"pose must be [x y z yaw] or [x y yaw], not {value!r}")


def parse(text: str, source: str, read: Callable[[str], str]) -> WorldSpec:
    """The world a .world file describes; `read(name)` gives an included file's text (relative
    names are the caller's to resolve) or raises OSError."""
    parents: dict[str, str] = {}
    defaults: dict[str, dict[str, Value]] = {}
    instances: list[Instance] = []
    spec = WorldSpec()

    def load(text: str, source: str, depth: int) -> None:
        parser = _Parser(_tokens(text, source), source)
        while parser.peek() is not None:
            word = parser.take()
            if word == "include":
                name = parser.value()
                if not isinstance(name, str) or depth > 10:
                    raise WorldFileError(f"{source}: include needs a file name (and no include loops)")
                try:
                    included = read(name)
                except OSError as exc:
                    raise WorldFileError(f"{source}: cannot include {name!r}: {exc.strerror or exc}") from None
                load(included, name, depth + 1)
            elif word == "define":
                name, parent = parser.take(), parser.take()
                if parser.take() != "(":
                    raise WorldFileError(f"{source}: define {name} {parent} needs a ( body )")
                parents[name] = parent
                defaults[name], _ = parser.body()
            elif parser.peek() == "(":
                parser.take()
                properties, _ = parser.body()
                instances.append(Instance(word, properties))
            elif word == "resolution":
                resolution = parser.value()
                if not isinstance(resolution, float) or not resolution > 0:
                    raise WorldFileError(f"{source}: resolution must be a number above 0")
                spec.resolution = resolution
            else:
                parser.value()  # a top-level setting the 2-D world has no use for

    def derives(kind: str, base: str) -> bool:
        seen = set()
        while kind not in seen:
            if kind == base:
                return True
            seen.add(kind)
            kind = parents.get(kind, "")
        return False

    def merged(instance: Instance) -> dict[str, Value]:
        chain = []
        kind = instance.kind
        while kind in defaults and kind not in chain:
            chain.append(kind)
            kind = parents.get(kind, "")
        properties: dict[str, Value] = {}
        for kind in reversed(chain):
            properties.update(defaults[kind])
        properties.update(instance.properties)
        return properties

    if text.lstrip().startswith("<"):
        raise WorldFileError(f"{source} is a Gazebo (SDF) world: kame's 2-D world reads Stage .world files "
                             "and map_server maps (map.yaml)")
    load(text, source, 0)
    for instance in instances:
        properties = merged(instance)
        if "bitmap" in properties:
            size = _numbers(properties.get("size"), "a floorplan's size")
            bitmap = properties["bitmap"]
            if not isinstance(bitmap, str) or len(size) < 2 or size[0] <= 0 or size[1] <= 0:
                raise WorldFileError(f"{source}: a floorplan needs a bitmap name and a size above 0")
            spec.floorplans.append(Floorplan(bitmap, (size[0], size[1]), _pose(properties.get("pose")),
                                             properties.get("boundary", 0.0) == 1.0))
        elif derives(instance.kind, "position"):
            name = properties.get("name", f"robot_{len(spec.robots)}")
            spec.robots.append(RobotPlacement(str(name), _pose(properties.get("pose"))))
        elif "size" in properties and "pose" in instance.properties:
            size = _numbers(properties["size"], "a model's size")
            if len(size) >= 2:
                spec.boxes.append(Box((size[0], size[1]), _pose(properties["pose"])))
    if not spec.floorplans:
        raise WorldFileError(f"{source}: no floorplan (a model with a bitmap): kame's world needs one")
    return spec


def rasterise(spec: WorldSpec, bitmaps: dict[str, np.ndarray]) -> Grid:
    """The occupancy grid of a world: its floorplans' dark pixels and boundaries, its boxes.
    `bitmaps` holds each floorplan's image (channel averages, row 0 at the top) by name."""
    res = spec.resolution
    corners = []
    for plan in spec.floorplans:
        if abs(plan.pose[2]) > 1e-9:
            raise WorldFileError(f"floorplan {plan.bitmap}: a rotated floorplan is not supported")
        corners.append((plan.pose[0] - plan.size[0] / 2, plan.pose[1] - plan.size[1] / 2,
                        plan.pose[0] + plan.size[0] / 2, plan.pose[1] + plan.size[1] / 2))
    left, bottom = min(c[0] for c in corners), min(c[1] for c in corners)
    right, top = max(c[2] for c in corners), max(c[3] for c in corners)
    width, height = max(1, round((right - left) / res)), max(1, round((top - bottom) / res))
    walls = np.zeros((height, width), dtype=bool)
    for plan, (x0, y0, x1, y1) in zip(spec.floorplans, corners, strict=True):
        image = bitmaps[plan.bitmap]
        c0, r0 = round((x0 - left) / res), round((y0 - bottom) / res)
        cols, rows = max(1, round((x1 - x0) / res)), max(1, round((y1 - y0) / res))
        cols, rows = min(cols, width - c0), min(rows, height - r0)
        # nearest pixel of each cell; the image's top row is the plan's top (+y)
        pixel_rows = ((rows - 1 - np.arange(rows) + 0.5) * image.shape[0] / rows).astype(np.int64)
        pixel_cols = ((np.arange(cols) + 0.5) * image.shape[1] / cols).astype(np.int64)
        block = image[np.clip(pixel_rows, 0, image.shape[0] - 1)][:, np.clip(pixel_cols, 0, image.shape[1] - 1)]
        walls[r0:r0 + rows, c0:c0 + cols] |= block < DARK
        if plan.boundary:
            walls[r0, c0:c0 + cols] = walls[r0 + rows - 1, c0:c0 + cols] = True
            walls[r0:r0 + rows, c0] = walls[r0:r0 + rows, c0 + cols - 1] = True
    centre_x = left + (np.arange(width) + 0.5) * res
    centre_y = bottom + (np.arange(height) + 0.5) * res
    for box in spec.boxes:
        x, y, yaw = box.pose
        along = (centre_x[None, :] - x) * math.cos(yaw) + (centre_y[:, None] - y) * math.sin(yaw)
        across = -(centre_x[None, :] - x) * math.sin(yaw) + (centre_y[:, None] - y) * math.cos(yaw)
        walls |= (np.abs(along) <= box.size[0] / 2) & (np.abs(across) <= box.size[1] / 2)
    return Grid(np.where(walls, OCCUPIED, 0).astype(np.int8), res, (left, bottom, 0.0))
