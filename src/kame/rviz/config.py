"""The .rviz file (YAML, as rviz writes it): Visualization Manager's Displays (Class, Name,
Enabled, and each display's own keys), Global Options (Fixed Frame, Background Color, Frame
Rate) and Views (Current: rviz/Orbit, rviz/TopDownOrtho or rviz/FPS). Keys kame does not use are kept and
written back, so a file saved by kame still opens in rviz with what rviz had put there.
As rviz's config reader, a section that is not a mapping (or list) where one belongs, and a
number that is not one (or is NaN or inf), count as absent: the defaults stand."""

from __future__ import annotations

import math
import posixpath
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import yaml

from kame.rviz.camera import FPS, ORBIT, TOP_DOWN, Camera
from kame.rviz.display import Display, format_color, parse_color
from kame.rviz.displays import (
    TF,
    Axes,
    Grid,
    LaserScan,
    OccupancyGrid,
    Odometry,
    Path,
    PointCloud2,
    PointStamped,
    Polygon,
    Pose,
    PoseArray,
)
from kame.rviz.interactive import InteractiveMarkers
from kame.rviz.markers import Marker, MarkerArray
from kame.rviz.robot import RobotModel
from kame.rviz.scene import Color
from kame.rviz.sensors import Camera as CameraDisplay
from kame.rviz.sensors import Image, Range, WrenchStamped

DISPLAY_CLASSES: dict[str, type[Display]] = {cls.class_name: cls for cls in (
    Grid, Axes, TF, LaserScan, PointCloud2, Odometry, Pose, PoseArray, PointStamped, Path, Polygon, OccupancyGrid,
    Marker, MarkerArray, InteractiveMarkers, RobotModel, Range, WrenchStamped, Image, CameraDisplay)}
COMMON_KEYS = ("Class", "Name", "Enabled")


def displays_by_topic(topics: list[tuple[str, str]]) -> list[tuple[str, str]]:
    """rviz's Add > By topic: (topic, display class) for each published topic a display shows."""
    return [(topic, class_name) for topic, type_name in sorted(topics)
            for class_name, cls in DISPLAY_CLASSES.items() if type_name in cls.message_types]


def display_for_topic(class_name: str, topic: str) -> Display:
    """A new display of `class_name` showing `topic`, named after the topic."""
    cls = DISPLAY_CLASSES[class_name]
    return cls(name=topic, options={cls.topic_key: topic})


@dataclass
class Config:
    fixed_frame: str = "map"
    background: Color = (48 / 255, 48 / 255, 48 / 255, 1.0)
    frame_rate: int = 30
    displays: list[Display] = field(default_factory=lambda: [Grid()])
    camera: Camera = field(default_factory=Camera)
    unknown_displays: list[dict[str, Any]] = field(default_factory=list)  # classes kame has not, kept for saving
    raw: dict[str, Any] = field(default_factory=dict)


def _float(value: Any, default: float) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return default
    return number if math.isfinite(number) else default


def _mapping(value: Any) -> dict[str, Any]:
    return value if isinstance(value, dict) else {}


def _entries(value: Any) -> list[Any]:
    return value if isinstance(value, list) else []


def display_from(entry: dict[str, Any]) -> Display | None:
    cls = DISPLAY_CLASSES.get(str(entry.get("Class", "")))
    if cls is None:
        return None
    options = {k: v for k, v in entry.items() if k not in COMMON_KEYS}
    return cls(str(entry.get("Name", "")), bool(entry.get("Enabled", True)), options)


def camera_from(view: dict[str, Any]) -> Camera:
    camera = Camera()
    kind = str(view.get("Class"))
    camera.kind = kind if kind in (TOP_DOWN, FPS) else ORBIT
    focal = _mapping(view.get("Focal Point"))
    camera.focal_point = np.array([_float(focal.get(axis), 0.0) for axis in "XYZ"])
    camera.distance = _float(view.get("Distance"), camera.distance)
    camera.yaw, camera.pitch = _float(view.get("Yaw"), camera.yaw), _float(view.get("Pitch"), camera.pitch)
    camera.scale = _float(view.get("Scale"), camera.scale)
    camera.angle = _float(view.get("Angle"), camera.angle)
    if camera.kind == TOP_DOWN:
        camera.focal_point = np.array([_float(view.get("X"), 0.0), _float(view.get("Y"), 0.0), 0.0])
    if camera.kind == FPS:
        position = _mapping(view.get("Position"))
        camera.position = np.array([_float(position.get(axis), 0.0) for axis in "XYZ"])
    return camera


def parse(text: str) -> Config:
    """A .rviz file's text; raises ValueError saying what is wrong with it."""
    try:
        document = yaml.safe_load(text) or {}
    except yaml.YAMLError as exc:
        raise ValueError(f"not YAML: {exc}") from None
    if not isinstance(document, dict):
        raise ValueError("a .rviz file is a YAML mapping")
    manager = _mapping(document.get("Visualization Manager"))
    options = _mapping(manager.get("Global Options"))
    config = Config(raw=document, displays=[])
    config.fixed_frame = str(options.get("Fixed Frame", config.fixed_frame))
    config.background = parse_color(options.get("Background Color"), config.background)
    config.frame_rate = int(_float(options.get("Frame Rate"), config.frame_rate))
    for entry in _entries(manager.get("Displays")):
        if not isinstance(entry, dict):
            continue
        display = display_from(entry)
        if display is None:
            config.unknown_displays.append(entry)
        else:
            config.displays.append(display)
    config.camera = camera_from(_mapping(_mapping(manager.get("Views")).get("Current")))
    return config


def load(path: str) -> Config:
    with open(path, encoding="utf-8") as f:
        return parse(f.read())


def display_entry(display: Display) -> dict[str, Any]:
    return {"Class": display.class_name, "Name": display.name, "Enabled": display.enabled, **display.options}


def view_entry(camera: Camera) -> dict[str, Any]:
    if camera.kind == TOP_DOWN:
        return {"Class": TOP_DOWN, "Name": "Current View", "Angle": camera.angle, "Scale": camera.scale,
                "X": float(camera.focal_point[0]), "Y": float(camera.focal_point[1]), "Target Frame": "<Fixed Frame>"}
    if camera.kind == FPS:
        x, y, z = (float(v) for v in camera.position)
        return {"Class": FPS, "Name": "Current View", "Invert Z Axis": False, "Near Clip Distance": camera.near,
                "Pitch": camera.pitch, "Position": {"X": x, "Y": y, "Z": z}, "Target Frame": "<Fixed Frame>",
                "Yaw": camera.yaw}
    x, y, z = (float(v) for v in camera.focal_point)
    return {"Class": ORBIT, "Name": "Current View", "Distance": camera.distance,
            "Focal Point": {"X": x, "Y": y, "Z": z}, "Pitch": camera.pitch, "Yaw": camera.yaw,
            "Target Frame": "<Fixed Frame>", "Field of View": camera.fov_y}


def dump(config: Config) -> str:
    document = dict(config.raw)
    manager = dict(_mapping(document.get("Visualization Manager")))
    manager["Class"] = ""
    manager["Displays"] = [display_entry(d) for d in config.displays] + config.unknown_displays
    manager["Enabled"] = True
    options = dict(_mapping(manager.get("Global Options")))
    options.update({"Fixed Frame": config.fixed_frame, "Background Color": format_color(config.background),
                    "Frame Rate": config.frame_rate})
    options.setdefault("Default Light", True)
    manager["Global Options"] = options
    views = dict(_mapping(manager.get("Views")))
    views["Current"] = view_entry(config.camera)
    views.setdefault("Saved", None)
    manager["Views"] = views
    document["Visualization Manager"] = manager
    document.setdefault("Panels", [{"Class": "rviz/Displays", "Name": "Displays"}])
    return yaml.safe_dump(document, sort_keys=False, default_flow_style=False)


def save(config: Config, path: str) -> None:
    with open(path, "w", encoding="utf-8") as f:
        f.write(dump(config))


def window_title(path: str) -> str:
    """rviz's title: the file's name (not its folder) before " - RViz", or "RViz" without a file."""
    return f"{posixpath.basename(path)} - RViz" if path else "RViz"


def window_size(config: Config, default: tuple[int, int] = (1280, 720)) -> tuple[int, int]:
    """The window's size as the file's Window Geometry gives it (rviz opens at that size)."""
    geometry = config.raw.get("Window Geometry")
    if isinstance(geometry, dict):
        width, height = geometry.get("Width"), geometry.get("Height")
        if isinstance(width, int) and isinstance(height, int) and width > 0 and height > 0:
            return width, height
    return default
