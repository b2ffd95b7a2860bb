"""The kame-specific messages gzserver sends its windows, as std_msgs/String JSON (Gazebo's own
travel over its transport, which ROS tools cannot read; JSON in a String can be read with
`rostopic echo` and needs no new message type on the wire):

- /gazebo/kame/scene (latched, sent again when a spawn or delete rebuilds the world): what to
  draw. {"format": 1, "world": name, "generation": n, "background": rgba, "ambient": rgba,
  "lights": [{"name", "type", "position", "orientation", "diffuse", "direction"}],
  "visuals": [{"link": "model::link", "name", "kind", "size", "position", "orientation",
  "color", "triangles"}]}, a pose's orientation a quaternion x y z w in its link's frame, a
  mesh's "triangles" its corners as little-endian float32 x y z, base64 (a 10k-triangle mesh
  is 480 kB in JSON numbers, 480 kB / 0.75 as base64), "" for the other shapes.
- /gazebo/kame/world_stats (5 times a second of wall time while someone listens): what
  gzclient's status bar shows. {"sim_time", "real_time", "iterations", "paused"}; while paused
  also "links" and "models", {name: [x, y, z, qx, qy, qz, qw]}: gazebo_ros publishes
  /gazebo/link_states and model_states after steps only, and a model moved or spawned in a paused
  world must still be drawn where it is.

Pure values both ways: the server encodes, the window's model decodes."""

from __future__ import annotations

import base64
import json
from dataclasses import dataclass
from typing import Any

import numpy as np

FORMAT = 1
SCENE_TOPIC = "/gazebo/kame/scene"
STATS_TOPIC = "/gazebo/kame/world_stats"
STEP_TOPIC = "/gazebo/kame/step"  # std_msgs/UInt32: so many iterations while paused (gzclient's step button)

Vector3 = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]
Rgba = tuple[float, float, float, float]


class SceneMessageError(ValueError):
    """A scene or stats message that is not what this module writes."""


@dataclass(frozen=True)
class VisualMessage:
    link: str  # "model::link"
    name: str
    kind: str  # box, cylinder, sphere, plane, mesh
    size: tuple[float, ...]  # box x y z; cylinder radius length; sphere radius; plane x y
    position: Vector3  # in the link's frame
    orientation: Quaternion
    color: Rgba
    triangles: np.ndarray | None  # a mesh's corners, 3M x 3 float32, in the visual's frame

    @property
    def model(self) -> str:
        return self.link.split("::", 1)[0]


@dataclass(frozen=True)
class LightMessage:
    name: str
    type: str  # directional, point, spot
    position: Vector3
    orientation: Quaternion
    diffuse: Rgba
    direction: Vector3


@dataclass(frozen=True)
class SceneMessage:
    world: str
    generation: int
    background: Rgba
    ambient: Rgba
    lights: tuple[LightMessage, ...]
    visuals: tuple[VisualMessage, ...]


Poses = dict[str, tuple[Vector3, Quaternion]]


@dataclass(frozen=True)
class WorldStats:
    sim_time: float  # seconds
    real_time: float  # seconds of wall time the world has been running (paused or not)
    iterations: int
    paused: bool
    links: Poses | None = None  # while paused: every link's pose, by "model::link"
    models: Poses | None = None  # while paused: every model's pose


def _floats(values: Any, count: int | None, what: str) -> tuple[float, ...]:
    if not isinstance(values, list) or (count is not None and len(values) != count) \
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        raise SceneMessageError(f"{what} must be a list of {count or 'some'} numbers, not {values!r}")
    return tuple(float(v) for v in values)


def _v3(values: Any, what: str) -> Vector3:
    x, y, z = _floats(values, 3, what)
    return x, y, z


def _v4(values: Any, what: str) -> tuple[float, float, float, float]:
    a, b, c, d = _floats(values, 4, what)
    return a, b, c, d


def _triangles_text(triangles: np.ndarray | None) -> str:
    if triangles is None:
        return ""
    return base64.b64encode(np.ascontiguousarray(triangles, dtype="<f4").tobytes()).decode("ascii")


def _triangles(text: Any) -> np.ndarray | None:
    if not isinstance(text, str):
        raise SceneMessageError(f"a visual's triangles must be base64 text, not {text!r}")
    if not text:
        return None
    raw = base64.b64decode(text, validate=True)
    if len(raw) % 36:
        raise SceneMessageError("a mesh's triangles must be whole triangles of three float32 corners")
    return np.frombuffer(raw, dtype="<f4").reshape(-1, 3).astype(np.float32)


def encode_scene(scene: SceneMessage) -> str:
    return json.dumps({
        "format": FORMAT, "world": scene.world, "generation": scene.generation,
        "background": list(scene.background), "ambient": list(scene.ambient),
        "lights": [{"name": light.name, "type": light.type, "position": list(light.position),
                    "orientation": list(light.orientation), "diffuse": list(light.diffuse),
                    "direction": list(light.direction)} for light in scene.lights],
        "visuals": [{"link": v.link, "name": v.name, "kind": v.kind, "size": list(v.size),
                     "position": list(v.position), "orientation": list(v.orientation), "color": list(v.color),
                     "triangles": _triangles_text(v.triangles)} for v in scene.visuals],
    }, separators=(",", ":"))


def decode_scene(text: str) -> SceneMessage:
    try:
        doc = json.loads(text)
        if not isinstance(doc, dict) or doc.get("format") != FORMAT:
            raise SceneMessageError(f"not a kame scene of format {FORMAT}")
        lights = tuple(LightMessage(str(light["name"]), str(light["type"]),
                                    _v3(light["position"], "a light's position"),
                                    _v4(light["orientation"], "a light's orientation"),
                                    _v4(light["diffuse"], "a light's diffuse colour"),
                                    _v3(light["direction"], "a light's direction"))
                       for light in doc["lights"])
        visuals = tuple(VisualMessage(str(v["link"]), str(v["name"]), str(v["kind"]),
                                      _floats(v["size"], None, "a size"),
                                      _v3(v["position"], "a visual's position"),
                                      _v4(v["orientation"], "a visual's orientation"),
                                      _v4(v["color"], "a colour"), _triangles(v["triangles"]))
                        for v in doc["visuals"])
        return SceneMessage(str(doc["world"]), int(doc["generation"]),
                            _v4(doc["background"], "the background"),
                            _v4(doc["ambient"], "the ambient light"),
                            lights, visuals)
    except (KeyError, TypeError, ValueError) as exc:
        if isinstance(exc, SceneMessageError):
            raise
        raise SceneMessageError(f"not a kame scene: {exc!r}") from exc


def _pose_lists(poses: Poses) -> dict[str, list[float]]:
    return {name: [*position, *orientation] for name, (position, orientation) in poses.items()}


def _poses(doc: Any) -> Poses | None:
    if doc is None:
        return None
    if not isinstance(doc, dict):
        raise SceneMessageError(f"poses must be an object of names, not {doc!r}")
    poses = {}
    for name, values in doc.items():
        x, y, z, qx, qy, qz, qw = _floats(values, 7, f"{name}'s pose")
        poses[str(name)] = ((x, y, z), (qx, qy, qz, qw))
    return poses


def encode_stats(stats: WorldStats) -> str:
    doc: dict[str, Any] = {"sim_time": stats.sim_time, "real_time": stats.real_time, "iterations": stats.iterations,
                           "paused": stats.paused}
    if stats.links is not None:
        doc["links"] = _pose_lists(stats.links)
    if stats.models is not None:
        doc["models"] = _pose_lists(stats.models)
    return json.dumps(doc, separators=(",", ":"))


def decode_stats(text: str) -> WorldStats:
    try:
        doc = json.loads(text)
        sim_time, real_time = _floats([doc["sim_time"], doc["real_time"]], 2, "the times")
        return WorldStats(sim_time, real_time, int(doc["iterations"]), bool(doc["paused"]), _poses(doc.get("links")),
                          _poses(doc.get("models")))
    except (KeyError, TypeError, ValueError) as exc:
        if isinstance(exc, SceneMessageError):
            raise
        raise SceneMessageError(f"not kame world stats: {exc!r}") from exc


